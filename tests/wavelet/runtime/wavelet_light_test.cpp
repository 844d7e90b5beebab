// SPDX-License-Identifier: MIT
// The per-frame wavelet light (SPEC §14, prt_wavelet.h): resampling of lat-long and cube images
// (prt_env_image), the per-face transform and the area-weighted selection, checked against
// properties (constants stay constant, power is conserved, a quarter turn is a quarter-width
// shift, strides and RGBA change no bit), directions computed here from SPEC §12 and an
// independent sort for the selection. (prt_env_image's rejections: tests/runtime/env_test.cpp.)
#include <gtest/gtest.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace {

constexpr prt_wavelet_param kCube = PRT_WAVELET_PARAM_CUBE;
constexpr prt_wavelet_param kParaboloid = PRT_WAVELET_PARAM_DUAL_PARABOLOID;
constexpr double kPi = 3.14159265358979323846;

struct Rotation {
  float m[9];
};

// SPEC §12: light from d comes from R d, R about +Y.
Rotation rotation_y(double degrees) {
  const double c = std::cos(degrees * kPi / 180), s = std::sin(degrees * kPi / 180);
  return {{float(c), 0, float(s), 0, 1, 0, float(-s), 0, float(c)}};
}

// A rotation about an oblique axis (Rodrigues), for "any rotation".
Rotation rotation_axis(double x, double y, double z, double degrees) {
  const double n = std::sqrt(x * x + y * y + z * z);
  x /= n, y /= n, z /= n;
  const double c = std::cos(degrees * kPi / 180), s = std::sin(degrees * kPi / 180), t = 1 - c;
  return {{float(t * x * x + c), float(t * x * y - s * z), float(t * x * z + s * y),
           float(t * x * y + s * z), float(t * y * y + c), float(t * y * z - s * x),
           float(t * x * z - s * y), float(t * y * z + s * x), float(t * z * z + c)}};
}

std::vector<Rotation> test_rotations() {
  return {rotation_y(0), rotation_y(37), rotation_axis(1, 2, -0.5, 71)};
}

uint32_t texel_count(prt_wavelet_param param, uint32_t size) {
  return prt_wavelet_coefficient_count(param, size);
}

bool inside(prt_wavelet_param param, uint32_t size, uint32_t j) {
  const uint32_t face = j / (size * size), x = j % size, y = (j / size) % size;
  return prt_wavelet_texel_solid_angle(param, size, face, x, y) > 0.0;
}

double solid_angle(prt_wavelet_param param, uint32_t size, uint32_t j) {
  return prt_wavelet_texel_solid_angle(param, size, j / (size * size), j % size, (j / size) % size);
}

// Normals for cosine-weighted comparisons: the axes and two oblique unit vectors.
const double kAxes[7][3] = {{1, 0, 0}, {-1, 0, 0},       {0, 1, 0},        {0, -1, 0},
                            {0, 0, 1}, {0.6, 0.0, -0.8}, {0.48, 0.6, 0.64}};

