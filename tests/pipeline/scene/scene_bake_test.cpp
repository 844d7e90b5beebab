// SPDX-License-Identifier: MIT
// prt-bake scene through its library entry (prt/baker/scene_bake.hpp): a technique per object
// that meets the budget against an independent reference, the content-hash cache, overrides,
// broken objects, and outputs written whole.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <prt/prt.hpp>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/scene_bake.hpp"
#include "prt/baker/technique.hpp"
#include "prt/io/radiance_error.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Material diffuse(const char* name, glm::vec3 colour) {
  Material m;
  m.name = name;
  m.base_color = glm::vec4(colour, 1.0f);
  return m;
}

// A small static scene: a ground tile with a sphere and a box on it, each its own node.
Scene small_scene(glm::vec3 box_colour = {0.3f, 0.7f, 0.3f}) {
  Scene scene;
  scene.materials = {diffuse("ground", {0.6f, 0.6f, 0.6f}), diffuse("sphere", {0.8f, 0.3f, 0.2f}),
                     diffuse("box", box_colour)};
  scene.meshes.push_back(make_plane_mesh("ground", 0, 1.0f, 1.0f, 12, 12));
  scene.meshes.push_back(make_sphere_mesh(1, {-0.4f, 0.3f, 0.0f}, 0.3f, 10, 20));
  scene.meshes.push_back(make_box_mesh(2, {0.4f, 0.2f, 0.1f}, 0.2f, 0.4f, 3));
  return scene;
}

Context quiet() {
  Context ctx;
  ctx.threads = 2;
  return ctx;
}

SceneBakeSettings settings_for(const std::string& scene, const std::string& out) {
  SceneBakeSettings s;
  s.scene = scene;
  s.out_dir = out;
  s.error_budget = 0.05;
  s.bounces = 0;
  s.ref_spp = 512;
  s.probe_vertices = 96;
  return s;
}

json read_json(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

const json& object_named(const json& report, const std::string& name) {
  for (const json& o : report["objects"]) {
    if (o["name"] == name) return o;
  }
  throw std::runtime_error("no object " + name);
}

class SceneBake : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new prt_test::TempDir("scene_bake");
    write_glb(small_scene(), dir_->file("small.glb"));
    SceneBakeSettings s = settings_for(dir_->file("small.glb"), dir_->file("out"));
    s.compare_single = true;
    summary_ = run_scene_bake(s, quiet());
  }
  static void TearDownTestSuite() { delete dir_; }
  static prt_test::TempDir* dir_;
  static SceneBakeSummary summary_;
};
prt_test::TempDir* SceneBake::dir_ = nullptr;
SceneBakeSummary SceneBake::summary_;

TEST_F(SceneBake, BakesEveryObjectWithinTheBudget) {
  EXPECT_EQ(summary_.objects, 3u);
  EXPECT_EQ(summary_.baked, 3u);
  EXPECT_EQ(summary_.broken, 0u);
  EXPECT_EQ(summary_.over_budget, 0u);
  const json report = read_json(dir_->file("out/report.json"));
  std::size_t bytes = 0;
  for (const json& o : report["objects"]) {
    EXPECT_TRUE(o["meets_budget"].get<bool>()) << o["name"];
    EXPECT_LE(o["error"].get<double>(), 0.05) << o["name"];
    EXPECT_EQ(fs::file_size(dir_->file("out/" + o["blob"].get<std::string>())),
              o["bytes"].get<std::size_t>());
    bytes += o["bytes"].get<std::size_t>();
  }
  EXPECT_EQ(report["summary"]["bytes"].get<std::size_t>(), bytes);
}

