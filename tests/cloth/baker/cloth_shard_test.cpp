// SPDX-License-Identifier: MIT
// Distributed cloth bakes (docs/farm.md): a range of the tables' views gives, bit for bit, the
// whole tables' columns; shards merged through the technique's hooks write the whole bake's blob
// byte for byte in 1, 2 and 3 parts, with an empty part and with the fabric the scene names; and
// the merge refuses parts that are not one bake, saying why.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "prt/baker/cloth/cloth_tables.hpp"
#include "prt/baker/cloth/fabrics.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "support/shard_test_util.hpp"

namespace prt::bake {
namespace {

using prt_test::two_threads;

// The cheapest grid that still splits: 4 x 4 lobe directions at 2 levels, 3 x 2 = 6 views.
const prt_test::ShardTestArgs kClothShardGrid = {
    {"--xi-size", "4"}, {"--levels", "2"}, {"--view-theta", "3"}, {"--view-phi", "2"}};
constexpr std::size_t kClothShardViews = 6;

prt_test::ShardTestArgs cloth_shard_args(const std::string& fabric) {
  prt_test::ShardTestArgs args = kClothShardGrid;
  args.push_back({"--fabric", fabric});
  args.push_back({"--bits", "8"});
  return args;
}

// A small sphere whose sheen material is named `fabric` (what --fabric scene bakes).
Scene cloth_shard_scene(const std::string& fabric) {
  Scene scene;
  scene.source = "cloth shard test";
  Material sheen;
  sheen.name = fabric;
  sheen.sheen = true;
  scene.materials = {sheen};
  scene.meshes.push_back(make_sphere_mesh(0, glm::vec3(0.0f), 1.0f, 4, 8));
  return scene;
}

ClothTablesOptions cloth_shard_options() {
  ClothTablesOptions options;
  options.grid.xi_size = 4;
  options.grid.lambda_levels = 2;
  options.grid.view_theta = 3;
  options.grid.view_phi = 2;
  return options;
}

// Columns [first, first + count) of `whole` against every column of `range`, bit for bit.
bool same_columns(const std::vector<float>& whole, std::size_t first, std::size_t count,
                  const std::vector<float>& range, std::size_t rows, std::size_t columns) {
  if (whole.size() != rows * columns || range.size() != rows * count) return false;
  for (std::size_t r = 0; r < rows; ++r)
    if (std::memcmp(whole.data() + r * columns + first, range.data() + r * count,
                    count * sizeof(float)) != 0)
      return false;
  return true;
}

TEST(ClothShard, ViewRangeColumnsAreTheWholeTablesColumns) {
  // Satin's threads need several tables of one multiset, velvet's another.
  std::vector<ClothFabricSource> fabrics;
  for (const char* name : {"polyester_satin_charmeuse", "velvet"}) {
    const ClothPreset& p = cloth_fabric(name);
    fabrics.push_back({p.name, p.params, p.weave});
  }
  const ClothTablesOptions options = cloth_shard_options();
  const Context ctx = two_threads();
  const std::size_t rows = options.grid.rows(), columns = options.grid.columns();
  const auto whole = sample_cloth_tables_of(fabrics, options, 0, columns, ctx);
  ASSERT_GT(whole.size(), 2u);
  // Views 1..4 and view 5 alone: each computed without the others.
  for (const auto& [first, count] : {std::pair<std::size_t, std::size_t>{1, 4}, {5, 1}}) {
    const auto range = sample_cloth_tables_of(fabrics, options, first, count, ctx);
    ASSERT_EQ(range.size(), whole.size());
    for (std::size_t t = 0; t < whole.size(); ++t) {
      EXPECT_TRUE(same_columns(whole[t].full, first, count, range[t].full, rows, columns))
          << "T of table " << t << ", views from " << first;
      EXPECT_TRUE(same_columns(whole[t].cone, first, count, range[t].cone, rows, columns))
          << "T_c of table " << t << ", views from " << first;
    }
  }
  // The whole bake factors what the range sampling of every view gives.
  const ClothTablesBake baked = bake_cloth_tables(fabrics, options, ctx);
  const ClothTablesBake factored = factor_cloth_tables(fabrics, options, whole, ctx);
  ASSERT_EQ(factored.section.tables.size(), baked.section.tables.size());
  for (std::size_t t = 0; t < baked.section.tables.size(); ++t) {
    EXPECT_EQ(factored.section.tables[t].full.u, baked.section.tables[t].full.u);
    EXPECT_EQ(factored.section.tables[t].cone.v, baked.section.tables[t].cone.v);
  }
  const auto empty = sample_cloth_tables_of(fabrics, options, columns, 0, ctx);
  ASSERT_EQ(empty.size(), whole.size());
  EXPECT_TRUE(empty[0].full.empty());
  EXPECT_THROW(sample_cloth_tables_of(fabrics, options, 4, 3, ctx), Error);
}

struct ClothShardCase {
  const char* name;
  const char* fabric;              // --fabric
  std::vector<std::size_t> sizes;  // the ranges' sizes, the last range taking the rest
};

class ClothShardMerge : public testing::TestWithParam<ClothShardCase> {};

TEST_P(ClothShardMerge, MergedShardsWriteTheWholeBlob) {
  const Scene scene = cloth_shard_scene("velvet");
  const Context ctx = two_threads();
  const prt_test::ShardTestArgs args = cloth_shard_args(GetParam().fabric);
  BakeInput input;
  input.scene = "sphere";
  const std::vector<std::uint8_t> whole =
      prt_test::whole_bake_blob("cloth", args, scene, input, ctx);
  const auto bake = prt_test::make_shard_test_bake("cloth", args);
  EXPECT_STREQ(bake->shard_unit(), "views");
  ASSERT_EQ(bake->shard_units(scene), kClothShardViews);
  const auto ranges = prt_test::shard_test_ranges(kClothShardViews, GetParam().sizes);
  const auto parts = prt_test::bake_shard_payloads("cloth", args, scene, input, ranges, ctx);
  const std::vector<std::uint8_t> merged =
      prt_test::merged_bake_blob("cloth", args, scene, input, parts, ctx);
  ASSERT_FALSE(whole.empty());
  EXPECT_EQ(merged.size(), whole.size());
  EXPECT_TRUE(merged == whole) << "the merged blob differs from the whole bake's";
}

INSTANTIATE_TEST_SUITE_P(
    Splits, ClothShardMerge,
    testing::Values(ClothShardCase{"one", "linen_plain,velvet", {}},
                    ClothShardCase{"two", "linen_plain,velvet", {3}},
                    ClothShardCase{"three_uneven", "polyester_satin_charmeuse", {1, 3}},
                    ClothShardCase{"with_an_empty_part", "linen_plain", {2, 0, 4}},
                    ClothShardCase{"scene_fabric", "scene", {4}}),
    [](const testing::TestParamInfo<ClothShardCase>& info) {
      return std::string(info.param.name);
    });

TEST(ClothShard, MergeRefusesPartsThatAreNotOneBake) {
  const Scene scene = cloth_shard_scene("velvet");
  const Context ctx = two_threads();
  const prt_test::ShardTestArgs args = cloth_shard_args("scene");
  BakeInput input;
  const auto ranges = prt_test::shard_test_ranges(kClothShardViews, {2, 2});
  const auto parts = prt_test::bake_shard_payloads("cloth", args, scene, input, ranges, ctx);
  const auto error = [&](const std::vector<std::vector<std::uint8_t>>& set) {
    return prt_test::merge_shards_error("cloth", args, scene, input, set, ctx);
  };
  EXPECT_EQ(error(parts), "");
  EXPECT_EQ(error({}), "cloth merge: no shards to merge");
  EXPECT_EQ(error({parts[0], parts[1]}),
            "cloth merge: views [4, 6) are in no shard (a part after shard 1 is missing)");
  EXPECT_EQ(error({parts[0], parts[2]}),
            "cloth merge: views [2, 4) are in no shard (a part before shard 1 is missing)");
  EXPECT_EQ(error({parts[0], parts[1], parts[1], parts[2]}),
            "cloth merge: shard 2 (views [2, 4)) overlaps the shards before it, which end at 4");

  prt_test::ShardTestArgs finer = args;
  finer[0].second = "5";
  finer.push_back({"--energy", "1e-3"});
  const auto other_grid =
      prt_test::bake_shard_payloads("cloth", finer, scene, input, {ranges[1]}, ctx);
  EXPECT_EQ(error({parts[0], other_grid[0], parts[2]}),
            "cloth merge: shard 1 was baked with other settings: --xi-size 5 (this merge: 4), "
            "--energy 0.001 (this merge: 1e-04)");

  const auto other_fabric = prt_test::bake_shard_payloads("cloth", cloth_shard_args("velvet"),
                                                          scene, input, {ranges[0]}, ctx);
  EXPECT_EQ(error({other_fabric[0], parts[1], parts[2]}),
            "cloth merge: shard 0 was baked with other settings: --fabric velvet (this merge: "
            "scene)");

  // --fabric scene of a scene whose cloth names another preset, or of another scene.
  const auto other_named = prt_test::bake_shard_payloads(
      "cloth", args, cloth_shard_scene("silk_shot"), input, {ranges[2]}, ctx);
  EXPECT_EQ(error({parts[0], parts[1], other_named[0]}),
            "cloth merge: shard 2 was baked for fabrics silk_shot (this merge: velvet)");
  Scene moved = scene;
  moved.meshes[0].positions[3].y += 0.01f;
  const auto other_scene =
      prt_test::bake_shard_payloads("cloth", args, moved, input, {ranges[1]}, ctx);
  EXPECT_EQ(error({parts[0], other_scene[0], parts[2]}),
            "cloth merge: shard 1 was baked from another scene (its geometry or materials "
            "differ)");

  std::vector<std::uint8_t> truncated = parts[2];
  truncated.resize(truncated.size() - 4);
  EXPECT_EQ(error({parts[0], parts[1], truncated}),
            "cloth merge: shard 2: the payload is truncated");
  std::vector<std::uint8_t> longer = parts[2];
  longer.push_back(0);
  EXPECT_EQ(error({parts[0], parts[1], longer}),
            "cloth merge: shard 2: the payload has 1 bytes more than its header says");
  std::vector<std::uint8_t> header_only(parts[1].begin(), parts[1].begin() + 40);
  EXPECT_EQ(error({parts[0], header_only, parts[2]}),
            "cloth merge: shard 1: the payload is truncated");
  const auto sh_part = prt_test::bake_shard_payloads("sh", {{"--order", "2"}, {"--rays", "4"}},
                                                     scene, input, {{0, 10}}, ctx);
  EXPECT_EQ(error({sh_part[0], parts[1], parts[2]}),
            "cloth merge: shard 0 is not a shard of technique cloth");
}

}  // namespace
}  // namespace prt::bake
