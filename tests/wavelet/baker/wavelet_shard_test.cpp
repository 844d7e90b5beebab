// SPDX-License-Identifier: MIT
// Distributed wavelet bakes (docs/farm.md): the direct pass of a range of vertices gives, bit for
// bit, the whole bake's truncated rows (with a vertex subset too); ranges joined and finished by
// the bounces are the whole transfer, statistics included; shards merged through the technique's
// hooks write the whole bake's blob byte for byte, with and without a bounce; and the merge
// refuses parts that are not one bake, saying why.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "prt/baker/wavelet/wavelet_transfer.hpp"
#include "sh/sh_test_scenes.hpp"
#include "support/render_test_scenes.hpp"
#include "support/shard_test_util.hpp"

namespace prt::bake {
namespace {

// An open box (a floor and four walls, five meshes: light bounces between them), 161 vertices,
// one of which has no usable normal. Small: the tests also run under ASan.
Scene shard_scene() {
  Scene scene = test::scene_of(test::make_fine_open_box(0.8f, 6, 3));
  scene.meshes[0].normals[5] = glm::vec3(0.0f);
  return scene;
}

using prt_test::two_threads;

WaveletTransferSettings shard_settings(int bounces) {
  WaveletTransferSettings s;
  s.size = 16;
  s.keep = 64;
  s.bounces = bounces;
  s.seed = 7;
  return s;
}

template <typename T>
bool same_bits(const T* a, const T* b, std::size_t n) {
  return n == 0 || std::memcmp(a, b, n * sizeof(T)) == 0;
}

// Vertices [first, first + range.vertex_count) of `whole` and every vertex of `range`: rows,
// albedo, baked and statistics, bit for bit.
::testing::AssertionResult same_rows(const WaveletTransfer& whole, std::size_t first,
                                     const WaveletTransfer& range) {
  if (range.param != whole.param || range.size != whole.size ||
      range.coefficient_count != whole.coefficient_count)
    return ::testing::AssertionFailure() << "another parameterisation";
  if (first + range.vertex_count > whole.vertex_count)
    return ::testing::AssertionFailure() << "the range is not in the whole";
  for (std::size_t i = 0; i < range.vertex_count; ++i) {
    const std::size_t v = first + i, n = range.row_size(i);
    const std::uint64_t a = whole.row_start[v], b = range.row_start[i];
    if (whole.row_size(v) != n || !same_bits(whole.index.data() + a, range.index.data() + b, n) ||
        !same_bits(whole.value.data() + a, range.value.data() + b, n) ||
        whole.baked[v] != range.baked[i] || !same_bits(&whole.albedo[v], &range.albedo[i], 1) ||
        !same_bits(&whole.energy_kept[v], &range.energy_kept[i], 1) ||
        whole.nonzeros_before[v] != range.nonzeros_before[i])
      return ::testing::AssertionFailure() << "vertex " << v << " differs";
  }
  return ::testing::AssertionSuccess();
}

TEST(WaveletShard, RangeRowsAreTheWholeBakesRows) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  WaveletTransferSettings s = shard_settings(0);
  const WaveletTransfer whole = compute_wavelet_transfer(scene, nullptr, s, ctx);
  // 37..137 starts and ends inside a task of the whole bake and crosses meshes.
  const WaveletTransfer range = compute_wavelet_direct_range(scene, nullptr, s, 37, 101, ctx);
  EXPECT_EQ(range.vertex_count, 101u);
  EXPECT_TRUE(same_rows(whole, 37, range));
  EXPECT_GT(range.rays_traced, 0u);
  // With a bounce the range is the direct pass: the rows of the bake without one.
  const WaveletTransfer direct =
      compute_wavelet_direct_range(scene, nullptr, shard_settings(1), 0, 20, ctx);
  EXPECT_TRUE(same_rows(whole, 0, direct));
  EXPECT_EQ(direct.vertices_without_normal, 1u);
  // A subset: every third vertex of the scene, the others empty, in a range as in the whole.
  s.vertex_stride = 3;
  const WaveletTransfer strided = compute_wavelet_transfer(scene, nullptr, s, ctx);
  const WaveletTransfer strided_range =
      compute_wavelet_direct_range(scene, nullptr, s, 37, 101, ctx);
  EXPECT_TRUE(same_rows(strided, 37, strided_range));
  EXPECT_EQ(strided_range.row_size(0), 0u);  // 37 is not in the subset
  EXPECT_GT(strided_range.row_size(2), 0u);  // 39 is
  EXPECT_THROW(compute_wavelet_direct_range(scene, nullptr, s, 200, 100, ctx), Error);
}

TEST(WaveletShard, JoinedRangesWithBouncesAreTheWholeTransfer) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  // Without bounces the join alone sums the statistics; with them the last pass does.
  const std::pair<int, double> cases[] = {{0, 0.0}, {1, 0.0}, {0, 0.99}};
  for (const auto& [bounces, keep_energy] : cases) {
    WaveletTransferSettings s = shard_settings(bounces);
    s.keep_energy = keep_energy;
    s.keep = keep_energy > 0.0 ? 0 : s.keep;
    const WaveletTransfer whole = compute_wavelet_transfer(scene, nullptr, s, ctx);
    std::vector<WaveletTransfer> ranges;
    const std::size_t cuts[4] = {0, 50, 123, scene.vertex_count()};
    for (int i = 0; i < 3; ++i) {
      ranges.push_back(
          compute_wavelet_direct_range(scene, nullptr, s, cuts[i], cuts[i + 1] - cuts[i], ctx));
    }
    WaveletTransfer joined = join_wavelet_ranges(s, std::move(ranges));
    add_wavelet_bounces(scene, nullptr, s, joined, ctx);
    ASSERT_EQ(joined.vertex_count, whole.vertex_count);
    EXPECT_TRUE(same_rows(whole, 0, joined))
        << "bounces " << bounces << ", keep energy " << keep_energy;
    EXPECT_EQ(joined.rays_traced, whole.rays_traced);
    EXPECT_EQ(joined.vertices_without_normal, 1u);
    // Summed as the whole bake sums them: the same doubles.
    EXPECT_EQ(joined.mean_energy_kept, whole.mean_energy_kept);
    EXPECT_EQ(joined.mean_nonzeros_before, whole.mean_nonzeros_before);
  }
  // The bounces need every vertex's direct pass.
  const WaveletTransferSettings s = shard_settings(1);
  WaveletTransfer part = compute_wavelet_direct_range(scene, nullptr, s, 0, 50, ctx);
  EXPECT_THROW(add_wavelet_bounces(scene, nullptr, s, part, ctx), Error);
}

