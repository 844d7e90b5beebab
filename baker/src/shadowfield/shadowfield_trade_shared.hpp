// SPDX-License-Identifier: MIT
// What both modes of prt-bake trade shadowfield share (private to the baker): the object-mode
// sweeps the scene mode reuses as its order, terms, rays and bits knobs, and the bias measure.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/shadowfield/shadowfield_bake.hpp"

namespace prt::bake::sf_trade {

struct SfTradeSettings {
  std::vector<std::uint32_t> orders{2, 3, 4, 5, 6}, terms{1, 2, 4, 8}, rays{64, 256, 1024};
  std::vector<int> bits{8, 16};
  std::uint32_t base_order = 4, base_terms = 4, base_rays = 256;
  int base_bits = 16;
  std::string brdf = "lambert";
  std::uint32_t rotations = 3;
  ShadowfieldBakeSettings bake;  // the rest of the bake (fields, basis, SRF), small by default
};

// (sum of x - ref) / sum of ref over every channel; 0 when the reference sums to 0.
inline double mean_bias(const std::vector<glm::vec3>& x, const std::vector<glm::vec3>& ref) {
  double diff = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      diff += double(x[i][c]) - ref[i][c];
      sum += ref[i][c];
    }
  }
  return sum != 0.0 ? diff / sum : 0.0;
}

}  // namespace prt::bake::sf_trade
