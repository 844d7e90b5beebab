// SH de-ringing (prt_sh_dering_light): the identity at strength 0, Sloan's band factors against
// their closed form with lambda found by the test's own bisection, a delta light's irradiance
// everywhere non-negative at the default strength (and not below it), commutation with rotation,
// and refused arguments.
#include <gtest/gtest.h>
#include <prt/prt_sh.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "sh/sh_test_util.hpp"

namespace {

using prt_sh_test::kPi;

std::vector<float> RandomLight(uint32_t order, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  std::vector<float> light(order * order * 3);
  for (float& c : light) c = u(rng);
  return light;
}

// The factor each coefficient and channel received, from a light of distinct non-zero values.
std::vector<double> Factors(uint32_t order, float strength) {
  std::vector<float> light(order * order * 3), out(order * order * 3);
  for (size_t i = 0; i < light.size(); ++i) light[i] = 0.5f + 0.25f * float(i % 7);
  EXPECT_EQ(prt_sh_dering_light(order, strength, light.data(), out.data()), PRT_OK);
  std::vector<double> factors(light.size());
  for (size_t i = 0; i < light.size(); ++i) factors[i] = double(out[i]) / double(light[i]);
  return factors;
}

// Sloan's window h_l = 1/(1 + lambda l^2 (l+1)^2); lambda recovered from band 1.
double LambdaOf(const std::vector<double>& factors) {
  return (1.0 / factors[3] - 1.0) / 4.0;
}

double SloanFactor(double lambda, uint32_t l) {
  const double ll1 = double(l) * double(l + 1);
  return 1.0 / (1.0 + lambda * ll1 * ll1);
}

// min over t = cos(angle) of a delta light's windowed irradiance relative to its maximum,
// sum_l h_l A_l (2l+1) P_l(t) (the 1/(4 pi) cancels), on a grid of angles.
double DeltaIrradianceMinimum(uint32_t order, double lambda) {
  double lowest = 1e300, highest = -1e300;
  const int steps = 4000;
  for (int k = 0; k <= steps; ++k) {
    const double t = std::cos(kPi * k / steps);
    double p0 = 1.0, p1 = t, e = 0.0;
    for (uint32_t l = 0; l < order; ++l) {
      const double pl = l == 0 ? 1.0 : l == 1 ? t : ((2.0 * l - 1.0) * t * p1 - (l - 1.0) * p0) / l;
      if (l >= 2) {
        p0 = p1;
        p1 = pl;
      }
      e += SloanFactor(lambda, l) * double(prt_sh_cosine_band_factor(l)) * (2.0 * l + 1.0) * pl;
    }
    lowest = std::min(lowest, e);
    highest = std::max(highest, e);
  }
  return lowest / highest;
}

TEST(ShDering, ZeroStrengthIsABitExactCopy) {
  std::mt19937 rng(3);
  for (uint32_t order : {1u, 3u, 6u, PRT_SH_MAX_ORDER}) {
    std::vector<float> light = RandomLight(order, rng);
    light[0] = std::numeric_limits<float>::denorm_min();
    light.back() = -0.0f;
    std::vector<float> out(light.size(), 7.0f), in_place = light;
    ASSERT_EQ(prt_sh_dering_light(order, 0.0f, light.data(), out.data()), PRT_OK);
    EXPECT_EQ(std::memcmp(out.data(), light.data(), light.size() * sizeof(float)), 0);
    ASSERT_EQ(prt_sh_dering_light(order, 0.0f, in_place.data(), in_place.data()), PRT_OK);
    EXPECT_EQ(std::memcmp(in_place.data(), light.data(), light.size() * sizeof(float)), 0);
  }
}

// Every m and channel of band l gets the same h_l, band 0 exactly 1, the rest Sloan's closed form
// with one lambda, proportional to the strength.
TEST(ShDering, BandFactorsFollowSloansWindow) {
  for (uint32_t order = 2; order <= PRT_SH_MAX_ORDER; ++order) {
    const std::vector<double> f = Factors(order, 1.0f);
    const double lambda = LambdaOf(f);
    EXPECT_GT(lambda, 0.0) << "order " << order;
    for (uint32_t l = 0; l < order; ++l) {
      for (uint32_t i = 3 * l * l; i < 3 * (l + 1) * (l + 1); ++i) {
        if (l == 0)
          EXPECT_EQ(f[i], 1.0);
        else
          EXPECT_NEAR(f[i], SloanFactor(lambda, l), 2e-6 * SloanFactor(lambda, l))
              << "order " << order << ", l " << l << ", i " << i;
      }
    }
    EXPECT_NEAR(LambdaOf(Factors(order, 2.5f)), 2.5 * lambda, 1e-5 * lambda) << "order " << order;
    EXPECT_NEAR(LambdaOf(Factors(order, 0.1f)), 0.1 * lambda, 1e-5 * lambda) << "order " << order;
  }
  // Order 1 is the mean alone: nothing to window.
  EXPECT_EQ(Factors(1, 1.0f), std::vector<double>(3, 1.0));
}

// Strength 1 is the smallest lambda for which a delta light's irradiance is non-negative at
// every angle: found here by bisection on the closed form, independently of the runtime's table.
TEST(ShDering, DefaultStrengthIsTheSmallestNonNegativeWindow) {
  for (uint32_t order = 2; order <= PRT_SH_MAX_ORDER; ++order) {
    double lo = 0.0, hi = 1.0;
    ASSERT_LT(DeltaIrradianceMinimum(order, lo), 0.0) << "order " << order;
    ASSERT_GE(DeltaIrradianceMinimum(order, hi), 0.0) << "order " << order;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      (DeltaIrradianceMinimum(order, mid) < 0.0 ? lo : hi) = mid;
    }
    const double lambda = LambdaOf(Factors(order, PRT_SH_DERING_DEFAULT_STRENGTH));
    EXPECT_NEAR(lambda, hi, 1e-5 * hi) << "order " << order;
  }
}

