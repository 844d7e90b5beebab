// SPDX-License-Identifier: MIT
// Which tables a set of fabrics needs and how their tangents share them, and the CLTH section of
// the fabrics with their sampled and factored tables (formats/SPEC.md §7.4).
#include "prt/baker/cloth/cloth_tables.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <utility>

#include "../common/numbers.hpp"
#include "../render/parallel_tasks.hpp"

namespace prt::bake {
namespace {

// A thread's multiset: (offset, multiplicity) by ascending offset, -0 written as 0.
using Multiset = std::vector<std::pair<float, std::uint32_t>>;

float without_negative_zero(float offset) {
  return offset == 0.0f ? 0.0f : offset;
}

Multiset multiset_of(const prt_cloth_weave& weave, int thread) {
  Multiset set;
  for (std::uint32_t k = 0; k < weave.tangent_count[thread]; ++k)
    set.emplace_back(without_negative_zero(weave.offsets[thread][k]),
                     weave.multiplicity[thread][k]);
  std::sort(set.begin(), set.end());
  return set;
}

// -S: every offset negated, so x -> -x of the canonical frame.
Multiset mirrored(const Multiset& set) {
  Multiset out;
  for (auto it = set.rbegin(); it != set.rend(); ++it)
    out.emplace_back(without_negative_zero(-it->first), it->second);
  return out;
}

ClothTableKey key_of(const Multiset& set, float offset) {
  ClothTableKey key;
  for (const auto& [tau, count] : set) {
    if (tau == offset) key.tangent = std::uint32_t(key.offsets.size());
    key.offsets.push_back(tau);
    key.multiplicities.push_back(count);
  }
  return key;
}

// The table offset tau of multiset `set` reads: its own, or that of -tau in -S read mirrored.
ClothTableKey stored_key(const Multiset& set, float tau, bool& mirror) {
  const Multiset other = mirrored(set);
  if (other < set || (other == set && tau < 0.0f)) {
    mirror = true;
    return key_of(other, without_negative_zero(-tau));
  }
  mirror = false;
  return key_of(set, tau);
}

std::uint32_t table_index(std::vector<ClothTableKey>& tables, const ClothTableKey& key) {
  const auto it = std::find(tables.begin(), tables.end(), key);
  if (it != tables.end()) return std::uint32_t(it - tables.begin());
  tables.push_back(key);
  return std::uint32_t(tables.size() - 1);
}

void check_fabrics(const std::vector<ClothFabricSource>& fabrics) {
  if (fabrics.empty() || fabrics.size() > 64)
    throw Error("cloth tables: " + std::to_string(fabrics.size()) + " fabrics (must be 1..64)");
  for (const ClothFabricSource& f : fabrics) {
    if (prt_cloth_params_validate(&f.params) != PRT_OK)
      throw Error("cloth tables: fabric '" + f.name + "': invalid parameters");
    if (prt_cloth_weave_validate(&f.weave) != PRT_OK)
      throw Error("cloth tables: fabric '" + f.name + "': invalid weave");
  }
}

// The tables of each multiset (indices into `tables`), multisets in order of first table.
std::vector<std::vector<std::size_t>> multiset_groups(const std::vector<ClothTableKey>& tables) {
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t t = 0; t < tables.size(); ++t) {
    auto same = [&](const std::vector<std::size_t>& g) {
      return tables[g[0]].offsets == tables[t].offsets &&
             tables[g[0]].multiplicities == tables[t].multiplicities;
    };
    const auto it = std::find_if(groups.begin(), groups.end(), same);
    if (it == groups.end())
      groups.push_back({t});
    else
      it->push_back(t);
  }
  return groups;
}

// Factors samples[k] (table group[k]) into the section and its report: task 2k takes T, 2k + 1
// T_c.
void factor_tables(const std::vector<ClothTableSamples>& samples,
                   const std::vector<std::size_t>& group, const ClothTablesOptions& options,
                   const Context& ctx, ClothTablesBake& bake) {
  const std::uint64_t rows = options.grid.rows(), columns = options.grid.columns();
  render::parallel_tasks(2 * group.size(), ctx, "cloth tables: factoring", [&](std::size_t task) {
    const ClothTableSamples& s = samples[task / 2];
    ClothTable& table = bake.section.tables[group[task / 2]];
    ClothTableReport& report = bake.tables[group[task / 2]];
    if (task % 2 == 0)
      table.full = factor_cloth_table(s.full, rows, columns, options.factor, &report.full);
    else
      table.cone = factor_cloth_table(s.cone, rows, columns, options.factor, &report.cone);
  });
}

}  // namespace

ClothTablePlan plan_cloth_tables(const std::vector<prt_cloth_weave>& weaves) {
  ClothTablePlan plan;
  plan.threads.resize(weaves.size());
  for (std::size_t f = 0; f < weaves.size(); ++f) {
    const prt_cloth_weave& weave = weaves[f];
    if (prt_cloth_weave_validate(&weave) != PRT_OK)
      throw Error("cloth tables: weave " + std::to_string(f) + " is invalid");
    for (int j = 0; j < 2; ++j) {
      const Multiset set = multiset_of(weave, j);
      for (std::uint32_t k = 0; k < weave.tangent_count[j]; ++k) {
        ClothTangent tangent;
        tangent.offset = without_negative_zero(weave.offsets[j][k]);
        tangent.multiplicity = weave.multiplicity[j][k];
        tangent.table = table_index(plan.tables, stored_key(set, tangent.offset, tangent.mirror));
        plan.threads[f][j].push_back(tangent);
      }
    }
  }
  return plan;
}