double dot(const double* a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The centre direction of texel j (prt_wavelet_direction; zero outside the paraboloid's disc).
std::array<double, 3> texel_centre(prt_wavelet_param param, uint32_t size, uint32_t j) {
  const uint32_t face = j / (size * size), y = (j % (size * size)) / size, x = j % size;
  float d[3] = {0, 0, 0};
  if (!prt_wavelet_direction(param, size, face, x + 0.5f, y + 0.5f, d)) return {0, 0, 0};
  return {d[0], d[1], d[2]};
}

std::vector<float> random_map(size_t texels, uint32_t seed, float lo = 0.0f, float hi = 1.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(lo, hi);
  std::vector<float> rgb(texels * 3);
  for (float& v : rgb) v = value(rng);
  return rgb;
}

// SPEC §12 lat-long texel centre direction and exact solid angle.
void latlong_direction(uint32_t x, uint32_t y, uint32_t w, uint32_t h, double d[3]) {
  const double phi = 2 * kPi * ((x + 0.5) / w - 0.5), theta = kPi * (y + 0.5) / h;
  d[0] = std::sin(theta) * std::sin(phi);
  d[1] = std::cos(theta);
  d[2] = -std::sin(theta) * std::cos(phi);
}
double latlong_solid_angle(uint32_t y, uint32_t w, uint32_t h) {
  return 2 * kPi / w * (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h));
}

std::vector<float> resample_latlong(prt_wavelet_param param, uint32_t size,
                                    const std::vector<float>& rgb, uint32_t width,
                                    const float* rotation) {
  std::vector<float> light(4 * size_t(texel_count(param, size)), -1.0f);
  const prt_env_image env = prt::latlong_env(width, width / 2, rgb.data(), 3, rotation);
  EXPECT_EQ(prt_wavelet_resample(param, size, &env, light.data()), PRT_OK);
  return light;
}

std::vector<float> resample_cube(prt_wavelet_param param, uint32_t size,
                                 const std::vector<float>& faces, uint32_t face_size,
                                 const float* rotation) {
  std::vector<float> light(4 * size_t(texel_count(param, size)), -1.0f);
  const prt_env_image env = prt::cube_env(face_size, faces.data(), 3, rotation);
  EXPECT_EQ(prt_wavelet_resample(param, size, &env, light.data()), PRT_OK);
  return light;
}

// A source coarser than the target: every texel takes a source texel's radiance (a big source
// texel landed whole, or the nearest one) times its own solid angle (SPEC §14), so a constant map
// L gives exactly L dw_j on every texel.
void expect_constant(prt_wavelet_param param, uint32_t size, const std::vector<float>& light,
                     const float rgb[3], const char* what) {
  // Each texel is a ratio of two float sums of up to ~2000 terms (the lat-long pole rows): each
  // sum is exact to n 2^-24 ~ 1e-4 relative.
  uint32_t wrong = 0;
  for (uint32_t j = 0; j < texel_count(param, size); ++j) {
    const bool in = inside(param, size, j);
    for (int c = 0; c < 3; ++c) {
      const double expected = in ? rgb[c] * solid_angle(param, size, j) : 0.0;
      if (std::fabs(light[4 * j + c] - expected) > 1e-4 * expected) ++wrong;
    }
    if (light[4 * j + 3] != 0.0f) ++wrong;
  }
  EXPECT_EQ(wrong, 0u) << what << " param " << param << " size " << size;
}

// A source finer than the target: each texel holds the power landed in it (SPEC §14), so a
// constant map keeps its power 4 pi L exactly (every target here receives ~20 or more source
// texels), while single texels differ from L dw_j by the share of boundary source texels they
// happen to receive: on the cube never by a factor 2 (the paraboloid's rim texels also collect
// the directions of the outside texels next to them, so the bound is the cube's).
void expect_constant_power(prt_wavelet_param param, uint32_t size, const std::vector<float>& light,
                           const float rgb[3], const char* what) {
  double power[3] = {0, 0, 0};
  uint32_t outside_band = 0;
  for (uint32_t j = 0; j < texel_count(param, size); ++j) {
    if (!inside(param, size, j)) continue;
    for (int c = 0; c < 3; ++c) {
      power[c] += double(light[4 * j + c]);
      const double ratio = light[4 * j + c] / (rgb[c] * solid_angle(param, size, j));
      if (param == kCube && !(ratio >= 0.5 && ratio <= 2.0)) ++outside_band;
    }
  }
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(power[c] / (4 * kPi * rgb[c]), 1.0, 1e-4) << what << " param " << param;
  EXPECT_EQ(outside_band, 0u) << what << " param " << param << " size " << size;
}

TEST(WaveletLight, ConstantLatLongStaysConstantOrKeepsItsPowerForAnyRotation) {
  const float rgb[3] = {0.75f, 2.5f, 40.0f};
  for (uint32_t width : {16u, 1024u}) {  // coarser and finer than the targets
    std::vector<float> map(size_t(width) * width / 2 * 3);
    for (size_t i = 0; i < map.size(); ++i) map[i] = rgb[i % 3];
    for (prt_wavelet_param param : {kCube, kParaboloid})
      for (uint32_t size : {16u, 64u})
        for (const Rotation& r : test_rotations()) {
          const std::vector<float> light = resample_latlong(param, size, map, width, r.m);
          if (width == 16)
            expect_constant(param, size, light, rgb, "coarse lat-long");
          else
            expect_constant_power(param, size, light, rgb, "fine lat-long");
        }
  }
}

// A sun: a 3 x 3 block of source texels 10^5 times brighter than a black sky, at several places
// and turns. Its power must arrive whole, whatever share of a target texel's solid angle its
// source texels happen to cover (dividing by the landed solid angle instead was off by up to
// +-25 % at S = 64, the bias that made the bunny under spiaggia 5.6 % too bright).
TEST(WaveletLight, SmallSunKeepsItsPowerExactly) {
  const uint32_t width = 1024, height = 512;
  for (uint32_t place = 0; place < 4; ++place) {
    std::vector<float> map(size_t(width) * height * 3, 0.0f);
    const uint32_t cx = 100 + 211 * place, cy = 60 + 97 * place;
    double source_power = 0.0;
    for (uint32_t y = cy; y < cy + 3; ++y)
      for (uint32_t x = cx; x < cx + 3; ++x) {
        map[3 * (size_t(y) * width + x)] = 1e5f;
        source_power += 1e5 * latlong_solid_angle(y, width, height);
      }
    const Rotation r = rotation_axis(0.2, 1, 0.1, 17.0 * place);
    for (prt_wavelet_param param : {kCube, kParaboloid})
      for (uint32_t size : {32u, 64u}) {
        const std::vector<float> light = resample_latlong(param, size, map, width, r.m);
        double power = 0.0;
        for (uint32_t j = 0; j < texel_count(param, size); ++j) power += double(light[4 * j]);
        EXPECT_NEAR(power / source_power, 1.0, 1e-5) << param << " " << size << " " << place;
      }
  }
}

TEST(WaveletLight, ConstantCubeStaysConstantOrKeepsItsPowerForAnyRotation) {
  const float rgb[3] = {3.0f, 0.125f, 1.0f};
  for (uint32_t face_size : {4u, 192u}) {
    std::vector<float> faces(6 * size_t(face_size) * face_size * 3);
    for (size_t i = 0; i < faces.size(); ++i) faces[i] = rgb[i % 3];
    for (prt_wavelet_param param : {kCube, kParaboloid})
      for (uint32_t size : {16u, 32u})
        for (const Rotation& r : test_rotations()) {
          const std::vector<float> light = resample_cube(param, size, faces, face_size, r.m);
          if (face_size == 4)
            expect_constant(param, size, light, rgb, "coarse cube");
          else
            expect_constant_power(param, size, light, rgb, "fine cube");
        }
  }
}

// Sum P_j over the target = sum L_s dw_s over a source finer than the target. On the paraboloid
// the inside texels' solid angles over-cover the sphere by their lattice excess, which bounds the
// deviation there.
TEST(WaveletLight, PowerOfAFineMapIsConserved) {
  const uint32_t width = 1024, height = 512;
  const std::vector<float> map = random_map(size_t(width) * height, 11);
  double source_power[3] = {0, 0, 0};
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        source_power[c] +=
            map[3 * (size_t(y) * width + x) + c] * latlong_solid_angle(y, width, height);
  const Rotation r = rotation_axis(0.3, 1, 0.2, 50);
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    for (uint32_t size : {16u, 64u}) {
      const std::vector<float> light = resample_latlong(param, size, map, width, r.m);
      double power[3] = {0, 0, 0}, covered = 0;
      for (uint32_t j = 0; j < texel_count(param, size); ++j) {
        covered += solid_angle(param, size, j);
        for (int c = 0; c < 3; ++c) power[c] += light[4 * j + c];
      }
      const double excess = std::fabs(covered / (4 * kPi) - 1);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(power[c] / source_power[c], 1.0, 2e-4 + excess) << param << " " << size;
    }
  }
}

