// SPDX-License-Identifier: MIT
// The prepared wavelet source (prt_wavelet_source.h) against prt_wavelet_resample, the
// reference: the scalar path runs the reference's loops on the prepared tables, so it gives the
// same bits; the AVX2 path lands every source texel in the same target texel and only sums in
// another order, so each texel agrees within the float rounding of its sum of positive terms.
// Power conservation, extreme maps and the argument errors.
#include <gtest/gtest.h>
#include <prt/prt.hpp>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "support/limited_context.hpp"

namespace {

constexpr prt_wavelet_param kCube = PRT_WAVELET_PARAM_CUBE;
constexpr prt_wavelet_param kParaboloid = PRT_WAVELET_PARAM_DUAL_PARABOLOID;
constexpr double kPi = 3.14159265358979323846;

struct Rotation {
  float m[9];
};

// A rotation from a unit quaternion (the identity for w = 1).
Rotation from_quaternion(double w, double x, double y, double z) {
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  return {{float(1 - 2 * (y * y + z * z)), float(2 * (x * y - w * z)), float(2 * (x * z + w * y)),
           float(2 * (x * y + w * z)), float(1 - 2 * (x * x + z * z)), float(2 * (y * z - w * x)),
           float(2 * (x * z - w * y)), float(2 * (y * z + w * x)), float(1 - 2 * (x * x + y * y))}};
}

Rotation product(const Rotation& a, const Rotation& b) {
  Rotation out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out.m[3 * i + j] = float(double(a.m[3 * i]) * b.m[j] + double(a.m[3 * i + 1]) * b.m[3 + j] +
                               double(a.m[3 * i + 2]) * b.m[6 + j]);
  return out;
}

// Rotations that put whole columns of a lat-long map of `width` columns on texel edges: a turn
// about +Y by half a column step puts the column centres 45 degrees from -Z on the face
// boundaries x = +-z (width a multiple of 8); a quarter turn about +X after it sends the poles to
// the +-Z face centres, where the meridians 0 and 90 degrees from -Z run along the texel edges
// sc = 0 and tc = 0 (even sizes).
std::vector<Rotation> edge_rotations(uint32_t width) {
  const double half_step = kPi / width;
  const Rotation turn = from_quaternion(std::cos(half_step / 2), 0, std::sin(half_step / 2), 0);
  const Rotation quarter = from_quaternion(std::cos(kPi / 4), std::sin(kPi / 4), 0, 0);
  return {turn, product(quarter, turn)};
}

// How many texels of a width x height lat-long map, turned by `rotation` as
// prt_wavelet_resample turns them (double), lie within `margin` texels of a cube texel edge.
size_t texels_near_edges(uint32_t size, uint32_t width, uint32_t height, const Rotation& rotation,
                         double margin) {
  size_t near = 0;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const double f = 2 * kPi * ((x + 0.5) / width - 0.5), t = kPi * (y + 0.5) / height;
      const double d[3] = {std::sin(t) * std::sin(f), std::cos(t), -std::sin(t) * std::cos(f)};
      double e[3], a[3];
      for (int r = 0; r < 3; ++r) {
        e[r] =
            rotation.m[3 * r] * d[0] + rotation.m[3 * r + 1] * d[1] + rotation.m[3 * r + 2] * d[2];
        a[r] = std::fabs(e[r]);
      }
      const int major = a[0] >= a[1] && a[0] >= a[2] ? 0 : (a[1] >= a[2] ? 1 : 2);
      bool edge = false;
      for (int r = 0; r < 3; ++r) {
        if (r == major) continue;
        const double c = (e[r] / a[major] + 1) * 0.5 * size;
        edge |= std::fabs(c - std::round(c)) < margin;
      }
      near += edge;
    }
  return near;
}

// The identity, a turn about +Y and random rotations (normal quaternions).
std::vector<Rotation> test_rotations() {
  std::vector<Rotation> out = {from_quaternion(1, 0, 0, 0),
                               from_quaternion(std::cos(0.3), 0, std::sin(0.3), 0)};
  std::mt19937 rng(12);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 4; ++i)
    out.push_back(from_quaternion(normal(rng), normal(rng), normal(rng), normal(rng)));
  return out;
}

// A positive map that varies from texel to texel (so a misplaced texel shows), 3 channels.
std::vector<float> random_map(size_t texels, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(0.1f, 10.0f);
  std::vector<float> map(3 * texels);
  for (float& v : map) v = value(rng);
  return map;
}

