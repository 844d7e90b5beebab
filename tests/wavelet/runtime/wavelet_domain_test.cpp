// SPDX-License-Identifier: MIT
// Parameterisations of the sphere (SPEC §14, prt_wavelet.h): texel directions, solid angles,
// direction -> texel and bands, checked against the spec's formulas evaluated here, round trips,
// brute-force searches and integrals of the sphere (4 pi).
#include <gtest/gtest.h>
#include <prt/prt_wavelet.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

constexpr prt_wavelet_param kCube = PRT_WAVELET_PARAM_CUBE;
constexpr prt_wavelet_param kParaboloid = PRT_WAVELET_PARAM_DUAL_PARABOLOID;
constexpr uint32_t kNoTexel = 0xFFFFFFFFu;
constexpr double kPi = 3.14159265358979323846;
constexpr uint32_t kSizes[] = {16, 32, 64, 128};

// The paraboloid's texel centre test with integers only: centre a = (2x + 1 - S) / S.
bool paraboloid_inside(uint32_t size, uint32_t x, uint32_t y) {
  const long long a = 2LL * x + 1 - size, b = 2LL * y + 1 - size;
  return a * a + b * b <= static_cast<long long>(size) * size;
}

// SPEC §13's exact cube texel solid angle, written out from the spec text.
double spec_cube_solid_angle(uint32_t size, uint32_t x, uint32_t y) {
  auto omega = [](double a, double b) { return std::atan(a * b / std::sqrt(a * a + b * b + 1)); };
  const double s0 = 2.0 * x / size - 1, s1 = 2.0 * (x + 1) / size - 1;
  const double t0 = 2.0 * y / size - 1, t1 = 2.0 * (y + 1) / size - 1;
  return omega(s1, t1) - omega(s0, t1) - omega(s1, t0) + omega(s0, t0);
}

TEST(WaveletDomain, FaceAndCoefficientCounts) {
  EXPECT_EQ(prt_wavelet_face_count(kCube), 6u);
  EXPECT_EQ(prt_wavelet_face_count(kParaboloid), 2u);
  EXPECT_EQ(prt_wavelet_face_count(static_cast<prt_wavelet_param>(2)), 0u);
  for (uint32_t size : kSizes) {
    EXPECT_EQ(prt_wavelet_coefficient_count(kCube, size), 6u * size * size);
    EXPECT_EQ(prt_wavelet_coefficient_count(kParaboloid, size), 2u * size * size);
  }
  for (uint32_t bad : {0u, 1u, 8u, 24u, 48u, 256u}) {
    EXPECT_EQ(prt_wavelet_coefficient_count(kCube, bad), 0u) << bad;
  }
  EXPECT_EQ(prt_wavelet_coefficient_count(static_cast<prt_wavelet_param>(7), 64), 0u);
}

TEST(WaveletDomain, CubeDirectionsFollowTheSpecTable) {
  // Face centres are the axes, in the order +X, -X, +Y, -Y, +Z, -Z.
  const float axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (uint32_t f = 0; f < 6; ++f) {
    float d[3];
    ASSERT_EQ(prt_wavelet_direction(kCube, 16, f, 8.0f, 8.0f, d), 1);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(d[k], axes[f][k], 1e-7) << f;
  }
  // The corner (u, v) = (S, 0): s_c = 1, t_c = -1; §13 table entries, normalised by sqrt 3.
  const float corners[6][3] = {{1, 1, -1}, {-1, 1, 1}, {1, 1, -1},
                               {1, -1, 1}, {1, 1, 1},  {-1, 1, -1}};
  const float k = 1.0f / std::sqrt(3.0f);
  for (uint32_t f = 0; f < 6; ++f) {
    float d[3];
    ASSERT_EQ(prt_wavelet_direction(kCube, 32, f, 32.0f, 0.0f, d), 1);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(d[c], corners[f][c] * k, 1e-6) << f << " " << c;
  }
}

