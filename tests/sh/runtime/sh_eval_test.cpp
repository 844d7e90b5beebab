// prt_sh_eval against independent values: textbook closed forms (l <= 3) written in our frame,
// orthonormality by a quadrature exact for the band limit, finiteness at the poles.
#include <gtest/gtest.h>
#include <prt/prt_sh.h>

#include <cmath>
#include <random>
#include <vector>

#include "sh/sh_test_util.hpp"

namespace {

using prt_sh_test::kPi;
using prt_sh_test::ShIndex;

// Real SH of l <= 3 from the textbook polynomial forms (e.g. Sloan, "Stupid SH tricks",
// appendix), no Condon-Shortley phase, in SH-frame coordinates (x, y, z).
std::vector<double> ClosedFormUpTo3(double x, double y, double z) {
  std::vector<double> v(16);
  const double pi = kPi;
  v[0] = 0.5 * std::sqrt(1.0 / pi);
  const double c1 = std::sqrt(3.0 / (4.0 * pi));
  v[1] = c1 * y;
  v[2] = c1 * z;
  v[3] = c1 * x;
  const double c2 = 0.5 * std::sqrt(15.0 / pi);
  v[4] = c2 * x * y;
  v[5] = c2 * y * z;
  v[6] = 0.25 * std::sqrt(5.0 / pi) * (3.0 * z * z - 1.0);
  v[7] = c2 * x * z;
  v[8] = 0.25 * std::sqrt(15.0 / pi) * (x * x - y * y);
  v[9] = 0.25 * std::sqrt(35.0 / (2.0 * pi)) * y * (3.0 * x * x - y * y);
  v[10] = 0.5 * std::sqrt(105.0 / pi) * x * y * z;
  v[11] = 0.25 * std::sqrt(21.0 / (2.0 * pi)) * y * (5.0 * z * z - 1.0);
  v[12] = 0.25 * std::sqrt(7.0 / pi) * z * (5.0 * z * z - 3.0);
  v[13] = 0.25 * std::sqrt(21.0 / (2.0 * pi)) * x * (5.0 * z * z - 1.0);
  v[14] = 0.25 * std::sqrt(105.0 / pi) * z * (x * x - y * y);
  v[15] = 0.25 * std::sqrt(35.0 / (2.0 * pi)) * x * (x * x - 3.0 * y * y);
  return v;
}

TEST(ShEval, MatchesClosedFormsUpToBand3InDocumentedFrame) {
  std::mt19937 rng(7);
  for (int k = 0; k < 200; ++k) {
    const auto d = prt_sh_test::RandomUnit(rng);
    float out[16];
    ASSERT_EQ(prt_sh_eval(4, d.data(), out), PRT_OK);
    // SH frame: x = X, y = -Z, z = Y.
    const auto expected = ClosedFormUpTo3(d[0], -d[2], d[1]);
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(out[i], expected[i], 2e-6) << "index " << i;
  }
}

TEST(ShEval, PolarAxisIsWorldUp) {
  const float up[3] = {0, 1, 0};
  float out[9];
  ASSERT_EQ(prt_sh_eval(3, up, out), PRT_OK);
  EXPECT_NEAR(out[ShIndex(1, 0)], std::sqrt(3.0 / (4.0 * kPi)), 1e-6);
  EXPECT_NEAR(out[ShIndex(2, 0)], std::sqrt(5.0 / (4.0 * kPi)), 1e-6);
  for (int m : {-1, 1}) EXPECT_NEAR(out[ShIndex(1, m)], 0.0, 1e-7);
}

// Gauss-Legendre in cos(theta) with n nodes is exact for polynomials of degree 2n-1 and uniform
// phi with M points is exact for trigonometric degree < M: products of two band-(L-1) functions
// are integrated exactly with n = L and M = 2L.
void ExpectOrthonormal(uint32_t order, double tolerance) {
  const auto gl = prt_sh_test::GaussLegendre(order + 1);
  const uint32_t count = order * order;
  const int phi_steps = 2 * static_cast<int>(order) + 2;
  std::vector<double> gram(count * count, 0.0);
  std::vector<float> y(count);
  for (size_t a = 0; a < gl.nodes.size(); ++a) {
    const double z = gl.nodes[a];
    const double s = std::sqrt(1.0 - z * z);
    for (int b = 0; b < phi_steps; ++b) {
      const double phi = 2.0 * kPi * (b + 0.25) / phi_steps;
      // SH frame (s cos phi, s sin phi, z) -> world (x, z, -y).
      const float world[3] = {static_cast<float>(s * std::cos(phi)), static_cast<float>(z),
                              static_cast<float>(-s * std::sin(phi))};
      ASSERT_EQ(prt_sh_eval(order, world, y.data()), PRT_OK);
      const double w = gl.weights[a] * 2.0 * kPi / phi_steps;
      for (uint32_t i = 0; i < count; ++i)
        for (uint32_t j = 0; j < count; ++j) gram[i * count + j] += w * y[i] * y[j];
    }
  }
  double worst = 0.0;
  for (uint32_t i = 0; i < count; ++i)
    for (uint32_t j = 0; j < count; ++j)
      worst = std::max(worst, std::abs(gram[i * count + j] - (i == j ? 1.0 : 0.0)));
  EXPECT_LT(worst, tolerance) << "order " << order;
}

TEST(ShEval, OrthonormalByExactQuadratureOrder8) {
  ExpectOrthonormal(8, 1e-5);
}
TEST(ShEval, OrthonormalByExactQuadratureMaxOrder) {
  ExpectOrthonormal(PRT_SH_MAX_ORDER, 1e-4);
}

TEST(ShEval, FiniteAtPolesAndRandomDirectionsForOrder1AndMax) {
  std::mt19937 rng(11);
  std::vector<std::array<float, 3>> dirs = {{0, 1, 0}, {0, -1, 0}, {0, 1e-30f, 0}, {1, 0, 0}};
  for (int k = 0; k < 100; ++k) dirs.push_back(prt_sh_test::RandomUnit(rng));
  std::vector<float> out(PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER);
  for (const auto& d : dirs) {
    for (uint32_t order : {1u, PRT_SH_MAX_ORDER}) {
      ASSERT_EQ(prt_sh_eval(order, d.data(), out.data()), PRT_OK);
      for (uint32_t i = 0; i < order * order; ++i) ASSERT_TRUE(std::isfinite(out[i]));
      // Addition theorem: sum_m Y_lm^2 = (2l+1)/(4 pi) for every band, at every direction.
      for (uint32_t l = 0; l < order; ++l) {
        double sum = 0.0;
        for (int m = -static_cast<int>(l); m <= static_cast<int>(l); ++m)
          sum += double(out[ShIndex(l, m)]) * out[ShIndex(l, m)];
        EXPECT_NEAR(sum, (2.0 * l + 1.0) / (4.0 * kPi), 1e-5 * (2.0 * l + 1.0));
      }
    }
  }
}

TEST(ShEval, NormalisesItsInputDirection) {
  const float d[3] = {0.3f, -0.5f, 0.8f};
  const float d_scaled[3] = {3.0f, -5.0f, 8.0f};
  float a[25], b[25];
  ASSERT_EQ(prt_sh_eval(5, d, a), PRT_OK);
  ASSERT_EQ(prt_sh_eval(5, d_scaled, b), PRT_OK);
  float unit[3];
  const float len = std::sqrt(0.09f + 0.25f + 0.64f);
  for (int i = 0; i < 3; ++i) unit[i] = d[i] / len;
  ASSERT_EQ(prt_sh_eval(5, unit, a), PRT_OK);
  for (int i = 0; i < 25; ++i) EXPECT_NEAR(a[i], b[i], 1e-6);
}

TEST(ShEval, RejectsInvalidArguments) {
  const float d[3] = {0, 0, 1};
  const float zero[3] = {0, 0, 0};
  const float nan_dir[3] = {NAN, 0, 1};
  float out[PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER];
  EXPECT_EQ(prt_sh_eval(0, d, out), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_eval(PRT_SH_MAX_ORDER + 1, d, out), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_eval(3, nullptr, out), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_eval(3, d, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_eval(3, zero, out), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_eval(3, nan_dir, out), PRT_ERROR_INVALID_ARGUMENT);
}

}  // namespace
