// SPDX-License-Identifier: MIT
// Input drives prt-viewer as a person's would: replayed events (--input-script, fed into the
// handlers the GLFW callbacks call) move the camera as the options that say the same thing do,
// `F` frames the scene again, and files dropped on the window are opened. The technique's live
// parameter (wavelet M) changes the picture through the same interface its option uses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "samples/viewer_app_test_util.hpp"

namespace {

using namespace prt_viewer_app_test;

// Two frames (screenshot()'s --frames 2): events of frame 0, then of frame 1, which is drawn and
// written.
const char* const kFixed = "--backend cpu --exposure 0";

std::string script(const std::string& name, const std::string& text) {
  return scratch().write(name, text);
}

Picture run(const std::string& blob, const std::string& map, const std::string& name,
            const std::string& extra, bool windowed = false) {
  return screenshot(blob, map, name, std::string(kFixed) + " " + extra, windowed);
}

// A left-drag of (60, 40) pixels turns the camera by 0.25 degrees a pixel: yaw -15, pitch +10
// (from the first view's atan 0.3 = 16.699 degrees).
void expect_drag_equals_options(bool windowed) {
  const std::string blob = sphere_sh_blob("input_sphere.prtk");
  const std::string map = sun_at_plus_x_map();
  const std::string drag = script("drag.txt",
                                  "0 move 100 100\n"
                                  "0 press left\n"
                                  "1 move 130 120\n"
                                  "1 move 160 140\n"
                                  "1 release left\n");
  const Picture dragged = run(blob, map, "dragged", "--input-script " + quote(drag), windowed);
  const Picture turned = run(blob, map, "turned", "--yaw -15 --pitch 26.699244", windowed);
  const Picture still = run(blob, map, "still", "", windowed);
  const Difference same = difference(dragged, turned), moved = difference(dragged, still);
  std::printf("drag vs --yaw/--pitch: largest %d; drag vs no drag: %zu pixels differ\n",
              same.largest, moved.pixels);
  EXPECT_LE(same.largest, 1);
  EXPECT_GT(moved.pixels, 1000u) << "the drag should have turned the camera";
}

TEST(PrtViewerInput, ReplayedDragTurnsTheCameraAsYawAndPitchDo) {
  expect_drag_equals_options(false);
}

TEST(PrtViewerInput, ReplayedDragInAWindowTurnsTheCameraAsYawAndPitchDo) {
  PRT_SKIP_WITHOUT_WINDOWS();
  expect_drag_equals_options(true);
}

// Resizing the window (or the headless frame) mid-run, as a user dragging its border: the
// next frame is drawn at the new size and framed for its aspect, as a run started at that size.
void expect_resize_equals_size_option(bool windowed) {
  const std::string blob = sphere_sh_blob("input_sphere.prtk");
  const std::string map = sun_at_plus_x_map();
  const Picture resized =
      run(blob, map, windowed ? "resized_window" : "resized",
          "--input-script " + quote(script("resize.txt", "0 resize 200 300\n")), windowed);
  const Picture direct =
      screenshot(blob, map, windowed ? "sized_window" : "sized", kFixed, windowed, "200x300");
  ASSERT_EQ(resized.width, 200);
  ASSERT_EQ(resized.height, 300);
  EXPECT_LE(difference(resized, direct).largest, 1);
  EXPECT_GT(centre_coverage(resized), 0.5) << "the sphere should fill the middle";
}

TEST(PrtViewerInput, ResizedFrameIsDrawnAsOneStartedAtThatSize) {
  expect_resize_equals_size_option(false);
}

TEST(PrtViewerInput, ResizedWindowIsDrawnAsOneStartedAtThatSize) {
  PRT_SKIP_WITHOUT_WINDOWS();
  expect_resize_equals_size_option(true);
}

TEST(PrtViewerInput, WheelZoomsAndFFramesTheSceneAgain) {
  const std::string blob = sphere_sh_blob("input_sphere.prtk");
  const std::string map = sun_at_plus_x_map();
  const Picture still = run(blob, map, "zoom_still", "");
  const Picture zoomed =
      run(blob, map, "zoomed", "--input-script " + quote(script("zoom.txt", "0 scroll 3\n")));
  const Picture reframed =
      run(blob, map, "reframed",
          "--input-script " + quote(script("frame.txt", "0 scroll 3\n1 key F\n")));
  // Three steps of 10 % closer: the sphere grows by 1 / 0.9^3 = 1.37, so more of the middle is
  // covered.
  EXPECT_GT(centre_coverage(zoomed), centre_coverage(still) + 0.05);
  EXPECT_LE(difference(reframed, still).largest, 1) << "F frames the scene as on load";
}

// A right-drag of 40 pixels turns the light by 10 degrees (0.25 a pixel), as --rotate 10 does;
// auto-spin turns it by its speed times 1/60 s a frame in a scripted run: 90 deg/s over two
// frames is --rotate 3.
TEST(PrtViewerInput, RightDragAndAutoSpinTurnTheLightAsRotateDoes) {
  const std::string blob = sphere_sh_blob("input_sphere.prtk");
  const std::string map = sun_at_plus_x_map();
  const std::string drag =
      script("right_drag.txt", "0 move 100 100\n0 press right\n1 move 140 100\n1 release right\n");
  const Picture dragged = run(blob, map, "light_dragged", "--input-script " + quote(drag));
  const Picture rotated = run(blob, map, "light_rotated", "--rotate 10");
  const Picture still = run(blob, map, "light_still", "");
  EXPECT_LE(difference(dragged, rotated).largest, 1);
  EXPECT_GT(difference(dragged, still).pixels, 1000u);
  const Picture spun = run(blob, map, "light_spun", "--spin 90");
  EXPECT_LE(difference(spun, run(blob, map, "light_rotated_3", "--rotate 3")).largest, 1);
  EXPECT_GT(difference(spun, still).pixels, 100u);
}

TEST(PrtViewerInput, DroppedBlobAndMapAreOpened) {
  const std::string sphere = sphere_sh_blob("input_sphere.prtk");
  const std::string map = sun_at_plus_x_map();
  const std::string sky = prt_view_test::write_test_sky();
  const std::string quad = prt_view_test::golden("sh_quad.prtk");
  // A blob dropped on the window replaces the first and is framed as if opened directly.
  const Picture dropped_blob =
      run(sphere, map, "dropped_blob",
          "--input-script " + quote(script("drop_blob.txt", "1 drop " + quad + "\n")));
  const Picture direct_blob = run(quad, map, "direct_blob", "");
  EXPECT_LE(difference(dropped_blob, direct_blob).largest, 1);
  // A map dropped on the window is added and picked.
  const Picture dropped_map =
      run(sphere, map, "dropped_map",
          "--input-script " + quote(script("drop_map.txt", "1 drop " + sky + "\n")));
  const Picture direct_map = run(sphere, sky, "direct_map", "");
  EXPECT_LE(difference(dropped_map, direct_map).largest, 1);
  EXPECT_GT(difference(dropped_map, run(sphere, map, "undropped", "")).pixels, 1000u);
}

// Each --env names one map (before or after the blob); the first is lit with.
TEST(PrtViewerInput, EveryEnvOptionAddsOneMapAndTheFirstIsCurrent) {
  const std::string sphere = sphere_sh_blob("input_sphere.prtk");
  const std::string map = sun_at_plus_x_map(), sky = prt_view_test::write_test_sky();
  const std::string png = scratch().file("two_maps.png");
  const prt_test::CommandResult result = run_viewer(
      "--env " + quote(map) + " " + quote(sphere) + " --env " + quote(sky) +
          " --backend cpu --exposure 0 --size 320x240 --frames 2 --screenshot " + quote(png),
      "two_maps");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_LE(difference(read_picture(png), run(sphere, map, "one_map", "")).largest, 1);
}

TEST(PrtViewerInput, DroppingAFileThatIsNotABlobIsReportedAndFailsAScriptedRun) {
  const std::string map = sun_at_plus_x_map();
  const std::string bad = scratch().write("not_a_blob.prtk", "hello");
  const std::string png = scratch().file("bad_drop.png");
  const prt_test::CommandResult result =
      run_viewer(quote(sphere_sh_blob("input_sphere.prtk")) + " --env " + quote(map) +
                     " --frames 3 --size 160x120 --screenshot " + quote(png) + " --input-script " +
                     quote(script("drop_bad.txt", "1 drop " + bad + "\n")),
                 "bad_drop");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("not_a_blob.prtk"), std::string::npos) << result.output;
}

