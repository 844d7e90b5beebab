// SPDX-License-Identifier: MIT
// The steps every technique's bake and trade run in the same order (prt/baker/technique.hpp).
#include "prt/baker/technique.hpp"

#include "atomic_file.hpp"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace prt::bake {
namespace {

namespace fs = std::filesystem;

// The map names a trade's tables and reference cache use: each file's stem, once.
void check_map_names(const std::vector<std::string>& envs) {
  std::set<std::string> names;
  for (const std::string& path : envs) {
    const std::string name = fs::path(path).stem().string();
    if (!names.insert(name).second) throw Error("--env: two maps are named '" + name + "'");
  }
}

// A mesh whose every triangle is degenerate casts no shadow and has no surface to draw, yet its
// vertices bake as if nothing were there: almost always a broken export (a zero scale, a wrong
// index buffer). It is a warning, not an error, because the blob is still valid and what it
// stores is exact for what the file describes; a pipeline baking many assets keeps going.
void warn_about_degenerate_meshes(const Scene& scene, const std::string& file, const Context& ctx) {
  const std::string what =
      "degenerate (a repeated or out-of-range index, a non-finite position or zero area)";
  std::size_t triangles = 0, degenerate = 0;
  std::vector<std::string> meshes;  // the meshes whose every triangle is degenerate
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    std::size_t bad = 0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) bad += is_degenerate_triangle(mesh, t);
    if (bad > 0 && bad == mesh.triangle_count())
      meshes.push_back("mesh " + std::to_string(m) + " ('" + mesh.name + "')");
    triangles += mesh.triangle_count();
    degenerate += bad;
  }
  if (triangles > 0 && degenerate == triangles) {
    ctx.warn(file + ": every triangle is " + what +
             ": nothing casts shadows and there is nothing to draw");
    return;
  }
  for (const std::string& mesh : meshes) {
    ctx.warn(file + ": every triangle of " + mesh + " is " + what +
             ": it casts no shadow and has nothing to draw");
  }
}

}  // namespace

OptionSpec& OptionSpec::choices(std::initializer_list<long long> values) {
  accepted.clear();
  for (long long v : values) accepted.push_back(std::to_string(v));
  return *this;
}

glm::vec3 parse_albedo(const std::string& text) {
  glm::vec3 rgb;
  char comma1 = 0, comma2 = 0, rest = 0;
  std::istringstream in(text);
  if (!(in >> rgb.r >> comma1 >> rgb.g >> comma2 >> rgb.b) || comma1 != ',' || comma2 != ',' ||
      (in >> rest)) {
    throw Error("--albedo: expected r,g,b (e.g. 0.8,0.8,0.8), got '" + text + "'");
  }
  return rgb;
}

Scene import_bake_scene(const BakeInput& input, const Context& ctx) {
  if (!input.albedo.empty()) parse_albedo(input.albedo);  // a typo fails before the import
  Scene scene = import_scene(input.scene, ctx);
  warn_about_degenerate_meshes(scene, input.scene, ctx);
  return scene;
}

void run_bake(TechniqueBake& bake, const BakeInput& input, const Context& ctx) {
  const Scene scene = import_bake_scene(input, ctx);
  bake.bake(scene, input, ctx);
  finish_bake(bake, scene, input, ctx);
}

void finish_bake(TechniqueBake& bake, const Scene& scene, const BakeInput& input,
                 const Context& ctx) {
  bake.quantize();
  const std::vector<std::uint8_t> blob = bake.write(scene, input);
  write_file_atomic(input.output, blob);
  ctx.info(bake.summary(scene, input, blob.size()));

  const SelfCheck check = bake.self_check(blob);
  if (!input.report.empty()) {
    BakeFacts facts;
    facts.vertices = scene.vertex_count();
    facts.triangles = scene.triangle_count();
    facts.threads = ctx.thread_count();
    facts.blob_bytes = blob.size();
    bake.write_report(input.report, input, facts);
    ctx.info("wrote " + input.report);
  }
  if (!check.passed) throw Error("self-check of " + input.output + ": " + check.message);
  ctx.info("self-check passed: " + check.message);
}

std::size_t TechniqueBake::shard_units(const Scene&) const {
  return 0;
}

std::vector<std::uint8_t> TechniqueBake::bake_shard(const Scene&, const BakeInput&, std::size_t,
                                                    std::size_t, const Context&) {
  throw Error("this technique's bake does not split into shards");
}

void TechniqueBake::merge_shards(const Scene&, const BakeInput&,
                                 const std::vector<std::vector<std::uint8_t>>&, const Context&) {
  throw Error("this technique's bake does not split into shards");
}

ObjectFit Technique::fit(const Scene&, int) const {
  return {false, std::string("technique ") + name() + " does not bake objects of a scene yet"};
}

std::vector<Rung> Technique::ladder(int) const {
  return {};
}

std::vector<glm::vec3> Technique::shade(const std::vector<std::uint8_t>&, const io::EnvMap&,
                                        const Context&) const {
  throw Error(std::string("technique ") + name() + " cannot be measured in a scene bake yet");
}

ObjectMeasureFactory Technique::measure() const {
  return &make_diffuse_measure;
}

Scene TechniqueTrade::load_scene(const TradeInput& input, const Context& ctx) {
  return import_scene(input.scene, ctx);
}

void run_trade(TechniqueTrade& trade, TradeInput input, const Context& ctx) {
  if (input.envs.empty()) throw Error("give at least one --env MAP");
  check_map_names(input.envs);
  if (input.frames < 1) throw Error("--frames: must be >= 1");
  if (!input.albedo.empty()) parse_albedo(input.albedo);
  trade.check(input);
  if (input.cache_dir.empty()) input.cache_dir = input.out_dir + "/cache";
  fs::create_directories(input.out_dir);
  fs::create_directories(input.cache_dir);

  const Scene scene = trade.load_scene(input, ctx);
  warn_about_degenerate_meshes(scene, input.scene, ctx);
  trade.prepare(scene, input, ctx);
  const EmbreeScene rays(scene, ctx);
  trade.sweep(scene, rays, input, ctx);
  ctx.info("wrote " + input.out_dir + "/trade.csv and trade.md");
}

}  // namespace prt::bake