// What the choice per object saves: every object baked with one technique at the settings its
// hardest object needs takes more bytes, and the report gives both figures.
TEST_F(SceneBake, ChoosingPerObjectTakesFewerBytesThanOneTechniqueForAll) {
  ASSERT_GT(summary_.single_bytes, 0u);
  EXPECT_LT(summary_.bytes, summary_.single_bytes);
  const json report = read_json(dir_->file("out/report.json"));
  EXPECT_EQ(report["summary"]["single_technique_bytes"].get<std::size_t>(), summary_.single_bytes);
  ASSERT_EQ(report["single_technique"].size(), 2u);  // sh and wavelet suit every object
  std::size_t smallest = SIZE_MAX;
  for (const json& single : report["single_technique"]) {
    EXPECT_GE(single["bytes"].get<std::size_t>(), summary_.bytes) << single["technique"];
    if (single["meets_budget"].get<bool>())
      smallest = std::min(smallest, single["bytes"].get<std::size_t>());
  }
  EXPECT_EQ(smallest, summary_.single_bytes);
}

// The whole scene's vertices (Scene order) that node `node`'s meshes hold, in their order.
std::vector<std::size_t> vertices_of(const Scene& scene, int node) {
  std::vector<std::size_t> vertices;
  std::size_t first = 0;
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.node == node) {
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) vertices.push_back(first + v);
    }
    first += mesh.vertex_count();
  }
  return vertices;
}

// The pipeline measures a subset of vertices against its own reference; here every vertex of
// each chosen blob is measured against a reference of the whole scene (the objects shadow one
// another) of another seed at twice the samples.
TEST_F(SceneBake, ChosenBlobsMeetTheBudgetOnEveryVertexAgainstAnIndependentReference) {
  const Context ctx = quiet();
  const Scene scene = import_scene(dir_->file("small.glb"), ctx);
  const std::vector<SceneObject> objects = scene_objects(scene);
  const json report = read_json(dir_->file("out/report.json"));
  const io::EnvMap sky = make_demo_sky();
  for (const SceneObject& object : objects) {
    const json& o = object_named(report, object.name);
    const Technique* technique = find_technique(o["technique"].get<std::string>());
    ASSERT_NE(technique, nullptr);
    const std::string blob_text =
        prt_test::read_bytes(dir_->file("out/" + o["blob"].get<std::string>()));
    const std::vector<std::uint8_t> blob(blob_text.begin(), blob_text.end());
    const std::vector<glm::vec3> shaded = technique->shade(blob, sky, ctx);
    // The whole scene, at the object's vertices: the other objects shadow it (no bounce here,
    // so nothing else of theirs reaches it).
    ReferenceSettings rs;
    rs.spp = 1024;
    rs.seed = 7;
    const ReferenceRenderer renderer(scene, sky, rs, ctx);
    const VertexRadiance ref = renderer.render_vertices(vertices_of(scene, object.node), ctx);
    const double measured = io::relative_rmse(shaded, ref.radiance);
    const double error =
        std::sqrt(std::max(0.0, measured * measured - ref.relative_rmse * ref.relative_rmse));
    // The pipeline's figure comes from 96 vertices at 512 samples: the two figures differ by up
    // to 6 % of themselves on this scene, so the budget is held to 10 % over and the figures to
    // 15 % of each other.
    const double pipeline = o["error"].get<double>();
    std::printf("%s: every vertex %.4f, the pipeline's vertices %.4f\n", object.name.c_str(), error,
                pipeline);
    EXPECT_LE(error, 0.05 * 1.1) << object.name;
    EXPECT_NEAR(error, pipeline, 0.15 * pipeline) << object.name;
  }
}

