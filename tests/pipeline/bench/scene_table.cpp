// SPDX-License-Identifier: MIT
// prt_scene_table: the measured table of docs/pipeline.md for the mixed scene
// (tests/support/mixed_scene.hpp with the shared asset characters/RiggedFigure.glb, lit by
// envmaps/grace_cross.hdr):
//   1. per budget E (5, 2, 1 %): the technique, error and bytes chosen per object, the total,
//      the one-technique baseline's bytes, and the bake's wall time from an empty cache;
//   2. at E = 5 %: the scene spread over 1, 2 and 4 shards (prt-bake scene --shard), each
//      shard's wall time from an empty cache, then the run that writes the outputs from the
//      cache, and whether its outputs are the one-machine bake's bytes.
// Shards run one after another here: a farm's wall time is the slowest shard's plus the last
// run's. Printed as Markdown, never asserted. Usage: prt_scene_table [OUT_DIR] (default: a
// folder under the system temp folder, removed at the end).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "prt/baker/scene_bake.hpp"
#include "support/mixed_scene.hpp"
#include "support/test_files.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using prt::bake::Context;
using prt::bake::run_scene_bake;
using prt::bake::Scene;
using prt::bake::SceneBakeSettings;
using prt::bake::SceneBakeSummary;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

json read_json(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Whether every blob and scene.json of `a` has the bytes of `b`'s.
bool same_outputs(const std::string& a, const std::string& b) {
  for (const auto& entry : fs::directory_iterator(a)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() || name == "report.json") continue;
    if (read_file(entry.path().string()) != read_file(b + "/" + name)) return false;
  }
  return true;
}

// Each one-technique baseline's bytes. Where its hardest object misses E even at the ladder's
// top, that top is what it bakes, marked "(over)": the bytes a pipeline without a choice per
// object would spend for the least error it can reach.
std::string baselines(const json& report) {
  std::string text;
  for (const json& single : report["single_technique"]) {
    text += (text.empty() ? "" : "; ") + single["technique"].get<std::string>() + " " +
            std::to_string(single["bytes"].get<std::size_t>()) +
            (single["meets_budget"].get<bool>() ? "" : " (over)");
  }
  return text.empty() ? "none" : text;
}

void budget_table(const Scene& scene, const std::string& light, const std::string& dir,
                  const Context& ctx) {
  std::printf(
      "| E | objects: technique, error, bytes | bytes | one technique per kind | wall s |\n");
  std::printf("| --- | --- | ---: | ---: | ---: |\n");
  for (const double percent : {5.0, 2.0, 1.0}) {
    const std::string out = dir + "/budget-" + std::to_string(int(percent));
    SceneBakeSettings s = prt_test::mixed_scene_settings(out, percent / 100.0, light);
    s.compare_single = true;
    const auto start = std::chrono::steady_clock::now();
    const SceneBakeSummary summary = run_scene_bake(s, scene, ctx);
    const double wall = seconds_since(start);
    std::string objects;
    const json report = read_json(out + "/report.json");
    for (const json& o : report["objects"]) {
      char figures[96];
      std::snprintf(figures, sizeof figures, ", %.2f %%, %zu B%s", 100 * o["error"].get<double>(),
                    o["bytes"].get<std::size_t>(), o["meets_budget"].get<bool>() ? "" : " (over)");
      objects += (objects.empty() ? "" : "; ") + o["name"].get<std::string>() + ": " +
                 o["technique"].get<std::string>() + figures;
    }
    std::printf("| %.0f %% | %s | %zu | %s | %.0f |\n", percent, objects.c_str(), summary.bytes,
                baselines(report).c_str(), wall);
    std::fflush(stdout);
  }
}

void shard_table(const Scene& scene, const std::string& light, const std::string& dir,
                 const Context& ctx) {
  const std::string whole = dir + "/budget-5";
  std::printf(
      "\n| shards | slowest shard s | all shards s | last run s | outputs as one machine's |\n");
  std::printf("| ---: | ---: | ---: | ---: | --- |\n");
  for (const std::size_t count : {1u, 2u, 4u}) {
    const std::string out = dir + "/shards-" + std::to_string(count);
    SceneBakeSettings s = prt_test::mixed_scene_settings(out, 0.05, light);
    double slowest = 0.0, total = 0.0;
    if (count > 1) {
      s.shard_count = count;
      for (std::size_t i = 0; i < count; ++i) {
        s.shard_index = i;
        const auto start = std::chrono::steady_clock::now();
        run_scene_bake(s, scene, ctx);
        const double wall = seconds_since(start);
        slowest = std::max(slowest, wall);
        total += wall;
      }
      s.shard_index = 0;
      s.shard_count = 1;
    }
    const auto start = std::chrono::steady_clock::now();
    run_scene_bake(s, scene, ctx);
    const double last = seconds_since(start);
    std::printf("| %zu | %.1f | %.1f | %.1f | %s |\n", count, slowest, total, last,
                same_outputs(out, whole) ? "yes" : "NO");
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string character = prt_test::shared_asset("characters/RiggedFigure.glb");
  const std::string light = prt_test::shared_asset("envmaps/grace_cross.hdr");
  if (character.empty() || light.empty()) {
    std::fprintf(stderr,
                 "prt_scene_table: the shared assets characters/RiggedFigure.glb and "
                 "envmaps/grace_cross.hdr are needed\n");
    return 1;
  }
  std::unique_ptr<prt_test::TempDir> temp;
  std::string dir;
  if (argc > 1) {
    dir = argv[1];
    fs::create_directories(dir);
  } else {
    temp = std::make_unique<prt_test::TempDir>("scene_table");
    dir = temp->dir();
  }
  Context ctx;
  ctx.log = [](prt::bake::LogLevel level, const std::string& text) {
    if (level >= prt::bake::LogLevel::Warning) std::fprintf(stderr, "%s\n", text.c_str());
  };
  std::printf(
      "mixed scene with RiggedFigure, lit by grace_cross.hdr, no bounce, 96 probe vertices at 512 "
      "spp, %u threads\n\n",
      ctx.thread_count());
  const Scene scene = prt_test::mixed_scene(prt::bake::import_scene(character, ctx));
  budget_table(scene, light, dir, ctx);
  shard_table(scene, light, dir, ctx);
  return 0;
}
