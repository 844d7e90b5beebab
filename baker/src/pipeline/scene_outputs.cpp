// SPDX-License-Identifier: MIT
// The content pipeline's files: blobs written whole or not at all, the scene manifests (JSON, and
// the binary one the runtime loads) and the report (scene_bake_detail.hpp; docs/pipeline.md
// describes them).
#include <prt/prt_technique.h>
#include <prt/prt_version.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "../common/atomic_file.hpp"
#include "prt/baker/context.hpp"
#include "prt/format/scene_writer.hpp"
#include "scene_bake_detail.hpp"

namespace prt::bake::pipeline {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// Why a candidate was or was not chosen.
std::string verdict(const Candidate& c, bool chosen) {
  if (chosen) return "chosen";
  if (!c.failure.empty()) return "failed";
  if (!c.meets) return "over the budget";
  return "meets the budget in more bytes";
}

ordered_json candidate_json(const Candidate& c, bool chosen) {
  ordered_json j;
  j["technique"] = c.technique;
  j["settings"] = c.args;
  j["verdict"] = verdict(c, chosen);
  if (!c.failure.empty()) {
    j["failure"] = c.failure;
    return j;
  }
  j["error"] = c.error;
  j["ref_noise"] = c.ref_noise;
  j["meets_budget"] = c.meets;
  j["bytes"] = c.bytes;
  j["bake_seconds"] = c.bake_seconds;
  j["from_cache"] = c.from_cache;
  return j;
}

ordered_json object_json(const ObjectResult& r) {
  ordered_json j;
  j["name"] = r.object->name;
  j["node"] = r.object->node;
  j["vertices"] = r.object->scene.vertex_count();
  if (r.object->skipped) {
    j["skipped"] = true;
    return j;
  }
  j["problems"] = r.problems;
  j["fits"] = r.fits;
  if (const Candidate* c = r.choice()) {
    j["technique"] = c->technique;
    j["settings"] = c->args;
    j["error"] = c->error;
    j["meets_budget"] = c->meets;
    j["bytes"] = c->bytes;
    j["bake_seconds"] = c->bake_seconds;
    j["from_cache"] = c->from_cache;
    j["blob"] = r.blob_file;
    j["reason"] = r.reason;
    j["hash"] = r.hash;
  }
  ordered_json candidates = ordered_json::array();
  for (std::size_t i = 0; i < r.candidates.size(); ++i)
    candidates.push_back(candidate_json(r.candidates[i], int(i) == r.chosen));
  j["candidates"] = candidates;
  return j;
}

void write_json(const std::string& path, const ordered_json& j) {
  write_file_atomic(path, j.dump(2) + "\n");
}

// The tag of the section a technique's blobs hold, from the runtime's table (the baker names
// techniques as the runtime does).
std::uint32_t technique_section_tag(const std::string& technique) {
  for (int t = 1; t < 32; ++t) {
    prt_technique_info info;
    std::memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    if (prt_technique_get_info(static_cast<prt_technique>(t), &info) == PRT_OK && info.name &&
        technique == info.name)
      return info.section_tag;
  }
  throw Error("scene manifest: the runtime has no technique '" + technique + "'");
}

// OUT/scene.prts (formats/SPEC.md §7.6): the objects of scene.json, in the same order.
std::vector<std::uint8_t> binary_manifest(const SceneBakeSettings& settings,
                                          const std::vector<ObjectResult>& results,
                                          const std::string& path) {
  std::vector<prt::format::SceneManifestObject> objects;
  for (const ObjectResult& r : results) {
    const Candidate* c = r.choice();
    if (!c) continue;
    prt::format::SceneManifestObject o;
    o.technique_tag = technique_section_tag(c->technique);
    o.name = r.object->name;
    o.blob = r.blob_file;
    const int node = r.object->node;
    if (node >= 0) {
      o.node = static_cast<std::uint32_t>(node);
      // Where the blob was baked: the node's world matrix at rest, column-major as glm stores it.
      const glm::mat4& world = r.object->scene.nodes.at(static_cast<std::size_t>(node)).world;
      std::memcpy(o.rest.data(), glm::value_ptr(world), sizeof(float) * 16);
    }
    objects.push_back(std::move(o));
  }
  prt::format::SceneManifestOptions options;
  options.producer = "prtkit " PRT_VERSION_STRING;
  options.info = "prtkit scene manifest: " + fs::path(settings.scene).filename().string();
  try {
    return prt::format::write_scene_manifest(objects, options);
  } catch (const std::invalid_argument& e) {  // objects are listed as in scene.json
    throw Error(path + ": " + e.what());
  }
}

}  // namespace

void write_manifest(const SceneBakeSettings& settings, const std::vector<ObjectResult>& results) {
  ordered_json j;
  j["format"] = "prtkit-scene";
  j["version"] = 1;
  j["source"] = fs::path(settings.scene).filename().string();
  ordered_json objects = ordered_json::array();
  for (const ObjectResult& r : results) {
    const Candidate* c = r.choice();
    if (!c) continue;
    ordered_json o;
    o["name"] = r.object->name;
    o["node"] = r.object->node;
    o["technique"] = c->technique;
    o["blob"] = r.blob_file;
    objects.push_back(o);
  }
  j["objects"] = objects;
  // The binary manifest is made first: it is the one that can refuse an object (then neither file
  // is written).
  const std::string binary_path = settings.out_dir + "/scene.prts";
  const std::vector<std::uint8_t> binary = binary_manifest(settings, results, binary_path);
  write_json(settings.out_dir + "/scene.json", j);
  write_file_atomic(binary_path, binary);
}

void write_report(const SceneBakeSettings& settings, const std::vector<LightInfo>& lights,
                  const std::vector<ObjectResult>& results,
                  const std::vector<SingleTechnique>& singles, const SceneBakeSummary& summary) {
  ordered_json j;
  j["scene"] = settings.scene;
  j["baker_version"] = PRT_VERSION_STRING;
  j["error_budget"] = settings.error_budget;
  j["bounces"] = settings.bounces;
  j["ref_spp"] = settings.ref_spp;
  j["probe_vertices"] = settings.probe_vertices;
  j["seed"] = settings.seed;
  ordered_json light_list = ordered_json::array();
  for (const LightInfo& light : lights)
    light_list.push_back({{"name", light.name}, {"hash", light.hash}});
  j["lights"] = light_list;
  j["summary"] = {{"objects", summary.objects},         {"baked", summary.baked},
                  {"from_cache", summary.from_cache},   {"broken", summary.broken},
                  {"over_budget", summary.over_budget}, {"bytes", summary.bytes}};
  if (settings.compare_single) {
    j["summary"]["single_technique_bytes"] = summary.single_bytes;
    ordered_json single_list = ordered_json::array();
    for (const SingleTechnique& single : singles) {
      ordered_json others = ordered_json::array();
      for (std::size_t g = 1; g < single.settings.size(); ++g)
        others.push_back(
            {{"technique", single.settings[g].first}, {"settings", single.settings[g].second}});
      ordered_json objects = ordered_json::object();
      for (const auto& [object, technique] : single.objects) objects[object] = technique;
      single_list.push_back({{"technique", single.technique},
                             {"settings", single.args},
                             {"others", others},
                             {"objects", objects},
                             {"bytes", single.bytes},
                             {"meets_budget", single.meets}});
    }
    j["single_technique"] = single_list;
  }
  ordered_json objects = ordered_json::array();
  for (const ObjectResult& r : results) objects.push_back(object_json(r));
  j["objects"] = objects;
  write_json(settings.out_dir + "/report.json", j);
}

}  // namespace prt::bake::pipeline
