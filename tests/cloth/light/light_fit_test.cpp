// SPDX-License-Identifier: MIT
// prt_cloth_fit_light, the runtime's per-frame SG light: a map that is a sum of separated SGs
// is recovered (lat-long and cube), power is kept for any map, a sun gets a sharp lobe of its
// own where the test finds the sun, black maps give no lobe, bad texels count as 0, the axes
// turn with the env's rotation, the report's error agrees with a brute-force one, the result is
// deterministic, and argument and allocation failures are reported.
#include <gtest/gtest.h>

#include <prt/io/envmap.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "cloth/light/sg_maps.hpp"
#include "support/counting_allocator.hpp"
#include "support/test_files.hpp"

namespace {

using namespace prt_test;

struct Fit {
  prt_result result = PRT_ERROR_INVALID_ARGUMENT;
  std::vector<prt_cloth_lobe> lobes;
  prt_cloth_fit_report report = prt::sized<prt_cloth_fit_report>();
  std::vector<prt_cloth_lobe> lit() const {
    return {lobes.begin(), lobes.begin() + report.lobe_count};
  }
};

Fit fit(const prt_env_image& env, std::uint32_t lobes, prt_context* context = nullptr) {
  auto [owned, made] = prt::create_context();
  EXPECT_EQ(made, PRT_OK);
  prt_cloth_fit_desc desc = prt::sized<prt_cloth_fit_desc>();
  desc.lobe_count = lobes;
  Fit out;
  out.lobes.assign(lobes, prt_cloth_lobe{});
  out.result = prt_cloth_fit_light(context ? context : owned.get(), &env, &desc, out.lobes.data(),
                                   &out.report);
  return out;
}

// The fitted lobe nearest each true lobe: its axis error (degrees), and its sharpness and
// amplitude errors relative to the true ones.
struct Recovery {
  double axis_degrees = 0.0, sharpness = 0.0, amplitude = 0.0;
};

Recovery worst_recovery(const std::vector<TrueLobe>& truth,
                        const std::vector<prt_cloth_lobe>& fit) {
  Recovery worst;
  for (const TrueLobe& t : truth) {
    const prt_cloth_lobe* nearest = &fit[0];
    for (const prt_cloth_lobe& l : fit)
      if (dot(axis_of(l), t.axis) > dot(axis_of(*nearest), t.axis)) nearest = &l;
    worst.axis_degrees = std::max(worst.axis_degrees, degrees_between(axis_of(*nearest), t.axis));
    worst.sharpness =
        std::max(worst.sharpness, std::fabs(nearest->sharpness - t.sharpness) / t.sharpness);
    for (int c = 0; c < 3; ++c)
      worst.amplitude = std::max(worst.amplitude, std::fabs(nearest->rgb[c] - t.rgb[c]) / t.rgb[c]);
  }
  return worst;
}

TEST(ClothLightFit, RecoversSeparatedLobesFromALatLongMap) {
  const std::vector<TrueLobe> truth = three_lobes();
  const EnvImage env = with_lobes(latlong_image(1024, 512), truth);
  const Fit f = fit(env.image(), 3);
  ASSERT_EQ(f.result, PRT_OK);
  ASSERT_EQ(f.report.lobe_count, 3u);
  const Recovery r = worst_recovery(truth, f.lobes);
  // Measured: 1.2e-6 degrees, 4.4e-6 and 2.8e-6 (sums of texel-centre samples of smooth
  // lobes; a grid cell is 2.8 degrees).
  EXPECT_LT(r.axis_degrees, 1e-5);
  EXPECT_LT(r.sharpness, 2e-5);
  EXPECT_LT(r.amplitude, 2e-5);
  // Measured: 7.6e-4, the report's own floor (its cell integrals of the lobes).
  EXPECT_LT(f.report.relative_error, 1.5e-3);
}

TEST(ClothLightFit, RecoversSeparatedLobesFromACubeMap) {
  const std::vector<TrueLobe> truth = three_lobes();
  const EnvImage env = with_lobes(cube_image(128), truth);
  const Fit f = fit(env.image(), 3);
  ASSERT_EQ(f.result, PRT_OK);
  ASSERT_EQ(f.report.lobe_count, 3u);
  const Recovery r = worst_recovery(truth, f.lobes);
  // Measured: 2.5e-4 degrees, 4.5e-5 and 1.2e-4 (the cube's texels are coarser near the lobes).
  EXPECT_LT(r.axis_degrees, 1e-3);
  EXPECT_LT(r.sharpness, 2e-4);
  EXPECT_LT(r.amplitude, 5e-4);
  // Measured: 0.030 (a cube's texels fill the lat-long cells raggedly).
  EXPECT_LT(f.report.relative_error, 0.06);
}

TEST(ClothLightFit, KeepsThePowerOfAnyMap) {
  const std::vector<EnvImage> maps = {with_noise(latlong_image(256, 128), 2.0f, 7),
                                      with_noise(cube_image(48), 2.0f, 8),
                                      with_lobes(latlong_image(512, 256), three_lobes())};
  for (const EnvImage& env : maps) {
    for (std::uint32_t k : {1u, 10u, 32u}) {
      const Fit f = fit(env.image(), k);
      ASSERT_EQ(f.result, PRT_OK);
      const double expected = map_power(env);
      const double error = std::fabs(power_of(f.lit()) - expected) / expected;
      // Measured: at most 2.4e-8 (float amplitudes).
      EXPECT_LT(error, 1e-7) << "K = " << k;
      EXPECT_LT(f.report.power_error, 1e-7) << "K = " << k;
    }
  }
}

TEST(ClothLightFit, AConstantMapIsOneFlatLobeOrASpreadOfTheSamePower) {
  const float radiance = 0.75f;
  EnvImage env = latlong_image(128, 64);
  std::fill(env.rgb.begin(), env.rgb.end(), radiance);
  const Fit one = fit(env.image(), 1);
  ASSERT_EQ(one.result, PRT_OK);
  ASSERT_EQ(one.report.lobe_count, 1u);
  // A uniform map has no mean direction: the flattest lobe, holding all of 4 pi L.
  EXPECT_EQ(one.lobes[0].sharpness, PRT_CLOTH_MIN_SHARPNESS);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(one.lobes[0].rgb[c] * sg_integral(PRT_CLOTH_MIN_SHARPNESS), 4.0 * kSgPi * radiance,
                1e-6 * 4.0 * kSgPi * radiance);
  const Fit many = fit(env.image(), 10);
  ASSERT_EQ(many.result, PRT_OK);
  EXPECT_EQ(many.report.lobe_count, 10u);
  EXPECT_NEAR(power_of(many.lit()), 3.0 * 4.0 * kSgPi * radiance, 1e-6 * 12.0 * kSgPi * radiance);
}

TEST(ClothLightFit, TheSunGetsASharpLobeWhereItIs) {
  const std::string path = shared_asset("envmaps/spiaggia_di_mondello_1k.hdr");
  if (path.empty()) GTEST_SKIP() << "shared asset spiaggia_di_mondello_1k.hdr not found";
  const prt::io::EnvMap map = prt::io::load_envmap(path, prt::io::EnvMapping::LatLong);
  EnvImage env = latlong_image(map.width(), map.height());
  env.rgb = map.pixels();
  // The sun, found here: the power-weighted mean direction of the texels at least a tenth as
  // bright as the brightest.
  float brightest = 0.0f;
  for (std::size_t k = 0; k < env.texels(); ++k)
    brightest = std::max(brightest, env.rgb[3 * k] + env.rgb[3 * k + 1] + env.rgb[3 * k + 2]);
  Vec3 sum{0.0, 0.0, 0.0};
  for_each_texel(env, [&](std::size_t k, const Vec3& d, double solid_angle) {
    const float level = env.rgb[3 * k] + env.rgb[3 * k + 1] + env.rgb[3 * k + 2];
    if (level < 0.1f * brightest) return;
    for (int c = 0; c < 3; ++c) sum[c] += level * solid_angle * d[c];
  });
  const Vec3 sun = normalised(sum);
  const Fit f = fit(env.image(), 10);
  ASSERT_EQ(f.result, PRT_OK);
  const std::vector<prt_cloth_lobe> lit = f.lit();
  const auto nearest = std::min_element(lit.begin(), lit.end(), [&](const auto& a, const auto& b) {
    return degrees_between(axis_of(a), sun) < degrees_between(axis_of(b), sun);
  });
  ASSERT_NE(nearest, lit.end());
  // Measured: 0.01 degrees, sharpness at its bound (1e4).
  EXPECT_LT(degrees_between(axis_of(*nearest), sun), 1.0);
  EXPECT_GT(nearest->sharpness, 1000.0f);
}

TEST(ClothLightFit, ABlackMapGivesNoLobe) {
  for (const EnvImage& env : {latlong_image(64, 32), cube_image(16)}) {
    const Fit f = fit(env.image(), 10);
    ASSERT_EQ(f.result, PRT_OK);
    EXPECT_EQ(f.report.lobe_count, 0u);
    EXPECT_EQ(f.report.relative_error, 0.0f);
    EXPECT_EQ(f.report.power_error, 0.0f);
    for (const prt_cloth_lobe& l : f.lobes) {
      EXPECT_EQ(l.rgb[0], 0.0f);
      EXPECT_EQ(l.rgb[1], 0.0f);
      EXPECT_EQ(l.rgb[2], 0.0f);
      EXPECT_EQ(l.sharpness, PRT_CLOTH_MIN_SHARPNESS);
      EXPECT_NEAR(dot(axis_of(l), axis_of(l)), 1.0, 1e-6);
    }
  }
}

TEST(ClothLightFit, NanInfiniteAndNegativeTexelsCountAsZero) {
  for (EnvImage clean :
       {with_noise(latlong_image(256, 128), 1.0f, 3), with_noise(cube_image(32), 1.0f, 4)}) {
    EnvImage bad = clean;
    const float values[4] = {std::numeric_limits<float>::quiet_NaN(),
                             std::numeric_limits<float>::infinity(),
                             -std::numeric_limits<float>::infinity(), -3.0f};
    for (std::size_t k = 0; k < bad.rgb.size(); k += 37) {
      bad.rgb[k] = values[(k / 37) % 4];
      clean.rgb[k] = 0.0f;
    }
    const Fit a = fit(bad.image(), 10), b = fit(clean.image(), 10);
    ASSERT_EQ(a.result, PRT_OK);
    ASSERT_EQ(b.result, PRT_OK);
    EXPECT_EQ(std::memcmp(a.lobes.data(), b.lobes.data(), a.lobes.size() * sizeof a.lobes[0]), 0);
    EXPECT_EQ(a.report.relative_error, b.report.relative_error);
    for (const prt_cloth_lobe& l : a.lobes)
      for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(l.rgb[c]));
  }
}

