// SPDX-License-Identifier: MIT
// Technique `cloth` split into shards (docs/farm.md). The unit is a view of the tables' grid (a
// column of every T and T_c): each step of the sampling that costs (W on the maps and along the
// cones, which calls the runtime's thread weights, and the lobe sums of T) is per view, so a
// shard's columns are the whole bake's bit for bit and no shard repeats another's W calls; only
// the lobe stencils, which depend on the lobe row and not on the view, are built again in every
// shard. The merge joins the columns and runs the truncated SVD of each table: it needs every
// view of a table at once, so it is not spread.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "prt/baker/cloth/cloth_tables.hpp"

#include "../common/numbers.hpp"
#include "../common/shard_payload.hpp"
#include "cloth_technique.hpp"

namespace prt::bake {
namespace {

// A shard's payload: this header, the fabrics as given and as named in the scene (chars, joined
// by commas), then per table (in the order of plan_cloth_tables) its T and its T_c for the
// range's views, rows() x count floats each, row-major. Native byte order.
constexpr std::uint32_t kClothShardMagic = 0x44534c43;  // "CLSD"
constexpr std::uint32_t kClothShardVersion = 1;
struct ClothShardHeader {
  std::uint32_t magic = kClothShardMagic, version = kClothShardVersion;
  std::uint32_t xi_size = 0, levels = 0, view_theta = 0, view_phi = 0;
  float lambda_min = 0.0f, lambda_max = 0.0f;
  std::uint32_t rank = 0, bits = 0;
  double energy = 0.0;
  std::uint32_t fabrics = 0, tables = 0;
  std::uint64_t scene = 0;  // shard_scene_fingerprint with --fabric scene, else 0
  std::uint64_t views = 0, first = 0, count = 0;
  std::uint64_t given_chars = 0, named_chars = 0;  // of the two texts that follow
  double seconds = 0.0;                            // sampling
};
static_assert(sizeof(ClothShardHeader) == 112, "ClothShardHeader has padding");

std::string cloth_shard_joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ",") + name;
  return text;
}

std::string cloth_shard_named(const ClothShardSettings& s) {
  std::vector<std::string> names;
  for (const ClothFabricSource& f : s.fabrics) names.push_back(f.name);
  return cloth_shard_joined(names);
}

bool cloth_shard_names_scene(const ClothShardSettings& s) {
  for (const std::string& name : s.fabric_names)
    if (name == "scene") return true;
  return false;
}

std::size_t cloth_shard_table_count(const ClothShardSettings& s) {
  std::vector<prt_cloth_weave> weaves;
  for (const ClothFabricSource& f : s.fabrics) weaves.push_back(f.weave);
  return plan_cloth_tables(weaves).tables.size();
}

// What a shard of this bake states about it, the range and time left 0.
ClothShardHeader cloth_shard_header(const Scene& scene, const ClothShardSettings& s) {
  const ClothGrid& g = s.options.grid;
  ClothShardHeader h;
  h.xi_size = g.xi_size;
  h.levels = g.lambda_levels;
  h.view_theta = g.view_theta;
  h.view_phi = g.view_phi;
  h.lambda_min = g.lambda_min;
  h.lambda_max = g.lambda_max;
  h.rank = s.options.factor.fixed_rank;
  h.bits = std::uint32_t(s.bits);
  h.energy = s.options.factor.energy;
  h.fabrics = std::uint32_t(s.fabrics.size());
  h.tables = std::uint32_t(cloth_shard_table_count(s));
  h.scene = cloth_shard_names_scene(s) ? shard_scene_fingerprint(scene) : 0;
  h.views = g.columns();
  h.given_chars = cloth_shard_joined(s.fabric_names).size();
  h.named_chars = cloth_shard_named(s).size();
  return h;
}

// Reads nothing for no values: ShardPayloadReader would memcpy into an empty vector's null data.
std::vector<float> cloth_shard_floats(ShardPayloadReader& in, std::uint64_t count) {
  return count == 0 ? std::vector<float>() : in.get_vector<float>(count);
}

std::string cloth_shard_text(ShardPayloadReader& in, std::uint64_t chars) {
  if (chars == 0) return std::string();
  const std::vector<char> text = in.get_vector<char>(chars);
  return std::string(text.begin(), text.end());
}

