// SPDX-License-Identifier: MIT
// The wavelet transfer against independent values: each cube texel of an unoccluded vertex
// (the mean of cos/pi over it, SPEC §14) against the exact clamped-cosine integral over the
// texel (Lambert's polygon formula) over its solid angle, within the texel's own bound (the
// cosine's variation over it); their solid-angle-weighted sum against integral cos/pi = 1; the Haar
// rows against the texels (the face's scaling coefficient is sum/size, Parseval); the horizon
// rule's ray count against the cube's geometry; truncation by count and by energy on hand-made
// rows; determinism over thread counts.
#include <gtest/gtest.h>

#include <prt/prt_wavelet.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "prt/baker/wavelet/wavelet_transfer.hpp"
#include "support/render_test_scenes.hpp"
#include "wavelet/wavelet_test_util.hpp"

namespace prt::bake {
namespace {

using test::kPi;

// Largest angle between two corners of a texel: its angular diameter (a convex spherical quad).
double texel_diameter(const std::vector<glm::dvec3>& corners) {
  double best = 0.0;
  for (const glm::dvec3& a : corners) {
    for (const glm::dvec3& b : corners) {
      best = std::max(
          best, std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)));
    }
  }
  return best;
}

void check_unoccluded_texels(std::uint32_t size, std::uint32_t samples, glm::dvec3 normal) {
  normal = glm::normalize(normal);
  const std::vector<float> texels =
      unoccluded_wavelet_texels(PRT_WAVELET_PARAM_CUBE, size, samples, glm::vec3(normal), 7);
  ASSERT_EQ(texels.size(), 6u * size * size);
  double sum = 0.0, exact_sum = 0.0, bound = 0.0;
  for (std::uint32_t f = 0; f < 6; ++f) {
    for (std::uint32_t y = 0; y < size; ++y) {
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::vector<glm::dvec3> corners = test::cube_texel(size, f, x, y);
        const double integral = test::clamped_cosine_integral(corners, normal) / kPi;
        const double omega = prt_wavelet_texel_solid_angle(PRT_WAVELET_PARAM_CUBE, size, f, x, y);
        // The estimate is a weighted mean of cos/pi over the texel; cos is 1-Lipschitz in
        // angle, so it differs from the exact mean by at most the diameter/pi.
        const double allowed = texel_diameter(corners) / kPi + 1e-6;
        const float t = texels[(f * size + y) * size + x];
        ASSERT_NEAR(t, integral / omega, allowed) << "face " << f << " texel " << x << "," << y;
        sum += t * omega;
        exact_sum += integral;
        bound += integral > 0.0 || t > 0.0 ? omega * allowed : 0.0;
      }
    }
  }
  EXPECT_NEAR(exact_sum, 1.0, 1e-9);  // the reference itself: integral of cos/pi = 1
  EXPECT_NEAR(sum, 1.0, bound);
  // Jitter errors cancel over thousands of texels: far inside the worst-case bound.
  EXPECT_NEAR(sum, 1.0, 0.02 * bound);
}

TEST(WaveletTransfer, UnoccludedTexelsMatchTheExactIntegralNormalUp) {
  check_unoccluded_texels(32, 1, {0, 1, 0});
}

TEST(WaveletTransfer, UnoccludedTexelsMatchTheExactIntegralTiltedNormalAndSupersampling) {
  check_unoccluded_texels(16, 4, {0.3, 0.8, -0.52});
  check_unoccluded_texels(16, 1, {-1, -0.2, 0.1});
}

TEST(WaveletTransfer, ParaboloidUnoccludedSumsToOne) {
  for (std::uint32_t size : {32u, 64u}) {
    const std::vector<float> texels =
        unoccluded_wavelet_texels(PRT_WAVELET_PARAM_DUAL_PARABOLOID, size, 4, {0, 1, 0}, 3);
    // The texel means weighted by their solid angles integrate cos/pi. The SPEC's texel solid
    // angle (Jacobian at the centre, rim texels whole or nothing) is a midpoint rule: its total
    // differs from 4 pi by the rim's share, and the transfer's sum from 1 by less (the rim is
    // the horizon of the normal +Y, where the cosine vanishes).
    double total = 0.0, sum = 0.0;
    for (std::uint32_t f = 0; f < 2; ++f)
      for (std::uint32_t y = 0; y < size; ++y)
        for (std::uint32_t x = 0; x < size; ++x) {
          const double omega =
              prt_wavelet_texel_solid_angle(PRT_WAVELET_PARAM_DUAL_PARABOLOID, size, f, x, y);
          total += omega;
          sum += omega * texels[(std::size_t(f) * size + y) * size + x];
        }
    const double rim = std::abs(total - 4.0 * kPi) / (4.0 * kPi);
    EXPECT_NEAR(sum, 1.0, rim) << size;
    // Nothing below the horizon: face 1 (y < 0) gets nothing for the normal +Y.
    for (std::size_t j = std::size_t(size) * size; j < texels.size(); ++j)
      ASSERT_EQ(texels[j], 0.0f);
  }
}

