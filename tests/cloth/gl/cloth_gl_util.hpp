// SPDX-License-Identifier: MIT
// Shared by the `cloth` GL tests and benchmark: assets of the preset fabrics over synthetic tables
// (smooth random factors on small grids, written by the baker's encoder), and what
// cloth_gl_target.hpp holds (lights, G-buffers, the GL target, the reference and its bound).
#pragma once

#include <gtest/gtest.h>

#include <GL/glcorearb.h>

#include <prt/baker/cloth/cloth_blob.hpp>
#include <prt/baker/cloth/fabrics.hpp>
#include <prt/prt.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "cloth/gl/cloth_gl_target.hpp"
#include "headless_gl.h"
#include "support/limited_context.hpp"
#include "support/mesh_blob.hpp"

namespace prt_test {

// ---- assets -------------------------------------------------------------------------------

// A smooth random function on [0, 1]^3: a constant and a few low-frequency cosines.
struct SmoothField {
  double constant = 0;
  struct Wave {
    double amplitude, k[3], phase;
  };
  std::vector<Wave> waves;
  double operator()(double x, double y, double z) const {
    double v = constant;
    for (const Wave& w : waves)
      v += w.amplitude * std::cos(w.k[0] * x + w.k[1] * y + w.k[2] * z + w.phase);
    return v;
  }
};

inline SmoothField smooth_field(std::mt19937& rng, double constant, double amplitude) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  SmoothField f;
  f.constant = constant;
  for (int i = 0; i < 3; ++i)
    f.waves.push_back({amplitude * unit(rng),
                       {6.0 * unit(rng) - 3.0, 6.0 * unit(rng) - 3.0, 6.0 * unit(rng) - 3.0},
                       2.0 * kClothPi * unit(rng)});
  return f;
}

// A factorisation of rank `rank` whose product is mostly in (0, 1) (a weight), sometimes a little
// outside it (the lookup clamps): component 0 carries the mean, the others small smooth ripples.
inline prt::bake::ClothFactor smooth_factor(const prt::bake::ClothGrid& g, uint32_t rank,
                                            std::mt19937& rng) {
  prt::bake::ClothFactor f;
  f.rank = rank;
  f.u.resize(g.rows() * rank);
  f.v.resize(g.columns() * rank);
  for (uint32_t r = 0; r < rank; ++r) {
    const SmoothField u = smooth_field(rng, r == 0 ? 0.75 : 0.0, r == 0 ? 0.25 : 0.35);
    const SmoothField v = smooth_field(rng, r == 0 ? 0.75 : 0.0, r == 0 ? 0.2 : 0.35);
    for (uint32_t l = 0; l < g.lambda_levels; ++l)
      for (uint32_t j = 0; j < g.xi_size; ++j)
        for (uint32_t i = 0; i < g.xi_size; ++i) {
          const size_t row = (size_t(l) * g.xi_size + j) * g.xi_size + i;
          f.u[row * rank + r] =
              float(u(double(i) / (g.xi_size - 1), double(j) / (g.xi_size - 1),
                      g.lambda_levels > 1 ? double(l) / (g.lambda_levels - 1) : 0));
        }
    for (uint32_t a = 0; a < g.view_theta; ++a)
      for (uint32_t b = 0; b < g.view_phi; ++b) {
        const size_t column = size_t(a) * g.view_phi + b;
        f.v[column * rank + r] =
            float(v(double(a) / (g.view_theta - 1), double(b) / (g.view_phi - 1), 0.5));
      }
  }
  return f;
}

// A fabric to put in a section: its name, default live parameters and weave.
struct FabricSpec {
  std::string name;
  prt_cloth_params params{};
  prt_cloth_weave weave{};
};

inline FabricSpec preset(const std::string& name) {
  const prt::bake::ClothPreset& p = prt::bake::cloth_fabric(name);
  return {p.name, p.params, p.weave};
}

inline std::vector<FabricSpec> presets(const std::vector<std::string>& names) {
  std::vector<FabricSpec> out;
  for (const std::string& name : names) out.push_back(preset(name));
  return out;
}

// Velvet's parameters on fibres at or near the vertical, where the front of a fibre is a whole
// half of its azimuths or none (tau = +-90 degrees) or closes over a sliver of elevations.
inline FabricSpec vertical_fabric() {
  FabricSpec f = preset("velvet");
  f.name = "vertical";
  const float degrees[2][2] = {{90.0f, -90.0f}, {89.0f, -75.0f}};
  for (int j = 0; j < 2; ++j) {
    f.weave.tangent_count[j] = 2;
    for (int k = 0; k < 2; ++k) {
      f.weave.offsets[j][k] = float(degrees[j][k] * kClothPi / 180.0);
      f.weave.multiplicity[j][k] = uint32_t(1 + k);
    }
  }
  return f;
}

// A section of the fabrics, each tangent reading a table of its own |offset| (a negative offset
// reads it mirrored), every table of smooth random factors with ranks from `ranks` in turn.
inline prt::bake::ClothSection cloth_section(const std::vector<FabricSpec>& fabrics,
                                             const prt::bake::ClothGrid& grid,
                                             const std::vector<uint32_t>& ranks, uint32_t seed) {
  std::mt19937 rng(seed);
  prt::bake::ClothSection s;
  s.grid = grid;
  std::vector<float> table_offsets;
  for (const FabricSpec& spec : fabrics) {
    prt::bake::ClothFabric fabric;
    fabric.name = spec.name;
    fabric.params = spec.params;
    for (int j = 0; j < 2; ++j)
      for (uint32_t k = 0; k < spec.weave.tangent_count[j]; ++k) {
        const float tau = spec.weave.offsets[j][k];
        uint32_t table = 0;
        while (table < table_offsets.size() && table_offsets[table] != std::fabs(tau)) ++table;
        if (table == table_offsets.size()) table_offsets.push_back(std::fabs(tau));
        fabric.threads[j].push_back({tau, spec.weave.multiplicity[j][k], table, tau < 0.0f});
      }
    s.fabrics.push_back(fabric);
  }
  for (size_t q = 0; q < table_offsets.size(); ++q) {
    prt::bake::ClothTable table;
    table.full = smooth_factor(grid, ranks[(2 * q) % ranks.size()], rng);
    table.cone = smooth_factor(grid, ranks[(2 * q + 1) % ranks.size()], rng);
    s.tables.push_back(table);
  }
  return s;
}

// Small grids over the whole sharpness range.
inline prt::bake::ClothGrid small_grid() {
  prt::bake::ClothGrid g;
  g.xi_size = 7;
  g.lambda_levels = 4;
  g.lambda_min = PRT_CLOTH_MIN_SHARPNESS;
  g.lambda_max = PRT_CLOTH_MAX_SHARPNESS;
  g.view_theta = 5;
  g.view_phi = 6;
  return g;
}

// A cloth asset loaded in its own context.
struct ClothAsset {
  prt::ContextPtr context;
  std::unique_ptr<LoadedAsset> loaded;
  ClothAsset(const prt::bake::ClothSection& section, int bits, prt_backend limit = PRT_BACKEND_AUTO,
             const prt_allocator* allocator = nullptr)
      : context(limited_context(limit, PRT_SIMD_ISA_AUTO, allocator)) {
    loaded = std::make_unique<LoadedAsset>(context.get(),
                                           prt::bake::write_cloth_blob(section, bits, nullptr, ""));
    EXPECT_EQ(loaded->result, PRT_OK) << message();
  }
  const prt_asset* asset() const { return loaded->asset; }
  std::string message() const { return prt_context_last_message(context.get()); }
};

}  // namespace prt_test