// The runtime loads the baked scene in one call (OUT/scene.prts and the blobs it names) and
// shades every object in one call per frame; each object's radiance meets the budget on every
// vertex against the whole scene's reference, as its blob shaded alone does.
TEST_F(SceneBake, TheRuntimeLoadsAndShadesTheSceneInOneCallEachWithinTheBudget) {
  const Context ctx = quiet();
  const Scene scene = import_scene(dir_->file("small.glb"), ctx);
  const json report = read_json(dir_->file("out/report.json"));
  const prt::ContextPtr runtime = prt::create_context().handle;
  ASSERT_NE(runtime, nullptr);
  const auto [owned, loaded_result] =
      prt::load_scene_file(runtime.get(), dir_->file("out/scene.prts").c_str());
  ASSERT_EQ(loaded_result, PRT_OK) << prt_context_last_message(runtime.get());
  prt_scene* loaded = owned.get();
  ASSERT_EQ(prt_scene_object_count(loaded), report["objects"].size());
  const io::EnvMap sky = make_demo_sky();
  ASSERT_EQ(sky.mapping(), io::EnvMapping::LatLong);
  const prt_env_image env = prt::latlong_env(sky.width(), sky.height(), sky.pixels().data());
  ASSERT_EQ(prt_scene_set_environment(loaded, &env), PRT_OK);
  prt_scene_frame frame = prt::sized<prt_scene_frame>();
  frame.backend = PRT_BACKEND_AUTO;
  ASSERT_EQ(prt_scene_shade(loaded, &frame), PRT_OK) << prt_context_last_message(runtime.get());
  for (std::uint32_t i = 0; i < prt_scene_object_count(loaded); ++i) {
    prt_scene_object_info info = prt::sized<prt_scene_object_info>();
    ASSERT_EQ(prt_scene_get_object(loaded, i, &info), PRT_OK);
    const json& o = object_named(report, info.name);
    prt_technique_info technique = prt::sized<prt_technique_info>();
    ASSERT_EQ(prt_technique_get_info(info.technique, &technique), PRT_OK);
    EXPECT_EQ(technique.name, o["technique"].get<std::string>()) << info.name;
    EXPECT_EQ(info.blob, o["blob"].get<std::string>());
    EXPECT_EQ(int(info.node), o["node"].get<int>());
    const glm::mat4& rest = scene.nodes[std::size_t(info.node)].world;
    for (int k = 0; k < 16; ++k) EXPECT_EQ(info.rest_transform[k], rest[k / 4][k % 4]) << k;
    const float* rgb = prt_scene_object_radiance(loaded, i);
    ASSERT_NE(rgb, nullptr);
    std::vector<glm::vec3> shaded(info.vertex_count);
    for (std::uint32_t v = 0; v < info.vertex_count; ++v)
      shaded[v] = {rgb[3 * v], rgb[3 * v + 1], rgb[3 * v + 2]};
    ReferenceSettings rs;
    rs.spp = 1024;
    rs.seed = 11;
    const ReferenceRenderer renderer(scene, sky, rs, ctx);
    const VertexRadiance ref = renderer.render_vertices(vertices_of(scene, int(info.node)), ctx);
    const double measured = io::relative_rmse(shaded, ref.radiance);
    const double error =
        std::sqrt(std::max(0.0, measured * measured - ref.relative_rmse * ref.relative_rmse));
    // As in the test above: the budget held to 10 % over for the pipeline's probe sampling.
    EXPECT_LE(error, 0.05 * 1.1) << info.name;
  }
}

TEST_F(SceneBake, TheReportSaysWhyAndListsTheRejectedCandidates) {
  const json report = read_json(dir_->file("out/report.json"));
  for (const json& o : report["objects"]) {
    EXPECT_FALSE(o["reason"].get<std::string>().empty());
    int chosen = 0;
    for (const json& c : o["candidates"]) {
      const std::string verdict = c["verdict"];
      chosen += verdict == "chosen";
      if (verdict == "over the budget") {
        EXPECT_GT(c["error"].get<double>(), 0.05);
      }
      if (verdict == "meets the budget in more bytes") {
        EXPECT_GE(c["bytes"].get<std::size_t>(), o["bytes"].get<std::size_t>());
      }
    }
    EXPECT_EQ(chosen, 1) << o["name"];
    // Both static techniques were asked; the others say why they do not suit.
    EXPECT_EQ(o["fits"].size(), techniques().size());
  }
  const json manifest = read_json(dir_->file("out/scene.json"));
  EXPECT_EQ(manifest["format"], "prtkit-scene");
  EXPECT_EQ(manifest["objects"].size(), 3u);
}