TEST(WaveletDomain, ParaboloidDirectionsFollowTheSpecFormula) {
  float d[3];
  // Disc centre: the poles.
  ASSERT_EQ(prt_wavelet_direction(kParaboloid, 16, 0, 8.0f, 8.0f, d), 1);
  EXPECT_NEAR(d[1], 1.0f, 1e-7);
  ASSERT_EQ(prt_wavelet_direction(kParaboloid, 16, 1, 8.0f, 8.0f, d), 1);
  EXPECT_NEAR(d[1], -1.0f, 1e-7);
  // Rim points (r = 1) are horizon directions: a = 1 -> +X on both faces; b = 1 -> +Z on the
  // upper face, -Z on the lower.
  ASSERT_EQ(prt_wavelet_direction(kParaboloid, 16, 0, 16.0f, 8.0f, d), 1);
  EXPECT_NEAR(d[0], 1.0f, 1e-7);
  ASSERT_EQ(prt_wavelet_direction(kParaboloid, 16, 1, 8.0f, 16.0f, d), 1);
  EXPECT_NEAR(d[2], -1.0f, 1e-7);
  ASSERT_EQ(prt_wavelet_direction(kParaboloid, 16, 0, 8.0f, 16.0f, d), 1);
  EXPECT_NEAR(d[2], 1.0f, 1e-7);
  // A corner is outside the disc.
  EXPECT_EQ(prt_wavelet_direction(kParaboloid, 16, 0, 0.0f, 0.0f, d), 0);
  // a = 0.5, b = 0 on face 0: (1, 0.75, 0) / 1.25.
  ASSERT_EQ(prt_wavelet_direction(kParaboloid, 16, 0, 12.0f, 8.0f, d), 1);
  EXPECT_NEAR(d[0], 0.8f, 1e-7);
  EXPECT_NEAR(d[1], 0.6f, 1e-7);
}

// The batch call is the single call point by point, bit for bit, including points with no
// direction (off the disc, outside the face, NaN), whose outputs it leaves untouched.
TEST(WaveletDomain, DirectionsAreTheSingleCallPointByPoint) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coordinate(-1.0f, 17.0f);
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    for (uint32_t face = 0; face < prt_wavelet_face_count(param); ++face) {
      std::vector<float> u(300), v(300);
      for (size_t i = 0; i < u.size(); ++i) u[i] = coordinate(rng), v[i] = coordinate(rng);
      u[0] = std::numeric_limits<float>::quiet_NaN();
      u[1] = 16.0f, v[1] = 0.0f;  // the closed face's edge
      std::vector<float> dirs(3 * u.size(), -7.0f);
      std::vector<uint8_t> has(u.size(), 9);
      ASSERT_EQ(prt_wavelet_directions(param, 16, face, uint32_t(u.size()), u.data(), v.data(),
                                       dirs.data(), has.data()),
                1);
      for (size_t i = 0; i < u.size(); ++i) {
        float d[3] = {-7.0f, -7.0f, -7.0f};
        const int one = prt_wavelet_direction(param, 16, face, u[i], v[i], d);
        ASSERT_EQ(int(has[i]), one) << i;
        for (int c = 0; c < 3; ++c) EXPECT_EQ(dirs[3 * i + c], d[c]) << i;  // -7 when none
      }
    }
  }
}

TEST(WaveletDomain, DirectionsRejectBadArgumentsAndWriteNothing) {
  const float u = 8.0f, v = 8.0f;
  float dir[3] = {-7.0f, -7.0f, -7.0f};
  uint8_t has = 9;
  EXPECT_EQ(prt_wavelet_directions(kCube, 24, 0, 1, &u, &v, dir, &has), 0);
  EXPECT_EQ(prt_wavelet_directions(kCube, 16, 6, 1, &u, &v, dir, &has), 0);
  EXPECT_EQ(prt_wavelet_directions(kParaboloid, 16, 2, 1, &u, &v, dir, &has), 0);
  EXPECT_EQ(prt_wavelet_directions(kCube, 16, 0, 1, nullptr, &v, dir, &has), 0);
  EXPECT_EQ(prt_wavelet_directions(kCube, 16, 0, 1, &u, &v, dir, nullptr), 0);
  EXPECT_EQ(dir[0], -7.0f);
  EXPECT_EQ(has, 9);
  EXPECT_EQ(prt_wavelet_directions(kCube, 16, 0, 0, nullptr, nullptr, nullptr, nullptr), 1);
}

