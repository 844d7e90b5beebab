// SPDX-License-Identifier: MIT
// Distributed pose bakes (docs/farm.md): the transfer of a range of training frames is, bit for
// bit, the whole training set's rows for them, whichever frames are baked with it; shards merged
// through the technique's hooks write the whole bake's blob byte for byte, split in 1, 2 and 3
// and with an empty shard, shadowed and interreflected; and the merge refuses parts that are not
// one bake, saying why.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "prt/baker/pose/pose_training.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/shards.hpp"
#include "support/shard_test_util.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using prt_test::two_threads;

constexpr const char* kPoseShardCharacter = "characters/RiggedSimple/RiggedSimple.gltf";

#define POSE_SHARD_IMPORT_OR_SKIP(var)                     \
  if (prt_test::shared_asset(kPoseShardCharacter).empty()) \
    GTEST_SKIP() << "shared assets not found";             \
  const Scene var = import_scene(prt_test::shared_asset(kPoseShardCharacter), Context{})

// The cheapest bake that still has a few frames to split and a model to fit.
const prt_test::ShardTestArgs kPoseShardArgs = {
    {"--order", "3"}, {"--rays", "32"}, {"--rate", "2"}, {"--basis-dims", "2"}};

BakeInput pose_shard_input() {
  BakeInput input;
  input.scene = "RiggedSimple";
  input.seed = 5;
  return input;
}

bool same_floats(const float* a, const float* b, std::size_t n) {
  return std::memcmp(a, b, n * sizeof(float)) == 0;
}

TEST(PoseShard, FrameRangesAreTheWholeTrainingsRows) {
  POSE_SHARD_IMPORT_OR_SKIP(scene);
  const Context ctx = two_threads();
  PoseTrainingSettings settings;
  settings.rate = 2.0;
  settings.transfer.order = 3;
  settings.transfer.rays = 32;
  settings.transfer.seed = 5;
  const PoseTrainingSet whole = bake_pose_training(scene, settings, ctx);
  const PoseTrainingSet sampled = sample_pose_training(scene, settings);
  const std::size_t frames = whole.frames.size();
  ASSERT_GE(frames, 3u);
  ASSERT_EQ(sampled.frames.size(), frames);
  EXPECT_TRUE(sampled.transfer.empty());
  ASSERT_EQ(sampled.normals.size(), whole.normals.size());
  EXPECT_TRUE(same_floats(sampled.normals.data(), whole.normals.data(), whole.normals.size()));
  for (std::size_t f = 0; f < frames; ++f) {
    EXPECT_EQ(sampled.frames[f].time, whole.frames[f].time);
    EXPECT_EQ(sampled.frames[f].features, whole.frames[f].features);
  }
  // A frame alone, the frames after it, and all of them: each frame's rows are the whole set's.
  const std::size_t row = whole.vertex_count * whole.coefficient_count();
  const std::size_t cuts[3][2] = {{1, 1}, {1, frames - 1}, {0, frames}};
  std::uint64_t rays = 0;
  for (const auto& [first, count] : cuts) {
    const PoseFramesTransfer part = bake_pose_frames(scene, settings, sampled, first, count, ctx);
    ASSERT_EQ(part.transfer.size(), count * row);
    EXPECT_TRUE(same_floats(part.transfer.data(), whole.frame_transfer(first), count * row))
        << "frames [" << first << ", " << first + count << ")";
    if (first == 0) rays = part.rays_traced;
  }
  EXPECT_EQ(rays, whole.rays_traced);
  EXPECT_TRUE(bake_pose_frames(scene, settings, sampled, frames, 0, ctx).transfer.empty());
  EXPECT_THROW(bake_pose_frames(scene, settings, sampled, frames - 1, 2, ctx), Error);
}

// The whole bake's blob, then the blob merged from the pipeline's even split into each of
// `splits` parts.
void expect_merged_blobs_are_whole(const Scene& scene, const prt_test::ShardTestArgs& args,
                                   const BakeInput& input, const std::vector<std::size_t>& splits) {
  const Context ctx = two_threads();
  const std::vector<std::uint8_t> whole =
      prt_test::whole_bake_blob("pose", args, scene, input, ctx);
  ASSERT_FALSE(whole.empty());
  const auto bake = prt_test::make_shard_test_bake("pose", args);
  EXPECT_STREQ(bake->shard_unit(), "frames");
  const std::size_t frames = bake->shard_units(scene);
  for (std::size_t n : splits) {
    std::vector<std::pair<std::size_t, std::size_t>> ranges;
    for (std::size_t i = 0; i < n; ++i) {
      const ShardRange range = shard_range(frames, ShardSpec{i, n});
      ranges.emplace_back(range.first, range.count);
    }
    const auto parts = prt_test::bake_shard_payloads("pose", args, scene, input, ranges, ctx);
    const std::vector<std::uint8_t> merged =
        prt_test::merged_bake_blob("pose", args, scene, input, parts, ctx);
    EXPECT_EQ(merged.size(), whole.size()) << n << " shards";
    EXPECT_TRUE(merged == whole) << "the blob merged from " << n
                                 << " shards differs from the whole bake's";
  }
}

TEST(PoseShard, MergedShardsWriteTheWholeBlob) {
  POSE_SHARD_IMPORT_OR_SKIP(scene);
  const std::size_t frames =
      prt_test::make_shard_test_bake("pose", kPoseShardArgs)->shard_units(scene);
  ASSERT_GE(frames, 3u);
  // frames + 1 parts: one of them is empty.
  expect_merged_blobs_are_whole(scene, kPoseShardArgs, pose_shard_input(), {1, 2, 3, frames + 1});
  // The blob does show the traced transfer: another seed's differs.
  BakeInput reseeded = pose_shard_input();
  reseeded.seed = 6;
  EXPECT_NE(
      prt_test::whole_bake_blob("pose", kPoseShardArgs, scene, reseeded, two_threads()),
      prt_test::whole_bake_blob("pose", kPoseShardArgs, scene, pose_shard_input(), two_threads()));
}

