// SPDX-License-Identifier: MIT
// Factoring the cloth tables (factor_cloth_table): the rank chosen by energy is the smallest that
// leaves at most that share of the squared norm, measured on the reconstruction itself; a full
// rank reproduces the table; the stored size follows SPEC §7.4; and bake_cloth_tables fills the
// section from the plan, the samples and the factors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "prt/baker/cloth/fabrics.hpp"
#include "prt/baker/cloth/cloth_tables.hpp"

namespace prt::bake {
namespace {

ClothGrid small_grid() {
  ClothGrid g = default_cloth_grid();
  g.xi_size = 8;
  g.lambda_levels = 3;
  g.view_theta = 4;
  g.view_phi = 4;
  return g;
}

ClothSampling small_sampling() {
  ClothSampling s;
  s.map_size = 64;
  return s;
}

// A sampled table: satin's warp, offset 18 degrees.
const ClothTableSamples& satin_table() {
  static const ClothTableSamples table = [] {
    ClothTableKey key;
    for (const double d : {-32.0, -18.0, 0.0, 18.0, 32.0})
      key.offsets.push_back(float(d * 3.14159265358979323846 / 180.0));
    key.multiplicities = {2, 1, 2, 1, 2};
    key.tangent = 3;
    return sample_cloth_tables({key}, small_grid(), small_sampling(), Context{})[0];
  }();
  return table;
}

// ||T - U V^T||_F^2 / ||T||_F^2 and max |T - U V^T|, from the factors.
std::pair<double, double> reconstruction_error(const std::vector<float>& t, const ClothFactor& f,
                                               std::uint64_t rows, std::uint64_t columns) {
  double error2 = 0.0, norm2 = 0.0, largest = 0.0;
  for (std::uint64_t r = 0; r < rows; ++r)
    for (std::uint64_t c = 0; c < columns; ++c) {
      double value = 0.0;
      for (std::uint32_t k = 0; k < f.rank; ++k)
        value += double(f.u[r * f.rank + k]) * f.v[c * f.rank + k];
      const double d = t[r * columns + c] - value;
      error2 += d * d;
      norm2 += double(t[r * columns + c]) * t[r * columns + c];
      largest = std::max(largest, std::fabs(d));
    }
  return {error2 / norm2, largest};
}

TEST(ClothTableFactor, TheRankByEnergyIsTheSmallestThatMeetsIt) {
  const ClothGrid g = small_grid();
  const ClothTableSamples& t = satin_table();
  for (const double energy : {1e-2, 1e-3, 1e-4}) {
    for (const std::vector<float>* table : {&t.full, &t.cone}) {
      ClothFactorOptions options;
      options.energy = energy;
      ClothFactorReport report;
      const ClothFactor f = factor_cloth_table(*table, g.rows(), g.columns(), options, &report);
      ASSERT_EQ(f.rank, report.rank);
      ASSERT_GE(f.rank, 2u);
      ASSERT_EQ(f.u.size(), g.rows() * f.rank);
      ASSERT_EQ(f.v.size(), g.columns() * f.rank);
      const auto [share, largest] = reconstruction_error(*table, f, g.rows(), g.columns());
      EXPECT_LE(share, energy * (1.0 + 1e-4));  // float factors
      EXPECT_NEAR(std::sqrt(share), report.relative_error, 1e-4);
      EXPECT_NEAR(largest, report.max_abs_error, 1e-5);
      // One rank fewer leaves more than `energy`.
      options.fixed_rank = f.rank - 1;
      const ClothFactor fewer = factor_cloth_table(*table, g.rows(), g.columns(), options);
      EXPECT_GT(reconstruction_error(*table, fewer, g.rows(), g.columns()).first, energy);
    }
  }
}

TEST(ClothTableFactor, FullRankReproducesTheTable) {
  const ClothGrid g = small_grid();
  ClothFactorOptions options;
  options.fixed_rank = std::uint32_t(g.columns());  // 16: every singular value
  const ClothTableSamples& t = satin_table();
  for (const std::vector<float>* table : {&t.full, &t.cone}) {
    const ClothFactor f = factor_cloth_table(*table, g.rows(), g.columns(), options);
    EXPECT_EQ(f.rank, g.columns());
    EXPECT_LE(reconstruction_error(*table, f, g.rows(), g.columns()).second, 1e-5);
  }
}

TEST(ClothTableFactor, SignsAreFixedByV) {
  const ClothGrid g = small_grid();
  const ClothFactor f = factor_cloth_table(satin_table().full, g.rows(), g.columns(), {});
  for (std::uint32_t k = 0; k < f.rank; ++k) {
    float largest = 0.0f;
    for (std::uint64_t c = 0; c < g.columns(); ++c)
      if (std::fabs(f.v[c * f.rank + k]) > std::fabs(largest)) largest = f.v[c * f.rank + k];
    EXPECT_GT(largest, 0.0f);
  }
}

TEST(ClothTableFactor, AZeroTableHasRankOne) {
  const ClothGrid g = small_grid();
  ClothFactorReport report;
  const ClothFactor f = factor_cloth_table(std::vector<float>(g.rows() * g.columns(), 0.0f),
                                           g.rows(), g.columns(), {}, &report);
  EXPECT_EQ(f.rank, 1u);
  EXPECT_EQ(report.relative_error, 0.0);
  EXPECT_EQ(report.max_abs_error, 0.0);
  for (const float u : f.u) EXPECT_EQ(u, 0.0f);
}

TEST(ClothTableFactor, StoredSizeFollowsTheSpec) {
  const ClothGrid g = small_grid();  // 192 rows, 16 columns
  // 8 R + align4(columns R b/8) + align4(rows R b/8)
  EXPECT_EQ(cloth_factor_bytes(g, 3, 16), 24u + 96u + 1152u);
  EXPECT_EQ(cloth_factor_bytes(g, 3, 8), 24u + 48u + 576u);
  ClothGrid odd = g;
  odd.view_phi = 3;  // 12 columns
  odd.xi_size = 3;   // 27 rows
  EXPECT_EQ(cloth_factor_bytes(odd, 1, 8), 8u + 12u + 28u);
}

TEST(ClothTableFactor, RanksForEnergyFromSingularValues) {
  const std::vector<double> s = {3.0, 2.0, 1.0, 0.1};  // squares 9, 4, 1, 0.01 of 14.01
  EXPECT_EQ(cloth_rank_for_energy(s, 0.3), 2u);        // leaves 1.01 / 14.01 = 0.072
  EXPECT_EQ(cloth_rank_for_energy(s, 0.05), 3u);       // leaves 0.0007
  EXPECT_EQ(cloth_rank_for_energy(s, 1e-5), 4u);
  EXPECT_EQ(cloth_rank_for_energy(s, 1e-5, 2), 2u);  // capped
}

TEST(ClothTablesBake, TheSectionHoldsTheFabricsAndTheirTables) {
  std::vector<ClothFabricSource> fabrics;
  for (const char* name : {"linen_plain", "polyester_satin_charmeuse"}) {
    const prt::bake::ClothPreset& p = prt::bake::cloth_fabric(name);
    fabrics.push_back({p.name, p.params, p.weave});
  }
  ClothTablesOptions options;
  options.grid = small_grid();
  options.sampling = small_sampling();
  const ClothTablesBake bake = bake_cloth_tables(fabrics, options, Context{});
  const ClothTablePlan plan = plan_cloth_tables({fabrics[0].weave, fabrics[1].weave});
  ASSERT_EQ(bake.section.fabrics.size(), 2u);
  ASSERT_EQ(bake.section.tables.size(), 5u);  // linen 1, satin 4
  ASSERT_EQ(bake.tables.size(), 5u);
  for (std::size_t f = 0; f < 2; ++f) {
    EXPECT_EQ(bake.section.fabrics[f].name, fabrics[f].name);
    EXPECT_EQ(bake.section.fabrics[f].params.threads[1].coverage,
              fabrics[f].params.threads[1].coverage);
    for (int j = 0; j < 2; ++j) {
      ASSERT_EQ(bake.section.fabrics[f].threads[j].size(), plan.threads[f][j].size());
      for (std::size_t k = 0; k < plan.threads[f][j].size(); ++k) {
        EXPECT_EQ(bake.section.fabrics[f].threads[j][k].table, plan.threads[f][j][k].table);
        EXPECT_EQ(bake.section.fabrics[f].threads[j][k].mirror, plan.threads[f][j][k].mirror);
      }
    }
  }
  for (std::size_t t = 0; t < 5; ++t) {
    EXPECT_EQ(bake.tables[t].key, plan.tables[t]);
    const ClothTable& table = bake.section.tables[t];
    EXPECT_EQ(table.full.rank, bake.tables[t].full.rank);
    EXPECT_EQ(table.cone.rank, bake.tables[t].cone.rank);
    EXPECT_EQ(bake.tables[t].bytes8, cloth_factor_bytes(options.grid, table.full.rank, 8) +
                                         cloth_factor_bytes(options.grid, table.cone.rank, 8));
    EXPECT_LE(bake.tables[t].full.relative_error, std::sqrt(options.factor.energy));
  }
  EXPECT_EQ(bake.section.grid.xi_size, options.grid.xi_size);
}

TEST(ClothTablesBake, RejectsInvalidFabrics) {
  prt::bake::ClothPreset p = prt::bake::cloth_fabric("linen_plain");
  p.params.threads[0].coverage = 0.9f;  // with 0.33: more than 1
  EXPECT_THROW(bake_cloth_tables({{p.name, p.params, p.weave}}, {}, Context{}), Error);
  EXPECT_THROW(bake_cloth_tables({}, {}, Context{}), Error);
}

}  // namespace
}  // namespace prt::bake