TEST(WaveletLight, QuarterTurnEqualsQuarterWidthShift) {
  const uint32_t width = 256, height = 128;
  const std::vector<float> map = random_map(size_t(width) * height, 3);
  std::vector<float> shifted(map.size());
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        shifted[3 * (size_t(y) * width + x) + c] =
            map[3 * (size_t(y) * width + (x + width / 4) % width) + c];
  const Rotation quarter = rotation_y(90);
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    for (uint32_t size : {16u, 32u}) {
      const std::vector<float> turned = resample_latlong(param, size, map, width, quarter.m);
      const std::vector<float> moved = resample_latlong(param, size, shifted, width, nullptr);
      uint32_t differ = 0;
      for (size_t i = 0; i < turned.size(); ++i)
        if (std::fabs(turned[i] - moved[i]) > 1e-5f * (1.0f + std::fabs(moved[i]))) ++differ;
      EXPECT_EQ(differ, 0u) << param << " " << size;
    }
  }
}

TEST(WaveletLight, SingleBrightTexelLandsWhereLocateSays) {
  const uint32_t width = 512, height = 256;
  const uint32_t picks[][2] = {{10, 3}, {200, 100}, {300, 128}, {511, 255}, {77, 190}};
  const Rotation r = rotation_axis(-1, 0.5, 2, 123);
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    const uint32_t size = 16;
    for (const auto& pick : picks) {
      std::vector<float> map(size_t(width) * height * 3, 0.0f);
      float* texel = &map[3 * (size_t(pick[1]) * width + pick[0])];
      texel[0] = 1000, texel[1] = 500, texel[2] = 250;
      const std::vector<float> light = resample_latlong(param, size, map, width, r.m);
      double d[3];
      latlong_direction(pick[0], pick[1], width, height, d);
      float rd[3];
      for (int i = 0; i < 3; ++i)
        rd[i] = float(r.m[3 * i] * d[0] + r.m[3 * i + 1] * d[1] + r.m[3 * i + 2] * d[2]);
      const uint32_t target = prt_wavelet_locate(param, size, rd);
      for (uint32_t j = 0; j < texel_count(param, size); ++j) {
        if (j == target) {
          EXPECT_GT(light[4 * j], 0.0f);
          EXPECT_FLOAT_EQ(light[4 * j], 2 * light[4 * j + 1]);
          EXPECT_FLOAT_EQ(light[4 * j], 4 * light[4 * j + 2]);
        } else {
          ASSERT_EQ(light[4 * j], 0.0f) << "param " << param << " texel " << j;
        }
      }
    }
  }
}