// Through the runtime's own evaluation and convolution: the irradiance of a unit delta light from
// d, over a dense Fibonacci sphere of normals, rings below zero without de-ringing, stays >= 0 at
// the default strength, and still rings a little below it.
double WorstIrradiance(uint32_t order, float strength, const std::vector<std::array<float, 3>>& n) {
  const std::array<float, 3> d = {0.36f, 0.48f, -0.8f};
  std::vector<float> y(order * order), light(order * order * 3), e(order * order * 3);
  EXPECT_EQ(prt_sh_eval(order, d.data(), y.data()), PRT_OK);
  for (size_t i = 0; i < light.size(); ++i) light[i] = y[i / 3];
  EXPECT_EQ(prt_sh_dering_light(order, strength, light.data(), light.data()), PRT_OK);
  EXPECT_EQ(prt_sh_convolve_cosine(order, light.data(), e.data(), 3), PRT_OK);
  double lowest = 1e300, highest = -1e300;
  for (const auto& normal : n) {
    EXPECT_EQ(prt_sh_eval(order, normal.data(), y.data()), PRT_OK);
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (uint32_t i = 0; i < order * order; ++i) sum += double(e[i * 3 + c]) * y[i];
      lowest = std::min(lowest, sum);
      highest = std::max(highest, sum);
    }
  }
  return lowest / highest;
}

TEST(ShDering, DeltaLightIrradianceHasNoNegativeLobeAtTheDefault) {
  std::vector<std::array<float, 3>> normals;
  const int count = 40000;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count, r = std::sqrt(1.0 - z * z);
    normals.push_back({float(r * std::cos(golden * i)), float(z), float(r * std::sin(golden * i))});
  }
  for (uint32_t order : {2u, 3u, 4u, 6u, 8u, 16u}) {
    // Without the window, ringing of at least 0.7 % of the peak (order 16; 33 % at order 2).
    EXPECT_LT(WorstIrradiance(order, 0.0f, normals), -0.005) << "order " << order;
    // Float rounding of the coefficients and of the sums.
    EXPECT_GE(WorstIrradiance(order, PRT_SH_DERING_DEFAULT_STRENGTH, normals), -1e-6)
        << "order " << order;
    EXPECT_LT(WorstIrradiance(order, 0.97f * PRT_SH_DERING_DEFAULT_STRENGTH, normals), -1e-4)
        << "order " << order;
  }
}

