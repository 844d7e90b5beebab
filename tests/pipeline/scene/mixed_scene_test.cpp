// SPDX-License-Identifier: MIT
// prt-bake scene on a mixed scene (issue 16's "Done when"): static ground and ring, a cloth rug,
// a crate that moves at run time and a shared-asset character, assembled in memory
// (append_scene). Each object gets the technique of its kind, meets the budget against the
// reference, and the choice per object takes fewer bytes than the one-technique baseline; the
// runtime then loads and shades the whole scene in one call each.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <prt/prt.hpp>

#include "prt/baker/scene_bake.hpp"
#include "prt/io/envmap.hpp"
#include "support/mixed_scene.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using nlohmann::json;

// The budget every technique meets on these objects within its ladder.
constexpr double kBudget = 0.05;

struct MixedSceneBake {
  SceneBakeSummary summary;
  json report;
};

MixedSceneBake bake_mixed_scene(const std::string& character, const std::string& light,
                                const std::string& out) {
  Context ctx;
  ctx.threads = 2;
  SceneBakeSettings s = prt_test::mixed_scene_settings(out, kBudget, light);
  s.compare_single = true;
  MixedSceneBake bake;
  bake.summary = run_scene_bake(s, prt_test::mixed_scene(import_scene(character, ctx)), ctx);
  std::ifstream in(out + "/report.json");
  bake.report = json::parse(in);
  return bake;
}

void expect_each_kind_gets_its_technique(const json& report) {
  const std::set<std::string> statics = {"sh", "wavelet"};
  std::size_t characters = 0;
  for (const json& o : report["objects"]) {
    const std::string name = o["name"], technique = o["technique"];
    std::printf("%s: %s, error %.2f %%, %zu bytes\n", name.c_str(), technique.c_str(),
                100 * o["error"].get<double>(), o["bytes"].get<std::size_t>());
    if (name == "ground" || name == "ring") {
      EXPECT_TRUE(statics.count(technique)) << name << ": " << technique;
    } else if (name == "rug") {
      EXPECT_EQ(technique, "cloth");
    } else if (name == "crate") {
      EXPECT_EQ(technique, "shadowfield");
    } else {
      EXPECT_EQ(technique, "pose") << name;
      ++characters;
    }
  }
  EXPECT_EQ(characters, 1u);
}

void expect_every_object_meets_the_budget(const MixedSceneBake& bake) {
  EXPECT_EQ(bake.summary.objects, 5u);
  EXPECT_EQ(bake.summary.baked, 5u);
  EXPECT_EQ(bake.summary.broken, 0u);
  EXPECT_EQ(bake.summary.over_budget, 0u);
  for (const json& o : bake.report["objects"]) {
    EXPECT_TRUE(o["meets_budget"].get<bool>()) << o["name"];
    EXPECT_LE(o["error"].get<double>(), kBudget) << o["name"];
  }
}

void expect_fewer_bytes_than_one_technique(const MixedSceneBake& bake) {
  std::printf("choice per object: %zu bytes; one technique per kind: %zu bytes\n",
              bake.summary.bytes, bake.summary.single_bytes);
  ASSERT_GT(bake.summary.single_bytes, 0u);
  EXPECT_LT(bake.summary.bytes, bake.summary.single_bytes);
  EXPECT_EQ(bake.report["summary"]["bytes"].get<std::size_t>(), bake.summary.bytes);
  EXPECT_EQ(bake.report["summary"]["single_technique_bytes"].get<std::size_t>(),
            bake.summary.single_bytes);
  // The static baselines keep the rug and the crate on their own techniques.
  for (const json& single : bake.report["single_technique"]) {
    if (single["technique"] != "sh" && single["technique"] != "wavelet") continue;
    EXPECT_EQ(single["objects"]["rug"], "cloth");
    EXPECT_EQ(single["objects"]["crate"], "shadowfield");
  }
}

const json& object_named(const json& report, const std::string& name) {
  for (const json& o : report["objects"])
    if (o["name"] == name) return o;
  throw std::runtime_error("no object " + name + " in the report");
}

bool lit_and_finite(const float* rgb, std::uint32_t vertices) {
  float brightest = 0.0f;
  for (std::size_t k = 0; k < 3 * std::size_t(vertices); ++k) {
    if (!std::isfinite(rgb[k])) return false;
    brightest = std::max(brightest, rgb[k]);
  }
  return brightest > 0.0f;
}