TEST(PoseShard, MergedInterreflectedSubdividedShardsWriteTheWholeBlob) {
  POSE_SHARD_IMPORT_OR_SKIP(scene);
  prt_test::ShardTestArgs args = kPoseShardArgs;
  args.insert(args.end(), {{"--transfer", "interreflected"},
                           {"--bounces", "1"},
                           {"--subdivide-to", "120"},
                           {"--model", "direct"},
                           {"--bits", "8"}});
  BakeInput input = pose_shard_input();
  input.albedo = "0.7,0.6,0.5";
  expect_merged_blobs_are_whole(scene, args, input, {2});
}

TEST(PoseShard, MergeRefusesPartsThatAreNotOneBake) {
  POSE_SHARD_IMPORT_OR_SKIP(scene);
  const Context ctx = two_threads();
  const prt_test::ShardTestArgs& args = kPoseShardArgs;
  const BakeInput input = pose_shard_input();
  const std::size_t frames = prt_test::make_shard_test_bake("pose", args)->shard_units(scene);
  ASSERT_GE(frames, 3u);
  const auto ranges = prt_test::shard_test_ranges(frames, {1, 1});
  const auto parts = prt_test::bake_shard_payloads("pose", args, scene, input, ranges, ctx);
  const auto error = [&](const std::vector<std::vector<std::uint8_t>>& set) {
    return prt_test::merge_shards_error("pose", args, scene, input, set, ctx);
  };
  const std::string all = std::to_string(frames);
  EXPECT_EQ(error(parts), "");
  EXPECT_EQ(error({}), "pose merge: no shards to merge");
  EXPECT_EQ(error({parts[0], parts[1]}), "pose merge: frames [2, " + all +
                                             ") are in no shard (a part after shard 1 is missing)");
  EXPECT_EQ(error({parts[0], parts[2]}),
            "pose merge: frames [1, 2) are in no shard (a part before shard 1 is missing)");
  EXPECT_EQ(error({parts[0], parts[1], parts[1], parts[2]}),
            "pose merge: shard 2 (frames [1, 2)) overlaps the shards before it, which end at 2");

  // Settings of the transfer, of the frames and of the model.
  prt_test::ShardTestArgs other = args;
  other[0].second = "4";                        // --order
  other.push_back({"--pose-variance", "0.8"});  // the model's
  EXPECT_EQ(error({parts[0],
                   prt_test::bake_shard_payloads("pose", other, scene, input, {ranges[1]}, ctx)[0],
                   parts[2]}),
            "pose merge: shard 1 was baked with other settings: --order 4 (this merge: 3), "
            "--pose-variance 0.8 (this merge: 0.9)");
  other = args;
  other[2].second = "3";  // --rate: other frames
  EXPECT_EQ(
      error({parts[0], parts[1],
             prt_test::bake_shard_payloads("pose", other, scene, input, {ranges[2]}, ctx)[0]}),
      "pose merge: shard 2 was baked with other settings: --rate 3 (this merge: 2)");
  BakeInput other_input = input;
  other_input.seed = 6;
  other_input.albedo = "0.5,0.5,0.5";
  EXPECT_EQ(
      error({prt_test::bake_shard_payloads("pose", args, scene, other_input, {ranges[0]}, ctx)[0],
             parts[1], parts[2]}),
      "pose merge: shard 0 was baked with other settings: --seed 6 (this merge: 5), "
      "--albedo 0.5,0.5,0.5 (this merge: 1,1,1)");

  // Another scene: its geometry, or its clip (the same geometry and frame count, other poses).
  Scene moved = scene;
  moved.meshes[0].positions[3].y += 0.01f;
  EXPECT_EQ(error({parts[0],
                   prt_test::bake_shard_payloads("pose", args, moved, input, {ranges[1]}, ctx)[0],
                   parts[2]}),
            "pose merge: shard 1 was baked from another scene (its geometry or materials differ)");
  Scene reposed = scene;
  for (AnimationChannel& channel : reposed.animations[0].channels)
    if (channel.path == AnimationChannel::Path::Rotation) channel.values.back() *= 0.5f;
  EXPECT_EQ(
      error({parts[0], parts[1],
             prt_test::bake_shard_payloads("pose", args, reposed, input, {ranges[2]}, ctx)[0]}),
      "pose merge: shard 2 was baked from another scene (its skeleton, skin or clips "
      "differ)");

  // Damaged payloads, and another technique's.
  std::vector<std::uint8_t> truncated = parts[2];
  truncated.resize(truncated.size() - 4);
  EXPECT_EQ(error({parts[0], parts[1], truncated}),
            "pose merge: shard 2: the payload is truncated");
  std::vector<std::uint8_t> longer = parts[2];
  longer.push_back(0);
  EXPECT_EQ(error({parts[0], parts[1], longer}),
            "pose merge: shard 2: the payload has 1 bytes more than its header says");
  EXPECT_EQ(error({std::vector<std::uint8_t>(parts[0].begin(), parts[0].begin() + 3), parts[1],
                   parts[2]}),
            "pose merge: shard 0: the payload is truncated");
  const auto sh_part = prt_test::bake_shard_payloads("sh", {{"--order", "2"}, {"--rays", "8"}},
                                                     scene, input, {{0, 10}}, ctx);
  EXPECT_EQ(error({sh_part[0], parts[1], parts[2]}),
            "pose merge: shard 0 is not a shard of technique pose");
}

}  // namespace
}  // namespace prt::bake
