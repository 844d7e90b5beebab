// SPDX-License-Identifier: MIT
// prt-viewer as a person uses it: a real window (under Xvfb on CI) or headless, a screenshot
// after N frames, and checks of what the picture shows: the object fills the middle of the
// frame, its lit side faces the sun and follows it when the light turns; the three backends,
// and the window and headless paths, give the same picture.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "samples/viewer_app_test_util.hpp"

namespace {

using namespace prt_viewer_app_test;

const std::string& sphere() {
  static const std::string path = sphere_sh_blob("sphere_sh.prtk");
  return path;
}
const std::string& sun_map() {
  static const std::string path = sun_at_plus_x_map();
  return path;
}

void expect_sphere_in_frame(const Picture& p, const std::string& what) {
  ASSERT_EQ(p.width, 320) << what;
  ASSERT_EQ(p.height, 240) << what;
  // The unit sphere framed from +Z fills the middle of the frame: a disc two thirds of the
  // height across covers 0.89 of the central quarter (the quarter's corners stick out).
  EXPECT_GT(centre_coverage(p), 0.8) << what;
}

TEST(PrtViewerWindow, OpensRendersAndItsScreenshotShowsTheLitSideTowardsTheSun) {
  PRT_SKIP_WITHOUT_WINDOWS();
  const Picture lit = screenshot(sphere(), sun_map(), "window_sun", "--backend cpu", true);
  expect_sphere_in_frame(lit, "sun at +X");
  const std::array<double, 2> sides = left_right_luminance(lit);
  std::printf("sun at +X: left %.1f, right %.1f\n", sides[0], sides[1]);
  EXPECT_GT(sides[1], 2.0 * sides[0]) << "the sun at +X lights the right of the sphere";

  // Turned half way round, the sun is at -X: the left side is lit.
  const Picture turned =
      screenshot(sphere(), sun_map(), "window_sun_turned", "--backend cpu --rotate 180", true);
  expect_sphere_in_frame(turned, "sun at -X");
  const std::array<double, 2> turned_sides = left_right_luminance(turned);
  std::printf("sun at -X: left %.1f, right %.1f\n", turned_sides[0], turned_sides[1]);
  EXPECT_GT(turned_sides[0], 2.0 * turned_sides[1]) << "the turned sun lights the left";
}

TEST(PrtViewerHeadless, ScreenshotShowsTheLitSideTowardsTheSun) {
  const Picture lit = screenshot(sphere(), sun_map(), "headless_sun", "--backend cpu");
  expect_sphere_in_frame(lit, "headless");
  const std::array<double, 2> sides = left_right_luminance(lit);
  EXPECT_GT(sides[1], 2.0 * sides[0]);
}

// The window (GLX, and EGL through GLFW) draws what the headless EGL context draws: the same
// code into the same kind of target on the same driver. Measured: identical bytes; allowed: one
// step in a channel.
TEST(PrtViewerWindow, WindowAndHeadlessGiveTheSamePicture) {
  PRT_SKIP_WITHOUT_WINDOWS();
  const Picture headless = screenshot(sphere(), sun_map(), "same_headless", "--backend cpu");
  for (const char* api : {"glx", "egl"}) {
    const Picture window = screenshot(sphere(), sun_map(), std::string("same_") + api,
                                      std::string("--backend cpu --window-api ") + api, true);
    const Difference d = difference(headless, window);
    std::printf("%s window vs headless: largest difference %d, %zu pixels differ\n", api, d.largest,
                d.pixels);
    EXPECT_LE(d.largest, 1) << api;
  }
}

// cpu, simd and gl shade the same radiance within float rounding (tests/gl states the
// backends' tolerance); on 8-bit pixels that is at most a step, at a few pixels.
void expect_backends_agree(const std::string& blob, const std::string& map,
                           const std::string& name) {
  const Picture cpu = screenshot(blob, map, name + "_cpu", "--backend cpu");
  ASSERT_FALSE(cpu.rgb.empty());
  std::vector<std::string> others;
  if (PRT_TEST_SIMD_COMPILED) others.push_back("simd");
  if (PRT_TEST_GL_COMPILED) others.push_back("gl");
  for (const std::string& backend : others) {
    const Picture other = screenshot(blob, map, name + "_" + backend, "--backend " + backend);
    const Difference d = difference(cpu, other);
    std::printf("%s: %s vs cpu: largest difference %d, %zu pixels differ\n", name.c_str(),
                backend.c_str(), d.largest, d.pixels);
    EXPECT_LE(d.largest, 1) << name << " " << backend;
  }
}

TEST(PrtViewerBackends, ShSphereLooksTheSameOnEveryBackend) {
  expect_backends_agree(sphere(), sun_map(), "sphere");
}

TEST(PrtViewerBackends, GoldenShAndWaveletBlobsLookTheSameOnEveryBackend) {
  const std::string sky = prt_view_test::write_test_sky();
  expect_backends_agree(prt_view_test::golden("sh_quad.prtk"), sky, "golden_sh");
  expect_backends_agree(prt_view_test::golden("wavelet_quad.prtk"), sky, "golden_wavelet");
}

// A glossy shadowfield object's radiance depends on the eye, which its GL shader reads as well:
// the golden quad, seen from the camera, agrees on every backend.
TEST(PrtViewerBackends, GoldenShadowfieldBlobLooksTheSameOnEveryBackend) {
  const std::string sky = prt_view_test::write_test_sky();
  expect_backends_agree(prt_view_test::golden("shadowfield_quad.prtk"), sky, "golden_shadowfield");
}

}  // namespace