struct Source {
  prt_wavelet_source* source = nullptr;
  prt_result result = PRT_ERROR_INVALID_ARGUMENT;
  Source(prt_context* context, prt_wavelet_param param, uint32_t size, const prt_env_image& env,
         uint32_t flags = 0) {
    prt_wavelet_source_desc desc = prt::sized<prt_wavelet_source_desc>();
    desc.param = param;
    desc.size = size;
    desc.env = &env;
    desc.flags = flags;
    result = prt_wavelet_source_create(context, &desc, &source);
  }
  ~Source() { prt_wavelet_source_destroy(source); }
  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;
};

std::vector<float> reference(prt_wavelet_param param, uint32_t size, prt_env_image env,
                             const Rotation& rotation) {
  env.rotation = rotation.m;
  std::vector<float> out(4 * size_t(prt_wavelet_coefficient_count(param, size)));
  EXPECT_EQ(prt_wavelet_resample(param, size, &env, out.data()), PRT_OK);
  return out;
}

std::vector<float> resampled(const Source& source, prt_wavelet_param param, uint32_t size,
                             const Rotation& rotation) {
  std::vector<float> out(4 * size_t(prt_wavelet_coefficient_count(param, size)), -1.0f);
  EXPECT_EQ(prt_wavelet_source_resample(source.source, rotation.m, out.data()), PRT_OK);
  return out;
}

// How many lat-long texels land in each target texel, from SPEC §12's directions located with
// prt_wavelet_locate (float: near an edge it may pick the neighbour, hence the slack the caller
// adds).
std::vector<uint32_t> landed_counts(prt_wavelet_param param, uint32_t size, uint32_t width,
                                    uint32_t height, const Rotation& rotation) {
  std::vector<uint32_t> count(prt_wavelet_coefficient_count(param, size), 0);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const double f = 2 * kPi * ((x + 0.5) / width - 0.5), t = kPi * (y + 0.5) / height;
      const double d[3] = {std::sin(t) * std::sin(f), std::cos(t), -std::sin(t) * std::cos(f)};
      float turned[3];
      for (int r = 0; r < 3; ++r)
        turned[r] = float(rotation.m[3 * r] * d[0] + rotation.m[3 * r + 1] * d[1] +
                          rotation.m[3 * r + 2] * d[2]);
      ++count[prt_wavelet_locate(param, size, turned)];
    }
  return count;
}

void expect_bitwise(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k)
    ASSERT_EQ(std::memcmp(&a[k], &b[k], sizeof(float)), 0)
        << "float " << k << ": " << a[k] << " vs " << b[k];
}

// ---- The scalar path: the reference's arithmetic in the reference's order. ----

TEST(WaveletSource, ScalarPathGivesTheReferenceBits) {
  auto context = prt_test::limited_context(PRT_BACKEND_AUTO, PRT_SIMD_ISA_NONE);
  const std::vector<float> latlong = random_map(250 * 125, 1);  // a width that is no multiple of 8
  const std::vector<float> wide = random_map(256 * 128, 3);
  const std::vector<float> cube = random_map(6 * 24 * 24, 2);
  const prt_env_image envs[3] = {prt::latlong_env(250, 125, latlong.data()),
                                 prt::latlong_env(256, 128, wide.data()),
                                 prt::cube_env(24, cube.data())};
  for (const prt_env_image& env : envs)
    for (prt_wavelet_param param : {kCube, kParaboloid})
      for (uint32_t size : {16u, 64u}) {
        Source source(context.get(), param, size, env);
        ASSERT_EQ(source.result, PRT_OK);
        std::vector<Rotation> rotations = test_rotations();
        if (env.layout == PRT_ENV_LATLONG)
          for (const Rotation& rotation : edge_rotations(env.width)) rotations.push_back(rotation);
        for (const Rotation& rotation : rotations) {
          SCOPED_TRACE(testing::Message() << "layout " << env.layout << " param " << param
                                          << " size " << size << " R[0] " << rotation.m[0]);
          expect_bitwise(resampled(source, param, size, rotation),
                         reference(param, size, env, rotation));
        }
      }
}

// ---- The SIMD paths (a lat-long map onto the cube: AVX2, and AVX-512 in a context without an
// ISA limit where the CPU has it; the scalar path for the rest, where this is the test above
// again). ----