// A vertex at the centre of a plane, nothing above: the ray count is the texels with some
// direction above the horizon (the +Y face and the upper halves of the four side faces: 3 S^2),
// times the samples; the rows after the transform hold the same function.
TEST(WaveletTransfer, UnoccludedVertexRowsAndRayCount) {
  Scene scene;
  scene.meshes.push_back(test::make_plane(1.0f, 2));
  WaveletTransferSettings s;
  s.size = 16;
  s.samples = 4;
  s.keep = 0;
  s.vertex_list = {4};  // the centre vertex
  Context ctx;
  const WaveletTransfer t = compute_wavelet_transfer(scene, nullptr, s, ctx);
  EXPECT_EQ(t.rays_traced, 3u * 16u * 16u * 4u);
  ASSERT_EQ(t.vertex_count, 9u);
  for (std::size_t v = 0; v < 9; ++v) EXPECT_EQ(t.row_size(v) > 0, v == 4) << v;
  double scaling = 0.0, energy = 0.0;
  for (std::uint64_t p = t.row_start[4]; p < t.row_start[5]; ++p) {
    const std::uint32_t within = t.index[p] % 256;
    if (within == 0) scaling += t.value[p];
    energy += double(t.value[p]) * t.value[p];
  }
  // Parseval: the same energy as the texels, and the face's scaling coefficient is sum/size, so
  // the six times S are the sum of the texel means (same seed and vertex key: vertex 4 of seed 0
  // is not unoccluded_wavelet_texels' key, so compare with the exact means within the bound).
  double exact_energy = 0.0, exact_sum = 0.0;
  for (std::uint32_t f = 0; f < 6; ++f)
    for (std::uint32_t y = 0; y < 16; ++y)
      for (std::uint32_t x = 0; x < 16; ++x) {
        const double e = test::clamped_cosine_integral(test::cube_texel(16, f, x, y), {0, 1, 0}) /
                         kPi / prt_wavelet_texel_solid_angle(PRT_WAVELET_PARAM_CUBE, 16, f, x, y);
        exact_energy += e * e;
        exact_sum += e;
      }
  // The 2 x 2 jittered rays estimate each texel's mean to within a fraction of the cosine's
  // variation over it, and those errors largely cancel over the 768 texels above the horizon:
  // a few times their spread over seeds (the energy's relative error is about twice the sum's).
  EXPECT_NEAR(scaling * 16.0, exact_sum, 0.003 * exact_sum);
  EXPECT_NEAR(energy, exact_energy, 0.005 * exact_energy);
}

TEST(WaveletTransfer, ParsevalAndScalingAgainstTheSameTexels) {
  // unoccluded_wavelet_texels and a transform by hand must give what the bake stores.
  std::vector<float> texels =
      unoccluded_wavelet_texels(PRT_WAVELET_PARAM_CUBE, 16, 1, {0, 1, 0}, 0);
  double energy = 0.0, sum = 0.0;
  for (float t : texels) {
    energy += double(t) * t;
    sum += t;
  }
  std::vector<float> row = texels;
  for (int f = 0; f < 6; ++f) ASSERT_EQ(prt_haar_forward(16, 1, row.data() + f * 256), PRT_OK);
  double row_energy = 0.0, scaling = 0.0;
  for (std::size_t j = 0; j < row.size(); ++j) {
    row_energy += double(row[j]) * row[j];
    if (j % 256 == 0) scaling += row[j];
  }
  EXPECT_NEAR(row_energy, energy, 1e-5 * energy);
  EXPECT_NEAR(scaling * 16.0, sum, 1e-5 * sum);
}

TEST(WaveletTruncation, KeepsTheLargestMagnitudesTiesToTheLowerIndex) {
  const std::vector<float> row = {0.0f, -5.0f, 1.0f, 3.0f, -3.0f, 0.5f, 0.0f, 2.0f};
  EXPECT_EQ(select_wavelet_coefficients(row, 3, 0.0), (std::vector<std::uint32_t>{1, 3, 4}));
  EXPECT_EQ(select_wavelet_coefficients(row, 2, 0.0), (std::vector<std::uint32_t>{1, 3}));
  // keep 0 = every non-zero; keep beyond the non-zeros = every non-zero.
  EXPECT_EQ(select_wavelet_coefficients(row, 0, 0.0),
            (std::vector<std::uint32_t>{1, 2, 3, 4, 5, 7}));
  EXPECT_EQ(select_wavelet_coefficients(row, 100, 0.0).size(), 6u);
}

