// SPDX-License-Identifier: MIT
// Shard files, their checks, and the shard and merge commands (prt/baker/shards.hpp).
#include "prt/baker/shards.hpp"

#include <prt/prt_version.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../common/atomic_file.hpp"
#include "../common/shard_payload.hpp"
#include "content_hash.hpp"

namespace prt::bake {
namespace {

using nlohmann::ordered_json;

// File layout: magic, version (u32), header length (u64), header (JSON), payload length (u64),
// payload, then the 32 hex digits of the XXH3-128 hash of everything before them.
constexpr char kShardMagic[8] = {'P', 'R', 'T', 'S', 'H', 'A', 'R', 'D'};
constexpr std::uint32_t kShardVersion = 1;
constexpr std::size_t kShardDigest = 32;

std::string digest_of(const std::uint8_t* data, std::size_t size) {
  ContentHash hash;
  hash.bytes(data, size);
  return hash.hex();
}

ordered_json header_json(const ShardFile& s) {
  return ordered_json{{"technique", s.technique},
                      {"args", s.args},
                      {"seed", s.seed},
                      {"albedo", s.albedo},
                      {"scene", s.scene},
                      {"scene_hash", s.scene_hash},
                      {"baker_version", s.baker_version},
                      {"unit", s.unit},
                      {"index", s.spec.index},
                      {"count", s.spec.count},
                      {"units", s.units},
                      {"first", s.range.first},
                      {"range_count", s.range.count}};
}

ShardFile from_header(const ordered_json& j) {
  ShardFile s;
  s.technique = j.at("technique");
  s.args = j.at("args").get<std::vector<std::string>>();
  s.seed = j.at("seed");
  s.albedo = j.at("albedo");
  s.scene = j.at("scene");
  s.scene_hash = j.at("scene_hash");
  s.baker_version = j.at("baker_version");
  s.unit = j.at("unit");
  s.spec.index = j.at("index");
  s.spec.count = j.at("count");
  s.units = j.at("units");
  s.range.first = j.at("first");
  s.range.count = j.at("range_count");
  return s;
}

// What makes two shards parts of different bakes, in words, or "" when nothing does.
std::string difference(const ShardFile& a, const ShardFile& b) {
  if (a.technique != b.technique) return "technique " + b.technique + ", not " + a.technique;
  if (a.scene_hash != b.scene_hash || a.scene != b.scene) return "another scene (or its bytes)";
  if (a.args != b.args || a.seed != b.seed || a.albedo != b.albedo) return "other settings";
  if (a.baker_version != b.baker_version) return "baker " + b.baker_version;
  if (a.spec.count != b.spec.count)
    return "a split into " + std::to_string(b.spec.count) + " parts, not " +
           std::to_string(a.spec.count);
  if (a.units != b.units) return "another unit count";
  return "";
}

std::vector<std::uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read");
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in),
                                   std::istreambuf_iterator<char>());
}

}  // namespace

ShardSpec parse_shard_spec(const std::string& text) {
  ShardSpec spec;
  std::istringstream in(text);
  char slash = 0, rest = 0;
  long long index = -1, count = 0;
  if (!(in >> index >> slash >> count) || slash != '/' || (in >> rest) || count < 1 || index < 0 ||
      index >= count)
    throw Error("--shard: expected i/N with 0 <= i < N (e.g. 0/4), got '" + text + "'");
  spec.index = std::size_t(index);
  spec.count = std::size_t(count);
  return spec;
}

ShardRange shard_range(std::size_t units, const ShardSpec& spec) {
  const std::size_t first = spec.index * units / spec.count;
  const std::size_t end = (spec.index + 1) * units / spec.count;
  return {first, end - first};
}

std::string ShardFile::bake_key() const {
  ContentHash hash;
  hash.text(technique).value(args.size());
  for (const std::string& arg : args) hash.text(arg);
  hash.value(seed).text(albedo).text(scene).text(scene_hash).text(baker_version);
  hash.value(spec.count).value(units);
  return hash.hex();
}

std::vector<std::uint8_t> encode_shard(const ShardFile& shard) {
  ShardPayloadWriter writer;
  writer.put_array(kShardMagic, sizeof kShardMagic);
  writer.put(kShardVersion);
  const std::string header = header_json(shard).dump();
  writer.put(std::uint64_t(header.size()));
  writer.put_array(header.data(), header.size());
  writer.put(std::uint64_t(shard.payload.size()));
  writer.put_vector(shard.payload);
  std::vector<std::uint8_t> out = std::move(writer).bytes();
  const std::string digest = digest_of(out.data(), out.size());
  out.insert(out.end(), digest.begin(), digest.end());
  return out;
}