// The context's path against the reference on random maps, under random rotations and under
// rotations that put thousands of texels within a rounding of a texel edge or a face boundary,
// where a float location alone would send some to the neighbour.
void expect_reference_up_to_summation_order(prt_context* ctx) {
  // Maps whose height is no multiple of the 16-row bands, one shorter than a band.
  for (const auto& [width, height] :
       {std::pair<uint32_t, uint32_t>{1024, 512}, {250, 125}, {36, 17}, {8, 3}}) {
    const std::vector<float> map = random_map(size_t(width) * height, width);
    const prt_env_image env = prt::latlong_env(width, height, map.data());
    std::vector<Rotation> rotations = test_rotations();
    for (const Rotation& rotation : edge_rotations(width)) rotations.push_back(rotation);
    if (width == 1024) {
      // The edge rotations do what they are for (64: every size's edges are its edges too).
      for (size_t k = rotations.size() - 2; k < rotations.size(); ++k)
        EXPECT_GT(texels_near_edges(64, width, height, rotations[k], 1e-5), size_t(height))
            << "edge rotation " << k;
    }
    for (prt_wavelet_param param : {kCube, kParaboloid})
      for (uint32_t size : {16u, 64u, 128u}) {
        Source source(ctx, param, size, env);
        ASSERT_EQ(source.result, PRT_OK);
        for (const Rotation& rotation : rotations) {
          SCOPED_TRACE(testing::Message()
                       << width << "x" << height << " param " << param << " size " << size << " R "
                       << rotation.m[0] << " " << rotation.m[1] << " " << rotation.m[2]);
          const std::vector<float> got = resampled(source, param, size, rotation);
          const std::vector<float> want = reference(param, size, env, rotation);
          const std::vector<uint32_t> count = landed_counts(param, size, width, height, rotation);
          for (size_t j = 0; j < count.size(); ++j)
            for (int c = 0; c < 4; ++c) {
              // Two sums of n positive terms in different orders: each within (n - 1) eps of
              // the exact sum; a misplaced texel would move a 1/n share, far more. The float
              // count can miss the texels on an edge: slack for them.
              const double n = double(count[j]) + 8.0;
              const double bound = 2.0 * n * double(FLT_EPSILON) * double(want[4 * j + c]);
              ASSERT_NEAR(got[4 * j + c], want[4 * j + c], bound) << "texel " << j << " c " << c;
            }
        }
      }
  }
}

class WaveletSourceSimd : public prt_test::SimdIsaTest {};

TEST_P(WaveletSourceSimd, EqualsTheReferenceUpToSummationOrder) {
  expect_reference_up_to_summation_order(ctx);
}

TEST(WaveletSource, UnlimitedContextEqualsTheReferenceUpToSummationOrder) {
  auto context = prt_test::limited_context();
  expect_reference_up_to_summation_order(context.get());
}

INSTANTIATE_TEST_SUITE_P(Isa, WaveletSourceSimd, prt_test::kSimdIsas, prt_test::isa_test_name);

// ---- Properties and extremes, on the context's best path. ----

double map_power(const std::vector<float>& map, uint32_t width, uint32_t height, int channel) {
  double power = 0;
  for (uint32_t y = 0; y < height; ++y) {
    const double dw =
        2 * kPi / width * (std::cos(kPi * y / height) - std::cos(kPi * (y + 1) / height));
    for (uint32_t x = 0; x < width; ++x) power += dw * map[3 * (size_t(y) * width + x) + channel];
  }
  return power;
}

TEST(WaveletSource, ConservesPower) {
  auto context = prt_test::limited_context();
  const uint32_t width = 1024, height = 512;
  const std::vector<float> map = random_map(size_t(width) * height, 5);
  const prt_env_image env = prt::latlong_env(width, height, map.data());
  Source source(context.get(), kCube, 64, env);
  ASSERT_EQ(source.result, PRT_OK);
  for (const Rotation& rotation : test_rotations()) {
    const std::vector<float> got = resampled(source, kCube, 64, rotation);
    for (int c = 0; c < 3; ++c) {
      double total = 0;
      for (size_t j = 0; j < got.size() / 4; ++j) total += got[4 * j + c];
      const double expected = map_power(map, width, height, c);
      // Float sums of ~500k positive terms in ~25k texels; the row solid angles in float.
      EXPECT_NEAR(total, expected, 1e-5 * expected) << "channel " << c;
    }
    for (size_t j = 0; j < got.size() / 4; ++j) ASSERT_EQ(got[4 * j + 3], 0.0f);
  }
}

