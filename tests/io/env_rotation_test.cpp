// SPDX-License-Identifier: MIT
// Turning the environment (EnvMap::set_rotation, rotation_about_y) against an independent
// construction: a lat-long map turned 90 degrees about +Y is the same map with its columns
// shifted by a quarter of the width (io/turned_maps.hpp derives the sign).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "io/turned_maps.hpp"
#include "prt/io/envmap.hpp"

namespace prt::io {
namespace {

using test::kHeight;
using test::kWidth;
using test::shifted_map;
using test::turned_map;

TEST(EnvRotation, MatrixIsTheDocumentedOne) {
  float r[9];
  rotation_about_y_row_major(30.0, r);
  const float c = std::cos(30.0f * 3.14159265f / 180.0f),
              s = std::sin(30.0f * 3.14159265f / 180.0f);
  const float expected[9] = {c, 0, s, 0, 1, 0, -s, 0, c};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(r[i], expected[i], 1e-6f) << i;
  // Light from +X (the map's three-quarter column) comes from R(+X) = (c, 0, -s) afterwards.
  const glm::vec3 moved = rotation_about_y(30.0) * glm::vec3(1.0f, 0.0f, 0.0f);
  EXPECT_NEAR(moved.x, c, 1e-6f);
  EXPECT_NEAR(moved.z, -s, 1e-6f);
}

TEST(EnvRotation, QuarterTurnOfLatLongEqualsQuarterColumnShift) {
  const EnvMap turned = turned_map(90.0), shifted = shifted_map();
  std::mt19937 rng(7);
  std::normal_distribution<float> normal;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(normal(rng), normal(rng), normal(rng)));
    const glm::vec3 a = turned.radiance(d), b = shifted.radiance(d);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-3f * (1.0f + b[c])) << i;
    int ax = 0, ay = 0, bx = 0, by = 0;
    turned.texel_of(d, &ax, &ay);
    shifted.texel_of(d, &bx, &by);
    // Nearest-texel lookups agree except on a texel border, where rounding may pick either side.
    if (ax != (bx + kWidth / 4) % kWidth || ay != by) {
      EXPECT_LT(glm::length(turned.texel_value(ax, ay) - shifted.texel_value(bx, by)) /
                    (1.0f + glm::length(shifted.texel_value(bx, by))),
                1.0f)
          << i;
    }
  }
  // Texel x of the turned map is seen where texel x - W/4 of the shifted map is.
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      glm::vec3 a, b;
      float wa = 0.0f, wb = 0.0f;
      ASSERT_TRUE(turned.texel(x, y, &a, &wa));
      ASSERT_TRUE(shifted.texel((x - kWidth / 4 + kWidth) % kWidth, y, &b, &wb));
      EXPECT_NEAR(glm::length(a - b), 0.0f, 1e-5f) << x << "," << y;
      EXPECT_FLOAT_EQ(wa, wb);
    }
  }
}

TEST(EnvRotation, FullTurnIsIdentityAndRejectsNonRotations) {
  const EnvMap turned = turned_map(360.0);
  EXPECT_FALSE(turned.rotated());
  EnvMap map = shifted_map();
  glm::mat3 mirror(1.0f);
  mirror[0][0] = -1.0f;
  EXPECT_THROW(map.set_rotation(mirror), Error);
  EXPECT_THROW(map.set_rotation(glm::mat3(2.0f)), Error);
}

}  // namespace
}  // namespace prt::io