TEST_F(SceneBake, NoTemporaryFileIsLeft) {
  for (const auto& entry : fs::recursive_directory_iterator(dir_->file("out"))) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

// A second run finds every candidate in the cache; a changed material re-bakes that object only,
// and the result is the bytes of a clean bake of the changed scene.
TEST_F(SceneBake, ReRunsBakeOnlyWhatChangedAndMatchAFreshBake) {
  const std::string out = dir_->file("again");
  fs::copy(dir_->file("out"), out, fs::copy_options::recursive);
  const SceneBakeSummary same = run_scene_bake(settings_for(dir_->file("small.glb"), out), quiet());
  EXPECT_EQ(same.from_cache, 3u);

  write_glb(small_scene({0.2f, 0.2f, 0.9f}), dir_->file("changed.glb"));
  const SceneBakeSummary changed =
      run_scene_bake(settings_for(dir_->file("changed.glb"), out), quiet());
  EXPECT_EQ(changed.baked, 3u);
  EXPECT_EQ(changed.from_cache, 2u);
  const json report = read_json(out + "/report.json");
  EXPECT_FALSE(object_named(report, "box")["from_cache"].get<bool>());

  const std::string clean = dir_->file("clean");
  run_scene_bake(settings_for(dir_->file("changed.glb"), clean), quiet());
  for (const char* file : {"ground.prtk", "sphere.prtk", "box.prtk", "scene.json"}) {
    EXPECT_EQ(prt_test::read_bytes(out + "/" + file), prt_test::read_bytes(clean + "/" + file))
        << file;
  }
  EXPECT_NE(prt_test::read_bytes(out + "/box.prtk"),
            prt_test::read_bytes(dir_->file("out/box.prtk")));
}

// --shard i/N: each shard bakes its objects into the shared cache and writes nothing else; the
// run without it then bakes nothing anew and writes the bytes of a whole bake.
TEST_F(SceneBake, ShardsFillTheCacheAndTheWholeRunWritesTheSameBytes) {
  const std::string out = dir_->file("sharded");
  SceneBakeSettings s = settings_for(dir_->file("small.glb"), out);
  s.shard_count = 2;
  const SceneBakeSummary first = run_scene_bake(s, quiet());
  EXPECT_EQ(first.objects, 2u);  // objects 0 and 2: the ground and the box
  EXPECT_EQ(first.baked, 2u);
  EXPECT_EQ(first.from_cache, 0u);
  EXPECT_FALSE(fs::exists(out + "/scene.json"));
  EXPECT_FALSE(fs::exists(out + "/ground.prtk"));
  s.shard_index = 1;
  EXPECT_EQ(run_scene_bake(s, quiet()).baked, 1u);

  s.shard_index = 0;
  s.shard_count = 1;
  const SceneBakeSummary whole = run_scene_bake(s, quiet());
  EXPECT_EQ(whole.baked, 3u);
  EXPECT_EQ(whole.from_cache, 3u);
  for (const char* file : {"ground.prtk", "sphere.prtk", "box.prtk", "scene.json"}) {
    EXPECT_EQ(prt_test::read_bytes(out + "/" + file),
              prt_test::read_bytes(dir_->file("out/") + file))
        << file;
  }
  s.shard_index = 2;
  s.shard_count = 2;
  EXPECT_THROW(run_scene_bake(s, quiet()), Error);
}

TEST_F(SceneBake, AnOverrideForcesTheTechniqueAndSettings) {
  SceneBakeSettings s = settings_for(dir_->file("small.glb"), dir_->file("forced"));
  s.cache_dir = dir_->file("out/.cache");
  s.overrides = {"sphere=wavelet:--keep,64,--cube,16,--bounces,0"};
  run_scene_bake(s, quiet());
  const json sphere = object_named(read_json(dir_->file("forced/report.json")), "sphere");
  EXPECT_EQ(sphere["technique"], "wavelet");
  EXPECT_EQ(sphere["candidates"].size(), 1u);
  EXPECT_EQ(sphere["settings"], json({"--keep", "64", "--cube", "16", "--bounces", "0"}));
  EXPECT_NE(sphere["reason"].get<std::string>().find("forced"), std::string::npos);
}

TEST_F(SceneBake, AnOverrideNamingNoTechniqueBreaksThatObjectOnly) {
  SceneBakeSettings s = settings_for(dir_->file("small.glb"), dir_->file("unknown"));
  s.cache_dir = dir_->file("out/.cache");
  s.overrides = {"box=haar"};
  const SceneBakeSummary summary = run_scene_bake(s, quiet());
  EXPECT_EQ(summary.broken, 1u);
  EXPECT_EQ(summary.baked, 2u);
  const json box = object_named(read_json(dir_->file("unknown/report.json")), "box");
  EXPECT_NE(box["problems"][0].get<std::string>().find("haar"), std::string::npos);
}

// A budget nothing meets: each object keeps the fewest bytes within 5 % of the smallest error
// its candidates reached, and says it is over budget.
TEST_F(SceneBake, OverBudgetObjectsKeepTheFewestBytesNearTheSmallestError) {
  SceneBakeSettings s = settings_for(dir_->file("small.glb"), dir_->file("tight"));
  s.cache_dir = dir_->file("out/.cache");
  s.error_budget = 1e-4;
  s.overrides = {"ground=sh", "sphere=sh", "box=sh"};
  const SceneBakeSummary summary = run_scene_bake(s, quiet());
  // No object meets so small a budget: the ground too, since the sphere and the box shadow it.
  EXPECT_EQ(summary.over_budget, 3u);
  const json report = read_json(dir_->file("tight/report.json"));  // outlives the loop
  for (const json& o : report["objects"]) {
    if (o["meets_budget"].get<bool>()) continue;
    double smallest = HUGE_VAL;
    for (const json& c : o["candidates"]) smallest = std::min(smallest, c["error"].get<double>());
    EXPECT_LE(o["error"].get<double>(), 1.05 * smallest) << o["name"];
    for (const json& c : o["candidates"]) {
      if (c["error"].get<double>() <= 1.05 * smallest) {
        EXPECT_GE(c["bytes"].get<std::size_t>(), o["bytes"].get<std::size_t>()) << o["name"];
      }
    }
    EXPECT_EQ(fs::file_size(dir_->file("tight/" + o["blob"].get<std::string>())),
              o["bytes"].get<std::size_t>());
  }
}

TEST(SceneObjects, BrokenMeshesAreListedWithTheirReason) {
  Scene scene = small_scene();
  Mesh flat = make_plane_mesh("flat", 0, 1.0f, 1.0f, 2, 2);
  for (std::uint32_t& index : flat.indices) index = 0;
  scene.meshes.push_back(flat);
  prt_test::TempDir dir("scene_objects_broken");
  write_glb(scene, dir.file("broken.glb"));
  Scene imported = import_scene(dir.file("broken.glb"), quiet());
  // A node whose transform went bad after the import checks: its positions are not finite.
  Mesh lost = make_plane_mesh("lost", 0, 1.0f, 1.0f, 2, 2);
  lost.positions[1].x = std::nanf("");
  lost.node = int(imported.nodes.size());
  imported.nodes.push_back(Node{});
  imported.nodes.back().name = "lost";
  imported.nodes.back().mesh = 99;
  imported.meshes.push_back(lost);

  const std::vector<SceneObject> objects = scene_objects(imported);
  ASSERT_EQ(objects.size(), 5u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_TRUE(objects[i].problems.empty()) << i;
  EXPECT_EQ(objects[3].name, "flat");
  ASSERT_EQ(objects[3].problems.size(), 1u);
  EXPECT_NE(objects[3].problems[0].find("degenerate"), std::string::npos);
  EXPECT_EQ(objects[4].name, "lost");
  ASSERT_FALSE(objects[4].problems.empty());
  EXPECT_NE(objects[4].problems[0].find("non-finite"), std::string::npos);
}

}  // namespace
}  // namespace prt::bake
