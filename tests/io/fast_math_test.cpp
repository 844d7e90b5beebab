// SPDX-License-Identifier: MIT
// atan2_float (the renderer's libm-free atan2) against the double-precision std::atan2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "prt/io/envmap.hpp"

namespace prt::io {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Atan2Float, MatchesDoubleAtan2AroundTheCircleToFloatPrecision) {
  // Every octant and its edges, at several radii: within 4 float ulps of pi (~1e-6 rad).
  double worst = 0.0;
  for (int k = 0; k < 100000; ++k) {
    const double angle = -kPi + 2.0 * kPi * (k + 0.37) / 100000.0;
    for (const double radius : {1e-3, 1.0, 7.5e3}) {
      const float x = static_cast<float>(radius * std::cos(angle));
      const float y = static_cast<float>(radius * std::sin(angle));
      const double expected = std::atan2(static_cast<double>(y), static_cast<double>(x));
      worst = std::max(worst, std::abs(static_cast<double>(atan2_float(y, x)) - expected));
    }
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(Atan2Float, AxesAndSignedZerosFollowAtan2) {
  EXPECT_EQ(atan2_float(0.0f, 1.0f), 0.0f);
  EXPECT_EQ(atan2_float(0.0f, 0.0f), 0.0f);
  EXPECT_NEAR(atan2_float(0.0f, -1.0f), kPi, 1e-6);
  EXPECT_NEAR(atan2_float(-0.0f, -1.0f), -kPi, 1e-6);
  EXPECT_NEAR(atan2_float(1.0f, 0.0f), 0.5 * kPi, 1e-6);
  EXPECT_NEAR(atan2_float(-1.0f, 0.0f), -0.5 * kPi, 1e-6);
  EXPECT_NEAR(atan2_float(1.0f, 1.0f), 0.25 * kPi, 1e-6);
  EXPECT_NEAR(atan2_float(-1.0f, -1.0f), -0.75 * kPi, 1e-6);
}

}  // namespace
}  // namespace prt::io