// The same texels given as RGBA (the fourth float NaN) with padded rows and faces.
prt_env_image padded(const EnvImage& env, std::vector<float>* storage) {
  const std::size_t row = std::size_t(env.width) * 4 + 3, face = row * env.height + 5;
  const std::size_t faces = env.layout == PRT_ENV_CUBE ? 6 : 1;
  storage->assign(face * faces, -1.0f);
  for (std::size_t f = 0; f < faces; ++f)
    for (std::size_t y = 0; y < env.height; ++y)
      for (std::size_t x = 0; x < env.width; ++x) {
        const std::size_t from = 3 * ((f * env.height + y) * env.width + x);
        float* to = storage->data() + f * face + y * row + 4 * x;
        for (int c = 0; c < 3; ++c) to[c] = env.rgb[from + c];
        to[3] = std::numeric_limits<float>::quiet_NaN();
      }
  prt_env_image image = env.image();
  image.channels = 4;
  image.texels = storage->data();
  image.row_stride = row;
  image.face_stride = env.layout == PRT_ENV_CUBE ? face : 0;
  return image;
}

TEST(ClothLightFit, ReadsRgbaAndStridesAsRgb) {
  std::vector<TrueLobe> lobes = three_lobes();
  lobes.push_back({normalised({0.0, 1.0, 0.1}), 1.0e4, {4.0e4, 4.0e4, 4.0e4}});  // a sun
  for (const EnvImage& env :
       {with_lobes(latlong_image(512, 256), lobes), with_lobes(cube_image(64), lobes)}) {
    std::vector<float> storage;
    const Fit a = fit(env.image(), 10), b = fit(padded(env, &storage), 10);
    ASSERT_EQ(a.result, PRT_OK);
    ASSERT_EQ(b.result, PRT_OK);
    EXPECT_EQ(std::memcmp(a.lobes.data(), b.lobes.data(), a.lobes.size() * sizeof a.lobes[0]), 0);
    EXPECT_EQ(std::memcmp(&a.report, &b.report, sizeof a.report), 0);
  }
}

