// prt_sh_rotate: against re-projection of a rotated analytic environment, and group properties
// (identity, inverse, composition, per-band norm), plus the band-1 case written by hand.
#include <gtest/gtest.h>
#include <prt/prt_sh.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "sh/sh_test_util.hpp"

namespace {

using prt_sh_test::kPi;
using Mat3 = std::array<double, 9>;

Mat3 AxisAngle(std::array<double, 3> axis, double angle) {
  const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  for (auto& a : axis) a /= len;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  const double x = axis[0], y = axis[1], z = axis[2];
  return {t * x * x + c,     t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
          t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c};
}

Mat3 Multiply(const Mat3& a, const Mat3& b) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i * 3 + j] += a[i * 3 + k] * b[k * 3 + j];
  return r;
}

Mat3 Transpose(const Mat3& a) {
  return {a[0], a[3], a[6], a[1], a[4], a[7], a[2], a[5], a[8]};
}

std::array<float, 9> ToFloat(const Mat3& m) {
  std::array<float, 9> f;
  for (int i = 0; i < 9; ++i) f[i] = float(m[i]);
  return f;
}

std::vector<float> Rotate(uint32_t order, const Mat3& r, const std::vector<float>& in,
                          uint32_t channels) {
  std::vector<float> out(in.size());
  const auto rf = ToFloat(r);
  EXPECT_EQ(prt_sh_rotate(order, rf.data(), in.data(), out.data(), channels), PRT_OK);
  return out;
}

// A smooth environment of three coloured Gaussian lobes.
struct Lobe {
  std::array<double, 3> axis;
  double sharpness;
  std::array<double, 3> colour;
};
const Lobe kLobes[] = {{{0.3, 0.8, -0.5}, 6.0, {4.0, 3.0, 2.0}},
                       {{-0.7, 0.1, 0.7}, 4.0, {0.5, 1.0, 2.0}},
                       {{0.2, -0.9, 0.4}, 8.0, {1.5, 0.2, 0.3}}};

std::array<double, 3> LobeRadiance(const std::array<double, 3>& d) {
  std::array<double, 3> sum = {0.05, 0.05, 0.05};
  for (const auto& lobe : kLobes) {
    const auto& a = lobe.axis;
    const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double cosine = (d[0] * a[0] + d[1] * a[1] + d[2] * a[2]) / len;
    const double g = std::exp(lobe.sharpness * (cosine - 1.0));
    for (int c = 0; c < 3; ++c) sum[c] += lobe.colour[c] * g;
  }
  return sum;
}

// Lat-long texel centres as formats/SPEC.md §12; optionally the map is rotated by R:
// L'(d) = L(R^T d).
std::vector<float> ProjectLobes(uint32_t order, const Mat3* rotation) {
  const uint32_t w = 512, h = 256;
  std::vector<float> image(size_t(w) * h * 3);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double phi = 2.0 * kPi * ((x + 0.5) / w - 0.5), theta = kPi * (y + 0.5) / h;
      std::array<double, 3> d = {std::sin(theta) * std::sin(phi), std::cos(theta),
                                 -std::sin(theta) * std::cos(phi)};
      if (rotation) {
        const Mat3 rt = Transpose(*rotation);
        d = {rt[0] * d[0] + rt[1] * d[1] + rt[2] * d[2], rt[3] * d[0] + rt[4] * d[1] + rt[5] * d[2],
             rt[6] * d[0] + rt[7] * d[1] + rt[8] * d[2]};
      }
      const auto l = LobeRadiance(d);
      for (int c = 0; c < 3; ++c) image[(size_t(y) * w + x) * 3 + c] = float(l[c]);
    }
  std::vector<float> out(order * order * 3);
  EXPECT_EQ(prt_sh_test::ProjectLatLong(order, w, h, image.data(), w * 3, out.data()), PRT_OK);
  return out;
}

double MaxAbs(const std::vector<float>& v) {
  double m = 0.0;
  for (float x : v) m = std::max(m, double(std::abs(x)));
  return m;
}

TEST(ShRotate, MatchesReprojectionOfRotatedEnvironmentOrder8) {
  const uint32_t order = 8;
  const auto original = ProjectLobes(order, nullptr);
  for (const Mat3& r : {AxisAngle({0, 1, 0}, 0.9), AxisAngle({1, 0.4, -0.3}, 2.2),
                        AxisAngle({-0.2, 0.5, 1.0}, -1.3)}) {
    const auto reprojected = ProjectLobes(order, &r);
    const auto rotated = Rotate(order, r, original, 3);
    const double scale = MaxAbs(original);
    for (size_t i = 0; i < rotated.size(); ++i)
      EXPECT_NEAR(rotated[i], reprojected[i], 2e-3 * scale) << "value " << i;
  }
}

std::vector<float> RandomCoefficients(uint32_t order, uint32_t channels, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> v(order * order * channels);
  for (auto& x : v) x = u(rng);
  return v;
}

