// SPDX-License-Identifier: MIT
// Helpers for the prt-view tests, which need no baker: running prt-view (support/command.hpp),
// the environment maps the tests write (Radiance .hdr from the tests' own RGBE encoder, read back
// with stb, in the three mappings of formats/SPEC.md §Environment maps, texel directions from the
// SPEC's formulas), blobs the tests build (support/blob_test_util.hpp and the technique builders)
// and comparing per-vertex radiance.
#pragma once

#include <gtest/gtest.h>
#include <stb_image.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "support/command.hpp"
#include "support/test_files.hpp"

namespace prt_view_test {

constexpr double kPi = 3.14159265358979323846;

// The scratch folder of this test process (removed at exit).
inline const prt_test::TempDir& scratch() {
  static const prt_test::TempDir dir("viewer");
  return dir;
}

inline std::string golden(const std::string& name) {
  return std::string(PRT_GOLDEN_DIR) + "/1.0/" + name;
}

inline std::string quote(const std::string& text) {
  return prt_test::shell_quote(text);
}

// Runs prt-view with `arguments` (shell words), its output logged in the scratch folder as
// <name>.log, after `environment` (e.g. "PRT_BACKEND=cpu").
inline prt_test::CommandResult run_view(const std::string& arguments, const std::string& name,
                                        const std::string& environment = "") {
  return prt_test::run_command(PRT_VIEW_EXE, arguments, scratch().file(name + ".log"), environment);
}

// One texel in Radiance's RGBE: a shared exponent e and mantissas m = round(v 2^(136 - e)), the
// largest in [128, 256), so that m 2^(e - 136) (what readers decode) is the nearest value RGBE
// holds: unbiased, where truncating writers make every texel darker by half a step on average.
inline void rgbe_encode(const float rgb[3], unsigned char out[4]) {
  const float largest = std::max({rgb[0], rgb[1], rgb[2]});
  out[0] = out[1] = out[2] = out[3] = 0;
  if (!(largest > 1e-32f)) return;
  int exponent = 0;
  std::frexp(largest, &exponent);  // largest = f 2^exponent, f in [0.5, 1)
  if (std::lround(std::ldexp(double(largest), 8 - exponent)) >= 256) ++exponent;
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<unsigned char>(
        std::lround(std::ldexp(double(std::max(rgb[c], 0.0f)), 8 - exponent)));
  out[3] = static_cast<unsigned char>(exponent + 128);
}

// Writes RGB float rows (from the top) as a Radiance .hdr in the scratch folder (flat scanlines,
// RGBE rounded to nearest); returns the path.
inline std::string write_hdr(const std::string& name, int width, int height,
                             const std::vector<float>& rgb) {
  std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) +
                      " +X " + std::to_string(width) + "\n";
  for (std::size_t i = 0; i < std::size_t(width) * height; ++i) {
    unsigned char texel[4];
    rgbe_encode(&rgb[3 * i], texel);
    bytes.append(reinterpret_cast<const char*>(texel), 4);
  }
  return scratch().write(name, bytes);
}

// The texels of a .hdr file as stored (RGBE-rounded), read with stb.
inline std::vector<float> read_hdr(const std::string& path, int* width, int* height) {
  int channels = 0;
  float* data = stbi_loadf(path.c_str(), width, height, &channels, 3);
  EXPECT_NE(data, nullptr) << path;
  if (!data) return {};
  std::vector<float> rgb(data, data + std::size_t(*width) * *height * 3);
  stbi_image_free(data);
  return rgb;
}

// formats/SPEC.md: lat-long texel (x, y) of W x H looks along
// d = (sin t sin p, cos t, -sin t cos p), p = 2 pi ((x + 0.5)/W - 0.5), t = pi (y + 0.5)/H.
inline void latlong_direction(int x, int y, int width, int height, double d[3]) {
  const double phi = 2.0 * kPi * ((x + 0.5) / width - 0.5), theta = kPi * (y + 0.5) / height;
  d[0] = std::sin(theta) * std::sin(phi);
  d[1] = std::cos(theta);
  d[2] = -std::sin(theta) * std::cos(phi);
}

// A radiance function of direction, RGB.
using Sky = std::function<void(const double d[3], float rgb[3])>;

