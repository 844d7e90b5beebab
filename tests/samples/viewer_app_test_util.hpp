// SPDX-License-Identifier: MIT
// Helpers for the prt-viewer tests: running it headless or in a real window (under xvfb-run
// when there is no display), reading its screenshots with stb (not the viewer's code), the
// scenes the tests build (a sphere with an unshadowed `sh` transfer, a map with a sun on one
// side) and measures of a picture (what covers the frame, where the light is).
#pragma once

#include <gtest/gtest.h>
#include <prt/prt.hpp>

#include <unistd.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "sh/sh_blob_test_util.hpp"
#include "support/command.hpp"
#include "support/mesh_blob.hpp"
#include "support/picture.hpp"
#include "viewer/viewer_test_util.hpp"

namespace prt_viewer_app_test {

using prt_view_test::kPi;
using prt_view_test::quote;
using prt_view_test::scratch;

// How a windowed run is started: directly with a display, under xvfb-run without one, "none"
// when neither works (the test then skips). xvfb-run -a looks for a free display from -n on;
// starting the search at a number of this process's own keeps parallel tests from racing for
// the same one.
inline std::string window_launcher() {
  const char* display = std::getenv("DISPLAY");
  if (display && *display) return "";
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) return "none";
  static int runs = 0;
  const int first = 100 + int((getpid() * 16 + runs++) % 20000);
  return "xvfb-run -a -n " + std::to_string(first) + " -s '-screen 0 1280x720x24' ";
}

#define PRT_SKIP_WITHOUT_WINDOWS()                                                           \
  if (prt_viewer_app_test::window_launcher() == "none")                                      \
  GTEST_SKIP() << "no X display and no xvfb-run: windowed prt-viewer runs cannot be tested " \
                  "(CI has xvfb)"

// LeakSanitizer's exit scan of a windowed run can crash in its own tracer ("Tracer caught
// signal 11"): it walks the dynamic TLS table, and a window's GL driver leaves a stale entry
// there, seen under load. use_tls=0 skips that walk, which only removes roots; what it then
// reports of the loader's own records is suppressed (window.lsan.supp), which also hides any leak
// whose stack passes through ld.so. The headless runs of the same drawing code keep the full scan.
inline std::string window_sanitizer_options() {
  const char* lsan = std::getenv("LSAN_OPTIONS");
  const std::string inherited = lsan && *lsan ? std::string(lsan) + ":" : "";
  return "LSAN_OPTIONS=" +
         quote(inherited + "use_tls=0:suppressions=" PRT_WINDOW_LSAN_SUPPRESSIONS) + " ";
}

// Runs prt-viewer with `arguments`; `windowed` opens a real window (GLX unless the arguments
// say --window-api egl), otherwise --headless is added.
inline prt_test::CommandResult run_viewer(const std::string& arguments, const std::string& name,
                                          bool windowed = false) {
  const std::string launcher = windowed ? window_sanitizer_options() + window_launcher() : "";
  const std::string command = launcher + quote(PRT_VIEWER_EXE);
  return prt_test::run_command(
      "/bin/sh", "-c " + quote(command + (windowed ? " " : " --headless ") + arguments),
      scratch().file(name + ".log"));
}

using prt_test::Picture;
using prt_test::read_picture;

// Renders `blob` under `map` headless (or windowed) with `extra` options at `size` and returns
// the screenshot; a failed run fails the test and gives an empty picture.
inline Picture screenshot(const std::string& blob, const std::string& map, const std::string& name,
                          const std::string& extra = "", bool windowed = false,
                          const std::string& size = "320x240") {
  const std::string png = scratch().file(name + ".png");
  const prt_test::CommandResult run =
      run_viewer(quote(blob) + " --env " + quote(map) + " --size " + size +
                     " --frames 2 --screenshot " + quote(png) + " " + extra,
                 name, windowed);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  if (run.exit_code != 0) return {};
  return read_picture(png);
}

// The largest difference of one channel between two pictures of one size (256 if they differ
// in size), and how many pixels differ at all.
struct Difference {
  int largest = 0;
  std::size_t pixels = 0;
};
inline Difference difference(const Picture& a, const Picture& b, int x0 = 0, int x1 = -1) {
  Difference d;
  if (a.width != b.width || a.height != b.height || a.rgb.empty()) return {256, 0};
  if (x1 < 0) x1 = a.width;
  for (int y = 0; y < a.height; ++y)
    for (int x = x0; x < x1; ++x) {
      int worst = 0;
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a.at(x, y)[c] - b.at(x, y)[c]));
      d.largest = std::max(d.largest, worst);
      d.pixels += worst > 0;
    }
  return d;
}

// Pixels that differ from `background` (the picture's top-left pixel: the map there) by more
// than two steps in a channel.
inline std::vector<bool> covered(const Picture& p) {
  std::vector<bool> mask(std::size_t(p.width) * p.height, false);
  if (p.rgb.empty()) return mask;
  const std::array<int, 3> background = p.at(0, 0);
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      int worst = 0;
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(p.at(x, y)[c] - background[c]));
      mask[std::size_t(y) * p.width + x] = worst > 2;
    }
  return mask;
}

