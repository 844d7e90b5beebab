// SPDX-License-Identifier: MIT
// Distributed sh bakes (docs/farm.md): the direct pass of a range of vertices is, bit for bit,
// the whole bake's rows; ranges joined and finished by the bounces are the whole transfer; shards
// merged through the technique's hooks write the whole bake's blob byte for byte, shadowed and
// interreflected; and the merge refuses parts that are not one bake, saying why.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "prt/baker/sh/sh_transfer.hpp"
#include "sh/sh_test_scenes.hpp"
#include "support/render_test_scenes.hpp"
#include "support/shard_test_util.hpp"

namespace prt::bake {
namespace {

// An open box (a floor and four walls, five meshes: light bounces between them), 261 vertices,
// one of which has no usable normal.
Scene shard_scene() {
  Scene scene = test::scene_of(test::make_fine_open_box(0.8f, 8, 4));
  scene.meshes[0].normals[5] = glm::vec3(0.0f);
  return scene;
}

using prt_test::two_threads;

ShTransferSettings shard_settings(ShTransferKind kind) {
  ShTransferSettings s;
  s.order = 3;
  s.rays = 64;
  s.kind = kind;
  s.bounces = 2;
  s.seed = 7;
  return s;
}

// Rows [first, first + count) of `whole` and every row of `range`, bit for bit.
bool same_rows(const ShTransfer& whole, std::size_t first, const ShTransfer& range) {
  const std::size_t row = 3 * whole.coefficient_count();
  return range.vertex_count * row == range.coefficients.size() &&
         (first + range.vertex_count) * row <= whole.coefficients.size() &&
         std::memcmp(whole.coefficients.data() + first * row, range.coefficients.data(),
                     range.coefficients.size() * sizeof(float)) == 0;
}

TEST(ShShard, RangeRowsAreTheWholeBakesRows) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  const ShTransferSettings shadowed = shard_settings(ShTransferKind::Shadowed);
  const ShTransfer whole = compute_sh_transfer(scene, nullptr, shadowed, ctx);
  // 37..137 starts and ends inside a task of the whole bake and crosses meshes.
  const ShTransfer range = compute_sh_direct_range(scene, nullptr, shadowed, 37, 101, ctx);
  EXPECT_EQ(range.vertex_count, 101u);
  EXPECT_TRUE(same_rows(whole, 37, range));
  EXPECT_EQ(range.vertices_without_normal, 0u);  // vertex 5 is before the range
  EXPECT_GT(range.rays_traced, 0u);
  // An interreflected bake's range is its direct pass: the shadowed transfer.
  const ShTransfer direct = compute_sh_direct_range(
      scene, nullptr, shard_settings(ShTransferKind::Interreflected), 0, 20, ctx);
  EXPECT_TRUE(same_rows(whole, 0, direct));
  EXPECT_EQ(direct.vertices_without_normal, 1u);
  // The whole scene as one range is the whole shadowed bake.
  const ShTransfer all =
      compute_sh_direct_range(scene, nullptr, shadowed, 0, scene.vertex_count(), ctx);
  EXPECT_TRUE(same_rows(whole, 0, all));
  EXPECT_EQ(all.rays_traced, whole.rays_traced);
  EXPECT_THROW(compute_sh_direct_range(scene, nullptr, shadowed, 200, 100, ctx), Error);
}

TEST(ShShard, JoinedRangesWithBouncesAreTheWholeTransfer) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  const ShTransferSettings s = shard_settings(ShTransferKind::Interreflected);
  const ShTransfer whole = compute_sh_transfer(scene, nullptr, s, ctx);
  std::vector<ShTransfer> ranges;
  const std::size_t cuts[4] = {0, 50, 200, scene.vertex_count()};
  for (int i = 0; i < 3; ++i) {
    ranges.push_back(
        compute_sh_direct_range(scene, nullptr, s, cuts[i], cuts[i + 1] - cuts[i], ctx));
  }
  ShTransfer joined = join_sh_ranges(std::move(ranges));
  add_sh_bounces(scene, nullptr, s, joined, ctx);
  EXPECT_EQ(joined.vertex_count, whole.vertex_count);
  EXPECT_TRUE(same_rows(whole, 0, joined));
  EXPECT_EQ(joined.rays_traced, whole.rays_traced);
  EXPECT_EQ(joined.vertices_without_normal, 1u);
  // The bounces need every vertex's direct pass.
  ShTransfer part = compute_sh_direct_range(scene, nullptr, s, 0, 50, ctx);
  EXPECT_THROW(add_sh_bounces(scene, nullptr, s, part, ctx), Error);
}

struct ShShardCase {
  const char* transfer;
  const char* albedo;  // --albedo; "" from the materials
};

class ShShardMerge : public testing::TestWithParam<ShShardCase> {};