TEST(ShRotate, IdentityInverseCompositionAndBandNorms) {
  const Mat3 a = AxisAngle({0.3, -0.4, 0.8}, 1.1), b = AxisAngle({-1.0, 0.2, 0.1}, 2.5);
  for (uint32_t order : {1u, 2u, 5u, 8u, PRT_SH_MAX_ORDER}) {
    const auto c = RandomCoefficients(order, 2, order);
    const double tol = 1e-4 * order;
    const auto same = Rotate(order, AxisAngle({0, 0, 1}, 0.0), c, 2);
    for (size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(same[i], c[i], 1e-6);
    const auto back = Rotate(order, Transpose(a), Rotate(order, a, c, 2), 2);
    for (size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(back[i], c[i], tol) << order;
    const auto two_steps = Rotate(order, b, Rotate(order, a, c, 2), 2);
    const auto one_step = Rotate(order, Multiply(b, a), c, 2);
    for (size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(two_steps[i], one_step[i], tol) << order;
    const auto rotated = Rotate(order, a, c, 2);
    for (uint32_t l = 0; l < order; ++l)
      for (uint32_t ch = 0; ch < 2; ++ch) {
        double n0 = 0.0, n1 = 0.0;
        for (uint32_t i = l * l; i < (l + 1) * (l + 1); ++i) {
          n0 += double(c[i * 2 + ch]) * c[i * 2 + ch];
          n1 += double(rotated[i * 2 + ch]) * rotated[i * 2 + ch];
        }
        EXPECT_NEAR(n1, n0, tol * (1.0 + n0)) << "order " << order << " band " << l;
      }
  }
}

// Band 1 by hand: radiance f(d) = g.d has coefficients sqrt(4 pi/3) (g_y, g_z, g_x) in the SH
// frame (y = -Z, z = Y, x = X); the rotated light f(R^T d) = (R g).d.
TEST(ShRotate, Band1IsTheRotatedLinearFunction) {
  const Mat3 r = AxisAngle({0.6, 0.2, -0.4}, 0.7);
  const std::array<double, 3> g = {0.3, -1.2, 0.8};
  const double k = std::sqrt(4.0 * kPi / 3.0);
  auto coeffs = [&](const std::array<double, 3>& v) {
    return std::vector<float>{0.0f, float(k * -v[2]), float(k * v[1]), float(k * v[0])};
  };
  const std::array<double, 3> rg = {r[0] * g[0] + r[1] * g[1] + r[2] * g[2],
                                    r[3] * g[0] + r[4] * g[1] + r[5] * g[2],
                                    r[6] * g[0] + r[7] * g[1] + r[8] * g[2]};
  const auto rotated = Rotate(2, r, coeffs(g), 1);
  const auto expected = coeffs(rg);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(rotated[i], expected[i], 1e-6);
}

// A rotation about world +Y is a rotation about the SH polar axis: zonal (m = 0) terms stay.
TEST(ShRotate, VerticalRotationKeepsZonalTerms) {
  const auto c = RandomCoefficients(8, 1, 3);
  const auto r = Rotate(8, AxisAngle({0, 1, 0}, 0.77), c, 1);
  for (uint32_t l = 0; l < 8; ++l) EXPECT_NEAR(r[l * (l + 1)], c[l * (l + 1)], 1e-5);
}

TEST(ShRotate, InPlaceEqualsOutOfPlace) {
  const Mat3 a = AxisAngle({0.1, 0.9, 0.3}, 2.0);
  auto c = RandomCoefficients(6, 3, 9);
  const auto expected = Rotate(6, a, c, 3);
  const auto af = ToFloat(a);
  ASSERT_EQ(prt_sh_rotate(6, af.data(), c.data(), c.data(), 3), PRT_OK);
  for (size_t i = 0; i < c.size(); ++i) EXPECT_EQ(c[i], expected[i]);
}

TEST(ShRotate, RejectsInvalidArguments) {
  const auto id = ToFloat(AxisAngle({0, 0, 1}, 0.0));
  std::vector<float> c(64 * 3, 1.0f), out(64 * 3);
  EXPECT_EQ(prt_sh_rotate(0, id.data(), c.data(), out.data(), 3), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_rotate(PRT_SH_MAX_ORDER + 1, id.data(), c.data(), out.data(), 3),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_rotate(3, nullptr, c.data(), out.data(), 3), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_rotate(3, id.data(), nullptr, out.data(), 3), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_rotate(3, id.data(), c.data(), nullptr, 3), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_rotate(3, id.data(), c.data(), out.data(), 0), PRT_ERROR_INVALID_ARGUMENT);
  const float mirror[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
  const float scaled[9] = {2, 0, 0, 0, 2, 0, 0, 0, 2};
  const float nan_m[9] = {NAN, 0, 0, 0, 1, 0, 0, 0, 1};
  EXPECT_EQ(prt_sh_rotate(3, mirror, c.data(), out.data(), 3), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_rotate(3, scaled, c.data(), out.data(), 3), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_rotate(3, nan_m, c.data(), out.data(), 3), PRT_ERROR_INVALID_ARGUMENT);
}

}  // namespace