TEST(ClothLightFit, TinyMapsGiveFiniteLobes) {
  std::vector<EnvImage> maps = {
      with_noise(latlong_image(1, 1), 1.0f, 5), with_noise(latlong_image(3, 1), 1.0f, 6),
      with_noise(latlong_image(1, 5), 1.0f, 7), with_noise(cube_image(1), 1.0f, 8)};
  for (const EnvImage& env : maps) {
    const Fit f = fit(env.image(), 10);
    ASSERT_EQ(f.result, PRT_OK);
    EXPECT_GE(f.report.lobe_count, 1u);
    EXPECT_TRUE(std::isfinite(f.report.relative_error));
    const double expected = map_power(env);
    EXPECT_NEAR(power_of(f.lit()), expected, 1e-6 * expected);
    for (const prt_cloth_lobe& l : f.lobes) {
      EXPECT_NEAR(dot(axis_of(l), axis_of(l)), 1.0, 1e-6);
      EXPECT_GE(l.sharpness, PRT_CLOTH_MIN_SHARPNESS);
      EXPECT_LE(l.sharpness, PRT_CLOTH_MAX_SHARPNESS);
      for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(l.rgb[c]) && l.rgb[c] >= 0.0f);
    }
  }
}

TEST(ClothLightFit, AxesTurnWithTheEnvRotation) {
  const EnvImage env = with_lobes(latlong_image(512, 256), three_lobes());
  // 40 degrees about (1, 2, 2) / 3, row-major (Rodrigues).
  const Vec3 k = normalised({1.0, 2.0, 2.0});
  const double a = 40.0 * kSgPi / 180.0, c = std::cos(a), s = std::sin(a);
  float r[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double cross = i == j ? 0.0 : ((j - i + 3) % 3 == 1 ? -k[3 - i - j] : k[3 - i - j]);
      r[3 * i + j] = static_cast<float>((i == j ? c : 0.0) + (1.0 - c) * k[i] * k[j] + s * cross);
    }
  prt_env_image turned = env.image();
  turned.rotation = r;
  const Fit plain = fit(env.image(), 6), rotated = fit(turned, 6);
  ASSERT_EQ(plain.result, PRT_OK);
  ASSERT_EQ(rotated.result, PRT_OK);
  ASSERT_EQ(plain.report.lobe_count, rotated.report.lobe_count);
  for (std::uint32_t i = 0; i < plain.report.lobe_count; ++i) {
    Vec3 expected{0.0, 0.0, 0.0};
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col)
        expected[row] += r[3 * row + col] * plain.lobes[i].axis[col];
    EXPECT_LT(degrees_between(axis_of(rotated.lobes[i]), expected), 1e-4);
    EXPECT_EQ(rotated.lobes[i].sharpness, plain.lobes[i].sharpness);
    EXPECT_EQ(rotated.lobes[i].rgb[0], plain.lobes[i].rgb[0]);
  }
}