TEST_P(ShShardMerge, MergedShardsWriteTheWholeBlob) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  const prt_test::ShardTestArgs args = {
      {"--order", "3"}, {"--rays", "64"}, {"--transfer", GetParam().transfer}, {"--bounces", "1"}};
  BakeInput input;
  input.scene = "open box";
  input.seed = 3;
  input.albedo = GetParam().albedo;
  const std::vector<std::uint8_t> whole = prt_test::whole_bake_blob("sh", args, scene, input, ctx);
  const std::size_t vertices = scene.vertex_count();
  EXPECT_EQ(find_technique("sh")->make_bake()->shard_units(scene), vertices);
  // Three uneven ranges, cut inside tasks of the whole bake.
  const auto ranges = prt_test::shard_test_ranges(vertices, {vertices / 6, vertices / 2});
  const auto parts = prt_test::bake_shard_payloads("sh", args, scene, input, ranges, ctx);
  const std::vector<std::uint8_t> merged =
      prt_test::merged_bake_blob("sh", args, scene, input, parts, ctx);
  ASSERT_FALSE(whole.empty());
  EXPECT_EQ(merged.size(), whole.size());
  EXPECT_TRUE(merged == whole) << "the merged blob differs from the whole bake's";
}

INSTANTIATE_TEST_SUITE_P(Kinds, ShShardMerge,
                         testing::Values(ShShardCase{"shadowed", ""},
                                         ShShardCase{"interreflected", "0.7,0.6,0.5"}),
                         [](const testing::TestParamInfo<ShShardCase>& info) {
                           return std::string(info.param.transfer);
                         });

TEST(ShShard, MergeRefusesPartsThatAreNotOneBake) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  const prt_test::ShardTestArgs args = {{"--order", "3"}, {"--rays", "16"}};
  BakeInput input;
  input.seed = 3;
  const std::size_t vertices = scene.vertex_count();
  const auto ranges = prt_test::shard_test_ranges(vertices, {60, 100});
  const auto parts = prt_test::bake_shard_payloads("sh", args, scene, input, ranges, ctx);
  const auto error = [&](const std::vector<std::vector<std::uint8_t>>& set) {
    return prt_test::merge_shards_error("sh", args, scene, input, set, ctx);
  };
  EXPECT_EQ(error(parts), "");
  EXPECT_EQ(error({}), "sh merge: no shards to merge");

  EXPECT_EQ(error({parts[0], parts[1]}),
            "sh merge: vertices [160, 261) are in no shard (a part after shard 1 is missing)");
  EXPECT_EQ(error({parts[0], parts[2]}),
            "sh merge: vertices [60, 160) are in no shard (a part before shard 1 is missing)");
  EXPECT_EQ(error({parts[1], parts[2]}),
            "sh merge: vertices [0, 60) are in no shard (a part before shard 0 is missing)");

  const auto overlapping =
      prt_test::bake_shard_payloads("sh", args, scene, input, {{0, 100}, {60, 201}}, ctx);
  EXPECT_EQ(error(overlapping),
            "sh merge: shard 1 (vertices [60, 261)) overlaps the shards before it, which end at "
            "100");
  EXPECT_EQ(error({parts[0], parts[1], parts[1], parts[2]}),
            "sh merge: shard 2 (vertices [60, 160)) overlaps the shards before it, which end at "
            "160");

  prt_test::ShardTestArgs order4 = args;
  order4[0].second = "4";
  const auto other_order =
      prt_test::bake_shard_payloads("sh", order4, scene, input, {ranges[1]}, ctx);
  EXPECT_EQ(error({parts[0], other_order[0], parts[2]}),
            "sh merge: shard 1 was baked with other settings: --order 4 (this merge: 3)");

  BakeInput other_input = input;
  other_input.seed = 4;
  other_input.albedo = "0.5,0.5,0.5";
  const auto other_seed =
      prt_test::bake_shard_payloads("sh", args, scene, other_input, {ranges[2]}, ctx);
  EXPECT_EQ(error({parts[0], parts[1], other_seed[0]}),
            "sh merge: shard 2 was baked with other settings: --seed 4 (this merge: 3), --albedo "
            "0.5,0.5,0.5 (this merge: from the materials)");

  prt_test::ShardTestArgs interreflected = args;
  interreflected.push_back({"--transfer", "interreflected"});
  const auto other_kind =
      prt_test::bake_shard_payloads("sh", interreflected, scene, input, {ranges[0]}, ctx);
  EXPECT_EQ(error({other_kind[0], parts[1], parts[2]}),
            "sh merge: shard 0 was baked with other settings: --transfer interreflected (this "
            "merge: shadowed), --bounces 1 (this merge: 0)");

  Scene moved = scene;
  moved.meshes[1].positions[3].y += 0.01f;
  const auto other_scene =
      prt_test::bake_shard_payloads("sh", args, moved, input, {ranges[1]}, ctx);
  EXPECT_EQ(error({parts[0], other_scene[0], parts[2]}),
            "sh merge: shard 1 was baked from another scene (its geometry or materials differ)");

  std::vector<std::uint8_t> truncated = parts[2];
  truncated.resize(truncated.size() - 4);
  EXPECT_EQ(error({parts[0], parts[1], truncated}), "sh merge: shard 2: the payload is truncated");
  std::vector<std::uint8_t> longer = parts[2];
  longer.push_back(0);
  EXPECT_EQ(error({parts[0], parts[1], longer}),
            "sh merge: shard 2: the payload has 1 bytes more than its header says");
  const auto wavelet_part =
      prt_test::bake_shard_payloads("wavelet", {{"--cube", "16"}}, scene, input, {ranges[0]}, ctx);
  EXPECT_EQ(error({wavelet_part[0], parts[1], parts[2]}),
            "sh merge: shard 0 is not a shard of technique sh");
}

}  // namespace
}  // namespace prt::bake