TEST(WaveletSource, OneBrightTexelLandsWhereTheReferencePutsIt) {
  auto context = prt_test::limited_context();
  const uint32_t width = 512, height = 256;
  std::mt19937 rng(9);
  for (int trial = 0; trial < 8; ++trial) {
    std::vector<float> map(3 * size_t(width) * height, 0.0f);
    const size_t texel = rng() % (size_t(width) * height);
    for (int c = 0; c < 3; ++c) map[3 * texel + c] = 1e30f;  // huge, yet L dw stays finite
    const prt_env_image env = prt::latlong_env(width, height, map.data());
    Source source(context.get(), kCube, 64, env);
    ASSERT_EQ(source.result, PRT_OK);
    for (const Rotation& rotation : test_rotations()) {
      const std::vector<float> got = resampled(source, kCube, 64, rotation);
      const std::vector<float> want = reference(kCube, 64, env, rotation);
      size_t lit = 0;
      for (size_t k = 0; k < got.size(); ++k) {
        ASSERT_EQ(got[k], want[k]) << "texel " << k / 4;  // one term: no summation order
        lit += got[k] > 0.0f;
      }
      EXPECT_EQ(lit, 3u);
    }
  }
}

TEST(WaveletSource, ZerosAndUnusableValuesGiveTheReference) {
  auto context = prt_test::limited_context();
  const uint32_t width = 256, height = 128;
  std::vector<float> zeros(3 * size_t(width) * height, 0.0f), odd = random_map(width * height, 3);
  for (size_t k = 0; k < odd.size(); k += 7) odd[k] = -1.0f;
  for (size_t k = 3; k < odd.size(); k += 11) odd[k] = std::numeric_limits<float>::quiet_NaN();
  for (size_t k = 5; k < odd.size(); k += 13) odd[k] = std::numeric_limits<float>::infinity();
  for (const std::vector<float>* map : {&zeros, &odd}) {
    const prt_env_image env = prt::latlong_env(width, height, map->data());
    Source source(context.get(), kCube, 32, env);
    ASSERT_EQ(source.result, PRT_OK);
    const Rotation rotation = test_rotations()[3];
    const std::vector<float> got = resampled(source, kCube, 32, rotation);
    const std::vector<float> want = reference(kCube, 32, env, rotation);
    for (size_t k = 0; k < got.size(); ++k) {
      ASSERT_TRUE(std::isfinite(got[k]));
      if (map == &zeros) {
        ASSERT_EQ(got[k], 0.0f);
      }
      ASSERT_NEAR(got[k], want[k], 1e-4 * std::fabs(want[k])) << "float " << k;
    }
  }
}

// ---- PRT_WAVELET_SOURCE_REDUCE_2X2: the reference's result for the half-size map. ----

// Each 2x2 block's power over its solid angle, computed here from SPEC §12's row solid angles.
std::vector<float> reduced_map(const std::vector<float>& map, uint32_t width, uint32_t height) {
  std::vector<float> out(3 * size_t(width / 2) * (height / 2));
  auto row_dw = [&](uint32_t y) {
    return 2 * kPi / width * (std::cos(kPi * y / height) - std::cos(kPi * (y + 1) / height));
  };
  for (uint32_t y = 0; y < height / 2; ++y)
    for (uint32_t x = 0; x < width / 2; ++x)
      for (int c = 0; c < 3; ++c) {
        double power = 0, dw = 0;
        for (uint32_t i = 0; i < 4; ++i) {
          const uint32_t sx = 2 * x + (i & 1), sy = 2 * y + (i >> 1);
          power += row_dw(sy) * map[3 * (size_t(sy) * width + sx) + c];
          dw += row_dw(sy);
        }
        out[3 * (size_t(y) * (width / 2) + x) + c] = float(power / dw);
      }
  return out;
}