TEST(WaveletDomain, DirectionLocateRoundTripOnEveryTexel) {
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    for (uint32_t size : kSizes) {
      const uint32_t faces = prt_wavelet_face_count(param);
      uint32_t failures = 0;
      for (uint32_t f = 0; f < faces; ++f) {
        for (uint32_t y = 0; y < size; ++y) {
          for (uint32_t x = 0; x < size; ++x) {
            float d[3];
            const int has = prt_wavelet_direction(param, size, f, x + 0.5f, y + 0.5f, d);
            const bool inside = param == kCube || paraboloid_inside(size, x, y);
            ASSERT_EQ(has, inside ? 1 : 0) << param << " " << size << " " << x << " " << y;
            if (!inside) continue;
            EXPECT_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0f, 1e-6f);
            const uint32_t j = f * size * size + y * size + x;
            if (prt_wavelet_locate(param, size, d) != j) ++failures;
          }
        }
      }
      EXPECT_EQ(failures, 0u) << "param " << param << " size " << size;
    }
  }
}

TEST(WaveletDomain, CubeSolidAnglesAreTheSpecFormulaAndSumTo4Pi) {
  for (uint32_t size : kSizes) {
    double total = 0.0;
    for (uint32_t f = 0; f < 6; ++f) {
      double face_total = 0.0;
      for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
          const double w = prt_wavelet_texel_solid_angle(kCube, size, f, x, y);
          EXPECT_NEAR(w, spec_cube_solid_angle(size, x, y), 1e-15);
          face_total += w;
        }
      }
      EXPECT_NEAR(face_total, 4.0 * kPi / 6.0, 1e-12);  // six congruent faces
      total += face_total;
    }
    EXPECT_NEAR(total, 4.0 * kPi, 1e-11);
  }
}

// Sum of the paraboloid's inside texels. Per face, with h = 2/S the texel side in disc units,
// delta = h / sqrt 2 its half diagonal, J = 4 / (1 + r^2)^2 and U the union of inside texels
// (centre in the unit disc D, so D(1 - delta) c U c D(1 + delta)):
//   sum J(centre) h^2 = int_U J + E_mid,  |E_mid| <= N h^4 (|J_aa| + |J_bb|)max / 24 <= N h^4 4/3
//   int_U J = 2 pi + (area U - pi) + E_rim,  |E_rim| <= max|J - 1| area(U xor D)
//           <= 2.43 delta * 4 pi delta   (|dJ/dr| <= 2.43 for r in [0.9, 1.1], J(1) = 1)
// with area U = N h^2, N the number of inside texels, counted here with integers.
TEST(WaveletDomain, ParaboloidSolidAnglesSumTo4PiWithinTheDiscretisationError) {
  for (uint32_t size : kSizes) {
    const double h = 2.0 / size, delta = h / std::sqrt(2.0);
    for (uint32_t f = 0; f < 2; ++f) {
      double total = 0.0;
      uint32_t inside = 0;
      for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
          const double w = prt_wavelet_texel_solid_angle(kParaboloid, size, f, x, y);
          if (paraboloid_inside(size, x, y)) {
            ++inside;
            EXPECT_GT(w, 0.0);
          } else {
            EXPECT_EQ(w, 0.0);
          }
          total += w;
        }
      }
      const double expected = 2.0 * kPi + (inside * h * h - kPi);
      const double bound = 2.43 * 4.0 * kPi * delta * delta + inside * h * h * h * h * 4.0 / 3.0;
      EXPECT_NEAR(total, expected, bound) << size;
      // The hemisphere itself: |area U - pi| <= pi ((1 + delta)^2 - 1) adds to the bound.
      EXPECT_NEAR(total, 2 * kPi, bound + kPi * (2 * delta + delta * delta)) << size;
    }
  }
}

