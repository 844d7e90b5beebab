// SPDX-License-Identifier: MIT
// prt-bake scene on a mixed scene (issue 16's "Done when"): static ground and ring, a cloth rug,
// a crate that moves at run time and a shared-asset character, assembled in memory
// (append_scene). Each object gets the technique of its kind, meets the budget against the
// reference, and the choice per object takes fewer bytes than the one-technique baseline.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "prt/baker/scene_bake.hpp"
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
  SceneBakeSettings s;
  s.scene = "mixed";
  s.out_dir = out;
  s.error_budget = kBudget;
  s.bounces = 0;
  s.ref_spp = 512;
  s.probe_vertices = 96;
  s.compare_single = true;
  s.envs = {light};
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
}

}  // namespace
}  // namespace prt::bake