TEST(WaveletSource, Reduce2x2GivesTheReferenceOfTheHalfSizeMap) {
  auto context = prt_test::limited_context();
  const uint32_t width = 1024, height = 512;
  const std::vector<float> map = random_map(size_t(width) * height, 8);
  const std::vector<float> half = reduced_map(map, width, height);
  const prt_env_image env = prt::latlong_env(width, height, map.data());
  const prt_env_image half_env = prt::latlong_env(width / 2, height / 2, half.data());
  Source source(context.get(), kCube, 64, env, PRT_WAVELET_SOURCE_REDUCE_2X2);
  ASSERT_EQ(source.result, PRT_OK);
  for (const Rotation& rotation : test_rotations()) {
    const std::vector<float> got = resampled(source, kCube, 64, rotation);
    const std::vector<float> want = reference(kCube, 64, half_env, rotation);
    const std::vector<uint32_t> count = landed_counts(kCube, 64, width / 2, height / 2, rotation);
    for (size_t j = 0; j < count.size(); ++j)
      for (int c = 0; c < 4; ++c) {
        // As above, plus one rounding of each reduced texel's radiance (here and there).
        const double n = double(count[j]) + 2.0;
        const double bound = 2.0 * (n + 1.0) * double(FLT_EPSILON) * double(want[4 * j + c]);
        ASSERT_NEAR(got[4 * j + c], want[4 * j + c], bound) << "texel " << j << " c " << c;
      }
  }
}

// ---- Errors. ----

TEST(WaveletSource, RejectsBadArguments) {
  auto context = prt_test::limited_context();
  prt_context* ctx = context.get();
  const std::vector<float> map = random_map(64 * 32, 4);
  const prt_env_image env = prt::latlong_env(64, 32, map.data());
  prt_wavelet_source_desc desc = prt::sized<prt_wavelet_source_desc>();
  desc.param = kCube;
  desc.size = 16;
  desc.env = &env;
  prt_wavelet_source* source = reinterpret_cast<prt_wavelet_source*>(&desc);  // must be reset
  EXPECT_EQ(prt_wavelet_source_create(nullptr, &desc, &source), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(source, nullptr);
  EXPECT_EQ(prt_wavelet_source_create(ctx, nullptr, &source), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_source_create(ctx, &desc, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  auto rejected = [&](prt_wavelet_source_desc bad) {
    prt_wavelet_source* s = nullptr;
    const prt_result r = prt_wavelet_source_create(ctx, &bad, &s);
    EXPECT_EQ(s, nullptr);
    prt_wavelet_source_destroy(s);
    return r == PRT_ERROR_INVALID_ARGUMENT;
  };
  prt_wavelet_source_desc bad = desc;
  bad.struct_size = sizeof(size_t);
  EXPECT_TRUE(rejected(bad));
  bad = desc, bad.size = 48;
  EXPECT_TRUE(rejected(bad));
  bad = desc, bad.size = 256;
  EXPECT_TRUE(rejected(bad));
  bad = desc, bad.param = prt_wavelet_param(7);
  EXPECT_TRUE(rejected(bad));
  bad = desc, bad.env = nullptr;
  EXPECT_TRUE(rejected(bad));
  const Rotation turn = test_rotations()[1];
  prt_env_image turned = env;
  turned.rotation = turn.m;
  bad = desc, bad.env = &turned;
  EXPECT_TRUE(rejected(bad));
  prt_env_image two_channels = env;
  two_channels.channels = 2;
  bad = desc, bad.env = &two_channels;
  EXPECT_TRUE(rejected(bad));

  bad = desc, bad.flags = 0x2;
  EXPECT_TRUE(rejected(bad));
  const prt_env_image odd = prt::latlong_env(63, 32, map.data());
  bad = desc, bad.env = &odd, bad.flags = PRT_WAVELET_SOURCE_REDUCE_2X2;
  EXPECT_TRUE(rejected(bad));
  const prt_env_image cube = prt::cube_env(8, map.data());
  bad = desc, bad.env = &cube, bad.flags = PRT_WAVELET_SOURCE_REDUCE_2X2;
  EXPECT_TRUE(rejected(bad));
  EXPECT_EQ(Source(ctx, kCube, 16, env, PRT_WAVELET_SOURCE_REDUCE_2X2).result, PRT_OK);

  ASSERT_EQ(prt_wavelet_source_create(ctx, &desc, &source), PRT_OK);
  std::vector<float> out(4 * size_t(prt_wavelet_coefficient_count(kCube, 16)));
  const float reflection[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
  const float stretched[9] = {2, 0, 0, 0, 1, 0, 0, 0, 1};
  EXPECT_EQ(prt_wavelet_source_resample(source, reflection, out.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_source_resample(source, stretched, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_source_resample(source, nullptr, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_source_resample(nullptr, nullptr, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_source_resample(source, nullptr, out.data()), PRT_OK);  // no rotation
  prt_wavelet_source_destroy(source);
  prt_wavelet_source_destroy(nullptr);
}

}  // namespace