// The report's relative error against one computed here: the map's mean per 8 x 8 texel cell
// and the lobes' mean per cell by a 32 x 32 midpoint rule.
TEST(ClothLightFit, TheReportedErrorIsTheGridsRmsError) {
  EnvImage env = latlong_image(512, 256);
  for (std::uint32_t y = 0; y < 256; ++y)
    for (std::uint32_t x = 0; x < 512; ++x) {
      const float v = ((x / 40 + y / 24) % 3 == 0) ? 4.0f : 0.5f + 0.002f * x;
      for (int c = 0; c < 3; ++c)
        env.rgb[3 * (std::size_t(y) * 512 + x) + c] = v * (1.0f + 0.2f * c);
    }
  const Fit f = fit(env.image(), 6);
  ASSERT_EQ(f.result, PRT_OK);
  const std::uint32_t rows = 64, cols = 128, sub = 32;
  double error = 0.0, norm = 0.0;
  for (std::uint32_t j = 0; j < rows; ++j)
    for (std::uint32_t i = 0; i < cols; ++i) {
      Vec3 map{0, 0, 0}, model{0, 0, 0};
      double map_area = 0.0, model_area = 0.0;
      for (std::uint32_t y = 4 * j; y < 4 * j + 4; ++y)
        for (std::uint32_t x = 4 * i; x < 4 * i + 4; ++x) {
          const double w = latlong_solid_angle(512, 256, y);
          for (int c = 0; c < 3; ++c) map[c] += w * env.rgb[3 * (std::size_t(y) * 512 + x) + c];
          map_area += w;
        }
      for (std::uint32_t y = 0; y < sub; ++y)
        for (std::uint32_t x = 0; x < sub; ++x) {
          const double w = latlong_solid_angle(cols * sub, rows * sub, j * sub + y);
          const Vec3 d = latlong_direction(cols * sub, rows * sub, i * sub + x, j * sub + y);
          for (const prt_cloth_lobe& l : f.lit())
            for (int c = 0; c < 3; ++c)
              model[c] += w * l.rgb[c] * std::exp(l.sharpness * (dot(axis_of(l), d) - 1.0));
          model_area += w;
        }
      for (int c = 0; c < 3; ++c) {
        const double m = map[c] / map_area, s = model[c] / model_area;
        error += map_area * (s - m) * (s - m);
        norm += map_area * m * m;
      }
    }
  const double expected = std::sqrt(error / norm);
  // Measured: 0.6633 both, 6e-7 apart relatively.
  EXPECT_NEAR(f.report.relative_error, expected, 3e-6 * expected);
}