TEST(WaveletDomain, CubeLocateTiesAndSpecialDirections) {
  const uint32_t s = 16, face = s * s;
  const float px[3] = {1, 0, 0}, tie_xy[3] = {1, 1, 0}, tie_yz[3] = {0, -1, 1};
  const float mz[3] = {0, 0, -2}, zero[3] = {0, 0, 0};
  const float nan[3] = {std::numeric_limits<float>::quiet_NaN(), 1, 0};
  const float inf[3] = {std::numeric_limits<float>::infinity(), 0, 0};
  // +X axis: s_c = t_c = 0 -> texel (S/2, S/2) of face 0.
  EXPECT_EQ(prt_wavelet_locate(kCube, s, px), 0 * face + 8 * s + 8);
  // Ties go to the earlier face: (1, 1, 0) -> +X (edge t_c = -1, row 0); (0, -1, 1) -> -Y.
  EXPECT_EQ(prt_wavelet_locate(kCube, s, tie_xy), 0 * face + 0 * s + 8);
  EXPECT_EQ(prt_wavelet_locate(kCube, s, tie_yz) / face, 3u);
  // Length does not matter; -Z axis -> face 5's middle.
  EXPECT_EQ(prt_wavelet_locate(kCube, s, mz), 5 * face + 8 * s + 8);
  EXPECT_EQ(prt_wavelet_locate(kCube, s, zero), 0u);
  EXPECT_EQ(prt_wavelet_locate(kCube, s, nan), 0u);
  EXPECT_EQ(prt_wavelet_locate(kCube, s, inf), 0u);
  EXPECT_EQ(prt_wavelet_locate(kCube, s, nullptr), 0u);
  EXPECT_EQ(prt_wavelet_locate(kCube, 20, px), kNoTexel);
  EXPECT_EQ(prt_wavelet_locate(static_cast<prt_wavelet_param>(5), 16, px), kNoTexel);
}

// The rim rule: a direction whose (a, b) lies in an outside texel belongs to the inside texel of
// the same face whose centre is nearest (a, b) (ties: lower index) — checked by brute force.
TEST(WaveletDomain, ParaboloidRimDirectionsGoToTheNearestInsideTexel) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi), height(-0.02, 0.02);
  for (uint32_t size : kSizes) {
    uint32_t rim_cases = 0;
    for (int i = 0; i < 2000; ++i) {
      const double phi = angle(rng), y = height(rng), r = std::sqrt(1.0 - y * y);
      const float d[3] = {float(r * std::cos(phi)), float(y), float(r * std::sin(phi))};
      const uint32_t j = prt_wavelet_locate(kParaboloid, size, d);
      ASSERT_LT(j, 2 * size * size);
      const uint32_t f = j / (size * size), x = j % size, yy = (j / size) % size;
      ASSERT_TRUE(paraboloid_inside(size, x, yy));
      // (a, b) from the spec's inverse, in double from the same float direction.
      const double dx = d[0], dy = d[1], dz = d[2];
      const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
      const double ux = dx / len, uy = dy / len, uz = dz / len;
      ASSERT_EQ(f, uy >= 0 ? 0u : 1u);
      const double a = f == 0 ? ux / (1 + uy) : ux / (1 - uy);
      const double b = f == 0 ? uz / (1 + uy) : -uz / (1 - uy);
      uint32_t best = 0;
      double best_distance = 1e300;
      for (uint32_t ty = 0; ty < size; ++ty) {
        for (uint32_t tx = 0; tx < size; ++tx) {
          if (!paraboloid_inside(size, tx, ty)) continue;
          const double ca = (2.0 * tx + 1) / size - 1, cb = (2.0 * ty + 1) / size - 1;
          const double dd = (ca - a) * (ca - a) + (cb - b) * (cb - b);
          if (dd < best_distance) best_distance = dd, best = ty * size + tx;
        }
      }
      const uint32_t cx = uint32_t(std::floor((a + 1) * 0.5 * size));
      const uint32_t cy = uint32_t(std::floor((b + 1) * 0.5 * size));
      const bool own_inside = cx < size && cy < size && paraboloid_inside(size, cx, cy);
      if (!own_inside) {
        ++rim_cases;
        EXPECT_EQ(j % (size * size), best) << size << " " << a << " " << b;
      } else {
        EXPECT_EQ(j % (size * size), cy * size + cx);
      }
    }
    EXPECT_GT(rim_cases, 100u) << size;  // the test exercised the rule
  }
  // No direction: an inside texel of face 0.
  const float zero[3] = {0, 0, 0};
  const uint32_t j = prt_wavelet_locate(kParaboloid, 16, zero);
  ASSERT_LT(j, 256u);
  EXPECT_TRUE(paraboloid_inside(16, j % 16, j / 16));
}