// The kept set against a full sort by (|value| descending, index ascending), on rows whose
// values crowd into few magnitudes (many in the bin of the keep-th largest, exact ties, zeros,
// subnormals, infinities), so the selection's pre-filter by magnitude bin is exercised.
TEST(WaveletTruncation, KeepsWhatAFullSortKeeps) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<float> row(1 + random() % 3000);
    const float base = std::ldexp(1.0f, int(random() % 60) - 30);
    for (float& value : row) {
      switch (random() % 6) {
        case 0:
          value = 0.0f;
          break;
        case 1:
          value = base;
          break;  // exact ties
        case 2:
          value = -base * (1.0f + float(random() % 8) / 64.0f);
          break;  // one bin
        case 3:
          value = std::ldexp(float(random() % 1000), int(random() % 40) - 20);
          break;
        case 4:
          value = trial % 10 == 0 ? 1e-42f : base;
          break;  // subnormal
        default:
          value = trial % 25 == 0 ? -INFINITY : base * 2.0f;
          break;
      }
    }
    std::vector<std::uint32_t> nonzero;
    for (std::uint32_t j = 0; j < row.size(); ++j)
      if (row[j] != 0.0f) nonzero.push_back(j);
    std::sort(nonzero.begin(), nonzero.end(), [&](std::uint32_t a, std::uint32_t b) {
      const float fa = std::abs(row[a]), fb = std::abs(row[b]);
      return fa > fb || (fa == fb && a < b);
    });
    const std::uint32_t keep = 1 + random() % 1200;
    std::vector<std::uint32_t> expected(
        nonzero.begin(), nonzero.begin() + std::min<std::size_t>(keep, nonzero.size()));
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(select_wavelet_coefficients(row, keep, 0.0), expected) << "trial " << trial;
  }
}

TEST(WaveletTruncation, KeepEnergyTakesTheFewestReachingTheFraction) {
  // Energies 25, 9, 9, 4, 1, 0.25: total 48.25.
  const std::vector<float> row = {0.0f, -5.0f, 1.0f, 3.0f, -3.0f, 0.5f, 0.0f, 2.0f};
  EXPECT_EQ(select_wavelet_coefficients(row, 0, 25.0 / 48.25), (std::vector<std::uint32_t>{1}));
  EXPECT_EQ(select_wavelet_coefficients(row, 0, 25.5 / 48.25), (std::vector<std::uint32_t>{1, 3}));
  EXPECT_EQ(select_wavelet_coefficients(row, 0, 0.9), (std::vector<std::uint32_t>{1, 3, 4, 7}));
  EXPECT_EQ(select_wavelet_coefficients(row, 0, 1.0).size(), 6u);
}

TEST(WaveletTransfer, SameRowsForOneAndTwoThreads) {
  Scene scene;
  scene.meshes.push_back(test::make_plane(1.0f, 4));
  scene.meshes.push_back(test::make_icosphere(1, 0.3f, {0.1f, 0.5f, 0.0f}));
  WaveletTransferSettings s;
  s.size = 16;
  s.keep = 40;
  s.seed = 5;
  Context one, two;
  one.threads = 1;
  two.threads = 2;
  const WaveletTransfer a = compute_wavelet_transfer(scene, nullptr, s, one);
  const WaveletTransfer b = compute_wavelet_transfer(scene, nullptr, s, two);
  EXPECT_EQ(a.row_start, b.row_start);
  EXPECT_EQ(a.index, b.index);
  EXPECT_EQ(a.value, b.value);  // bit for bit
  EXPECT_EQ(a.rays_traced, b.rays_traced);
  s.seed = 6;  // and the seed matters
  EXPECT_NE(compute_wavelet_transfer(scene, nullptr, s, one).value, a.value);
}

TEST(WaveletTransfer, RejectsBadSettings) {
  Scene scene;
  scene.meshes.push_back(test::make_plane(1.0f, 1));
  Context ctx;
  auto bake = [&](WaveletTransferSettings s) { compute_wavelet_transfer(scene, nullptr, s, ctx); };
  WaveletTransferSettings s;
  s.size = 24;
  EXPECT_THROW(bake(s), Error);
  s.size = 256;
  EXPECT_THROW(bake(s), Error);
  s = WaveletTransferSettings();
  s.samples = 2;
  EXPECT_THROW(bake(s), Error);
  s = WaveletTransferSettings();
  s.keep_energy = 1.5;
  EXPECT_THROW(bake(s), Error);
  s = WaveletTransferSettings();
  s.param = 7;
  EXPECT_THROW(bake(s), Error);
  s = WaveletTransferSettings();
  s.vertex_list = {100};
  EXPECT_THROW(bake(s), Error);
  EXPECT_THROW(parse_wavelet_param("sphere"), Error);
}

}  // namespace
}  // namespace prt::bake
