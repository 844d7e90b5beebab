// SPDX-License-Identifier: MIT
// Technique `shadowfield` in prt-bake scene (prt/baker/scene_bake.hpp): which nodes it suits, its
// ladder of bake settings, and its measurement (the object above a floor it shadows, at
// placements of its own clip, on the runtime against the path tracer): a finer rung measures
// closer, a blob of the object at the wrong size measures far off, and the pipeline bakes and
// measures it end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/options.hpp"
#include "prt/baker/scene_bake.hpp"
#include "prt/baker/technique.hpp"
#include "support/checked_blob.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

const Technique& shadowfield() {
  const Technique* technique = find_technique("shadowfield");
  if (!technique) throw std::runtime_error("no technique shadowfield");
  return *technique;
}

Context two_threads() {
  Context ctx;
  ctx.threads = 2;
  return ctx;
}

constexpr glm::vec3 kBoxCentre{0.0f, 0.25f, 0.0f};

// A box on its own node; `half` its half side (the scene's is 0.2).
Scene box_object(float half = 0.2f) {
  Scene scene;
  Material m;
  m.name = "box";
  m.base_color = glm::vec4(0.8f, 0.5f, 0.3f, 1.0f);
  scene.materials.push_back(m);
  Mesh mesh = make_box_mesh(0, kBoxCentre, half, 0.3f, 3);
  mesh.node = 0;
  mesh.local_positions = mesh.positions;
  mesh.local_normals = mesh.normals;
  scene.meshes.push_back(std::move(mesh));
  Node node;
  node.name = "box";
  node.mesh = 0;
  scene.nodes.push_back(node);
  return scene;
}

// The box turned about +Y and slid along +X by a clip on its node.
Scene animated_box(float half = 0.2f) {
  Scene scene = box_object(half);
  AnimationChannel turn;
  turn.node = 0;
  turn.path = AnimationChannel::Path::Rotation;
  turn.components = 4;
  turn.times = {0.0f, 1.0f, 2.0f};
  for (const float degrees : {0.0f, 50.0f, 100.0f}) {
    const glm::quat q = glm::angleAxis(glm::radians(degrees), glm::vec3(0, 1, 0));
    turn.values.insert(turn.values.end(), {q.x, q.y, q.z, q.w});
  }
  AnimationChannel slide;
  slide.node = 0;
  slide.path = AnimationChannel::Path::Translation;
  slide.times = {0.0f, 2.0f};
  slide.values = {0.0f, 0.0f, 0.0f, 0.6f, 0.0f, 0.0f};
  Animation clip;
  clip.name = "slide";
  clip.channels = {turn, slide};
  clip.duration = 2.0f;
  scene.animations.push_back(clip);
  scene.nodes[0].animated = true;
  return scene;
}

TEST(ShadowfieldSceneFit, SuitsRigidMovingNodesOnly) {
  Scene scene = box_object();
  EXPECT_FALSE(shadowfield().fit(scene, 0).suits);  // static: sh and wavelet's
  EXPECT_FALSE(shadowfield().fit(scene, 0).reason.empty());
  scene.nodes[0].hints.dynamic = true;
  EXPECT_TRUE(shadowfield().fit(scene, 0).suits);
  EXPECT_TRUE(shadowfield().fit(animated_box(), 0).suits);

  Scene skinned = scene;
  skinned.skins.push_back({"skin", {0}, {glm::mat4(1.0f)}, 0});
  skinned.nodes[0].skin = 0;
  EXPECT_FALSE(shadowfield().fit(skinned, 0).suits);
  EXPECT_NE(shadowfield().fit(skinned, 0).reason.find("skinned"), std::string::npos);

  Scene cloth = scene;
  cloth.materials[0].cloth = true;
  EXPECT_FALSE(shadowfield().fit(cloth, 0).suits);
}

std::string arg_after(const Rung& rung, const std::string& flag) {
  for (std::size_t i = 0; i + 1 < rung.args.size(); ++i)
    if (rung.args[i] == flag) return rung.args[i + 1];
  return "";
}

TEST(ShadowfieldSceneLadder, EveryRungIsABakeSettingAndTheOrderClimbs) {
  for (const int bounces : {0, 1, 3}) {
    const std::vector<Rung> ladder = shadowfield().ladder(bounces);
    ASSERT_GE(ladder.size(), 4u);
    ASSERT_LE(ladder.size(), 8u);
    int previous_order = 0;
    for (const Rung& rung : ladder) {
      std::unique_ptr<TechniqueBake> bake = shadowfield().make_bake();
      EXPECT_NO_THROW(apply_option_args(bake->options(), rung.args));
      const int order = std::stoi(arg_after(rung, "--order"));
      EXPECT_GE(order, previous_order);
      previous_order = order;
      // The runtime reads the source fields only for bounces: without, they are the smallest.
      if (bounces == 0) {
        EXPECT_EQ(arg_after(rung, "--srf-shells"), "1");
      }
    }
    EXPECT_EQ(arg_after(ladder.front(), "--order"), "2");
    EXPECT_EQ(arg_after(ladder.back(), "--order"), "6");
  }
}

// How much farther 16 bits may measure than 8: twice the tenth of a point between them on the
// teapot (docs/shadowfield/trade.md).
constexpr double kBitsSlack = 0.002;