// `sky` at the texel centres of a W x H lat-long map (W = 2H).
inline std::vector<float> latlong_map(const Sky& sky, int width, int height) {
  std::vector<float> rgb(std::size_t(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double d[3];
      latlong_direction(x, y, width, height, d);
      sky(d, &rgb[(std::size_t(y) * width + x) * 3]);
    }
  return rgb;
}

// `sky` at the texel centres of a vertical cross of faces F x F (3F x 4F, padding black), per the
// SPEC's face table: cell [col, row] and the direction for face coordinates (s, t).
inline std::vector<float> cross_map(const Sky& sky, int face) {
  const int width = 3 * face, height = 4 * face;
  std::vector<float> rgb(std::size_t(width) * height * 3, 0.0f);
  struct Cell {
    int col, row;
    int axis[3];     // which of (s, t, 1) each direction component takes
    double sign[3];  // and its sign
  };
  // +Y (s,1,t); -X (-1,t,-s); -Z (s,t,-1); +X (1,t,s); -Y (s,-1,-t); +Z (s,-t,1).
  const Cell cells[6] = {{1, 0, {0, 2, 1}, {1, 1, 1}},   {0, 1, {2, 1, 0}, {-1, 1, -1}},
                         {1, 1, {0, 1, 2}, {1, 1, -1}},  {2, 1, {2, 1, 0}, {1, 1, 1}},
                         {1, 2, {0, 2, 1}, {1, -1, -1}}, {1, 3, {0, 1, 2}, {1, -1, 1}}};
  for (const Cell& cell : cells)
    for (int j = 0; j < face; ++j)
      for (int i = 0; i < face; ++i) {
        const double st1[3] = {2.0 * (i + 0.5) / face - 1.0, 1.0 - 2.0 * (j + 0.5) / face, 1.0};
        double d[3], norm = 0.0;
        for (int k = 0; k < 3; ++k) {
          d[k] = cell.sign[k] * st1[cell.axis[k]];
          norm += d[k] * d[k];
        }
        for (double& v : d) v /= std::sqrt(norm);
        const int x = cell.col * face + i, y = cell.row * face + j;
        sky(d, &rgb[(std::size_t(y) * width + x) * 3]);
      }
  return rgb;
}

// `sky` at the texel centres of a W x W angular light probe (texels outside the disc black):
// u, v in the unit disc, theta = pi r, phi = atan2(v, u), d = (sin t cos p, sin t sin p, -cos t).
inline std::vector<float> probe_map(const Sky& sky, int width) {
  std::vector<float> rgb(std::size_t(width) * width * 3, 0.0f);
  for (int i = 0; i < width; ++i)
    for (int j = 0; j < width; ++j) {
      const double u = (j + 0.5 - width / 2.0) / (width / 2.0);
      const double v = (width / 2.0 - i - 0.5) / (width / 2.0);
      const double r = std::sqrt(u * u + v * v);
      if (r > 1.0) continue;
      const double theta = kPi * r, phi = std::atan2(v, u);
      const double d[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                           -std::cos(theta)};
      sky(d, &rgb[(std::size_t(i) * width + j) * 3]);
    }
  return rgb;
}

// The tests' sky: a gradient from a pale horizon (tinted with the azimuth, so a turn about +Y
// changes the light) to a blue zenith, a dark ground, and a small bright sun 40 degrees up,
// 30 degrees from -Z towards +X.
inline void test_sky(const double d[3], float rgb[3]) {
  const double elevation = 40.0 * kPi / 180.0, azimuth = 30.0 * kPi / 180.0;
  const double sun[3] = {std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                         -std::cos(elevation) * std::cos(azimuth)};
  const double tint = 1.0 + 0.4 * d[0] - 0.2 * d[2];
  if (d[1] >= 0.0) {
    rgb[0] = float((0.9 - 0.7 * d[1]) * tint);
    rgb[1] = float(0.95 - 0.55 * d[1]);
    rgb[2] = float((1.0 - 0.2 * d[1]) / tint);
  } else {
    rgb[0] = 0.15f, rgb[1] = 0.12f, rgb[2] = 0.1f;
  }
  if (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] > std::cos(8.0 * kPi / 180.0)) {
    rgb[0] += 40.0f, rgb[1] += 36.0f, rgb[2] += 30.0f;
  }
}

constexpr int kSkyWidth = 64, kSkyHeight = 32;

// The test sky as a 64 x 32 lat-long .hdr in the scratch folder.
inline std::string write_test_sky(const std::string& name = "sky.hdr") {
  return write_hdr(name, kSkyWidth, kSkyHeight, latlong_map(test_sky, kSkyWidth, kSkyHeight));
}

// A lat-long map turned 90 degrees about +Y: turned(x, y) = original((x + W/4) mod W, y)
// (formats/SPEC.md, Turning the environment).
inline std::vector<float> quarter_turned(const std::vector<float>& rgb, int width, int height) {
  std::vector<float> turned(rgb.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        turned[(std::size_t(y) * width + x) * 3 + c] =
            rgb[(std::size_t(y) * width + (x + width / 4) % width) * 3 + c];
  return turned;
}

// prt-view's --vertex-out for `blob` under `map` with `extra` options: [V * 3] floats, empty
// (and a test failure) when prt-view fails or writes something else than a [V, 3] array.
inline std::vector<float> view_vertices(const std::string& blob, const std::string& map,
                                        const std::string& name, const std::string& extra = "") {
  const std::string out = scratch().file(name + ".npy");
  const prt_test::CommandResult run = run_view(
      quote(blob) + " --env " + quote(map) + " --headless --vertex-out " + quote(out) + " " + extra,
      name);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  const prt_test::NpyArray array = prt_test::read_npy_f32(out);
  EXPECT_EQ(array.columns, 3u) << out;
  return array.values;
}

// sqrt(sum (a - b)^2 / sum b^2).
inline double relative_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double diff = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < b.size() && i < a.size(); ++i) {
    diff += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    norm += double(b[i]) * b[i];
  }
  return std::sqrt(diff / norm);
}

// Writes `bytes` (a blob) to the scratch folder; returns the path.
inline std::string write_blob(const std::string& name, const std::vector<std::uint8_t>& bytes) {
  return scratch().write(name, std::string(bytes.begin(), bytes.end()));
}

}  // namespace prt_view_test
