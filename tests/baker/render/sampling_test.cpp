// SPDX-License-Identifier: MIT
// Sampling: the scrambled Sobol points are stratified, cosine directions follow their density,
// and the environment distribution's density matches what it samples and integrates to one.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "prt/baker/sampling.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(SampleStream, EveryPowerOfTwoPrefixIsStratifiedInBothDimensions) {
  // A (0,m,2)-net in base 2: each of the 2^m intervals of width 2^-m of each coordinate holds
  // exactly one of the first 2^m points, whatever the scrambling seed and the dimension pair.
  for (const std::uint32_t seed : {0u, 1u, 12345u}) {
    const SampleStream stream(seed);
    for (const std::uint32_t pair : {0u, 1u, 7u}) {
      const int m = 10, n = 1 << m;
      std::set<int> xs, ys, cells;
      for (int i = 0; i < n; ++i) {
        const glm::vec2 u = stream.get_2d(i, pair);
        ASSERT_GE(u.x, 0.0f);
        ASSERT_LT(u.x, 1.0f);
        ASSERT_GE(u.y, 0.0f);
        ASSERT_LT(u.y, 1.0f);
        xs.insert(static_cast<int>(u.x * n));
        ys.insert(static_cast<int>(u.y * n));
        cells.insert(static_cast<int>(u.x * 32) * 32 + static_cast<int>(u.y * 32));
      }
      EXPECT_EQ(xs.size(), static_cast<std::size_t>(n));
      EXPECT_EQ(ys.size(), static_cast<std::size_t>(n));
      EXPECT_EQ(cells.size(), 1024u);  // the 32x32 elementary squares: one point each
    }
  }
}

TEST(SampleStream, DifferentSeedsAndPairsAreDifferentPoints) {
  const SampleStream a(1), b(2);
  EXPECT_NE(a.get_2d(5, 0), b.get_2d(5, 0));
  EXPECT_NE(a.get_2d(5, 0), a.get_2d(5, 1));
  EXPECT_EQ(a.get_2d(5, 3), SampleStream(1).get_2d(5, 3));
}

TEST(Sampling, CosineHemisphereHasTheMeanOfItsDensity) {
  // E[z] under pdf z/pi over the hemisphere = integral z^2/pi dw = 2/3; E[x] = E[y] = 0.
  const SampleStream stream(3);
  glm::dvec3 sum(0.0);
  const int n = 1 << 14;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 w = cosine_hemisphere(stream.get_2d(i, 0));
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
    ASSERT_GE(w.z, 0.0f);
    sum += glm::dvec3(w);
  }
  // 2^14 scrambled Sobol points of a smooth integrand: far below plain Monte Carlo's 1/sqrt(n);
  // a few times the largest error over seeds.
  EXPECT_NEAR(sum.z / n, 2.0 / 3.0, 5e-5);
  EXPECT_NEAR(sum.x / n, 0.0, 5e-5);
  EXPECT_NEAR(sum.y / n, 0.0, 5e-5);
}

TEST(Sampling, FrameIsOrthonormal) {
  for (const glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0),
                            glm::normalize(glm::vec3(0.3f, -0.8f, 0.1f))}) {
    const Frame f(n);
    EXPECT_NEAR(glm::dot(f.t, f.b), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.t, f.n), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.b, f.n), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f.b), 1.0f, 1e-6f);
  }
}

TEST(EnvDistribution, SampledDensityMatchesEvaluatedDensityAndIntegratesToOne) {
  const io::EnvMap sun = test::make_sun_map(128, 40, 10, 3, glm::vec3(5000.0f, 4000.0f, 3000.0f));
  std::vector<float> rgb = sun.pixels();
  for (float& v : rgb) v += 0.5f;  // a dim sky so every direction has some density
  const io::EnvMap env(128, 64, rgb, io::EnvMapping::LatLong, "sky");
  const EnvDistribution dist(env);
  ASSERT_TRUE(dist.valid());

  const SampleStream stream(11);
  double inverse_sum = 0.0;
  int mismatches = 0;
  const int n = 1 << 14;
  for (int i = 0; i < n; ++i) {
    float pdf = 0.0f;
    const glm::vec3 w = dist.sample(stream.get_2d(i, 0), &pdf);
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
    ASSERT_GT(pdf, 0.0f);
    // Equal but for directions that float rounding puts just across a cell's edge.
    mismatches += std::abs(dist.pdf(w) - pdf) > 1e-4f * pdf;
    inverse_sum += 1.0 / pdf;  // E[1/pdf] = the sphere's solid angle
  }
  EXPECT_LE(mismatches, n / 1000);
  // 1/pdf is large in the dim sky and small on the sun: a few times the spread over seeds.
  EXPECT_NEAR(inverse_sum / n / (4.0 * kPi), 1.0, 0.008);

  // Integrating the density over the sphere (midpoint rule, 4x4 points per cell) gives one: it
  // is constant on each cell, so but for the rounding of the float densities.
  const int rows = 4 * dist.rows(), columns = 4 * dist.columns();
  double integral = 0.0;
  for (int r = 0; r < rows; ++r) {
    const double theta0 = kPi * r / rows, theta1 = kPi * (r + 1) / rows;
    const double theta = 0.5 * (theta0 + theta1);
    const double omega = (std::cos(theta0) - std::cos(theta1)) * 2.0 * kPi / columns;
    for (int c = 0; c < columns; ++c) {
      const double phi = 2.0 * kPi * (c + 0.5) / columns;
      integral += omega * dist.pdf(glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                             std::sin(theta) * std::sin(phi)));
    }
  }
  EXPECT_NEAR(integral, 1.0, 4.0 * std::ldexp(1.0, -24));
}

