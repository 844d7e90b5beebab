// SPDX-License-Identifier: MIT
// Distributed bakes (docs/farm.md): `prt-bake bake <t> SCENE --shard i/N -o PART` bakes the i-th
// of N even ranges of the technique's units (TechniqueBake::shard_units: vertices for sh and
// wavelet) into a shard file; `prt-bake merge -o OUT.prtk PART...` checks that the parts are one
// whole bake and writes the blob the whole bake writes, byte for byte.
//
// A shard file names its bake: the technique, the options as given, the seed and albedo, the
// scene as given and a hash of its bytes, and the baker's version. The merge refuses a set with a
// part missing or repeated, or a part of another bake, naming the file and what differs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/baker/technique.hpp"

namespace prt::bake {

// "i/N": shard i (from 0) of N.
struct ShardSpec {
  std::size_t index = 0, count = 1;
};
// Throws Error unless the text is i/N with 0 <= i < N.
ShardSpec parse_shard_spec(const std::string& text);
// Shard `spec`'s units of `units`: [first, first + count), the N ranges covering them in order,
// their sizes differing by at most one.
struct ShardRange {
  std::size_t first = 0, count = 0;
};
ShardRange shard_range(std::size_t units, const ShardSpec& spec);

struct ShardFile {
  std::string technique;
  std::vector<std::string> args;  // the technique's options as given, in command-line order
  std::uint32_t seed = 0;
  std::string albedo;
  std::string scene;       // SCENE as given to the bake
  std::string scene_hash;  // of the scene file's bytes
  std::string baker_version;
  std::string unit;  // what the ranges count ("vertices")
  ShardSpec spec;
  std::size_t units = 0;  // in the whole bake
  ShardRange range;
  std::vector<std::uint8_t> payload;  // TechniqueBake::bake_shard's bytes

  // Everything but the part: two shards of one bake have the same key.
  std::string bake_key() const;
};

std::vector<std::uint8_t> encode_shard(const ShardFile& shard);
// Throws Error naming `path` when the bytes are not a whole shard file (bad magic, truncated,
// checksum mismatch).
ShardFile decode_shard(const std::vector<std::uint8_t>& bytes, const std::string& path);

// Orders the shards of `paths` by index and checks that they are every part of one bake, once;
// throws Error naming the file and what differs otherwise.
std::vector<ShardFile> check_shard_set(std::vector<ShardFile> shards,
                                       const std::vector<std::string>& paths);

// prt-bake bake <t> --shard: imports input.scene, bakes shard `spec` with `bake` (whose options
// hold `given_args`) and writes the shard file to input.output.
void run_shard_bake(const Technique& technique, TechniqueBake& bake, const BakeInput& input,
                    const std::vector<std::string>& given_args, const ShardSpec& spec,
                    const Context& ctx);

// prt-bake merge: reads and checks the shards, re-imports their scene (which must still have
// the bytes they were baked from), merges and finishes the bake (finish_bake) into `output`
// (and `report` when not empty).
void run_merge(const std::vector<std::string>& shard_paths, const std::string& output,
               const std::string& report, const Context& ctx);

}  // namespace prt::bake
