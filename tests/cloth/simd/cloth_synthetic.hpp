// SPDX-License-Identifier: MIT
// Cloth assets with synthetic tables for the shading backends' tests and benchmark: the presets'
// parameters and weaves (baker/include/prt/baker/cloth/fabrics.hpp) over smooth random factors of
// a chosen rank and grid, encoded by the baker's write_cloth_blob. A fabric's distinct |tau| share
// one table, read mirrored for a negative offset, as a bake shares them.
#pragma once

#include <prt/prt_cloth.h>
#include <prt/baker/cloth/cloth_blob.hpp>
#include <prt/baker/cloth/fabrics.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace prt_test {

struct SyntheticGrid {
  std::uint32_t xi_size = 8, levels = 4, view_theta = 6, view_phi = 8;
  std::uint32_t rank = 4, cone_rank = 3;
  int bits = 16;
};

// A smooth random factor pair over the grid: T = sum_r u_r v_r is about 0.5 +- 0.35 (the first
// component) with smaller, faster components; a few values leave [0, 1] for the clamp.
inline prt::bake::ClothFactor synthetic_factor(const prt::bake::ClothGrid& g, std::uint32_t rank,
                                               std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  prt::bake::ClothFactor f;
  f.rank = rank;
  f.u.resize(g.rows() * rank);
  f.v.resize(g.columns() * rank);
  for (std::uint32_t r = 0; r < rank; ++r) {
    const float amp = r == 0 ? 0.7f : 0.3f / float(r);
    const float a[4] = {unit(rng), unit(rng), unit(rng), unit(rng)};
    const float k = float(r % 3 + 1);
    for (std::uint32_t l = 0; l < g.lambda_levels; ++l)
      for (std::uint32_t j = 0; j < g.xi_size; ++j)
        for (std::uint32_t i = 0; i < g.xi_size; ++i) {
          const float x = float(i) / float(g.xi_size - 1), y = float(j) / float(g.xi_size - 1);
          const float z = g.lambda_levels > 1 ? float(l) / float(g.lambda_levels - 1) : 0.0f;
          const float value = (r == 0 ? 1.0f : 0.0f) + 0.25f * a[0] * std::cos(3.14159f * k * x) +
                              0.25f * a[1] * std::sin(3.14159f * k * y + a[2]) +
                              0.2f * a[3] * std::cos(2.0f * z + x);
          f.u[(std::size_t(l) * g.xi_size * g.xi_size + j * g.xi_size + i) * rank + r] =
              amp * value;
        }
    const float b[3] = {unit(rng), unit(rng), unit(rng)};
    for (std::uint32_t t = 0; t < g.view_theta; ++t)
      for (std::uint32_t p = 0; p < g.view_phi; ++p) {
        const float x = float(t) / float(g.view_theta - 1), y = float(p) / float(g.view_phi - 1);
        const float value = (r == 0 ? 0.7f : 0.0f) + 0.3f * b[0] * std::cos(2.0f * k * x + b[2]) +
                            0.2f * b[1] * std::sin(3.0f * y);
        f.v[(std::size_t(t) * g.view_phi + p) * rank + r] = value;
      }
  }
  return f;
}

// The presets called `names` (all six when empty) over synthetic tables.
inline std::vector<std::uint8_t> synthetic_cloth_blob(const SyntheticGrid& grid,
                                                      std::vector<std::string> names,
                                                      unsigned seed) {
  prt::bake::ClothSection s;
  s.grid.xi_size = grid.xi_size;
  s.grid.lambda_levels = grid.levels;
  s.grid.lambda_min = PRT_CLOTH_MIN_SHARPNESS;
  s.grid.lambda_max = grid.levels > 1 ? PRT_CLOTH_MAX_SHARPNESS : PRT_CLOTH_MIN_SHARPNESS;
  s.grid.view_theta = grid.view_theta;
  s.grid.view_phi = grid.view_phi;
  if (names.empty()) names = prt::bake::cloth_fabric_names();
  std::mt19937 rng(seed);
  for (const std::string& name : names) {
    const prt::bake::ClothPreset& preset = prt::bake::cloth_fabric(name);
    prt::bake::ClothFabric fabric;
    fabric.name = preset.name;
    fabric.params = preset.params;
    // satin back's 0.67f + 0.33f is above 1 (the format adds them in double) and is refused
    float& weft = fabric.params.threads[1].coverage;
    while (double(fabric.params.threads[0].coverage) + weft > 1.0)
      weft = std::nextafter(weft, 0.0f);
    std::vector<float> magnitudes;  // this fabric's distinct |tau|, one table each
    std::vector<std::uint32_t> tables;
    for (int j = 0; j < 2; ++j)
      for (std::uint32_t i = 0; i < preset.weave.tangent_count[j]; ++i) {
        const float tau = preset.weave.offsets[j][i];
        std::size_t m = 0;
        while (m < magnitudes.size() && magnitudes[m] != std::fabs(tau)) ++m;
        if (m == magnitudes.size()) {
          magnitudes.push_back(std::fabs(tau));
          tables.push_back(std::uint32_t(s.tables.size()));
          s.tables.push_back({synthetic_factor(s.grid, grid.rank, rng),
                              synthetic_factor(s.grid, grid.cone_rank, rng)});
        }
        prt::bake::ClothTangent t;
        t.offset = tau;
        t.multiplicity = preset.weave.multiplicity[j][i];
        t.table = tables[m];
        t.mirror = tau < 0.0f;
        fabric.threads[j].push_back(t);
      }
    s.fabrics.push_back(fabric);
  }
  return prt::bake::write_cloth_blob(s, grid.bits, nullptr, "");
}

// A light like a fitted sky: `count` lobes of sharpness log-uniform in [lo, hi] spread over the
// sphere (a Fibonacci spiral), amplitudes falling with sharpness so each carries a similar power,
// and optionally a sun.
inline std::vector<prt_cloth_lobe> sky_lobes(unsigned count, float lo, float hi, bool sun,
                                             unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<prt_cloth_lobe> lobes;
  for (unsigned k = 0; k < count; ++k) {
    const float z = 1.0f - 2.0f * (float(k) + 0.5f) / float(count);
    const float r = std::sqrt(1.0f - z * z), a = 2.39996323f * float(k);
    prt_cloth_lobe lobe{};
    lobe.axis[0] = r * std::cos(a);
    lobe.axis[1] = r * std::sin(a);
    lobe.axis[2] = z;
    lobe.sharpness = lo * std::pow(hi / lo, count > 1 ? float(k) / float(count - 1) : 0.5f);
    for (int c = 0; c < 3; ++c) lobe.rgb[c] = (0.5f + unit(rng)) * lobe.sharpness / 20.0f;
    lobes.push_back(lobe);
  }
  if (sun) {
    prt_cloth_lobe s{};
    s.axis[0] = 0.3f, s.axis[1] = 0.5f, s.axis[2] = 0.81240384f;
    s.sharpness = 5000.0f;
    s.rgb[0] = s.rgb[1] = s.rgb[2] = 2000.0f;
    lobes.push_back(s);
  }
  return lobes;
}

}  // namespace prt_test
