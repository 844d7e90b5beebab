// SPDX-License-Identifier: MIT
// A technique's bake run whole and run as shards (TechniqueBake::bake_shard, merge_shards), the
// way prt-bake runs them but in process, for the techniques' shard tests: each shard and the
// merge get a bake of their own, as they would on a farm.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "prt/baker/technique.hpp"

namespace prt_test {

// Option name and value as the command line spells them: {"--order", "3"}.
using ShardTestArgs = std::vector<std::pair<std::string, std::string>>;

// A bake of `technique` with `args` set, as the command sets them (marking them given).
inline std::unique_ptr<prt::bake::TechniqueBake> make_shard_test_bake(const std::string& technique,
                                                                      const ShardTestArgs& args) {
  const prt::bake::Technique* entry = prt::bake::find_technique(technique);
  if (!entry) throw prt::bake::Error("no technique " + technique);
  std::unique_ptr<prt::bake::TechniqueBake> bake = entry->make_bake();
  std::vector<std::string> flat;
  for (const auto& [name, value] : args) flat.insert(flat.end(), {name, value});
  prt::bake::apply_option_args(bake->options(), flat);
  return bake;
}

inline prt::bake::Context two_threads() {
  prt::bake::Context ctx;
  ctx.threads = 2;
  return ctx;
}

// bake(), quantize(), write(): the blob of the whole bake.
inline std::vector<std::uint8_t> whole_bake_blob(const std::string& technique,
                                                 const ShardTestArgs& args,
                                                 const prt::bake::Scene& scene,
                                                 const prt::bake::BakeInput& input,
                                                 const prt::bake::Context& ctx) {
  const auto bake = make_shard_test_bake(technique, args);
  bake->bake(scene, input, ctx);
  bake->quantize();
  return bake->write(scene, input);
}

// Splits `units` into ranges of these sizes, the last taking the rest.
inline std::vector<std::pair<std::size_t, std::size_t>> shard_test_ranges(
    std::size_t units, const std::vector<std::size_t>& sizes) {
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  std::size_t first = 0;
  for (std::size_t size : sizes) {
    ranges.emplace_back(first, size);
    first += size;
  }
  ranges.emplace_back(first, units - first);
  return ranges;
}

// One payload per range, each from a fresh bake.
inline std::vector<std::vector<std::uint8_t>> bake_shard_payloads(
    const std::string& technique, const ShardTestArgs& args, const prt::bake::Scene& scene,
    const prt::bake::BakeInput& input,
    const std::vector<std::pair<std::size_t, std::size_t>>& ranges, const prt::bake::Context& ctx) {
  std::vector<std::vector<std::uint8_t>> parts;
  for (const auto& [first, count] : ranges)
    parts.push_back(
        make_shard_test_bake(technique, args)->bake_shard(scene, input, first, count, ctx));
  return parts;
}

// merge_shards(), quantize(), write() in a fresh bake, then the self-check of the blob (which
// must pass: the merge leaves the bake as bake() does).
inline std::vector<std::uint8_t> merged_bake_blob(
    const std::string& technique, const ShardTestArgs& args, const prt::bake::Scene& scene,
    const prt::bake::BakeInput& input, const std::vector<std::vector<std::uint8_t>>& parts,
    const prt::bake::Context& ctx) {
  const auto bake = make_shard_test_bake(technique, args);
  bake->merge_shards(scene, input, parts, ctx);
  bake->quantize();
  std::vector<std::uint8_t> blob = bake->write(scene, input);
  const prt::bake::SelfCheck check = bake->self_check(blob);
  EXPECT_TRUE(check.passed) << check.message;
  return blob;
}

// The message merge_shards throws for these parts ("" when it does not throw).
inline std::string merge_shards_error(const std::string& technique, const ShardTestArgs& args,
                                      const prt::bake::Scene& scene,
                                      const prt::bake::BakeInput& input,
                                      const std::vector<std::vector<std::uint8_t>>& parts,
                                      const prt::bake::Context& ctx) {
  try {
    make_shard_test_bake(technique, args)->merge_shards(scene, input, parts, ctx);
  } catch (const prt::bake::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace prt_test
