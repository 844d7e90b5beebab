// prt_sh_project on lat-long and cube images against analytic projections: a constant map, and a
// map that is itself a known combination of low-order SH written from the textbook closed forms
// (so its projection is those weights, by orthonormality); strides, RGBA and the rotation
// argument against the plain image. (prt_env_image's rejections: tests/runtime/env_test.cpp.)
#include <gtest/gtest.h>
#include <prt/prt.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "sh/sh_test_util.hpp"

namespace {

using prt_sh_test::kPi;
using prt_sh_test::ProjectLatLong;
using Radiance = std::function<std::array<double, 3>(const std::array<double, 3>&)>;

// Lat-long texel centre direction, from formats/SPEC.md §12.
std::array<double, 3> LatLongDirection(uint32_t x, uint32_t y, uint32_t w, uint32_t h) {
  const double phi = 2.0 * kPi * ((x + 0.5) / w - 0.5);
  const double theta = kPi * (y + 0.5) / h;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

std::vector<float> SampleLatLong(uint32_t w, uint32_t h, const Radiance& f) {
  std::vector<float> image(size_t(w) * h * 3);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const auto l = f(LatLongDirection(x, y, w, h));
      for (int c = 0; c < 3; ++c) image[(size_t(y) * w + x) * 3 + c] = float(l[c]);
    }
  return image;
}

// GL cube-map convention (OpenGL 4.6 spec, table 8.19): major axis and (sc, tc) per face.
std::array<double, 3> CubeDirection(int face, double s, double t) {
  const double sc = 2.0 * s - 1.0, tc = 2.0 * t - 1.0;
  switch (face) {
    case 0:
      return {1, -tc, -sc};
    case 1:
      return {-1, -tc, sc};
    case 2:
      return {sc, 1, tc};
    case 3:
      return {sc, -1, -tc};
    case 4:
      return {sc, -tc, 1};
    default:
      return {-sc, -tc, -1};
  }
}

std::array<std::vector<float>, 6> SampleCube(uint32_t size, const Radiance& f) {
  std::array<std::vector<float>, 6> faces;
  for (int face = 0; face < 6; ++face) {
    faces[face].resize(size_t(size) * size * 3);
    for (uint32_t j = 0; j < size; ++j)
      for (uint32_t i = 0; i < size; ++i) {
        auto d = CubeDirection(face, (i + 0.5) / size, (j + 0.5) / size);
        const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (auto& v : d) v /= len;
        const auto l = f(d);
        for (int c = 0; c < 3; ++c) faces[face][(size_t(j) * size + i) * 3 + c] = float(l[c]);
      }
  }
  return faces;
}

// The six faces back to back, as a cube prt_env_image takes them.
std::vector<float> Packed(const std::array<std::vector<float>, 6>& faces) {
  std::vector<float> packed;
  for (const auto& face : faces) packed.insert(packed.end(), face.begin(), face.end());
  return packed;
}

std::vector<float> ProjectCube(uint32_t order, uint32_t size,
                               const std::array<std::vector<float>, 6>& faces,
                               const float* rotation = nullptr) {
  const std::vector<float> packed = Packed(faces);
  const prt_env_image env = prt::cube_env(size, packed.data(), 3, rotation);
  std::vector<float> out(order * order * 3);
  EXPECT_EQ(prt_sh_project(order, &env, out.data()), PRT_OK);
  return out;
}

const std::array<double, 3> kConstant = {0.5, 1.25, 2.0};

// The l > 0 terms of a constant are quadrature residue: O(texel size^2) relative to the DC term.
void ExpectOnlyDc(const std::vector<float>& coeffs, double relative_tolerance) {
  for (int c = 0; c < 3; ++c) {
    const double dc = std::sqrt(4.0 * kPi) * kConstant[c];
    EXPECT_NEAR(coeffs[c], dc, 1e-6 * dc);
    for (size_t i = 1; i < coeffs.size() / 3; ++i)
      EXPECT_NEAR(coeffs[i * 3 + c], 0.0, relative_tolerance * dc) << "coefficient " << i;
  }
}

TEST(ShProject, ConstantLatLongGivesOnlyDc) {
  const auto image = SampleLatLong(512, 256, [](const auto&) { return kConstant; });
  std::vector<float> out(64 * 3);
  ASSERT_EQ(ProjectLatLong(8, 512, 256, image.data(), 512 * 3, out.data()), PRT_OK);
  ExpectOnlyDc(out, 5e-5);
}

TEST(ShProject, ConstantCubeGivesOnlyDc) {
  const auto faces = SampleCube(128, [](const auto&) { return kConstant; });
  ExpectOnlyDc(ProjectCube(8, 128, faces), 5e-5);
}

// A positive map made of the band <= 3 closed forms with known weights.
std::array<double, 16> KnownWeights() {
  std::array<double, 16> w{};
  w[0] = 2.0;
  for (int i = 1; i < 16; ++i) w[i] = 0.08 * std::sin(1.7 * i + 0.3);
  return w;
}

double KnownMap(const std::array<double, 3>& world) {
  // SH frame of prt_sh.h: x = X, y = -Z, z = Y; closed forms as in sh_eval_test.cpp.
  const double x = world[0], y = -world[2], z = world[1], pi = kPi;
  const double b[16] = {0.5 * std::sqrt(1.0 / pi),
                        std::sqrt(3.0 / (4.0 * pi)) * y,
                        std::sqrt(3.0 / (4.0 * pi)) * z,
                        std::sqrt(3.0 / (4.0 * pi)) * x,
                        0.5 * std::sqrt(15.0 / pi) * x * y,
                        0.5 * std::sqrt(15.0 / pi) * y * z,
                        0.25 * std::sqrt(5.0 / pi) * (3.0 * z * z - 1.0),
                        0.5 * std::sqrt(15.0 / pi) * x * z,
                        0.25 * std::sqrt(15.0 / pi) * (x * x - y * y),
                        0.25 * std::sqrt(35.0 / (2.0 * pi)) * y * (3.0 * x * x - y * y),
                        0.5 * std::sqrt(105.0 / pi) * x * y * z,
                        0.25 * std::sqrt(21.0 / (2.0 * pi)) * y * (5.0 * z * z - 1.0),
                        0.25 * std::sqrt(7.0 / pi) * z * (5.0 * z * z - 3.0),
                        0.25 * std::sqrt(21.0 / (2.0 * pi)) * x * (5.0 * z * z - 1.0),
                        0.25 * std::sqrt(105.0 / pi) * z * (x * x - y * y),
                        0.25 * std::sqrt(35.0 / (2.0 * pi)) * x * (x * x - 3.0 * y * y)};
  const auto w = KnownWeights();
  double sum = 0.0;
  for (int i = 0; i < 16; ++i) sum += w[i] * b[i];
  return sum;
}

std::array<double, 3> KnownMapRgb(const std::array<double, 3>& d) {
  const double v = KnownMap(d);
  return {v, 0.5 * v, 2.0 * v};
}

void ExpectKnownWeights(const std::vector<float>& out, uint32_t order, double tolerance) {
  const auto w = KnownWeights();
  const double scale[3] = {1.0, 0.5, 2.0};
  for (uint32_t i = 0; i < order * order; ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(out[i * 3 + c], (i < 16 ? w[i] : 0.0) * scale[c], tolerance * scale[c])
          << "coefficient " << i << " channel " << c;
}

TEST(ShProject, LatLongOfKnownShCombinationRecoversWeights) {
  const uint32_t w = 256, h = 128;
  const auto image = SampleLatLong(w, h, KnownMapRgb);
  std::vector<float> out(36 * 3);
  ASSERT_EQ(ProjectLatLong(6, w, h, image.data(), w * 3, out.data()), PRT_OK);
  ExpectKnownWeights(out, 6, 2e-3);
}

TEST(ShProject, LatLongHonoursRowStride) {
  const uint32_t w = 64, h = 32, stride = w * 3 + 5;
  const auto tight = SampleLatLong(w, h, KnownMapRgb);
  std::vector<float> padded(size_t(stride) * h, -1.0f);
  for (uint32_t y = 0; y < h; ++y)
    std::copy(tight.begin() + y * w * 3, tight.begin() + (y + 1) * w * 3,
              padded.begin() + y * stride);
  std::vector<float> a(16 * 3), b(16 * 3);
  ASSERT_EQ(ProjectLatLong(4, w, h, tight.data(), w * 3, a.data()), PRT_OK);
  ASSERT_EQ(ProjectLatLong(4, w, h, padded.data(), stride, b.data()), PRT_OK);
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
}

TEST(ShProject, CubeOfKnownShCombinationRecoversWeights) {
  const uint32_t size = 64;
  ExpectKnownWeights(ProjectCube(6, size, SampleCube(size, KnownMapRgb)), 6, 2e-3);
}

// Two independent quadratures of the same smooth map (two coloured Gaussian lobes) agree at
// order 8: checks every cube face's orientation beyond band 3.
TEST(ShProject, CubeAndLatLongAgreeOnSmoothMapOrder8) {
  const auto lobes = [](const std::array<double, 3>& d) {
    const double a = std::exp(5.0 * (0.6 * d[0] + 0.48 * d[1] - 0.64 * d[2] - 1.0));
    const double b = std::exp(7.0 * (-0.8 * d[1] + 0.6 * d[2] - 1.0));
    return std::array<double, 3>{0.1 + 3.0 * a + b, 0.1 + a, 0.1 + 2.0 * b};
  };
  const uint32_t w = 512, h = 256, size = 96, order = 8;
  const auto image = SampleLatLong(w, h, lobes);
  std::vector<float> latlong(order * order * 3);
  ASSERT_EQ(ProjectLatLong(order, w, h, image.data(), w * 3, latlong.data()), PRT_OK);
  const auto cube = ProjectCube(order, size, SampleCube(size, lobes));
  double scale = 0.0;
  for (float v : latlong) scale = std::max(scale, double(std::abs(v)));
  for (size_t i = 0; i < cube.size(); ++i)
    EXPECT_NEAR(cube[i], latlong[i], 2e-3 * scale) << "value " << i;
}

TEST(ShProject, NonFiniteAndNegativeTexelsCountAsZero) {
  const uint32_t w = 32, h = 16;
  auto image = SampleLatLong(w, h, [](const auto&) { return kConstant; });
  auto clean = image;
  // Row 3, column 5: NaN / -Inf / negative; the clean copy has zeros there.
  const size_t at = (3 * w + 5) * 3;
  image[at] = NAN;
  image[at + 1] = -INFINITY;
  image[at + 2] = -4.0f;
  clean[at] = clean[at + 1] = clean[at + 2] = 0.0f;
  image[at + 3] = INFINITY;
  clean[at + 3] = 0.0f;
  std::vector<float> a(9 * 3), b(9 * 3);
  ASSERT_EQ(ProjectLatLong(3, w, h, image.data(), w * 3, a.data()), PRT_OK);
  ASSERT_EQ(ProjectLatLong(3, w, h, clean.data(), w * 3, b.data()), PRT_OK);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(std::isfinite(a[i]));
    EXPECT_FLOAT_EQ(a[i], b[i]);
  }
}

TEST(ShProject, AllBlackMapsGiveZero) {
  const auto black = [](const auto&) { return std::array<double, 3>{0, 0, 0}; };
  const auto image = SampleLatLong(64, 32, black);
  std::vector<float> out(64 * 3, 1.0f);
  ASSERT_EQ(ProjectLatLong(8, 64, 32, image.data(), 64 * 3, out.data()), PRT_OK);
  for (float v : out) EXPECT_EQ(v, 0.0f);
  for (float v : ProjectCube(8, 16, SampleCube(16, black))) EXPECT_EQ(v, 0.0f);
}

// A 10^5 : 1 sun in one texel over a unit sky: finite, and the DC term is the exact radiant
// sum (4 pi sky + 10^5 sun solid angle) / sqrt(4 pi), with the solid angle from SPEC §12.
TEST(ShProject, BrightSunStaysFiniteAndAddsItsPower) {
  const uint32_t w = 256, h = 128, sun_x = 77, sun_y = 30;
  auto image = SampleLatLong(w, h, [](const auto&) { return std::array<double, 3>{1, 1, 1}; });
  for (int c = 0; c < 3; ++c) image[(size_t(sun_y) * w + sun_x) * 3 + c] = 1e5f;
  std::vector<float> out(PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER * 3);
  ASSERT_EQ(ProjectLatLong(PRT_SH_MAX_ORDER, w, h, image.data(), w * 3, out.data()), PRT_OK);
  for (float v : out) ASSERT_TRUE(std::isfinite(v));
  const double sun_solid_angle =
      2.0 * kPi / w * (std::cos(kPi * sun_y / h) - std::cos(kPi * (sun_y + 1) / h));
  const double power = 4.0 * kPi + (1e5 - 1.0) * sun_solid_angle;
  EXPECT_NEAR(out[0], power / std::sqrt(4.0 * kPi), 1e-5 * power);
}

TEST(ShProject, RejectsInvalidArguments) {
  std::vector<float> image(8 * 4 * 3, 1.0f), out(PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER * 3);
  const prt_env_image latlong = prt::latlong_env(8, 4, image.data());
  const prt_env_image cube = prt::cube_env(2, image.data());
  EXPECT_EQ(prt_sh_project(0, &latlong, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_project(PRT_SH_MAX_ORDER + 1, &latlong, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_project(3, &latlong, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_project(3, nullptr, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_project(3, &latlong, out.data()), PRT_OK);
  EXPECT_EQ(prt_sh_project(0, &cube, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_project(3, &cube, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_sh_project(3, &cube, out.data()), PRT_OK);
}

TEST(ShProject, MaxOrderProjectionIsFinite) {
  const auto image = SampleLatLong(64, 32, KnownMapRgb);
  std::vector<float> out(PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER * 3);
  ASSERT_EQ(ProjectLatLong(PRT_SH_MAX_ORDER, 64, 32, image.data(), 64 * 3, out.data()), PRT_OK);
  for (float v : out) EXPECT_TRUE(std::isfinite(v));
}

// RGBA texels (the 4th float ignored, here a NaN that would poison any sum it reached) and padded
// rows give the bits of the tight RGB image.
TEST(ShProject, RgbaAndPaddedRowsGiveTheTightResult) {
  const uint32_t w = 64, h = 32, stride = w * 4 + 7;
  const auto tight = SampleLatLong(w, h, KnownMapRgb);
  std::vector<float> rgba(size_t(stride) * h, -1.0f);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) rgba[y * stride + 4 * x + c] = tight[(y * w + x) * 3 + c];
      rgba[y * stride + 4 * x + 3] = NAN;
    }
  std::vector<float> a(16 * 3), b(16 * 3);
  ASSERT_EQ(ProjectLatLong(4, w, h, tight.data(), w * 3, a.data()), PRT_OK);
  prt_env_image env = prt::latlong_env(w, h, rgba.data(), 4);
  env.row_stride = stride;
  ASSERT_EQ(prt_sh_project(4, &env, b.data()), PRT_OK);
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << i;
}

// Cube faces with padded rows and gaps between the faces give the bits of the packed faces.
TEST(ShProject, CubeHonoursRowAndFaceStrides) {
  const uint32_t size = 16, row_stride = size * 4 + 3, face_stride = row_stride * size + 11;
  const auto faces = SampleCube(size, KnownMapRgb);
  std::vector<float> spaced(size_t(face_stride) * 6, NAN);
  for (uint32_t f = 0; f < 6; ++f)
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        for (int c = 0; c < 3; ++c)
          spaced[f * face_stride + y * row_stride + 4 * x + c] = faces[f][(y * size + x) * 3 + c];
      }
  prt_env_image env = prt::cube_env(size, spaced.data(), 4);
  env.row_stride = row_stride;
  env.face_stride = face_stride;
  std::vector<float> spaced_out(16 * 3);
  ASSERT_EQ(prt_sh_project(4, &env, spaced_out.data()), PRT_OK);
  const std::vector<float> tight_out = ProjectCube(4, size, faces);
  for (size_t i = 0; i < tight_out.size(); ++i) EXPECT_EQ(spaced_out[i], tight_out[i]) << i;
}

// A turn about +Y by a whole number of lat-long columns is the same quadrature on shifted
// columns, and SH rotation about the pole is exact: the rotation argument must match the
// projection of the column-shifted image to float rounding.
TEST(ShProject, RotationAboutTheVerticalMatchesShiftedColumns) {
  const uint32_t w = 128, h = 64, order = 6, shift = 16;  // 2 pi * 16 / 128 = 45 degrees
  const double angle = 2.0 * kPi * shift / w;
  const auto image = SampleLatLong(w, h, KnownMapRgb);
  // R, the turn about +Y by `angle`, takes -Z (azimuth f = 0, SPEC §12) to (-sin a, 0, -cos a),
  // azimuth -a: light from column x then comes from column x - shift.
  std::vector<float> shifted(image.size());
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        shifted[(y * w + (x + w - shift) % w) * 3 + c] = image[(y * w + x) * 3 + c];
  const float cs = float(std::cos(angle)), sn = float(std::sin(angle));
  const float rotation[9] = {cs, 0, sn, 0, 1, 0, -sn, 0, cs};
  std::vector<float> turned(order * order * 3), expected(order * order * 3);
  const prt_env_image env = prt::latlong_env(w, h, image.data(), 3, rotation);
  ASSERT_EQ(prt_sh_project(order, &env, turned.data()), PRT_OK);
  ASSERT_EQ(ProjectLatLong(order, w, h, shifted.data(), w * 3, expected.data()), PRT_OK);
  double scale = 0.0;
  for (float v : expected) scale = std::max(scale, double(std::abs(v)));
  for (size_t i = 0; i < turned.size(); ++i)
    EXPECT_NEAR(turned[i], expected[i], 1e-5 * scale) << "coefficient " << i / 3;
}

// A turn about another axis: the rotated projection of the band-limited map recovers the weights
// of the map sampled already turned (f(R^T d)), within the quadrature error of the other tests.
TEST(ShProject, RotationAboutATiltedAxisMatchesTheTurnedMap) {
  const uint32_t size = 64, order = 4;
  const double a = 0.7;  // about +X
  const float rotation[9] = {1,
                             0,
                             0,
                             0,
                             float(std::cos(a)),
                             -float(std::sin(a)),
                             0,
                             float(std::sin(a)),
                             float(std::cos(a))};
  const auto turned_map = [&](const std::array<double, 3>& d) {
    // R^T d
    const std::array<double, 3> back = {d[0], std::cos(a) * d[1] + std::sin(a) * d[2],
                                        -std::sin(a) * d[1] + std::cos(a) * d[2]};
    return KnownMapRgb(back);
  };
  const auto rotated = ProjectCube(order, size, SampleCube(size, KnownMapRgb), rotation);
  const auto expected = ProjectCube(order, size, SampleCube(size, turned_map));
  for (size_t i = 0; i < rotated.size(); ++i)
    EXPECT_NEAR(rotated[i], expected[i], 4e-3) << "coefficient " << i / 3;
}

}  // namespace
