// SPDX-License-Identifier: MIT
// Shard files and the checks the merge makes before it trusts a set (prt/baker/shards.hpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/shards.hpp"
#include "support/command.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

ShardFile shard_of(std::size_t index, std::size_t count, std::size_t units = 10) {
  ShardFile s;
  s.technique = "sh";
  s.args = {"--order=4"};
  s.seed = 3;
  s.scene = "scene.glb";
  s.scene_hash = "abc";
  s.baker_version = "0.1.0";
  s.unit = "vertices";
  s.spec = {index, count};
  s.units = units;
  s.range = shard_range(units, s.spec);
  s.payload = {std::uint8_t(index), 7, 9};
  return s;
}

std::string refusal(std::vector<ShardFile> shards) {
  std::vector<std::string> paths;
  for (std::size_t i = 0; i < shards.size(); ++i) paths.push_back("part" + std::to_string(i));
  try {
    check_shard_set(std::move(shards), paths);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ShardSpec, ParsesIOfNAndRefusesTheRest) {
  const ShardSpec spec = parse_shard_spec("2/5");
  EXPECT_EQ(spec.index, 2u);
  EXPECT_EQ(spec.count, 5u);
  for (const char* bad : {"5/5", "-1/4", "1/0", "1", "1/4x", "a/b", ""})
    EXPECT_THROW(parse_shard_spec(bad), Error) << bad;
}

TEST(ShardRange, TheRangesCoverEveryUnitOnceInOrder) {
  for (std::size_t units : {0u, 1u, 7u, 10u, 1000003u}) {
    for (std::size_t count : {1u, 2u, 3u, 4u, 16u}) {
      std::size_t next = 0, smallest = units, largest = 0;
      for (std::size_t i = 0; i < count; ++i) {
        const ShardRange r = shard_range(units, {i, count});
        EXPECT_EQ(r.first, next) << units << " " << count;
        next += r.count;
        smallest = std::min(smallest, r.count);
        largest = std::max(largest, r.count);
      }
      EXPECT_EQ(next, units);
      EXPECT_LE(largest - smallest, 1u);
    }
  }
}

TEST(ShardFile, RoundTripsAndRefusesDamage) {
  const ShardFile s = shard_of(1, 3);
  const std::vector<std::uint8_t> bytes = encode_shard(s);
  const ShardFile back = decode_shard(bytes, "x");
  EXPECT_EQ(back.bake_key(), s.bake_key());
  EXPECT_EQ(back.payload, s.payload);
  EXPECT_EQ(back.range.first, s.range.first);
  EXPECT_EQ(back.range.count, s.range.count);

  std::vector<std::uint8_t> flipped = bytes;
  flipped[flipped.size() / 2] ^= 1;
  EXPECT_THROW(decode_shard(flipped, "x"), Error);
  const std::vector<std::uint8_t> cut(bytes.begin(), bytes.end() - 1);
  EXPECT_THROW(decode_shard(cut, "x"), Error);
  EXPECT_THROW(decode_shard({1, 2, 3}, "x"), Error);
}

TEST(ShardSet, IsOrderedByIndex) {
  const std::vector<ShardFile> set =
      check_shard_set({shard_of(2, 3), shard_of(0, 3), shard_of(1, 3)}, {"c", "a", "b"});
  for (std::size_t i = 0; i < set.size(); ++i) EXPECT_EQ(set[i].spec.index, i);
}

TEST(ShardSet, RefusesAMissingRepeatedOrForeignPart) {
  EXPECT_NE(refusal({shard_of(0, 3), shard_of(2, 3)}).find("shard 1/3 is missing"),
            std::string::npos);
  EXPECT_NE(refusal({shard_of(0, 2), shard_of(1, 2), shard_of(1, 2)}).find("are both shard 1/2"),
            std::string::npos);
  ShardFile other_seed = shard_of(1, 2);
  other_seed.seed = 4;
  EXPECT_NE(refusal({shard_of(0, 2), other_seed})
                .find("part1: belongs to another bake than "
                      "part0 (other settings)"),
            std::string::npos);
  ShardFile other_scene = shard_of(1, 2);
  other_scene.scene_hash = "abd";
  EXPECT_NE(refusal({shard_of(0, 2), other_scene}).find("another scene"), std::string::npos);
  EXPECT_NE(refusal({shard_of(0, 2), shard_of(1, 3)}).find("a split into 3 parts, not 2"),
            std::string::npos);
  ShardFile moved = shard_of(1, 2);
  moved.range.first += 1;
  EXPECT_NE(refusal({shard_of(0, 2), moved}).find("its range does not match"), std::string::npos);
  EXPECT_NE(refusal({}).find("no shards"), std::string::npos);
}

// Through the command, as a farm runs it: shards baked in any order merge into the bytes of the
// whole bake, and a merge that is refused writes nothing.
TEST(PrtBakeMerge, ShardsMergeIntoTheWholeBakesBytes) {
  prt_test::TempDir dir("prt_bake_merge");
  Scene scene;
  scene.materials.resize(1);
  scene.meshes.push_back(make_plane_mesh("ground", 0, 1.0f, 1.0f, 8, 8));
  scene.meshes.push_back(make_sphere_mesh(0, {0.0f, 0.3f, 0.0f}, 0.3f, 8, 16));
  write_glb(scene, dir.file("two.glb"));
  const auto prt_bake = [&](const std::string& args, const std::string& log) {
    return prt_test::run_command(PRT_BAKE_EXE, "--threads 2 " + args, dir.file(log));
  };
  const std::string bake = "bake sh " + prt_test::shell_quote(dir.file("two.glb")) +
                           " --order 3 --rays 32 --transfer interreflected";
  ASSERT_EQ(prt_bake(bake + " -o " + dir.file("whole.prtk"), "whole.log").exit_code, 0);
  for (const char* i : {"2", "0", "1"}) {
    const auto r = prt_bake(bake + " --shard " + i + "/3 -o " + dir.file(std::string(i) + ".shard"),
                            std::string("shard") + i + ".log");
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const std::string parts =
      dir.file("1.shard") + " " + dir.file("2.shard") + " " + dir.file("0.shard");
  const auto merged = prt_bake("merge -o " + dir.file("merged.prtk") + " " + parts, "merge.log");
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  EXPECT_EQ(prt_test::read_bytes(dir.file("merged.prtk")),
            prt_test::read_bytes(dir.file("whole.prtk")));

  const auto refused = prt_bake("merge -o " + dir.file("refused.prtk") + " " + dir.file("0.shard") +
                                    " " + dir.file("2.shard"),
                                "refused.log");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("shard 1/3 is missing"), std::string::npos) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("refused.prtk")));

  const auto no_report =
      prt_bake(bake + " --shard 0/3 -o x.shard --report x.json", "no_report.log");
  EXPECT_NE(no_report.exit_code, 0);
  EXPECT_NE(no_report.output.find("give it to `prt-bake merge`"), std::string::npos);
}