TEST(WaveletDomain, BandsNumberedByHand) {
  // S = 16: log2 S + 1 = 5 bands per face: the scaling coefficient, then levels 0..3.
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 0), 0u);                           // (0, 0) scaling
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 1), 1u);                           // (1, 0) level 0
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 16), 1u);                          // (0, 1) level 0
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 17), 1u);                          // (1, 1) level 0
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 3 * 16 + 2), 2u);                  // (2, 3) level 1
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 4), 3u);                           // (4, 0) level 2
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 7 * 16 + 7), 3u);                  // (7, 7) level 2
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 8 * 16), 4u);                      // (0, 8) level 3
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 255), 4u);                         // (15, 15) level 3
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 256), 5u);                         // face 1 scaling
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 6 * 256 - 1), 29u);                // face 5, level 3
  EXPECT_EQ(prt_wavelet_band(kParaboloid, 128, 128 * 128 + 64), 8u + 7u);  // face 1, level 6
  EXPECT_EQ(prt_wavelet_band(kCube, 16, 6 * 256), kNoTexel);
  EXPECT_EQ(prt_wavelet_band(kParaboloid, 16, 2 * 256), kNoTexel);
  EXPECT_EQ(prt_wavelet_band(kCube, 12, 0), kNoTexel);
  EXPECT_EQ(prt_wavelet_band(static_cast<prt_wavelet_param>(9), 16, 0), kNoTexel);
}

TEST(WaveletDomain, BadArgumentsRejected) {
  float d[3];
  EXPECT_EQ(prt_wavelet_direction(kCube, 16, 6, 1, 1, d), 0);
  EXPECT_EQ(prt_wavelet_direction(kParaboloid, 16, 2, 8, 8, d), 0);
  EXPECT_EQ(prt_wavelet_direction(kCube, 16, 0, -0.5f, 1, d), 0);
  EXPECT_EQ(prt_wavelet_direction(kCube, 16, 0, 1, 16.5f, d), 0);
  EXPECT_EQ(prt_wavelet_direction(kCube, 16, 0, std::nanf(""), 1, d), 0);
  EXPECT_EQ(prt_wavelet_direction(kCube, 16, 0, 1, 1, nullptr), 0);
  EXPECT_EQ(prt_wavelet_direction(kCube, 256, 0, 1, 1, d), 0);
  EXPECT_EQ(prt_wavelet_direction(static_cast<prt_wavelet_param>(3), 16, 0, 1, 1, d), 0);
  EXPECT_EQ(prt_wavelet_texel_solid_angle(kCube, 16, 6, 0, 0), 0.0);
  EXPECT_EQ(prt_wavelet_texel_solid_angle(kCube, 16, 0, 16, 0), 0.0);
  EXPECT_EQ(prt_wavelet_texel_solid_angle(kCube, 16, 0, 0, 16), 0.0);
  EXPECT_EQ(prt_wavelet_texel_solid_angle(kCube, 17, 0, 0, 0), 0.0);
  EXPECT_EQ(prt_wavelet_texel_solid_angle(kParaboloid, 16, 0, 0, 0), 0.0);  // outside the disc
}

}  // namespace