// The fraction of the central quarter of the frame (the middle half of each axis) covered.
inline double centre_coverage(const Picture& p) {
  const std::vector<bool> mask = covered(p);
  std::size_t hit = 0, all = 0;
  for (int y = p.height / 4; y < 3 * p.height / 4; ++y)
    for (int x = p.width / 4; x < 3 * p.width / 4; ++x, ++all)
      hit += mask[std::size_t(y) * p.width + x];
  return all ? double(hit) / all : 0.0;
}

// Mean luminance of the covered pixels left and right of the covered area's middle column.
inline std::array<double, 2> left_right_luminance(const Picture& p) {
  const std::vector<bool> mask = covered(p);
  int lo = p.width, hi = -1;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      if (mask[std::size_t(y) * p.width + x]) lo = std::min(lo, x), hi = std::max(hi, x);
  const double middle = 0.5 * (lo + hi);
  double sum[2] = {0, 0}, count[2] = {0, 0};
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      if (!mask[std::size_t(y) * p.width + x]) continue;
      const int side = x < middle ? 0 : 1;
      sum[side] += p.luminance(x, y);
      count[side] += 1;
    }
  return {count[0] ? sum[0] / count[0] : 0.0, count[1] ? sum[1] / count[1] : 0.0};
}

// A lat-long map (64 x 32): a uniform grey sky of 0.2 and a sun (radiance 400, 10 degrees
// across) on the horizon at +X. From prt-viewer's first camera (from +Z) +X is to the right, and
// the sun is out of the picture.
inline std::string sun_at_plus_x_map() {
  return prt_view_test::write_hdr("sun_plus_x.hdr", 64, 32,
                                  prt_view_test::latlong_map(
                                      [](const double d[3], float rgb[3]) {
                                        const bool sun = d[0] > std::cos(10.0 * kPi / 180.0);
                                        for (int c = 0; c < 3; ++c) rgb[c] = sun ? 400.0f : 0.2f;
                                      },
                                      64, 32));
}

// A unit sphere (`rings` x `segments` vertices) whose every vertex has the unshadowed diffuse
// transfer of albedo (0.8, 0.8, 0.3) for its normal, order 3: the SH projection (by the runtime,
// prt_sh_project, of a lat-long image of the lobe) of rho max(0, n . w) / pi. The albedo gives
// the sphere a hue the grey sky does not have, so its pixels stand out.
inline std::string sphere_sh_blob(const std::string& name, int rings = 16, int segments = 32) {
  std::vector<float> positions;
  std::vector<std::uint32_t> triangles;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const double theta = kPi * r / rings, phi = 2.0 * kPi * s / segments;
      positions.insert(positions.end(),
                       {float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                        float(std::sin(theta) * std::sin(phi))});
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = r * (segments + 1) + s, b = a + segments + 1;
      triangles.insert(triangles.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  const std::uint32_t vertices = std::uint32_t(positions.size() / 3), order = 3;
  const float albedo[3] = {0.8f, 0.8f, 0.3f};
  const int w = 64, h = 32;
  std::vector<std::vector<float>> transfer(vertices);
  for (std::uint32_t v = 0; v < vertices; ++v) {
    const float* n = &positions[3 * v];
    std::vector<float> lobe(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double d[3];
        prt_view_test::latlong_direction(x, y, w, h, d);
        const double cosine = std::max(0.0, n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / kPi;
        for (int c = 0; c < 3; ++c)
          lobe[(std::size_t(y) * w + x) * 3 + c] = float(albedo[c] * cosine);
      }
    // prt_sh_project writes coefficient-major RGB; SHTR entries are c n^2 + k (formats/SPEC.md
    // §7.1).
    std::vector<float> projected(3 * order * order);
    const prt_env_image env = prt::latlong_env(w, h, lobe.data());
    EXPECT_EQ(prt_sh_project(order, &env, projected.data()), PRT_OK);
    transfer[v].resize(projected.size());
    for (std::uint32_t k = 0; k < order * order; ++k)
      for (int c = 0; c < 3; ++c) transfer[v][c * order * order + k] = projected[3 * k + c];
  }
  // 16-bit quantisation per coefficient between its smallest and largest value.
  prt_test::Transfer t;
  t.order = order, t.vertices = vertices, t.channels = 3, t.bits = 16, t.kind = 0;
  const std::uint32_t coefficients = t.coefficients();
  t.offset.assign(coefficients, 0.0f);
  t.scale.assign(coefficients, 0.0f);
  for (std::uint32_t j = 0; j < coefficients; ++j) {
    float lo = transfer[0][j], hi = transfer[0][j];
    for (const auto& row : transfer) lo = std::min(lo, row[j]), hi = std::max(hi, row[j]);
    t.offset[j] = lo;
    t.scale[j] = (hi - lo) / 65535.0f;
  }
  for (const auto& row : transfer)
    for (std::uint32_t j = 0; j < coefficients; ++j)
      t.q.push_back(
          t.scale[j] > 0.0f ? std::uint32_t(std::lround((row[j] - t.offset[j]) / t.scale[j])) : 0u);
  return prt_view_test::write_blob(
      name, prt_test::mesh_blob(positions, triangles, PRT_BLOB_TAG_SHTR, prt_test::encode(t)));
}

}  // namespace prt_viewer_app_test