// A per-band scale commutes with rotation (each band rotates within itself).
TEST(ShDering, CommutesWithRotation) {
  std::mt19937 rng(11);
  const uint32_t order = 8;
  const std::vector<float> light = RandomLight(order, rng);
  // Rotation about the unit axis a by 1.1 rad (Rodrigues), row-major.
  const std::array<double, 3> a = {0.267261, 0.534522, 0.801784};
  const double c = std::cos(1.1), s = std::sin(1.1), t = 1.0 - c;
  const float r[9] = {float(t * a[0] * a[0] + c),        float(t * a[0] * a[1] - s * a[2]),
                      float(t * a[0] * a[2] + s * a[1]), float(t * a[0] * a[1] + s * a[2]),
                      float(t * a[1] * a[1] + c),        float(t * a[1] * a[2] - s * a[0]),
                      float(t * a[0] * a[2] - s * a[1]), float(t * a[1] * a[2] + s * a[0]),
                      float(t * a[2] * a[2] + c)};
  std::vector<float> rotated_first(light.size()), windowed_first(light.size());
  ASSERT_EQ(prt_sh_rotate(order, r, light.data(), rotated_first.data(), 3), PRT_OK);
  ASSERT_EQ(prt_sh_dering_light(order, 0.5f, rotated_first.data(), rotated_first.data()), PRT_OK);
  ASSERT_EQ(prt_sh_dering_light(order, 0.5f, light.data(), windowed_first.data()), PRT_OK);
  ASSERT_EQ(prt_sh_rotate(order, r, windowed_first.data(), windowed_first.data(), 3), PRT_OK);
  for (size_t i = 0; i < light.size(); ++i)
    EXPECT_NEAR(rotated_first[i], windowed_first[i], 2e-5) << i;
}

// A huge strength leaves the mean and (almost) nothing else; finite throughout.
TEST(ShDering, HugeStrengthKeepsTheMeanOnly) {
  std::mt19937 rng(5);
  const std::vector<float> light = RandomLight(6, rng);
  std::vector<float> out(light.size());
  ASSERT_EQ(prt_sh_dering_light(6, FLT_MAX, light.data(), out.data()), PRT_OK);
  for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(out[ch], light[ch]);
  for (size_t i = 3; i < out.size(); ++i) {
    EXPECT_TRUE(std::isfinite(out[i]));
    EXPECT_LE(std::abs(out[i]), 1e-30f);
  }
}

TEST(ShDering, RejectsInvalidArguments) {
  std::vector<float> light(PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER * 3 + 3, 1.0f), out = light;
  const float* l = light.data();
  float* o = out.data();
  EXPECT_EQ(prt_sh_dering_light(3, 1.0f, nullptr, o), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_dering_light(3, 1.0f, l, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_dering_light(0, 1.0f, l, o), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_dering_light(PRT_SH_MAX_ORDER + 1, 1.0f, l, o), PRT_ERROR_INVALID_ARGUMENT);
  for (float bad :
       {-1.0f, -FLT_MIN, std::numeric_limits<float>::quiet_NaN(),
        std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()})
    EXPECT_EQ(prt_sh_dering_light(3, bad, l, o), PRT_ERROR_INVALID_ARGUMENT) << bad;
  // A refused call writes nothing.
  EXPECT_EQ(out, light);
  EXPECT_EQ(prt_sh_dering_light(PRT_SH_MAX_ORDER, 1.0f, l, o), PRT_OK);
}

}  // namespace