// "One scene, one load": the runtime loads OUT/scene.prts with every blob in one call, and one
// call per frame shades all five objects, each by its technique; the crate moves, the character
// bends, the static objects refuse to move.
void expect_the_runtime_loads_and_shades_it(const std::string& out, const std::string& light,
                                            const json& report) {
  const prt::ContextPtr context = prt::create_context().handle;
  const auto [scene, loaded] = prt::load_scene_file(context.get(), (out + "/scene.prts").c_str());
  ASSERT_EQ(loaded, PRT_OK) << prt_context_last_message(context.get());
  ASSERT_EQ(prt_scene_object_count(scene.get()), report["objects"].size());
  const io::EnvMap map = io::load_envmap(light, io::EnvMapping::Auto);
  std::vector<float> faces;
  for (const std::vector<float>& face : io::resample_to_cube(map, 32))
    faces.insert(faces.end(), face.begin(), face.end());
  const prt_env_image env = prt::cube_env(32, faces.data());
  ASSERT_EQ(prt_scene_set_environment(scene.get(), &env), PRT_OK)
      << prt_context_last_message(context.get());
  prt_scene_frame frame = prt::sized<prt_scene_frame>();
  frame.eye[1] = 1.5f;
  frame.eye[2] = 4.0f;
  ASSERT_EQ(prt_scene_shade(scene.get(), &frame), PRT_OK)
      << prt_context_last_message(context.get());
  std::vector<std::vector<float>> first(prt_scene_object_count(scene.get()));
  for (std::uint32_t i = 0; i < prt_scene_object_count(scene.get()); ++i) {
    prt_scene_object_info info = prt::sized<prt_scene_object_info>();
    ASSERT_EQ(prt_scene_get_object(scene.get(), i, &info), PRT_OK);
    prt_technique_info technique = prt::sized<prt_technique_info>();
    ASSERT_EQ(prt_technique_get_info(info.technique, &technique), PRT_OK);
    EXPECT_EQ(technique.name, object_named(report, info.name)["technique"].get<std::string>());
    const float* rgb = prt_scene_object_radiance(scene.get(), i);
    EXPECT_TRUE(lit_and_finite(rgb, info.vertex_count)) << info.name;
    first[i].assign(rgb, rgb + 3 * std::size_t(info.vertex_count));
    // A quarter turn about +Y: under a distant light a lone diffuse object's radiance changes
    // with its turn, not with where it stands.
    prt_scene_placement placement = prt::sized<prt_scene_placement>();
    placement.rotation[2] = 1.0f;
    placement.rotation[4] = 1.0f;
    placement.rotation[6] = -1.0f;
    placement.translation[0] = 0.5f;
    placement.scale = 1.0f;
    EXPECT_EQ(prt_scene_set_placement(scene.get(), i, &placement),
              info.moves ? PRT_OK : PRT_ERROR_INVALID_OPERATION)
        << info.name;
    if (info.poses) {
      auto pose_info = prt::sized<prt_pose_info>();
      ASSERT_EQ(prt_pose_get_info(info.asset, &pose_info), PRT_OK);
      std::vector<float> rotations(4 * std::size_t(pose_info.joint_count));
      ASSERT_EQ(prt_pose_bind_pose(info.asset, rotations.data(), nullptr, nullptr), PRT_OK);
      for (std::size_t j = 1; j < pose_info.joint_count; ++j) {  // every joint but the root bent
        rotations[4 * j] += 0.4f;
      }
      prt_pose_input pose = prt::sized<prt_pose_input>();
      pose.joint_rotations = rotations.data();
      EXPECT_EQ(prt_scene_set_pose(scene.get(), i, &pose), PRT_OK);
    }
  }
  ASSERT_EQ(prt_scene_shade(scene.get(), &frame), PRT_OK)
      << prt_context_last_message(context.get());
  for (std::uint32_t i = 0; i < prt_scene_object_count(scene.get()); ++i) {
    prt_scene_object_info info = prt::sized<prt_scene_object_info>();
    ASSERT_EQ(prt_scene_get_object(scene.get(), i, &info), PRT_OK);
    const float* rgb = prt_scene_object_radiance(scene.get(), i);
    const std::vector<float> second(rgb, rgb + 3 * std::size_t(info.vertex_count));
    EXPECT_TRUE(lit_and_finite(rgb, info.vertex_count)) << info.name;
    // What moved or bent shades otherwise; what is baked in place shades the same.
    if (info.moves || info.poses)
      EXPECT_NE(second, first[i]) << info.name;
    else
      EXPECT_EQ(second, first[i]) << info.name;
  }
}

// One test: ctest runs each test in a process of its own, and the bake is the costly part.
TEST(MixedScene, EachObjectGetsItsKindsTechniqueMeetsTheBudgetAndTakesFewerBytes) {
  const std::string character = prt_test::shared_asset("characters/RiggedSimple/RiggedSimple.gltf");
  if (character.empty())
    GTEST_SKIP() << "shared asset characters/RiggedSimple/RiggedSimple.gltf is absent";
  const prt_test::TempDir dir("mixed_scene");
  const std::string light = prt_test::shared_asset("envmaps/grace_cross.hdr");
  if (light.empty()) GTEST_SKIP() << "shared asset envmaps/grace_cross.hdr is absent";
  const MixedSceneBake bake = bake_mixed_scene(character, light, dir.file("out"));
  {
    SCOPED_TRACE("each kind of object gets its technique");
    expect_each_kind_gets_its_technique(bake.report);
  }
  {
    SCOPED_TRACE("every object meets the budget against the reference");
    expect_every_object_meets_the_budget(bake);
  }
  {
    SCOPED_TRACE("the choice per object takes fewer bytes than one technique for all");
    expect_fewer_bytes_than_one_technique(bake);
  }
  {
    SCOPED_TRACE("the runtime loads the scene in one call and shades it in one call per frame");
    expect_the_runtime_loads_and_shades_it(dir.file("out"), light, bake.report);
  }
}

}  // namespace
}  // namespace prt::bake
