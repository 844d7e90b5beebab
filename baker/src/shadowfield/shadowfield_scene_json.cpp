// SPDX-License-Identifier: MIT
// The JSON form of a shadowfield scene, which the app reads (schema: docs/shadowfield/scenes.md).
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../common/numbers.hpp"
#include "prt/baker/context.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"
#include "prt/io/error.hpp"

namespace prt::bake {
namespace {

// Ordered, so the file reads in the order of the schema (docs/shadowfield/scenes.md).
using json = nlohmann::ordered_json;

constexpr const char* kFormat = "prtkit shadowfield scene";
constexpr int kVersion = 1;

json vec3_json(const glm::vec3& v) {
  return json::array({shortest(v.x), shortest(v.y), shortest(v.z)});
}

// glTF's order: x, y, z, w.
json quat_json(const glm::quat& q) {
  return json::array({shortest(q.x), shortest(q.y), shortest(q.z), shortest(q.w)});
}

json instance_json(const ShadowfieldInstance& instance) {
  const ShadowfieldPath& path = instance.path;
  json keyframes = json::array();
  for (const ShadowfieldKeyframe& k : path.keyframes) {
    keyframes.push_back({{"time", shortest(k.time)},
                         {"translation", vec3_json(k.placement.translation)},
                         {"rotation", quat_json(k.placement.rotation)},
                         {"scale", shortest(k.placement.scale)}});
  }
  return {
      {"object", instance.object}, {"duration", shortest(path.duration)}, {"keyframes", keyframes}};
}

glm::vec3 read_vec3(const json& j) {
  if (!j.is_array() || j.size() != 3) throw Error("expected an array of 3 numbers");
  return {j.at(0).get<float>(), j.at(1).get<float>(), j.at(2).get<float>()};
}

glm::quat read_quat(const json& j) {
  if (!j.is_array() || j.size() != 4) throw Error("expected an array of 4 numbers (x, y, z, w)");
  return {j.at(3).get<float>(), j.at(0).get<float>(), j.at(1).get<float>(), j.at(2).get<float>()};
}

// The path's own reason, as the baker's Error every caller of this file catches.
void check_path(const ShadowfieldPath& path) {
  try {
    path.check();
  } catch (const io::Error& e) {
    throw Error(std::string("shadowfield ") + e.what());
  }
}

ShadowfieldPath read_path(const json& j) {
  ShadowfieldPath path;
  path.duration = j.value("duration", 0.0f);
  for (const json& k : j.at("keyframes")) {
    ShadowfieldKeyframe keyframe;
    keyframe.time = k.at("time").get<float>();
    keyframe.placement.translation = read_vec3(k.at("translation"));
    keyframe.placement.rotation = read_quat(k.at("rotation"));
    keyframe.placement.scale = k.at("scale").get<float>();
    path.keyframes.push_back(keyframe);
  }
  check_path(path);
  return path;
}

ShadowfieldSceneFile read_scene(const json& j) {
  if (j.value("format", std::string()) != kFormat) throw Error("not a shadowfield scene");
  if (j.value("version", 0) != kVersion)
    throw Error("unsupported version (expected " + std::to_string(kVersion) + ")");
  ShadowfieldSceneFile scene;
  scene.name = j.value("name", std::string());
  scene.env = j.at("env").get<std::string>();
  scene.camera.eye = read_vec3(j.at("camera").at("eye"));
  scene.camera.target = read_vec3(j.at("camera").at("target"));
  for (const json& o : j.at("objects")) {
    scene.objects.push_back({o.at("name").get<std::string>(), o.at("blob").get<std::string>()});
  }
  for (const json& i : j.at("instances")) {
    ShadowfieldInstance instance;
    instance.object = i.at("object").get<std::size_t>();
    if (instance.object >= scene.objects.size())
      throw Error("instance names object " + std::to_string(instance.object) + " of " +
                  std::to_string(scene.objects.size()));
    instance.path = read_path(i);
    scene.instances.push_back(std::move(instance));
  }
  return scene;
}

}  // namespace

void write_shadowfield_scene_json(const ShadowfieldSceneDescription& description,
                                  const std::vector<std::string>& blob_names,
                                  const std::string& path) {
  if (blob_names.size() != description.objects.size())
    throw Error(path + ": " + std::to_string(blob_names.size()) + " blob names for " +
                std::to_string(description.objects.size()) + " objects");
  json objects = json::array(), instances = json::array();
  for (std::size_t i = 0; i < blob_names.size(); ++i) {
    objects.push_back({{"name", description.objects[i].name}, {"blob", blob_names[i]}});
  }
  for (const ShadowfieldInstance& instance : description.instances) {
    if (instance.object >= description.objects.size())
      throw Error(path + ": an instance names object " + std::to_string(instance.object) + " of " +
                  std::to_string(description.objects.size()));
    check_path(instance.path);
    instances.push_back(instance_json(instance));
  }
  const json scene = {{"format", kFormat},
                      {"version", kVersion},
                      {"name", description.name},
                      {"env", description.env},
                      {"camera",
                       {{"eye", vec3_json(description.camera.eye)},
                        {"target", vec3_json(description.camera.target)}}},
                      {"objects", objects},
                      {"instances", instances}};
  std::ofstream out(path, std::ios::binary);
  out << scene.dump(2) << '\n';
  if (!out) throw Error(path + ": cannot write");
}

ShadowfieldSceneFile read_shadowfield_scene_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open");
  try {
    return read_scene(json::parse(in));
  } catch (const json::exception& e) {
    throw Error(path + ": " + e.what());
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
}

}  // namespace prt::bake