ShardFile decode_shard(const std::vector<std::uint8_t>& bytes, const std::string& path) {
  if (bytes.size() < sizeof kShardMagic + kShardDigest ||
      std::memcmp(bytes.data(), kShardMagic, sizeof kShardMagic) != 0)
    throw Error(path + ": not a prtkit shard file");
  const std::size_t body = bytes.size() - kShardDigest;
  if (digest_of(bytes.data(), body) !=
      std::string(bytes.begin() + std::ptrdiff_t(body), bytes.end()))
    throw Error(path + ": the shard file is damaged (its checksum does not match)");
  const std::vector<std::uint8_t> in(bytes.begin(), bytes.begin() + std::ptrdiff_t(body));
  ShardPayloadReader reader(in, path + ": not a whole shard file");
  reader.get_vector<char>(sizeof kShardMagic);
  if (const auto version = reader.get<std::uint32_t>(); version != kShardVersion)
    throw Error(path + ": shard file version " + std::to_string(version) + ", this baker reads " +
                std::to_string(kShardVersion));
  const std::vector<char> header = reader.get_vector<char>(reader.get<std::uint64_t>());
  ShardFile shard;
  try {
    shard = from_header(ordered_json::parse(header.begin(), header.end()));
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": the shard's header does not read: " + e.what());
  }
  shard.payload = reader.get_vector<std::uint8_t>(reader.get<std::uint64_t>());
  reader.finish();
  return shard;
}

std::vector<ShardFile> check_shard_set(std::vector<ShardFile> shards,
                                       const std::vector<std::string>& paths) {
  if (shards.empty()) throw Error("merge: no shards given");
  const ShardFile& first = shards.front();
  std::vector<int> owner(first.spec.count, -1);
  for (std::size_t i = 0; i < shards.size(); ++i) {
    const std::string differs = difference(first, shards[i]);
    if (!differs.empty())
      throw Error(paths[i] + ": belongs to another bake than " + paths[0] + " (" + differs + ")");
    const ShardFile& s = shards[i];
    const ShardRange expected = shard_range(s.units, s.spec);
    if (s.range.first != expected.first || s.range.count != expected.count)
      throw Error(paths[i] + ": its range does not match shard " + std::to_string(s.spec.index) +
                  "/" + std::to_string(s.spec.count));
    int& seen = owner[s.spec.index];
    if (seen >= 0)
      throw Error(paths[i] + " and " + paths[std::size_t(seen)] + " are both shard " +
                  std::to_string(s.spec.index) + "/" + std::to_string(s.spec.count));
    seen = int(i);
  }
  for (std::size_t k = 0; k < owner.size(); ++k) {
    if (owner[k] < 0)
      throw Error("merge: shard " + std::to_string(k) + "/" + std::to_string(first.spec.count) +
                  " is missing (" + std::to_string(shards.size()) + " of " +
                  std::to_string(first.spec.count) + " given)");
  }
  std::sort(shards.begin(), shards.end(),
            [](const ShardFile& a, const ShardFile& b) { return a.spec.index < b.spec.index; });
  return shards;
}

void run_shard_bake(const Technique& technique, TechniqueBake& bake, const BakeInput& input,
                    const std::vector<std::string>& given_args, const ShardSpec& spec,
                    const Context& ctx) {
  const Scene scene = import_bake_scene(input, ctx);
  ShardFile shard;
  shard.technique = technique.name();
  shard.args = given_args;
  shard.seed = input.seed;
  shard.albedo = input.albedo;
  shard.scene = input.scene;
  shard.scene_hash = file_hash(input.scene);
  shard.baker_version = PRT_VERSION_STRING;
  shard.unit = bake.shard_unit();
  shard.spec = spec;
  shard.units = bake.shard_units(scene);
  if (shard.units == 0)
    throw Error(std::string("--shard: technique ") + technique.name() +
                "'s bake does not split into shards");
  shard.range = shard_range(shard.units, spec);
  shard.payload = bake.bake_shard(scene, input, shard.range.first, shard.range.count, ctx);
  write_file_atomic(input.output, encode_shard(shard));
  ctx.info("shard " + std::to_string(spec.index) + "/" + std::to_string(spec.count) + ": " +
           shard.unit + " " + std::to_string(shard.range.first) + " to " +
           std::to_string(shard.range.first + shard.range.count) + " of " +
           std::to_string(shard.units) + "; wrote " + input.output);
}

void run_merge(const std::vector<std::string>& shard_paths, const std::string& output,
               const std::string& report, const Context& ctx) {
  std::vector<ShardFile> shards;
  for (const std::string& path : shard_paths) shards.push_back(decode_shard(read_file(path), path));
  shards = check_shard_set(std::move(shards), shard_paths);
  const ShardFile& first = shards.front();
  const Technique* technique = find_technique(first.technique);
  if (!technique) throw Error("merge: this baker has no technique '" + first.technique + "'");
  if (first.baker_version != PRT_VERSION_STRING)
    throw Error("merge: the shards were baked by prt-bake " + first.baker_version + ", this is " +
                PRT_VERSION_STRING);
  if (file_hash(first.scene) != first.scene_hash)
    throw Error("merge: " + first.scene + " has changed since its shards were baked");

  std::unique_ptr<TechniqueBake> bake = technique->make_bake();
  apply_option_args(bake->options(), first.args);
  BakeInput input;
  input.scene = first.scene;
  input.albedo = first.albedo;
  input.seed = first.seed;
  input.output = output;
  input.report = report;
  const Scene scene = import_bake_scene(input, ctx);
  std::vector<std::vector<std::uint8_t>> parts;
  for (ShardFile& shard : shards) parts.push_back(std::move(shard.payload));
  bake->merge_shards(scene, input, parts, ctx);
  finish_bake(*bake, scene, input, ctx);
}

}  // namespace prt::bake
