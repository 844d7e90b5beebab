// Clamped-cosine convolution: band factors against published values and an independent
// quadrature; irradiance of a constant map and of a delta light.
#include <gtest/gtest.h>
#include <prt/prt_sh.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "sh/sh_test_util.hpp"

namespace {

using prt_sh_test::kPi;

TEST(ShConvolve, BandFactorsMatchPublishedValues) {
  // Ramamoorthi and Hanrahan 2001, eq. 9 and the values printed after it.
  EXPECT_NEAR(prt_sh_cosine_band_factor(0), kPi, 1e-6);
  EXPECT_NEAR(prt_sh_cosine_band_factor(1), 2.0 * kPi / 3.0, 1e-6);
  EXPECT_NEAR(prt_sh_cosine_band_factor(2), kPi / 4.0, 1e-6);
  EXPECT_EQ(prt_sh_cosine_band_factor(3), 0.0f);
  EXPECT_NEAR(prt_sh_cosine_band_factor(4), -kPi / 24.0, 1e-6);
  EXPECT_EQ(prt_sh_cosine_band_factor(5), 0.0f);
  EXPECT_NEAR(prt_sh_cosine_band_factor(6), kPi / 64.0, 1e-6);
  EXPECT_EQ(prt_sh_cosine_band_factor(PRT_SH_MAX_ORDER), 0.0f);
}

// A_l = sqrt(4 pi/(2l+1)) * 2 pi * integral_0^1 z Y_l0(z) dz, Y_l0 = sqrt((2l+1)/(4 pi)) P_l, so
// A_l = 2 pi * integral_0^1 z P_l(z) dz; Gauss-Legendre on [0, 1] is exact for this polynomial.
TEST(ShConvolve, BandFactorsMatchQuadratureOfClampedCosine) {
  const auto gl = prt_sh_test::GaussLegendre(PRT_SH_MAX_ORDER + 2);
  for (uint32_t l = 0; l < PRT_SH_MAX_ORDER; ++l) {
    double integral = 0.0;
    for (size_t i = 0; i < gl.nodes.size(); ++i) {
      const double z = 0.5 * (gl.nodes[i] + 1.0);
      double p0 = 1.0, p1 = z;  // Bonnet recurrence for P_l(z)
      double pl = (l == 0) ? 1.0 : z;
      for (uint32_t k = 2; k <= l; ++k) {
        pl = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pl;
      }
      integral += 0.5 * gl.weights[i] * z * pl;
    }
    EXPECT_NEAR(prt_sh_cosine_band_factor(l), 2.0 * kPi * integral, 1e-6) << "l = " << l;
  }
}

TEST(ShConvolve, ConstantMapGivesPiTimesRadianceAtEveryNormal) {
  const std::array<float, 3> radiance = {0.7f, 1.5f, 3.0f};
  const uint32_t w = 64, h = 32, order = 5;
  std::vector<float> image(size_t(w) * h * 3);
  for (size_t i = 0; i < image.size(); ++i) image[i] = radiance[i % 3];
  std::vector<float> coeffs(order * order * 3), irradiance(order * order * 3);
  ASSERT_EQ(prt_sh_test::ProjectLatLong(order, w, h, image.data(), w * 3, coeffs.data()), PRT_OK);
  ASSERT_EQ(prt_sh_convolve_cosine(order, coeffs.data(), irradiance.data(), 3), PRT_OK);
  std::mt19937 rng(5);
  for (int k = 0; k < 20; ++k) {
    const auto n = prt_sh_test::RandomUnit(rng);
    std::vector<float> y(order * order);
    ASSERT_EQ(prt_sh_eval(order, n.data(), y.data()), PRT_OK);
    for (int c = 0; c < 3; ++c) {
      double e = 0.0;
      for (uint32_t i = 0; i < order * order; ++i) e += double(irradiance[i * 3 + c]) * y[i];
      // The l > 0 terms of the projection are midpoint-rule residue (O(1/H^2)).
      EXPECT_NEAR(e, kPi * radiance[c], 2e-3 * radiance[c]);
    }
  }
}

// Bound on the truncation error: |E_n(n) - max(0, n.d)| <= sum_{l >= order} |A_l| (2l+1)/(4 pi)
// (addition theorem, |P_l| <= 1). A_l from the closed form, summed far out, plus the analytic
// tail |A_l| (2l+1)/(4pi) ~ sqrt(2/pi) l^(-3/2) summed over even l > N: <= 1/sqrt(N).
double TruncationBound(uint32_t order) {
  const uint32_t n_max = 200000;
  double bound = 1.0 / std::sqrt(double(n_max));
  double central = 1.0;  // binom(l, l/2) / 2^l
  for (uint32_t l = 2; l <= n_max; l += 2) {
    central *= double(l - 1) / double(l);
    if (l < order) continue;
    const double a = 2.0 * kPi / (double(l + 2) * double(l - 1)) * central;
    bound += a * (2.0 * l + 1.0) / (4.0 * kPi);
  }
  return bound;
}

TEST(ShConvolve, DeltaLightApproachesClampedCosine) {
  const std::array<float, 3> d = {0.48f, 0.6f, -0.64f};
  std::mt19937 rng(1);
  double previous_error = 1e9;
  for (uint32_t order : {4u, 8u, 16u}) {
    // SH of a unit-power delta light from d: L_lm = Y_lm(d).
    std::vector<float> coeffs(order * order), irradiance(order * order), y(order * order);
    ASSERT_EQ(prt_sh_eval(order, d.data(), coeffs.data()), PRT_OK);
    ASSERT_EQ(prt_sh_convolve_cosine(order, coeffs.data(), irradiance.data(), 1), PRT_OK);
    const double bound = TruncationBound(order);
    double worst = 0.0;
    for (int k = 0; k < 400; ++k) {
      const auto n = prt_sh_test::RandomUnit(rng);
      ASSERT_EQ(prt_sh_eval(order, n.data(), y.data()), PRT_OK);
      double e = 0.0;
      for (uint32_t i = 0; i < order * order; ++i) e += double(irradiance[i]) * y[i];
      const double exact = std::max(0.0, double(n[0] * d[0] + n[1] * d[1] + n[2] * d[2]));
      worst = std::max(worst, std::abs(e - exact));
    }
    EXPECT_LE(worst, bound + 1e-5) << "order " << order;
    EXPECT_LT(worst, previous_error) << "order " << order;
    previous_error = worst;
  }
}

TEST(ShConvolve, InPlaceAndRejectsInvalidArguments) {
  std::vector<float> c(9 * 2, 1.0f);
  ASSERT_EQ(prt_sh_convolve_cosine(3, c.data(), c.data(), 2), PRT_OK);
  EXPECT_NEAR(c[0], kPi, 1e-6);
  EXPECT_NEAR(c[2 * 2], 2.0 * kPi / 3.0, 1e-6);
  EXPECT_NEAR(c[8 * 2 + 1], kPi / 4.0, 1e-6);
  EXPECT_EQ(prt_sh_convolve_cosine(0, c.data(), c.data(), 2), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_convolve_cosine(PRT_SH_MAX_ORDER + 1, c.data(), c.data(), 2),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_convolve_cosine(3, nullptr, c.data(), 2), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_convolve_cosine(3, c.data(), nullptr, 2), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_convolve_cosine(3, c.data(), c.data(), 0), PRT_ERROR_INVALID_ARGUMENT);
}

}  // namespace