// Every rung of the animated box's ladder and a wrong blob, measured against one reference, in
// one test: ctest runs each test in its own process, and the bakes are most of the file's time.
TEST(ShadowfieldSceneMeasure, ErrorsFallAlongTheLadderAndAWrongBlobMeasuresFarOff) {
  const std::string map = prt_test::shared_asset("envmaps/grace_cross.hdr");
  if (map.empty()) GTEST_SKIP() << "shared asset envmaps/grace_cross.hdr missing";
  const Scene object = animated_box();
  const io::EnvMap grace = io::load_envmap(map, io::EnvMapping::Auto);
  ObjectMeasureInput input;
  input.scene = input.object = &object;
  input.node = 0;
  input.lights = {&grace};
  input.bounces = 1;
  input.ref_spp = 512;
  input.probe_vertices = 96;
  const std::vector<Rung> ladder = shadowfield().ladder(input.bounces);
  const Context ctx = two_threads();
  std::unique_ptr<ObjectMeasure> measure = shadowfield().measure()(input);
  std::vector<Measurement> rungs;
  std::vector<std::size_t> bytes;
  for (const Rung& rung : ladder) {
    const std::vector<std::uint8_t> blob =
        prt_test::checked_blob("shadowfield", rung.args, object, "test object", two_threads());
    rungs.push_back(measure->measure(shadowfield(), blob, ctx));
    bytes.push_back(blob.size());
    std::printf("rung %zu: %zu bytes, error %.4f (reference noise %.4f)\n", rungs.size(),
                blob.size(), rungs.back().error, rungs.back().ref_noise);
  }
  for (std::size_t k = 1; k < rungs.size(); ++k) {
    EXPECT_GT(bytes[k], bytes[k - 1]) << "rung " << k;
    // The last rung only stores the same values in 16 bits: as close, not closer.
    EXPECT_LE(rungs[k].error, rungs[k - 1].error + kBitsSlack) << "rung " << k;
  }
  const Measurement& top = rungs.back();
  EXPECT_LT(top.error, rungs.front().error);
  EXPECT_GT(top.ref_noise, 0.0);
  // docs/shadowfield/trade.md: the floor under the teapot, under the same map, is some 3 % off
  // at the defaults; a diffuse box carries no glossy lobe, so the top rung (the reference's noise
  // taken out) stays within twice that.
  EXPECT_LT(top.error, 0.06);

  // The same box at half its size, same vertices: its own shading is alike (flat faces), the
  // shadow it casts on the floor is not.
  const Measurement wrong =
      measure->measure(shadowfield(),
                       prt_test::checked_blob("shadowfield", ladder.back().args, animated_box(0.1f),
                                              "test object", two_threads()),
                       ctx);
  std::printf("wrong size: error %.4f\n", wrong.error);
  EXPECT_GT(wrong.error, 4.0 * top.error);
}

TEST(ShadowfieldSceneMeasureInput, ABlobOfAnotherObjectIsRefused) {
  const Scene object = animated_box();
  const io::EnvMap sky = make_demo_sky();
  ObjectMeasureInput input;
  input.scene = input.object = &object;
  input.node = 0;
  input.lights = {&sky};
  input.bounces = 0;
  input.ref_spp = 16;
  input.probe_vertices = 8;
  Scene other = object;
  other.meshes[0] = make_box_mesh(0, kBoxCentre, 0.2f, 0.0f, 2);
  const std::vector<Rung> ladder = shadowfield().ladder(0);
  std::unique_ptr<ObjectMeasure> measure = shadowfield().measure()(input);
  EXPECT_THROW(measure->measure(shadowfield(),
                                prt_test::checked_blob("shadowfield", ladder.front().args, other,
                                                       "test object", two_threads()),
                                two_threads()),
               Error);
}

// The pipeline end to end. write_glb writes static nodes only (no extras.prt.dynamic, no
// clips), so the technique is forced on the box by an override: its measurement then takes the
// fixed placements of an object that only says it moves.
TEST(ShadowfieldSceneBake, ForcedOnAnObjectItBakesAndMeasures) {
  prt_test::TempDir dir("shadowfield_scene_bake");
  write_glb(box_object(), dir.file("box.glb"));
  SceneBakeSettings s;
  s.scene = dir.file("box.glb");
  s.out_dir = dir.file("out");
  s.error_budget = 0.5;
  s.bounces = 0;
  s.ref_spp = 128;
  s.probe_vertices = 48;
  std::string forced = "box=shadowfield:";
  const std::vector<std::string> args = shadowfield().ladder(0).front().args;
  for (std::size_t i = 0; i < args.size(); ++i) forced += (i ? "," : "") + args[i];
  s.overrides = {forced};
  const SceneBakeSummary summary = run_scene_bake(s, two_threads());
  EXPECT_EQ(summary.objects, 1u);
  EXPECT_EQ(summary.baked, 1u);
  EXPECT_EQ(summary.broken, 0u);
  std::ifstream in(dir.file("out/report.json"));
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& box = report["objects"][0];
  EXPECT_EQ(box["technique"], "shadowfield");
  const double error = box["error"].get<double>();
  EXPECT_TRUE(std::isfinite(error));
  EXPECT_GT(error, 0.0);
  EXPECT_LT(error, 0.5);
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/" + box["blob"].get<std::string>())));
}

}  // namespace
}  // namespace prt::bake