TEST(WaveletLight, NonFiniteAndNegativeChannelsAreZeroBitForBit) {
  const float bad[] = {std::numeric_limits<float>::quiet_NaN(),
                       std::numeric_limits<float>::infinity(),
                       -std::numeric_limits<float>::infinity(), -3.0f, -0.0f};
  for (uint32_t width : {8u, 256u}) {  // the coarse map exercises the nearest-texel fill
    std::vector<float> dirty = random_map(size_t(width) * width / 2, 5, 0.1f, 2.0f);
    std::vector<float> clean = dirty;
    for (size_t i = 0; i < dirty.size(); i += 7) {
      dirty[i] = bad[(i / 7) % 5];
      clean[i] = 0.0f;
    }
    std::vector<float> dirty_faces = random_map(6 * 8 * 8, 6, 0.1f, 2.0f);
    std::vector<float> clean_faces = dirty_faces;
    for (size_t i = 0; i < dirty_faces.size(); i += 5) {
      dirty_faces[i] = bad[(i / 5) % 5];
      clean_faces[i] = 0.0f;
    }
    const Rotation r = rotation_y(20);
    for (prt_wavelet_param param : {kCube, kParaboloid}) {
      const std::vector<float> a = resample_latlong(param, 32, dirty, width, r.m);
      const std::vector<float> b = resample_latlong(param, 32, clean, width, r.m);
      EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
      const std::vector<float> c = resample_cube(param, 32, dirty_faces, 8, r.m);
      const std::vector<float> d = resample_cube(param, 32, clean_faces, 8, r.m);
      EXPECT_EQ(std::memcmp(c.data(), d.data(), c.size() * sizeof(float)), 0);
    }
  }
}

// A source coarser than the target leaves targets no source texel landed in; each takes the
// source texel holding R^T c (c its centre), computed here from SPEC §12's direction -> image.
TEST(WaveletLight, CoarseSourceFillsEveryTexelFromTheNearestSourceTexel) {
  const uint32_t width = 8, height = 4;
  std::vector<float> map(size_t(width) * height * 3);
  for (size_t i = 0; i < map.size(); ++i) map[i] = 1.0f + float(i);  // distinct, positive
  const Rotation r = rotation_y(30);
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    const uint32_t size = 128;
    const std::vector<float> light = resample_latlong(param, size, map, width, r.m);
    uint32_t texels = 0, from_nearest = 0, empty = 0;
    for (uint32_t j = 0; j < texel_count(param, size); ++j) {
      if (!inside(param, size, j)) continue;
      ++texels;
      if (!(light[4 * j] > 0.0f)) ++empty;
      float c[3];
      ASSERT_EQ(prt_wavelet_direction(param, size, j / (size * size), (j % size) + 0.5f,
                                      ((j / size) % size) + 0.5f, c),
                1);
      double e[3];
      for (int i = 0; i < 3; ++i)
        e[i] = r.m[i] * c[0] + r.m[3 + i] * c[1] + r.m[6 + i] * c[2];  // R^T c
      const double u = 0.5 + std::atan2(e[0], -e[2]) / (2 * kPi);
      const double v = std::acos(std::clamp(e[1], -1.0, 1.0)) / kPi;
      const uint32_t x = std::min(width - 1, uint32_t(u * width));
      const uint32_t y = std::min(height - 1, uint32_t(v * height));
      // The nearest texel's radiance times the texel's solid angle, rounded once (SPEC §14).
      const float expected = float(double(map[3 * (y * width + x)]) * solid_angle(param, size, j));
      if (light[4 * j] == expected) ++from_nearest;
    }
    EXPECT_EQ(empty, 0u);
    // All but the (32) targets a source centre landed in, and some near seams.
    EXPECT_GT(from_nearest, texels - texels / 100) << param;
  }
}