// Every technique through the command: 3 shards, given in another order, merge into the bytes
// of the whole bake, each technique at settings cheap enough for a test.
struct CommandShardCase {
  const char* technique;
  const char* scene;  // "two" (the ground and sphere written here) or a golden scene's file
  const char* options;
};

class PrtBakeMergeEveryTechnique : public ::testing::TestWithParam<CommandShardCase> {};

TEST_P(PrtBakeMergeEveryTechnique, ShardsMergeIntoTheWholeBakesBytes) {
  const CommandShardCase& c = GetParam();
  prt_test::TempDir dir(std::string("prt_bake_merge_") + c.technique);
  std::string scene = std::string(PRT_GOLDEN_DIR) + "/scenes/" + c.scene;
  if (std::string(c.scene) == "two") {
    Scene two;
    two.materials.resize(1);
    two.meshes.push_back(make_plane_mesh("ground", 0, 1.0f, 1.0f, 4, 4));
    two.meshes.push_back(make_sphere_mesh(0, {0.0f, 0.3f, 0.0f}, 0.3f, 6, 12));
    scene = dir.file("two.glb");
    write_glb(two, scene);
  }
  const auto prt_bake = [&](const std::string& args, const std::string& log) {
    return prt_test::run_command(PRT_BAKE_EXE, "--threads 2 " + args, dir.file(log));
  };
  const std::string bake =
      std::string("bake ") + c.technique + " " + prt_test::shell_quote(scene) + " " + c.options;
  const auto whole = prt_bake(bake + " -o " + dir.file("whole.prtk"), "whole.log");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  std::string parts;
  for (const char* i : {"1", "2", "0"}) {
    const auto r = prt_bake(bake + " --shard " + i + "/3 -o " + dir.file(std::string(i) + ".shard"),
                            std::string("shard") + i + ".log");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    parts += " " + dir.file(std::string(i) + ".shard");
  }
  const auto merged = prt_bake("merge -o " + dir.file("merged.prtk") + parts, "merge.log");
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  const std::string whole_bytes = prt_test::read_bytes(dir.file("whole.prtk"));
  ASSERT_FALSE(whole_bytes.empty());
  EXPECT_EQ(prt_test::read_bytes(dir.file("merged.prtk")), whole_bytes);
}

INSTANTIATE_TEST_SUITE_P(
    Techniques, PrtBakeMergeEveryTechnique,
    ::testing::Values(
        CommandShardCase{"sh", "two", "--order 3 --rays 16"},
        CommandShardCase{"wavelet", "two", "--keep 16 --cube 16 --bounces 1"},
        CommandShardCase{"pose", "hinge.gltf", "--order 3 --rays 16 --rate 4 --basis-dims 2"},
        CommandShardCase{"cloth", "two",
                         "--xi-size 4 --levels 2 --view-theta 3 --view-phi 2 --bits 8"},
        CommandShardCase{"shadowfield", "two",
                         "--order 2 --shells 3 --face-size 2 --srf-shells 2 --srf-face-size 2 "
                         "--basis 3 --lights 12 --field-rays 32 --transfer-rays 16 --srf-rays 32 "
                         "--brdf-grid 8"}),
    [](const ::testing::TestParamInfo<CommandShardCase>& info) {
      return std::string(info.param.technique);
    });

}  // namespace
}  // namespace prt::bake
