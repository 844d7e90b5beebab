// SPDX-License-Identifier: MIT
// The texel grid's shared corner test: below_horizon from corners_above gives, texel by texel,
// the answer of the direct four-corner test, for normals along the axes, the cube's diagonals and
// spread over the sphere, on both parameterisations.
#include <gtest/gtest.h>

#include <prt/prt_wavelet.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../../../baker/src/wavelet/wavelet_grid.hpp"
#include "prt/baker/sampling.hpp"

namespace prt::bake::wavelet {
namespace {

std::vector<glm::vec3> test_normals() {
  std::vector<glm::vec3> out = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},    {0, -1, 0},
                                {0, 0, 1}, {0, 0, -1}, {1, 1, 1},    {-1, 1, -1},
                                {1, 0, 1}, {0, 1, -1}, {1, 1e-7f, 0}};
  const SampleStream stream(hash_key(5, 0, 0x47524944));
  for (std::uint32_t i = 0; i < 64; ++i) {
    const glm::vec2 u = stream.get_2d(i, 0);
    const float z = 1.0f - 2.0f * u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    out.emplace_back(r * std::cos(6.2831853f * u.y), r * std::sin(6.2831853f * u.y), z);
  }
  for (glm::vec3& n : out) n = glm::normalize(n);
  return out;
}

TEST(TexelGrid, SharedCornerTestMatchesDirectTest) {
  for (std::uint32_t param : {PRT_WAVELET_PARAM_CUBE, PRT_WAVELET_PARAM_DUAL_PARABOLOID}) {
    for (std::uint32_t size : {16u, 32u}) {
      const TexelGrid grid(param, size);
      std::vector<unsigned char> above;
      std::size_t below = 0;
      for (const glm::vec3& n : test_normals()) {
        grid.corners_above(n, &above);
        for (std::uint32_t j = 0; j < grid.count(); ++j) {
          const bool direct = grid.below_horizon(j, n);
          below += direct ? 1 : 0;
          ASSERT_EQ(grid.below_horizon(j, n, above), direct)
              << "param " << param << " size " << size << " texel " << j << " normal " << n.x << ","
              << n.y << "," << n.z;
        }
      }
      // Both answers occur: about half the texels are below any horizon.
      EXPECT_GT(below, 0u);
      EXPECT_LT(below, test_normals().size() * grid.count());
    }
  }
}

}  // namespace
}  // namespace prt::bake::wavelet