// In a split screen, a left-drag that starts on the divider moves it instead of the camera.
TEST(PrtViewerInput, DraggingTheDividerMovesIt) {
  const std::string sky = prt_view_test::write_test_sky();
  const std::string sh = prt_view_test::golden("sh_quad.prtk");
  const std::string split = quote(prt_view_test::golden("wavelet_quad.prtk")) + " --compare split ";
  const std::string drag =
      script("divider.txt", "0 move 160 120\n0 press left\n1 move 80 100\n1 release left\n");
  const Picture dragged = run(sh, sky, "divider_dragged", split + "--input-script " + quote(drag));
  const Picture quarter = run(sh, sky, "divider_quarter", split + "--divider 0.25");
  const Picture half = run(sh, sky, "divider_half", split);
  EXPECT_LE(difference(dragged, quarter).largest, 1);
  EXPECT_GT(difference(dragged, half).pixels, 100u);
}

// P (or F12) writes a numbered screenshot in the working folder.
TEST(PrtViewerInput, ScreenshotKeyWritesANumberedPicture) {
  const std::string folder = scratch().file("key_shot");
  std::filesystem::create_directories(folder);
  const std::string command = "cd " + quote(folder) + " && " + quote(PRT_VIEWER_EXE) +
                              " --headless " + quote(sphere_sh_blob("input_sphere.prtk")) +
                              " --env " + quote(sun_at_plus_x_map()) +
                              " --size 160x120 --frames 2 --input-script " +
                              quote(script("key_p.txt", "0 key P\n1 key F12\n"));
  const prt_test::CommandResult result =
      prt_test::run_command("/bin/sh", "-c " + quote(command), scratch().file("key_shot.log"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* name : {"prt-viewer-000.png", "prt-viewer-001.png"}) {
    const Picture p = read_picture(folder + "/" + name);
    EXPECT_EQ(p.width, 160) << name;
    EXPECT_GT(centre_coverage(p), 0.5) << name;
  }
}

// wavelet's light coefficients M, a live parameter: the option sets it as the slider does.
TEST(PrtViewerLiveParameters, WaveletLightCoefficientsChangeThePicture) {
  const std::string sky = prt_view_test::write_test_sky();
  const std::string blob = prt_view_test::golden("wavelet_quad.prtk");
  const Picture all = run(blob, sky, "m_all", "");
  const Picture few = run(blob, sky, "m_0", "--light-coefficients 0");
  const Picture same = run(blob, sky, "m_big", "--light-coefficients 100000");
  EXPECT_GT(difference(all, few).pixels, 100u) << "keeping no detail coefficient blurs the light";
  EXPECT_LE(difference(all, same).largest, 0) << "M beyond the count keeps all";
}

// sh's de-ringing, a live parameter: under a sun alone, order-3 SH light rings, and the sphere's
// far side gets negative radiance; prt_sh_dering_light at strength 1 is the weakest window that
// keeps a point light's irradiance non-negative (prt_sh.h), so with --dering no vertex is
// negative. prt-view and prt-viewer take the option from the same LiveParameter.
TEST(PrtViewerLiveParameters, ShDeRingingRemovesTheNegativeFarSide) {
  const std::string sphere = sphere_sh_blob("input_sphere.prtk");
  const std::string sun = prt_view_test::write_hdr(
      "sun_only.hdr", 64, 32,
      prt_view_test::latlong_map(
          [](const double d[3], float rgb[3]) {
            const float v = d[0] > std::cos(10.0 * kPi / 180.0) ? 400.0f : 0.0f;
            rgb[0] = rgb[1] = rgb[2] = v;
          },
          64, 32));
  auto extremes = [](const std::vector<float>& rgb) {
    const auto [lo, hi] = std::minmax_element(rgb.begin(), rgb.end());
    return std::pair<float, float>{*lo, *hi};
  };
  const auto ringing =
      extremes(prt_view_test::view_vertices(sphere, sun, "ringing", "--backend cpu"));
  const auto dering =
      extremes(prt_view_test::view_vertices(sphere, sun, "dering", "--backend cpu --dering"));
  std::printf("radiance without de-ringing [%g, %g], with [%g, %g]\n", ringing.first,
              ringing.second, dering.first, dering.second);
  EXPECT_LT(ringing.first, -0.01f * ringing.second) << "SH of a lone sun rings";
  EXPECT_GE(dering.first, -1e-5f * dering.second) << "de-ringed light gives no negative radiance";
  const Picture plain = run(sphere, sun, "dering_off", "");
  const Picture windowed = run(sphere, sun, "dering_on", "--dering");
  const Picture stronger = run(sphere, sun, "dering_strong", "--dering --dering-strength 2");
  EXPECT_GT(difference(plain, windowed).pixels, 1000u);
  EXPECT_GT(difference(windowed, stronger).pixels, 1000u);
}

}  // namespace
