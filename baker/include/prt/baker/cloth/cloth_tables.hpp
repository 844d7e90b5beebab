// SPDX-License-Identifier: MIT
// The shadowing/masking tables of technique `cloth` (formats/SPEC.md §7.4, docs/cloth/model.md):
// which tables a set of fabrics needs and how their tangents share them, each table sampled on
// the section's grids, its truncated SVD, and the CLTH section of the fabrics with their tables.
#pragma once

#include <prt/prt_cloth.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/cloth/cloth_blob.hpp"
#include "prt/baker/context.hpp"

namespace prt::bake {

// A fabric to bake: its name, default live parameters and weave (what a preset carries).
struct ClothFabricSource {
  std::string name;
  prt_cloth_params params{};
  prt_cloth_weave weave{};
};

// What one table depends on: a thread's tangent multiset and one distinct offset of it, in the
// thread's canonical frame (x_j, y_j, n). Any thread of any fabric with this multiset reads it.
struct ClothTableKey {
  std::vector<float> offsets;                 // distinct, ascending, never -0
  std::vector<std::uint32_t> multiplicities;  // copies of each offset, 1..64
  std::uint32_t tangent = 0;                  // the table's offset: offsets[tangent]

  float offset() const { return offsets[tangent]; }
  bool operator==(const ClothTableKey& other) const;
};

// The tables a list of weaves needs, each once, in order of first use (fabric after fabric,
// thread 0 then 1, offsets in weave order), and each fabric's tangent records: per thread, one
// record per distinct offset in weave order. A record reads its own table or, for the offset -tau
// of a multiset S, the table of tau of -S mirrored (x -> -x); which of the two is stored is fixed
// by the multisets alone (the lexicographically smaller of S and -S; tau >= 0 when S = -S).
struct ClothTablePlan {
  std::vector<ClothTableKey> tables;
  std::vector<std::array<std::vector<ClothTangent>, 2>> threads;  // per weave
};
ClothTablePlan plan_cloth_tables(const std::vector<prt_cloth_weave>& weaves);

// The quadrature of the tables (how they are computed, not what they mean; the defaults are
// chosen by measured convergence).
struct ClothSampling {
  // W is read from maps per view. A hemi-octahedral map over z >= 0 with (map_size + 1)^2
  // vertices (map_size a power of two, 8..1024; its edge is the cloth's plane, sampled just above
  // it), filtered to coarser levels; a lobe reads the coarsest level whose spacing is at most its
  // width 1/sqrt(lambda) / map_texels_per_width.
  std::uint32_t map_size = 128;
  double map_texels_per_width = 4.0;
  // Where the fibre runs end-on into D's boundary (t or -t), W depends on the direction of
  // approach and no map of fixed spacing resolves it: there, within polar_radius, W is read from
  // a polar map, polar_rings log-spaced radii from polar_radius_min times polar_angles angles.
  double polar_radius = 0.2;
  double polar_radius_min = 1e-5;
  std::uint32_t polar_rings = 48;
  std::uint32_t polar_angles = 65;
  // Lobe-adapted quadrature of T: azimuth_nodes great half-circles from the lobe's axis (even;
  // crowded towards D for a lobe outside it), each clipped to D and cut into pieces of the lobe's
  // mass (at 1, 3, 7, 15, ... times its decay length, and at most radial_step long in s = 1 -
  // w . xi), each piece sampled at radial_nodes points of equal lobe mass.
  std::uint32_t radial_nodes = 2;
  double radial_step = 0.1;
  std::uint32_t azimuth_nodes = 128;
  // T_c: W at cone_nodes points of equal dphi along the cone's arc in D (a power of two, 8..65536),
  // averaged in pairs to coarser levels; a lobe reads the coarsest level whose spacing is at most
  // its width along the cone / cone_nodes_per_width.
  std::uint32_t cone_nodes = 1024;
  double cone_nodes_per_width = 2.0;
  // No level of the hemi map or the cone coarser than this spacing (radians) is read: W has
  // features this fine whatever the lobe.
  double max_spacing = 0.025;
  // Paper 003 as printed, for measuring: T divided by the closed form of the lobe's integral over
  // the whole sphere, 2 pi (1 - exp(-2 lambda)) / lambda, instead of its integral over D (T_c
  // unchanged). Off for every bake.
  bool full_sphere_denominator = false;
};

// The default grids: N_xi 32, L 10 over lambda 0.25 .. 1e4 (the light's sharpness range), views
// 16 x 16.
ClothGrid default_cloth_grid();

// One table on the grids: T and T_c, rows() x columns() each, row-major (row = level N_xi^2 +
// j N_xi + i, column = a N_phi + b), every value in [0, 1].
struct ClothTableSamples {
  std::vector<float> full;
  std::vector<float> cone;
};

// Samples every table, in parallel over views and lobe rows; the result does not depend on the
// thread count. Throws Error for invalid grids, sampling or keys, or when cancelled.
std::vector<ClothTableSamples> sample_cloth_tables(const std::vector<ClothTableKey>& keys,
                                                   const ClothGrid& grid,
                                                   const ClothSampling& sampling,
                                                   const Context& ctx);

// Columns [first_view, first_view + view_count) of every table (a shard of a bake, docs/farm.md):
// rows() x view_count each, column c bit for bit column first_view + c of sample_cloth_tables.
// Throws as sample_cloth_tables, or Error when the views are beyond the grid's columns().
std::vector<ClothTableSamples> sample_cloth_table_views(
    const std::vector<ClothTableKey>& keys, const ClothGrid& grid, const ClothSampling& sampling,
    std::uint64_t first_view, std::uint64_t view_count, const Context& ctx);

// T and T_c of one table for one view at any lobe, by the quadrature the bake uses (tests and
// tools). `view` is unit, in the canonical frame, above the cloth (z > 0).
class ClothTableProbe {
 public:
  ClothTableProbe(const ClothTableKey& key, const double view[3], const ClothSampling& sampling);
  ~ClothTableProbe();
  ClothTableProbe(const ClothTableProbe&) = delete;
  ClothTableProbe& operator=(const ClothTableProbe&) = delete;