TEST(ClothLightFit, IsDeterministic) {
  const EnvImage env = with_noise(latlong_image(256, 128), 3.0f, 11);
  const Fit a = fit(env.image(), 12), b = fit(env.image(), 12);
  ASSERT_EQ(a.result, PRT_OK);
  ASSERT_EQ(b.result, PRT_OK);
  EXPECT_EQ(std::memcmp(a.lobes.data(), b.lobes.data(), a.lobes.size() * sizeof a.lobes[0]), 0);
  EXPECT_EQ(std::memcmp(&a.report, &b.report, sizeof a.report), 0);
}

TEST(ClothLightFit, RejectsBadArguments) {
  auto [context, made] = prt::create_context();
  ASSERT_EQ(made, PRT_OK);
  const EnvImage env = with_noise(latlong_image(32, 16), 1.0f, 1);
  const prt_env_image image = env.image();
  prt_cloth_fit_desc desc = prt::sized<prt_cloth_fit_desc>();
  std::vector<prt_cloth_lobe> lobes(PRT_CLOTH_MAX_LOBES + 1);
  prt_cloth_fit_report report = prt::sized<prt_cloth_fit_report>();
  prt_context* ctx = context.get();
  EXPECT_EQ(prt_cloth_fit_light(nullptr, &image, &desc, lobes.data(), &report),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_fit_light(ctx, nullptr, &desc, lobes.data(), &report),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_fit_light(ctx, &image, nullptr, lobes.data(), &report),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_cloth_fit_light(ctx, &image, &desc, nullptr, &report), PRT_ERROR_INVALID_ARGUMENT);
  prt_cloth_fit_desc small = desc;
  small.struct_size = sizeof(size_t);
  EXPECT_EQ(prt_cloth_fit_light(ctx, &image, &small, lobes.data(), &report),
            PRT_ERROR_INVALID_ARGUMENT);
  prt_cloth_fit_report small_report = report;
  small_report.struct_size = sizeof(size_t);
  EXPECT_EQ(prt_cloth_fit_light(ctx, &image, &desc, lobes.data(), &small_report),
            PRT_ERROR_INVALID_ARGUMENT);
  prt_cloth_fit_desc too_many = desc;
  too_many.lobe_count = PRT_CLOTH_MAX_LOBES + 1;
  EXPECT_EQ(prt_cloth_fit_light(ctx, &image, &too_many, lobes.data(), &report),
            PRT_ERROR_INVALID_ARGUMENT);
  prt_env_image bad = image;
  bad.channels = 2;
  EXPECT_EQ(prt_cloth_fit_light(ctx, &bad, &desc, lobes.data(), &report),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_context_last_result(ctx), PRT_ERROR_INVALID_ARGUMENT);
  // The report is optional.
  EXPECT_EQ(prt_cloth_fit_light(ctx, &image, &desc, lobes.data(), nullptr), PRT_OK);
}

TEST(ClothLightFit, ReportsEveryAllocationFailure) {
  // A map with a compact bright source, so that its texel list is allocated too.
  std::vector<TrueLobe> lobes = three_lobes();
  lobes.push_back({normalised({0.0, 1.0, 0.1}), 1.0e4, {4.0e4, 4.0e4, 4.0e4}});
  for (const EnvImage& env :
       {with_lobes(latlong_image(512, 256), lobes), with_lobes(cube_image(64), lobes)}) {
    const prt_env_image image = env.image();
    expect_every_allocation_failure_reported(
        [&](prt_context* context) {
          const Fit f = fit(image, 10, context);
          if (f.result == PRT_OK) {
            EXPECT_GT(f.lobes[0].sharpness, 1000.0f);  // the sun's
          }
          return f.result;
        },
        "prt_cloth_fit_light");
  }
}

}  // namespace