// The same smooth environment given as lat-long and as cube faces resamples to the same light:
// checks the cube source's face order and orientation against the lat-long convention.
TEST(WaveletLight, CubeAndLatLongSourcesAgree) {
  auto environment = [](double x, double y, double z, int c) {
    return 1.0 + 0.5 * x + 0.3 * (c + 1) * y - 0.4 * z + 0.2 * x * z;
  };
  const uint32_t width = 1024, height = 512, face_size = 128;
  std::vector<float> map(size_t(width) * height * 3);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      double d[3];
      latlong_direction(x, y, width, height, d);
      for (int c = 0; c < 3; ++c)
        map[3 * (size_t(y) * width + x) + c] = float(environment(d[0], d[1], d[2], c));
    }
  // SPEC §13's runtime cube faces.
  std::vector<float> faces(6 * size_t(face_size) * face_size * 3);
  for (uint32_t f = 0; f < 6; ++f)
    for (uint32_t j = 0; j < face_size; ++j)
      for (uint32_t i = 0; i < face_size; ++i) {
        const double s = 2 * (i + 0.5) / face_size - 1, t = 2 * (j + 0.5) / face_size - 1;
        const double table[6][3] = {{1, -t, -s}, {-1, -t, s}, {s, 1, t},
                                    {s, -1, -t}, {s, -t, 1},  {-s, -t, -1}};
        const double* d = table[f];
        const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int c = 0; c < 3; ++c)
          faces[3 * ((size_t(f) * face_size + j) * face_size + i) + c] =
              float(environment(d[0] / n, d[1] / n, d[2] / n, c));
      }
  const Rotation r = rotation_axis(1, 1, 0, 33);
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    const std::vector<float> a = resample_latlong(param, 16, map, width, r.m);
    const std::vector<float> b = resample_cube(param, 16, faces, face_size, r.m);
    // Each target holds the power that landed in it, and which boundary source texels land in it
    // differs between the two sources, so single texels differ by a few per cent; what shading
    // sees, the power weighted by a smooth transfer, agrees closely: the cosine-weighted power
    // about several normals (a smooth function of the texel) within 2e-3.
    for (const double* n : {kAxes[0], kAxes[2], kAxes[5], kAxes[6]}) {
      double sa = 0.0, sb = 0.0;
      for (uint32_t j = 0; j < texel_count(param, 16); ++j) {
        const double cosine = std::max(0.0, dot(n, texel_centre(param, 16, j)));
        sa += a[4 * j] * cosine;
        sb += b[4 * j] * cosine;
      }
      EXPECT_NEAR(sa / sb, 1.0, 2e-3) << param;
    }
  }
}

TEST(WaveletLight, TransformOfAConstantLightIsItsScalingCoefficients) {
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    const uint32_t size = 32, faces = prt_wavelet_face_count(param);
    std::vector<float> light(4 * size_t(texel_count(param, size)));
    for (size_t i = 0; i < light.size(); ++i) light[i] = (i % 4 == 3) ? 0.0f : float(i % 4 + 1);
    ASSERT_EQ(prt_wavelet_transform_light(param, size, light.data()), PRT_OK);
    for (uint32_t j = 0; j < texel_count(param, size); ++j) {
      const bool scaling = j % (size * size) == 0;
      for (int c = 0; c < 4; ++c) {
        // Orthonormal Haar: the scaling coefficient of a constant face is sum / size.
        const float expected = (scaling && c < 3) ? float(c + 1) * size : 0.0f;
        ASSERT_NEAR(light[4 * j + c], expected, 1e-4f * size) << j << " " << c;
      }
    }
    (void)faces;
  }
}