// The probability `dist` gives the lat-long texels of `env` for which inside(x, y) holds: its
// density integrated by a 16 x 16 midpoint rule over each of those texels (SPEC §12 directions).
template <typename Inside>
double density_mass(const EnvDistribution& dist, const io::EnvMap& env, Inside inside) {
  const int k = 16, w = env.width(), h = env.height();
  double mass = 0.0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!inside(x, y)) continue;
      for (int j = 0; j < k; ++j) {
        const double theta0 = kPi * (y + double(j) / k) / h,
                     theta1 = kPi * (y + double(j + 1) / k) / h;
        const double omega = (std::cos(theta0) - std::cos(theta1)) * 2.0 * kPi / (w * k);
        const double theta = 0.5 * (theta0 + theta1);
        for (int i = 0; i < k; ++i) {
          const double phi = 2.0 * kPi * ((x + (i + 0.5) / k) / w - 0.5);
          const glm::vec3 d(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)),
                            float(-std::sin(theta) * std::cos(phi)));
          mass += omega * dist.pdf(d);
        }
      }
    }
  }
  return mass;
}

TEST(EnvDistribution, PutsTheSunsShareOfPowerOnTheSun) {
  // Sun texels 1e4 against a sky of 1: the fraction of samples landing in the sun's texels is
  // (close to) the sun's share of the map's luminance x solid angle.
  const int width = 64;
  const io::EnvMap sun = test::make_sun_map(width, 20, 8, 2, glm::vec3(1e4f));
  std::vector<float> rgb = sun.pixels();
  for (float& v : rgb) v = std::max(v, 1.0f);
  const io::EnvMap env(width, width / 2, rgb, io::EnvMapping::LatLong, "sky");
  double sun_power = 0.0, total_power = 0.0;
  for (int y = 0; y < env.height(); ++y) {
    for (int x = 0; x < env.width(); ++x) {
      float omega = 0.0f;
      ASSERT_TRUE(env.texel(x, y, nullptr, &omega));
      const double power = env.texel_value(x, y).g * omega;
      total_power += power;
      if (env.texel_value(x, y).g > 1.0f) sun_power += power;
    }
  }
  const EnvDistribution dist(env);
  const SampleStream stream(5);
  int in_sun = 0;
  const int n = 1 << 14;
  for (int i = 0; i < n; ++i) {
    float pdf = 0.0f;
    int x = 0, y = 0;
    env.texel_of(dist.sample(stream.get_2d(i, 0), &pdf), &x, &y);
    in_sun += env.texel_value(x, y).g > 1.0f;
  }
  // The density's mass on the sun's texels (a fine midpoint rule) is between half the sun's
  // share of the power and all of it: half the distribution's weight follows the texels, the
  // other half the bilinear interpolation, which spreads the sun over its neighbours.
  const double share = sun_power / total_power;
  const double mass =
      density_mass(dist, env, [&](int x, int y) { return env.texel_value(x, y).g > 1.0f; });
  EXPECT_GT(mass, 0.5 * share);
  EXPECT_LE(mass, share);
  // The samples follow the density: stratified (a (0,m,2)-net), they land on the sun a few
  // samples off its mass at most over seeds; ten are allowed.
  EXPECT_NEAR(in_sun, mass * n, 10.0);
}

TEST(EnvDistribution, BlackMapIsNotSampleable) {
  const EnvDistribution dist(io::constant_envmap(glm::vec3(0.0f)));
  EXPECT_FALSE(dist.valid());
  EXPECT_EQ(dist.pdf(glm::vec3(0, 1, 0)), 0.0f);
}

}  // namespace
}  // namespace prt::bake
