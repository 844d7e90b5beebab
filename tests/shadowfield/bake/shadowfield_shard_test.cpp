// SPDX-License-Identifier: MIT
// Distributed shadowfield bakes (docs/farm.md): a range of shells or vertices is, bit for bit, the
// whole bake's values there; shards merged through the technique's hooks write the whole bake's
// blob byte for byte, however the units are split (N = 1, 2, 3, uneven, an empty part), diffuse
// and glossy; and the merge refuses parts that are not one bake, saying why.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/shadowfield/shadowfield_bake.hpp"
#include "support/shard_test_util.hpp"

namespace prt::bake {
namespace {

using prt_test::ShardTestArgs;
using prt_test::two_threads;

// A small torus (it shadows itself) and a box beside it, 101 vertices, one without a usable
// normal.
Scene shard_scene() {
  Mesh mesh = make_torus_mesh(0, glm::vec3(0.0f), 0.5f, 0.2f, 6, 10);
  append_mesh(mesh, make_box_mesh(0, glm::vec3(0.9f, 0.0f, 0.0f), 0.2f, 0.3f, 1));
  mesh.normals[7] = glm::vec3(0.0f);
  Scene scene;
  scene.source = "generated";
  Material material;
  material.base_color = glm::vec4(0.7f, 0.6f, 0.5f, 1.0f);
  scene.materials.push_back(material);
  scene.meshes.push_back(std::move(mesh));
  return scene;
}

// 3 occlusion shells of 24 points (vertex blocks of 24), 2 source radiance shells, few rays, a
// small BRDF table.
const ShardTestArgs kCheap = {
    {"--order", "2"},          {"--shells", "3"},    {"--face-size", "2"}, {"--srf-shells", "2"},
    {"--srf-face-size", "2"},  {"--basis", "3"},     {"--lights", "12"},   {"--field-rays", "32"},
    {"--transfer-rays", "16"}, {"--srf-rays", "32"}, {"--brdf-grid", "8"}};

ShardTestArgs with_args(ShardTestArgs args, const ShardTestArgs& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

std::size_t units_of(const ShardTestArgs& args, const Scene& scene) {
  return prt_test::make_shard_test_bake("shadowfield", args)->shard_units(scene);
}

// The N even ranges prt-bake's --shard i/N takes.
std::vector<std::pair<std::size_t, std::size_t>> even_ranges(std::size_t units, std::size_t n) {
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  for (std::size_t i = 0; i < n; ++i)
    ranges.emplace_back(i * units / n, (i + 1) * units / n - i * units / n);
  return ranges;
}

bool same_floats(const std::vector<float>& whole, std::size_t first,
                 const std::vector<float>& range) {
  return first + range.size() <= whole.size() &&
         std::memcmp(whole.data() + first, range.data(), range.size() * sizeof(float)) == 0;
}

TEST(ShadowfieldShard, RangesAreTheWholeBakesValues) {
  const Scene scene = shard_scene();
  ShadowfieldBakeSettings s;
  s.fields.order = 3;
  s.fields.oof_shells = 3;
  s.fields.oof_face_size = 2;
  s.fields.field_directions = 32;
  s.fields.transfer_rays = 16;
  s.fields.seed = 5;
  s.basis.size = 3;
  s.basis.lights = 12;
  s.srf.shells = 3;
  s.srf.face_size = 2;
  s.srf.directions = 32;
  s.srf.seed = 5;
  const ShadowfieldBakeResult whole =
      bake_shadowfield_object(scene, ShadowfieldMaterial{}, s, two_threads());
  // The ranges on one thread, the whole on two: neither the split nor the threads matter.
  const Context one;
  ShadowfieldObject object = make_shadowfield_object(scene, ShadowfieldMaterial{}, 3);
  const EmbreeScene rays(shadowfield_rays_scene(object), one);
  object.oof_shells = occlusion_field_grid(object, s.fields);
  const std::size_t coeffs = 9, per_shell = 24;
  EXPECT_TRUE(same_floats(whole.object.oof, per_shell * coeffs,
                          bake_occlusion_shells(object, rays, s.fields, 1, 2, one)));
  EXPECT_TRUE(
      same_floats(whole.object.oof, 0, bake_occlusion_shells(object, rays, s.fields, 0, 1, one)));
  EXPECT_THROW(bake_occlusion_shells(object, rays, s.fields, 2, 2, one), Error);

  std::vector<float> transfer;
  EXPECT_EQ(bake_self_transfer_range(object, rays, s.fields, 5, 30, &transfer, one), 1u);
  EXPECT_TRUE(same_floats(whole.object.transfer, 5 * coeffs, transfer));
  EXPECT_EQ(bake_self_transfer_range(object, rays, s.fields, 8, 93, &transfer, one), 0u);
  EXPECT_TRUE(same_floats(whole.object.transfer, 8 * coeffs, transfer));

  bake_surface_basis(object, rays, s.basis, one);
  EXPECT_EQ(object.basis, whole.object.basis);
  // Shell 1 alone: field f's points are at f * 72 + 24 of the whole bake's.
  const std::vector<float> srf = bake_source_radiance_shells(object, rays, s.srf, 1, 1, one);
  ASSERT_EQ(srf.size(), 3 * per_shell * coeffs);
  for (std::size_t f = 0; f < 3; ++f) {
    const std::vector<float> field(srf.begin() + f * per_shell * coeffs,
                                   srf.begin() + (f + 1) * per_shell * coeffs);
    EXPECT_TRUE(same_floats(whole.object.srf, (f * 3 * per_shell + per_shell) * coeffs, field))
        << "field " << f;
  }
}

struct ShadowfieldShardCase {
  const char* name;
  ShardTestArgs extra;
  const char* albedo;  // --albedo; "" from the materials
};

class ShadowfieldShardMerge : public testing::TestWithParam<ShadowfieldShardCase> {};

TEST_P(ShadowfieldShardMerge, MergedShardsWriteTheWholeBlob) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  const ShardTestArgs args = with_args(kCheap, GetParam().extra);
  BakeInput input;
  input.scene = "torus and box";
  input.seed = 3;
  input.albedo = GetParam().albedo;
  const std::vector<std::uint8_t> whole =
      prt_test::whole_bake_blob("shadowfield", args, scene, input, ctx);
  ASSERT_FALSE(whole.empty());
  // 3 + 2 shells, then ceil(101 / 24) = 5 vertex blocks.
  const std::size_t units = units_of(args, scene);
  ASSERT_EQ(units, 10u);
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> splits;
  for (std::size_t n : {1, 2, 3}) splits.push_back(even_ranges(units, n));
  // Uneven, a part with no unit, and one of kinds mixed: shells of both grids and blocks.
  splits.push_back({{0, 0}, {0, 4}, {4, 1}, {5, 5}});
  splits.push_back({{0, 2}, {2, 7}, {9, 1}});
  for (const auto& ranges : splits) {
    const auto parts =
        prt_test::bake_shard_payloads("shadowfield", args, scene, input, ranges, ctx);
    const std::vector<std::uint8_t> merged =
        prt_test::merged_bake_blob("shadowfield", args, scene, input, parts, ctx);
    EXPECT_TRUE(merged == whole) << ranges.size() << " parts: the merged blob differs from the "
                                 << "whole bake's";
  }
}

INSTANTIATE_TEST_SUITE_P(Materials, ShadowfieldShardMerge,
                         testing::Values(ShadowfieldShardCase{"lambert", {}, ""},
                                         ShadowfieldShardCase{"phong",
                                                              {{"--brdf", "phong:8,0.6,0.3"},
                                                               {"--terms", "2"},
                                                               {"--brdf-grid", "8"},
                                                               {"--bits", "8"}},
                                                              "0.5,0.4,0.3"}),
                         [](const testing::TestParamInfo<ShadowfieldShardCase>& info) {
                           return std::string(info.param.name);
                         });

TEST(ShadowfieldShard, MergeRefusesPartsThatAreNotOneBake) {
  const Scene scene = shard_scene();
  const Context ctx = two_threads();
  BakeInput input;
  input.seed = 3;
  // Shard 0: occlusion shells and the first radiance shell; 1: the second and 2 blocks; 2: the
  // rest of the blocks.
  const std::vector<std::pair<std::size_t, std::size_t>> ranges = {{0, 4}, {4, 3}, {7, 3}};
  const auto parts =
      prt_test::bake_shard_payloads("shadowfield", kCheap, scene, input, ranges, ctx);
  const auto error = [&](const std::vector<std::vector<std::uint8_t>>& set) {
    return prt_test::merge_shards_error("shadowfield", kCheap, scene, input, set, ctx);
  };
  EXPECT_EQ(error(parts), "");
  EXPECT_EQ(error({}), "shadowfield merge: no shards to merge");
  EXPECT_EQ(error({parts[0], parts[1]}),
            "shadowfield merge: shells and vertex blocks [7, 10) are in no shard (a part after "
            "shard 1 is missing)");
  EXPECT_EQ(error({parts[0], parts[2]}),
            "shadowfield merge: shells and vertex blocks [4, 7) are in no shard (a part before "
            "shard 1 is missing)");
  EXPECT_EQ(error({parts[0], parts[1], parts[1], parts[2]}),
            "shadowfield merge: shard 2 (shells and vertex blocks [4, 7)) overlaps the shards "
            "before it, which end at 7");

  const auto other_shells = prt_test::bake_shard_payloads(
      "shadowfield", with_args(kCheap, {{"--srf-rays", "64"}, {"--inner", "0.3"}}), scene, input,
      {ranges[1]}, ctx);
  EXPECT_EQ(error({parts[0], other_shells[0], parts[2]}),
            "shadowfield merge: shard 1 was baked with other settings: --inner 0.3 (this merge: "
            "0.2), --srf-rays 64 (this merge: 32)");
  const auto other_brdf = prt_test::bake_shard_payloads(
      "shadowfield", with_args(kCheap, {{"--brdf", "phong:8"}}), scene, input, {ranges[2]}, ctx);
  EXPECT_EQ(error({parts[0], parts[1], other_brdf[0]}),
            "shadowfield merge: shard 2 was baked with other settings: --brdf phong:8,1,0 (this "
            "merge: lambert)");
  BakeInput other_input = input;
  other_input.seed = 4;
  other_input.albedo = "0.5,0.5,0.5";
  const auto other_seed =
      prt_test::bake_shard_payloads("shadowfield", kCheap, scene, other_input, {ranges[0]}, ctx);
  EXPECT_EQ(error({other_seed[0], parts[1], parts[2]}),
            "shadowfield merge: shard 0 was baked with other settings: --seed 4 (this merge: 3), "
            "--albedo 0.5,0.5,0.5 (this merge: from the materials)");

  Scene moved = scene;
  moved.meshes[0].positions[3].y += 0.01f;
  const auto other_scene =
      prt_test::bake_shard_payloads("shadowfield", kCheap, moved, input, {ranges[1]}, ctx);
  EXPECT_EQ(error({parts[0], other_scene[0], parts[2]}),
            "shadowfield merge: shard 1 was baked from another scene (its geometry or materials "
            "differ)");

  std::vector<std::uint8_t> truncated = parts[2];
  truncated.resize(truncated.size() - 4);
  EXPECT_EQ(error({parts[0], parts[1], truncated}),
            "shadowfield merge: shard 2: the payload is truncated");
  std::vector<std::uint8_t> longer = parts[1];
  longer.push_back(0);
  EXPECT_EQ(error({parts[0], longer, parts[2]}),
            "shadowfield merge: shard 1: the payload has 1 bytes more than its header says");
  // Shard 1 holds no occlusion shell: its basis follows the 200-byte header and "lambert".
  std::vector<std::uint8_t> other_basis = parts[1];
  other_basis[200 + 7] ^= 1;
  EXPECT_EQ(error({parts[0], other_basis, parts[2]}),
            "shadowfield merge: shard 1 projected its source radiance shells on another surface "
            "basis than shard 0 (their machines trace rays differently)");
  const auto sh_part = prt_test::bake_shard_payloads("sh", {{"--order", "2"}, {"--rays", "8"}},
                                                     scene, input, {{0, 4}}, ctx);
  EXPECT_EQ(error({sh_part[0], parts[1], parts[2]}),
            "shadowfield merge: shard 0 is not a shard of technique shadowfield");
  // A bake with no range beyond its units.
  EXPECT_THROW(
      prt_test::make_shard_test_bake("shadowfield", kCheap)->bake_shard(scene, input, 10, 3, ctx),
      Error);
}

}  // namespace
}  // namespace prt::bake