class WaveletShardMerge : public testing::TestWithParam<prt_test::ShardTestArgs> {};

TEST_P(WaveletShardMerge, MergedShardsWriteTheWholeBlob) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  prt_test::ShardTestArgs args = {{"--cube", "16"}};
  args.insert(args.end(), GetParam().begin(), GetParam().end());
  BakeInput input;
  input.scene = "open box";
  input.seed = 3;
  input.albedo = "0.7,0.6,0.5";
  const std::vector<std::uint8_t> whole =
      prt_test::whole_bake_blob("wavelet", args, scene, input, ctx);
  const std::size_t vertices = scene.vertex_count();
  EXPECT_EQ(find_technique("wavelet")->make_bake()->shard_units(scene), vertices);
  // Three uneven ranges, cut inside tasks of the whole bake.
  const auto ranges = prt_test::shard_test_ranges(vertices, {vertices / 6, vertices / 2});
  const auto parts = prt_test::bake_shard_payloads("wavelet", args, scene, input, ranges, ctx);
  const std::vector<std::uint8_t> merged =
      prt_test::merged_bake_blob("wavelet", args, scene, input, parts, ctx);
  ASSERT_FALSE(whole.empty());
  EXPECT_EQ(merged.size(), whole.size());
  EXPECT_TRUE(merged == whole) << "the merged blob differs from the whole bake's";
}