  double full(const double xi[3], double lambda) const;  // xi unit, lambda > 0
  double cone(const double xi[3], double lambda) const;

 private:
  struct State;
  State* state_;
};

// ---- Factoring --------------------------------------------------------------------------------

struct ClothFactorOptions {
  // The rank is the smallest R <= max_rank (and <= 64) whose truncation leaves at most this share
  // of the table's squared Frobenius norm...
  double energy = 1e-4;
  std::uint32_t max_rank = 64;
  // ... or this rank when it is not 0 (capped by 64 and the table's size).
  std::uint32_t fixed_rank = 0;
};

struct ClothFactorReport {
  std::uint32_t rank = 0;
  double relative_error = 0.0;          // ||T - U V^T||_F / ||T||_F (0 for a zero table)
  double max_abs_error = 0.0;           // max |T - U V^T| over the entries
  std::vector<double> singular_values;  // all of them, descending
};

// The truncated SVD (Eigen's BDCSVD, in double) of a rows x columns row-major table: u = U S
// (rows x R), v = V (columns x R), each column's sign fixed so that its largest |V| is positive.
ClothFactor factor_cloth_table(const std::vector<float>& table, std::uint64_t rows,
                               std::uint64_t columns, const ClothFactorOptions& options,
                               ClothFactorReport* report = nullptr);

// The smallest rank (1..max_rank, at most 64) whose truncation leaves at most `energy` of the
// squared norm, from the singular values (descending).
std::uint32_t cloth_rank_for_energy(const std::vector<double>& singular_values, double energy,
                                    std::uint32_t max_rank = 64);

// Bytes of one stored factorisation of rank R at `bits` (8 or 16) per value (SPEC §7.4).
std::uint64_t cloth_factor_bytes(const ClothGrid& grid, std::uint32_t rank, int bits);

// ---- The section ------------------------------------------------------------------------------

struct ClothTablesOptions {
  ClothGrid grid = default_cloth_grid();
  ClothSampling sampling;
  ClothFactorOptions factor;
};

struct ClothTableReport {
  ClothTableKey key;
  ClothFactorReport full, cone;
  std::uint64_t bytes16 = 0, bytes8 = 0;  // T and T_c stored, at 16 and 8 bits
};

struct ClothTablesBake {
  ClothSection section;
  std::vector<ClothTableReport> tables;  // as section.tables
  double sample_seconds = 0.0, factor_seconds = 0.0;
};

// The fabrics' CLTH section: their parameters, tangent records and factored tables. Throws
// Error for an invalid fabric (prt_cloth_params_validate, prt_cloth_weave_validate), more than
// 64 fabrics, or as sample_cloth_tables.
ClothTablesBake bake_cloth_tables(const std::vector<ClothFabricSource>& fabrics,
                                  const ClothTablesOptions& options, const Context& ctx);

// bake_cloth_tables in two steps, for a bake split into shards (docs/farm.md): a shard samples
// views [first_view, first_view + view_count) of every table the fabrics need (in the order of
// plan_cloth_tables), and the merge factors the tables joined from every shard's views (whole,
// in the same order) into what bake_cloth_tables returns, bit for bit (sample_seconds 0). Throw
// as bake_cloth_tables, or Error when a table's size does not match the grid.
std::vector<ClothTableSamples> sample_cloth_tables_of(const std::vector<ClothFabricSource>& fabrics,
                                                      const ClothTablesOptions& options,
                                                      std::uint64_t first_view,
                                                      std::uint64_t view_count, const Context& ctx);
ClothTablesBake factor_cloth_tables(const std::vector<ClothFabricSource>& fabrics,
                                    const ClothTablesOptions& options,
                                    std::vector<ClothTableSamples> samples, const Context& ctx);

}  // namespace prt::bake
