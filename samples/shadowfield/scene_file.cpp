// SPDX-License-Identifier: MIT
#include "scene_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "prt/io/error.hpp"

namespace prt::shadowfield_app {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

constexpr const char* kFormat = "prtkit shadowfield scene";
constexpr int kVersion = 1;

glm::vec3 read_vec3(const json& j) {
  if (!j.is_array() || j.size() != 3) throw SceneError("expected 3 numbers");
  return {j[0].get<float>(), j[1].get<float>(), j[2].get<float>()};
}

Path read_path(const json& instance) {
  Path path;
  path.duration = instance.value("duration", 0.0f);
  for (const json& k : instance.at("keyframes")) {
    Keyframe key;
    key.time = k.at("time").get<float>();
    key.placement.translation = read_vec3(k.at("translation"));
    const json& q = k.at("rotation");  // glTF order x, y, z, w
    if (!q.is_array() || q.size() != 4) throw SceneError("rotation: expected 4 numbers");
    key.placement.rotation =
        glm::quat(q[3].get<float>(), q[0].get<float>(), q[1].get<float>(), q[2].get<float>());
    key.placement.scale = k.at("scale").get<float>();
    path.keyframes.push_back(key);
  }
  try {
    path.check();
  } catch (const io::Error& e) {
    throw SceneError(e.what());
  }
  for (Keyframe& k : path.keyframes) k.placement.rotation = glm::normalize(k.placement.rotation);
  return path;
}

SceneFile read_scene(const json& j, const fs::path& folder) {
  if (j.value("format", std::string()) != kFormat) throw SceneError("not a shadowfield scene");
  if (j.value("version", 0) != kVersion)
    throw SceneError("unsupported version (expected " + std::to_string(kVersion) + ")");
  SceneFile scene;
  scene.name = j.value("name", std::string());
  scene.env = j.value("env", std::string("builtin:sky"));
  scene.eye = read_vec3(j.at("camera").at("eye"));
  scene.target = read_vec3(j.at("camera").at("target"));
  for (const json& o : j.at("objects")) {
    const fs::path blob = folder / o.at("blob").get<std::string>();
    if (!fs::is_regular_file(blob)) throw SceneError("blob " + blob.string() + " not found");
    scene.objects.push_back({o.at("name").get<std::string>(), blob.string()});
  }
  if (scene.objects.empty()) throw SceneError("no object");
  for (const json& i : j.at("instances")) {
    SceneInstance instance;
    instance.object = i.at("object").get<std::size_t>();
    if (instance.object >= scene.objects.size())
      throw SceneError("an instance names object " + std::to_string(instance.object) + " of " +
                       std::to_string(scene.objects.size()));
    try {
      instance.path = read_path(i);
    } catch (const SceneError& e) {
      throw SceneError("instance " + std::to_string(scene.instances.size()) + ": " + e.what());
    }
    scene.instances.push_back(std::move(instance));
  }
  if (scene.instances.empty()) throw SceneError("no instance");
  return scene;
}

json vec3_json(const glm::vec3& v) {
  return json::array({v.x, v.y, v.z});
}

}  // namespace

SceneFile read_scene_file(const std::string& where) {
  fs::path file = where;
  if (fs::is_directory(file) || file.extension() != ".json") file /= "scene.json";
  std::ifstream in(file);
  if (!in)
    throw SceneError(file.string() +
                     ": cannot read it (give a folder holding scene.json, as prt-bake "
                     "shadowfield-scene writes it, or the JSON file)");
  try {
    const json j = json::parse(in);
    SceneFile scene = read_scene(j, fs::absolute(file).parent_path());
    scene.path = file.string();
    return scene;
  } catch (const json::exception& e) {
    throw SceneError(file.string() + ": " + e.what());
  } catch (const SceneError& e) {
    throw SceneError(file.string() + ": " + e.what());
  }
}

void write_placed_scene_file(const SceneFile& scene, const std::vector<Placement>& placements,
                             const std::string& env, const std::string& path) {
  json objects = json::array(), instances = json::array();
  // Relative to the new file's folder, as the format says, however a reader joins the two.
  const fs::path folder = fs::absolute(path).parent_path();
  for (const SceneObject& o : scene.objects)
    objects.push_back(
        {{"name", o.name}, {"blob", fs::relative(fs::absolute(o.blob), folder).string()}});
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const Placement& p = placements.at(i);
    const json key = {
        {"time", 0.0},
        {"translation", vec3_json(p.translation)},
        {"rotation", json::array({p.rotation.x, p.rotation.y, p.rotation.z, p.rotation.w})},
        {"scale", p.scale}};
    instances.push_back(
        {{"object", scene.instances[i].object}, {"duration", 0.0}, {"keyframes", {key}}});
  }
  const json j = {{"format", kFormat},
                  {"version", kVersion},
                  {"name", scene.name},
                  {"env", env},
                  {"camera", {{"eye", vec3_json(scene.eye)}, {"target", vec3_json(scene.target)}}},
                  {"objects", objects},
                  {"instances", instances}};
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) throw SceneError(path + ": cannot write it");
}

}  // namespace prt::shadowfield_app