// ---- Selection ----

uint32_t level_area(uint32_t size, uint32_t j) {
  const uint32_t x = j % size, y = (j / size) % size;
  const int level = prt_haar_level(size, x, y);
  const uint32_t support = size >> level;
  return support * support;
}

bool is_scaling(uint32_t size, uint32_t j) {
  return j % (size * size) == 0;
}

TEST(WaveletSelect, ZeroKeepsExactlyTheScalingCoefficients) {
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    const uint32_t size = 16;
    std::vector<float> light = random_map(texel_count(param, size) * 4 / 3 + 1, 9, -1, 1);
    light.resize(4 * size_t(texel_count(param, size)));
    const std::vector<float> before = light;
    ASSERT_EQ(prt_wavelet_select_light(param, size, 0, light.data()), PRT_OK);
    for (uint32_t j = 0; j < texel_count(param, size); ++j)
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(light[4 * j + c], is_scaling(size, j) ? before[4 * j + c] : 0.0f);
  }
}

TEST(WaveletSelect, AllKeepsEverythingUnchanged) {
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    const uint32_t size = 32;
    const uint32_t details = texel_count(param, size) - prt_wavelet_face_count(param);
    std::vector<float> light(4 * size_t(texel_count(param, size)));
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> value(-5, 5);
    for (float& v : light) v = value(rng);
    for (uint32_t m : {details, details + 1, 0xFFFFFFFFu}) {
      std::vector<float> copy = light;
      ASSERT_EQ(prt_wavelet_select_light(param, size, m, copy.data()), PRT_OK);
      EXPECT_EQ(std::memcmp(copy.data(), light.data(), light.size() * sizeof(float)), 0) << m;
    }
  }
}

TEST(WaveletSelect, AreaWeightingPrefersTheCoarseCoefficient) {
  const uint32_t size = 16;
  std::vector<float> light(4 * size_t(texel_count(kCube, size)), 0.0f);
  // Grey, so the luminance is the value: a level-0 coefficient (support 16 x 16 = 256 texels) of
  // 1.0 against a larger level-3 one (support 2 x 2 = 4 texels) of 1.5 on another face:
  // weights 256 and 6, so M = 1 keeps the coarse one although it is smaller.
  const uint32_t coarse = 1 * 256 + 1 * 16 + 0;  // face 1, (0, 1): level 0
  const uint32_t fine = 3 * 256 + 9 * 16 + 12;   // face 3, (12, 9): level 3
  for (int c = 0; c < 3; ++c) light[4 * coarse + c] = 1.0f, light[4 * fine + c] = -1.5f;
  std::vector<float> kept = light;
  ASSERT_EQ(prt_wavelet_select_light(kCube, size, 1, kept.data()), PRT_OK);
  EXPECT_EQ(kept[4 * coarse], 1.0f);
  EXPECT_EQ(kept[4 * fine], 0.0f);
  // Unweighted magnitude would have picked the fine one: the order really changed.
  EXPECT_GT(std::fabs(light[4 * fine]), std::fabs(light[4 * coarse]));
}

TEST(WaveletSelect, TiesKeepTheLowerIndex) {
  const uint32_t size = 16;
  std::vector<float> light(4 * size_t(texel_count(kParaboloid, size)), 0.0f);
  // Four equal level-2 coefficients (same area, same luminance) and one larger.
  const uint32_t tied[] = {256 + 5 * 16 + 6, 4 * 16 + 7, 256 + 4, 6 * 16 + 4};
  for (uint32_t j : tied) light[4 * j] = 2.0f, light[4 * j + 1] = 1.0f;
  light[4 * (200)] = 9.0f;  // (8, 12): level 3, area 4, weight 9 * 0.2126 * 4 = 7.65 < 2 * ...
  // Weights: tied 16 * (2 * 0.2126 + 0.7152) = 18.25; the single 7.65.
  std::vector<float> kept = light;
  ASSERT_EQ(prt_wavelet_select_light(kParaboloid, size, 2, kept.data()), PRT_OK);
  std::vector<uint32_t> sorted(std::begin(tied), std::end(tied));
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t j : sorted) {
    const bool keep = j == sorted[0] || j == sorted[1];
    EXPECT_EQ(kept[4 * j], keep ? 2.0f : 0.0f) << j;
  }
  EXPECT_EQ(kept[4 * 200], 0.0f);
}