namespace {

// The tables of one multiset sampled: group holds their indices in the plan, keys their keys.
using ClothGroupSampler = std::function<std::vector<ClothTableSamples>(
    const std::vector<std::size_t>& group, const std::vector<ClothTableKey>& keys)>;

// The section of the fabrics and its reports, each multiset's tables sampled by `sample_group`
// (a whole bake's sampling, or a merge's shards joined) and factored.
ClothTablesBake cloth_tables_by_multiset(const std::vector<ClothFabricSource>& fabrics,
                                         const ClothTablesOptions& options,
                                         const ClothGroupSampler& sample_group,
                                         const Context& ctx) {
  check_fabrics(fabrics);
  std::vector<prt_cloth_weave> weaves;
  for (const ClothFabricSource& f : fabrics) weaves.push_back(f.weave);
  const ClothTablePlan plan = plan_cloth_tables(weaves);

  ClothTablesBake bake;
  bake.section.grid = options.grid;
  // resize and assign: the fabric records are built in place.
  bake.section.fabrics.resize(fabrics.size());
  for (std::size_t f = 0; f < fabrics.size(); ++f) {
    bake.section.fabrics[f].name = fabrics[f].name;
    bake.section.fabrics[f].params = fabrics[f].params;
    bake.section.fabrics[f].threads = plan.threads[f];
  }

  const std::size_t count = plan.tables.size();
  bake.section.tables.resize(count);
  bake.tables.resize(count);
  // One multiset at a time (its tables share their W calls), each factored as soon as sampled so
  // that only one multiset's samples are held.
  for (const std::vector<std::size_t>& group : multiset_groups(plan.tables)) {
    std::vector<ClothTableKey> keys;
    for (const std::size_t t : group) keys.push_back(plan.tables[t]);
    auto start = std::chrono::steady_clock::now();
    const std::vector<ClothTableSamples> samples = sample_group(group, keys);
    bake.sample_seconds += seconds_since(start);
    start = std::chrono::steady_clock::now();
    factor_tables(samples, group, options, ctx, bake);
    bake.factor_seconds += seconds_since(start);
  }
  for (std::size_t t = 0; t < count; ++t) {
    ClothTableReport& report = bake.tables[t];
    report.key = plan.tables[t];
    report.bytes16 = cloth_factor_bytes(options.grid, report.full.rank, 16) +
                     cloth_factor_bytes(options.grid, report.cone.rank, 16);
    report.bytes8 = cloth_factor_bytes(options.grid, report.full.rank, 8) +
                    cloth_factor_bytes(options.grid, report.cone.rank, 8);
    ctx.info("cloth table " + std::to_string(t) + ": rank " + std::to_string(report.full.rank) +
             " (T), " + std::to_string(report.cone.rank) + " (T_c)");
  }
  return bake;
}

}  // namespace

ClothTablesBake bake_cloth_tables(const std::vector<ClothFabricSource>& fabrics,
                                  const ClothTablesOptions& options, const Context& ctx) {
  const auto sample = [&](const std::vector<std::size_t>&, const std::vector<ClothTableKey>& keys) {
    return sample_cloth_tables(keys, options.grid, options.sampling, ctx);
  };
  return cloth_tables_by_multiset(fabrics, options, sample, ctx);
}

std::vector<ClothTableSamples> sample_cloth_tables_of(const std::vector<ClothFabricSource>& fabrics,
                                                      const ClothTablesOptions& options,
                                                      std::uint64_t first_view,
                                                      std::uint64_t view_count,
                                                      const Context& ctx) {
  check_fabrics(fabrics);
  std::vector<prt_cloth_weave> weaves;
  for (const ClothFabricSource& f : fabrics) weaves.push_back(f.weave);
  const ClothTablePlan plan = plan_cloth_tables(weaves);
  std::vector<ClothTableSamples> out(plan.tables.size());
  // By multiset, as bake_cloth_tables samples them.
  for (const std::vector<std::size_t>& group : multiset_groups(plan.tables)) {
    std::vector<ClothTableKey> keys;
    for (const std::size_t t : group) keys.push_back(plan.tables[t]);
    std::vector<ClothTableSamples> samples =
        sample_cloth_table_views(keys, options.grid, options.sampling, first_view, view_count, ctx);
    for (std::size_t k = 0; k < group.size(); ++k) out[group[k]] = std::move(samples[k]);
  }
  return out;
}

ClothTablesBake factor_cloth_tables(const std::vector<ClothFabricSource>& fabrics,
                                    const ClothTablesOptions& options,
                                    std::vector<ClothTableSamples> samples, const Context& ctx) {
  const std::uint64_t size = options.grid.rows() * options.grid.columns();
  const auto take = [&](const std::vector<std::size_t>& group, const std::vector<ClothTableKey>&) {
    std::vector<ClothTableSamples> taken;
    for (const std::size_t t : group) {
      if (t >= samples.size() || samples[t].full.size() != size || samples[t].cone.size() != size)
        throw Error("cloth tables: table " + std::to_string(t) +
                    "'s samples do not match the fabrics and grid");
      taken.push_back(std::move(samples[t]));
    }
    return taken;
  };
  ClothTablesBake bake = cloth_tables_by_multiset(fabrics, options, take, ctx);
  bake.sample_seconds = 0.0;
  return bake;
}

}  // namespace prt::bake