// Reads a part's header and fabrics; Error naming what differs from `expected` (this merge's).
ClothShardHeader cloth_shard_read_header(ShardPayloadReader& in, const ClothShardHeader& expected,
                                         const ClothShardSettings& s) {
  const ClothShardHeader h = in.get<ClothShardHeader>();
  if (h.magic != kClothShardMagic) throw Error(in.who() + " is not a shard of technique cloth");
  if (h.version != kClothShardVersion) {
    throw Error(in.who() + " has cloth shard version " + std::to_string(h.version) +
                ", this baker reads " + std::to_string(kClothShardVersion));
  }
  const std::string given = cloth_shard_text(in, h.given_chars);
  const std::string named = cloth_shard_text(in, h.named_chars);
  ShardSettingsDiff diff;
  diff.compare("--fabric", given, cloth_shard_joined(s.fabric_names));
  diff.compare("--xi-size", h.xi_size, expected.xi_size);
  diff.compare("--levels", h.levels, expected.levels);
  diff.compare("--view-theta", h.view_theta, expected.view_theta);
  diff.compare("--view-phi", h.view_phi, expected.view_phi);
  diff.compare("--energy", h.energy, expected.energy);
  diff.compare("--rank", h.rank, expected.rank);
  diff.compare("--bits", h.bits, expected.bits);
  diff.compare("the lowest sharpness", double(h.lambda_min), double(expected.lambda_min));
  diff.compare("the highest sharpness", double(h.lambda_max), double(expected.lambda_max));
  diff.check(in.who());
  if (named != cloth_shard_named(s)) {
    throw Error(in.who() + " was baked for fabrics " + named +
                " (this merge: " + cloth_shard_named(s) + ")");
  }
  if (h.scene != expected.scene)
    throw Error(in.who() + " was baked from another scene (its geometry or materials differ)");
  if (h.fabrics != expected.fabrics || h.tables != expected.tables || h.views != expected.views) {
    throw Error(in.who() + " has " + std::to_string(h.tables) + " tables of " +
                std::to_string(h.views) + " views, this merge " + std::to_string(expected.tables) +
                " of " + std::to_string(expected.views));
  }
  // Before the data is read: a range within the views bounds its size.
  if (h.first > h.views || h.count > h.views - h.first) {
    throw Error(in.who() + " has views [" + std::to_string(h.first) + ", " +
                std::to_string(h.first + h.count) + "), beyond the grid's " +
                std::to_string(h.views));
  }
  return h;
}

// Copies a part's rows x count values into columns [first, first + count) of a rows x columns
// table.
void cloth_shard_place(const std::vector<float>& part, std::uint64_t rows, std::uint64_t columns,
                       std::uint64_t first, std::uint64_t count, std::vector<float>& table) {
  for (std::uint64_t r = 0; r < rows; ++r)
    std::copy(part.begin() + std::ptrdiff_t(r * count),
              part.begin() + std::ptrdiff_t(r * count + count),
              table.begin() + std::ptrdiff_t(r * columns + first));
}

}  // namespace

std::vector<std::uint8_t> bake_cloth_shard(const Scene& scene, const ClothShardSettings& settings,
                                           std::size_t first, std::size_t count,
                                           const Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<ClothTableSamples> samples =
      sample_cloth_tables_of(settings.fabrics, settings.options, first, count, ctx);
  ClothShardHeader h = cloth_shard_header(scene, settings);
  h.first = first;
  h.count = count;
  h.seconds = seconds_since(start);
  ShardPayloadWriter out;
  out.put(h);
  const std::string given = cloth_shard_joined(settings.fabric_names);
  const std::string named = cloth_shard_named(settings);
  out.put_array(given.data(), given.size());
  out.put_array(named.data(), named.size());
  for (const ClothTableSamples& table : samples) {
    out.put_vector(table.full);
    out.put_vector(table.cone);
  }
  return std::move(out).bytes();
}

ClothTablesBake merge_cloth_shards(const Scene& scene, const ClothShardSettings& settings,
                                   const std::vector<std::vector<std::uint8_t>>& parts,
                                   const Context& ctx) {
  const ClothShardHeader expected = cloth_shard_header(scene, settings);
  const std::uint64_t rows = settings.options.grid.rows(), columns = expected.views;
  std::vector<ClothTableSamples> tables(expected.tables);
  for (ClothTableSamples& t : tables) {
    t.full.assign(rows * columns, 0.0f);
    t.cone.assign(rows * columns, 0.0f);
  }
  std::vector<ShardPartRange> spans;
  double seconds = 0.0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    ShardPayloadReader in(parts[i], "cloth merge: shard " + std::to_string(i));
    const ClothShardHeader h = cloth_shard_read_header(in, expected, settings);
    spans.push_back({h.first, h.count, h.views});
    for (ClothTableSamples& t : tables) {
      cloth_shard_place(cloth_shard_floats(in, rows * h.count), rows, columns, h.first, h.count,
                        t.full);
      cloth_shard_place(cloth_shard_floats(in, rows * h.count), rows, columns, h.first, h.count,
                        t.cone);
    }
    in.finish();
    seconds += h.seconds;
  }
  check_shard_ranges("cloth", "views", spans, columns);
  ClothTablesBake bake =
      factor_cloth_tables(settings.fabrics, settings.options, std::move(tables), ctx);
  bake.sample_seconds = seconds;
  return bake;
}

}  // namespace prt::bake