// Distinct weights by construction (odd integer values times powers of four stay distinct and
// below 2^24), compared with a plain sort of the spec's weights.
TEST(WaveletSelect, KeepsExactlyTheMLargestWeights) {
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    const uint32_t size = 16, count = texel_count(param, size);
    std::vector<uint32_t> values(count);
    std::iota(values.begin(), values.end(), 0u);
    std::mt19937 rng(param + 21);
    std::shuffle(values.begin(), values.end(), rng);
    std::vector<float> light(4 * size_t(count));
    for (uint32_t j = 0; j < count; ++j) {
      const float v = float(2 * values[j] + 1) * ((j % 3) ? 1.0f : -1.0f);
      light[4 * j] = light[4 * j + 1] = light[4 * j + 2] = v;
      light[4 * j + 3] = 0.0f;
    }
    std::vector<uint32_t> order;
    for (uint32_t j = 0; j < count; ++j)
      if (!is_scaling(size, j)) order.push_back(j);
    auto weight = [&](uint32_t j) { return double(level_area(size, j)) * std::fabs(light[4 * j]); };
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return weight(a) > weight(b) || (weight(a) == weight(b) && a < b);
    });
    for (uint32_t m : {1u, 2u, 37u, 256u, 1000u, count - 10}) {
      if (m >= order.size()) continue;
      std::vector<float> kept = light;
      ASSERT_EQ(prt_wavelet_select_light(param, size, m, kept.data()), PRT_OK);
      std::vector<bool> expected(count, false);
      for (uint32_t k = 0; k < m; ++k) expected[order[k]] = true;
      uint32_t kept_details = 0, wrong = 0;
      for (uint32_t j = 0; j < count; ++j) {
        const bool keep = is_scaling(size, j) || expected[j];
        if (!is_scaling(size, j) && kept[4 * j] != 0.0f) ++kept_details;
        if (kept[4 * j] != (keep ? light[4 * j] : 0.0f)) ++wrong;
      }
      EXPECT_EQ(kept_details, m);
      EXPECT_EQ(wrong, 0u) << "param " << param << " m " << m;
    }
  }
}

// The padding float is scratch during selection (the weights' bits) and must come back as 0
// (prt_wavelet.h) for every detail coefficient, kept or not, whatever the caller left there.
TEST(WaveletSelect, PaddingComesBackAsZero) {
  const uint32_t size = 16, count = texel_count(kCube, size);
  std::vector<float> light(4 * size_t(count));
  for (uint32_t j = 0; j < count; ++j) {
    light[4 * j] = light[4 * j + 1] = light[4 * j + 2] = float(j % 97 + 1);
    light[4 * j + 3] = std::numeric_limits<float>::quiet_NaN();
  }
  ASSERT_EQ(prt_wavelet_select_light(kCube, size, 300, light.data()), PRT_OK);
  uint32_t kept = 0;
  for (uint32_t j = 0; j < count; ++j) {
    if (is_scaling(size, j)) continue;
    kept += light[4 * j] != 0.0f;
    EXPECT_EQ(light[4 * j + 3], 0.0f) << j;
  }
  EXPECT_EQ(kept, 300u);
}

TEST(WaveletSelect, ExactlyMKeptAmongManyEqualWeights) {
  const uint32_t size = 32, count = texel_count(kCube, size);
  std::vector<float> light(4 * size_t(count), 0.0f);
  for (uint32_t j = 0; j < count; ++j) light[4 * j] = 1.0f;  // level ties everywhere
  std::vector<float> kept = light;
  ASSERT_EQ(prt_wavelet_select_light(kCube, size, 100, kept.data()), PRT_OK);
  uint32_t kept_details = 0;
  for (uint32_t j = 0; j < count; ++j)
    if (!is_scaling(size, j) && kept[4 * j] != 0.0f) ++kept_details;
  EXPECT_EQ(kept_details, 100u);
}