// Outside the macro, whose arguments' commas would split them.
const prt_test::ShardTestArgs kWaveletShardCases[] = {
    {{"--bounces", "0"}},
    {{"--bounces", "1"}},
    {{"--bounces", "1"}, {"--vertex-stride", "3"}, {"--quantizer", "vertex"}},
    {{"--bounces", "0"}, {"--keep-energy", "0.95"}},
};

std::string wavelet_shard_case_name(const testing::TestParamInfo<prt_test::ShardTestArgs>& info) {
  const char* names[] = {"Direct", "OneBounce", "OneBounceStrided", "KeepEnergy"};
  return names[info.index];
}

INSTANTIATE_TEST_SUITE_P(Bounces, WaveletShardMerge, testing::ValuesIn(kWaveletShardCases),
                         wavelet_shard_case_name);

TEST(WaveletShard, MergeRefusesPartsThatAreNotOneBake) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  const prt_test::ShardTestArgs args = {{"--cube", "16"}, {"--bounces", "1"}};
  BakeInput input;
  input.seed = 3;
  const std::size_t vertices = scene.vertex_count();
  const auto ranges = prt_test::shard_test_ranges(vertices, {40, 70});
  const auto parts = prt_test::bake_shard_payloads("wavelet", args, scene, input, ranges, ctx);
  const auto error = [&](const std::vector<std::vector<std::uint8_t>>& set) {
    return prt_test::merge_shards_error("wavelet", args, scene, input, set, ctx);
  };
  EXPECT_EQ(error(parts), "");
  EXPECT_EQ(error({parts[0], parts[1]}),
            "wavelet merge: vertices [110, 161) are in no shard (a part after shard 1 is "
            "missing)");
  EXPECT_EQ(error({parts[0], parts[2]}),
            "wavelet merge: vertices [40, 110) are in no shard (a part before shard 1 is "
            "missing)");
  const auto overlapping =
      prt_test::bake_shard_payloads("wavelet", args, scene, input, {{0, 100}, {60, 101}}, ctx);
  EXPECT_EQ(error(overlapping),
            "wavelet merge: shard 1 (vertices [60, 161)) overlaps the shards before it, which "
            "end at 100");

  // The default --keep follows the cube's size, so it differs too.
  const auto other_cube = prt_test::bake_shard_payloads(
      "wavelet", {{"--cube", "32"}, {"--bounces", "1"}}, scene, input, {ranges[1]}, ctx);
  EXPECT_EQ(error({parts[0], other_cube[0], parts[2]}),
            "wavelet merge: shard 1 was baked with other settings: --cube 32 (this merge: 16), "
            "--keep 250 (this merge: 64)");
  BakeInput other_input = input;
  other_input.seed = 4;
  const auto other_seed =
      prt_test::bake_shard_payloads("wavelet", args, scene, other_input, {ranges[2]}, ctx);
  EXPECT_EQ(error({parts[0], parts[1], other_seed[0]}),
            "wavelet merge: shard 2 was baked with other settings: --seed 4 (this merge: 3)");
  const auto no_bounce = prt_test::bake_shard_payloads(
      "wavelet", {{"--cube", "16"}, {"--bounces", "0"}}, scene, input, {ranges[0]}, ctx);
  EXPECT_EQ(error({no_bounce[0], parts[1], parts[2]}),
            "wavelet merge: shard 0 was baked with other settings: --bounces 0 (this merge: 1)");

  std::vector<std::uint8_t> truncated = parts[1];
  truncated.resize(truncated.size() - 4);
  EXPECT_EQ(error({parts[0], truncated, parts[2]}),
            "wavelet merge: shard 1: the payload is truncated");
  const auto sh_part =
      prt_test::bake_shard_payloads("sh", {{"--rays", "16"}}, scene, input, {ranges[0]}, ctx);
  EXPECT_EQ(error({sh_part[0], parts[1], parts[2]}),
            "wavelet merge: shard 0 is not a shard of technique wavelet");
}

}  // namespace
}  // namespace prt::bake