TEST(WaveletLight, BadArgumentsRejected) {
  std::vector<float> map(64 * 32 * 3, 1.0f), light(4 * 6 * 16 * 16);
  const prt_env_image latlong = prt::latlong_env(64, 32, map.data());
  const prt_env_image cube = prt::cube_env(4, map.data());
  const auto bad_param = static_cast<prt_wavelet_param>(2);
  EXPECT_EQ(prt_wavelet_resample(kCube, 16, &latlong, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_resample(kCube, 16, &cube, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_resample(kCube, 16, nullptr, light.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_resample(kCube, 16, &latlong, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_resample(kCube, 16, &cube, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_resample(kCube, 24, &latlong, light.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_resample(kCube, 256, &cube, light.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_resample(static_cast<prt_wavelet_param>(4), 16, &latlong, light.data()),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_transform_light(kCube, 16, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_transform_light(kCube, 8, light.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_transform_light(bad_param, 16, light.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_select_light(kCube, 16, 5, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_select_light(kCube, 512, 5, light.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_wavelet_select_light(static_cast<prt_wavelet_param>(3), 16, 5, light.data()),
            PRT_ERROR_INVALID_ARGUMENT);
}

// RGBA texels (the 4th float a NaN that would poison any sum it reached) with padded rows, and
// cube faces with gaps between them, give the bits of the tight RGB images.
TEST(WaveletLight, RgbaAndStridesGiveTheTightResult) {
  const Rotation r = rotation_axis(1, 2, -0.5, 71);
  const uint32_t width = 128, height = 64, row_stride = 4 * width + 9;
  const std::vector<float> map = random_map(size_t(width) * height, 21, 0.1f, 3.0f);
  std::vector<float> rgba(size_t(row_stride) * height, -7.0f);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      for (int c = 0; c < 3; ++c) rgba[y * row_stride + 4 * x + c] = map[(y * width + x) * 3 + c];
      rgba[y * row_stride + 4 * x + 3] = std::nanf("");
    }
  const uint32_t face = 16, face_row = 4 * face + 1, face_stride = face_row * face + 5;
  const std::vector<float> faces = random_map(6 * size_t(face) * face, 22, 0.1f, 3.0f);
  std::vector<float> spaced(6 * size_t(face_stride), std::nanf(""));
  for (uint32_t f = 0; f < 6; ++f)
    for (uint32_t y = 0; y < face; ++y)
      for (uint32_t x = 0; x < face; ++x)
        for (int c = 0; c < 3; ++c)
          spaced[f * face_stride + y * face_row + 4 * x + c] =
              faces[((f * face + y) * face + x) * 3 + c];
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    std::vector<float> light(4 * size_t(texel_count(param, 32)));
    prt_env_image env = prt::latlong_env(width, height, rgba.data(), 4, r.m);
    env.row_stride = row_stride;
    ASSERT_EQ(prt_wavelet_resample(param, 32, &env, light.data()), PRT_OK);
    const std::vector<float> tight = resample_latlong(param, 32, map, width, r.m);
    EXPECT_EQ(std::memcmp(light.data(), tight.data(), light.size() * sizeof(float)), 0);
    env = prt::cube_env(face, spaced.data(), 4, r.m);
    env.row_stride = face_row;
    env.face_stride = face_stride;
    ASSERT_EQ(prt_wavelet_resample(param, 32, &env, light.data()), PRT_OK);
    const std::vector<float> tight_cube = resample_cube(param, 32, faces, face, r.m);
    EXPECT_EQ(std::memcmp(light.data(), tight_cube.data(), light.size() * sizeof(float)), 0);
  }
}

// A lat-long map need not be 2:1 (prt_env.h): a constant 3:1 map gives L dw on every texel, as
// a 2:1 one does (expect_constant's property, with the source coarser than the target).
TEST(WaveletLight, LatLongOfAnyAspectIsAccepted) {
  const float rgb[3] = {1.5f, 0.25f, 8.0f};
  const uint32_t width = 24, height = 8;
  std::vector<float> map(size_t(width) * height * 3);
  for (size_t i = 0; i < map.size(); ++i) map[i] = rgb[i % 3];
  for (prt_wavelet_param param : {kCube, kParaboloid}) {
    std::vector<float> light(4 * size_t(texel_count(param, 16)), -1.0f);
    const prt_env_image env = prt::latlong_env(width, height, map.data());
    ASSERT_EQ(prt_wavelet_resample(param, 16, &env, light.data()), PRT_OK);
    expect_constant(param, 16, light, rgb, "3:1 lat-long");
  }
}

}  // namespace
