// SPDX-License-Identifier: MIT
// prt-viewer's compare modes, checked against its single-blob pictures: a split screen shows
// blob A left of the divider and blob B right of it exactly as each alone (one camera, one
// exposure), so it differs from either where the techniques differ; the error mode's RMSE
// against a reference that is the blob's own radiance scaled by a known factor.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "samples/viewer_app_test_util.hpp"

namespace {

using namespace prt_viewer_app_test;

// A fixed exposure: metering would see different pixels in each mode.
const char* const kFixed = "--backend cpu --exposure 0";

struct Pair {
  std::string a, b, map, name;
};

void expect_split_is_both_singles(const Pair& pair, bool windowed) {
  const Picture a = screenshot(pair.a, pair.map, pair.name + "_a", kFixed, windowed);
  const Picture b = screenshot(pair.b, pair.map, pair.name + "_b", kFixed, windowed);
  const std::string args = quote(pair.b) + " --compare split " + kFixed;
  const Picture both = screenshot(pair.a, pair.map, pair.name + "_split", args, windowed);
  ASSERT_EQ(both.width, a.width);
  const int half = a.width / 2;
  const Difference left = difference(both, a, 0, half), right = difference(both, b, half);
  EXPECT_LE(left.largest, 1) << "left of the divider is blob A";
  EXPECT_LE(right.largest, 1) << "right of the divider is blob B";
  // Where the techniques differ, the split differs from either single picture.
  const Difference a_b = difference(a, b, half);
  const Difference split_a = difference(both, a, half);
  std::printf("%s: A and B differ at %zu pixels right of the divider, the split and A at %zu\n",
              pair.name.c_str(), a_b.pixels, split_a.pixels);
  EXPECT_GT(a_b.pixels, 100u) << "the two techniques should differ visibly";
  EXPECT_EQ(split_a.pixels, a_b.pixels);
}

TEST(PrtViewerCompare, SplitScreenIsBlobALeftAndBlobBRightOfTheDivider) {
  expect_split_is_both_singles(
      {prt_view_test::golden("sh_quad.prtk"), prt_view_test::golden("wavelet_quad.prtk"),
       prt_view_test::write_test_sky(), "golden"},
      false);
}

TEST(PrtViewerCompare, SideBySideHalvesAreEachBlobInAHalfFrame) {
  const std::string sky = prt_view_test::write_test_sky();
  const std::string sh = prt_view_test::golden("sh_quad.prtk");
  const std::string wavelet = prt_view_test::golden("wavelet_quad.prtk");
  // Each half is a 160 x 240 view: the same as a single run at that size.
  const Picture a = screenshot(sh, sky, "side_a", kFixed, false, "160x240");
  const Picture b = screenshot(wavelet, sky, "side_b", kFixed, false, "160x240");
  const Picture side =
      screenshot(sh, sky, "side", quote(wavelet) + " --compare side " + kFixed, false, "320x240");
  ASSERT_EQ(side.width, 320);
  Picture left, right;
  left.width = right.width = 160, left.height = right.height = 240;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x)
      for (int c = 0; c < 3; ++c) (x < 160 ? left : right).rgb.push_back(side.at(x, y)[c]);
  EXPECT_LE(difference(left, a).largest, 1);
  EXPECT_LE(difference(right, b).largest, 1);
}

// The reference is the blob's own radiance (prt-view --vertex-out, its CPU shading) times 1.25,
// so the relative RMSE is 0.25 / 1.25 = 0.2 exactly, whatever the scene.
TEST(PrtViewerCompare, ErrorModePrintsTheRelativeRmseAgainstTheReference) {
  const std::string sky = prt_view_test::write_test_sky();
  const std::string blob = prt_view_test::golden("sh_quad.prtk");
  std::vector<float> radiance = prt_view_test::view_vertices(blob, sky, "error_x", "--backend cpu");
  ASSERT_FALSE(radiance.empty());
  for (float& v : radiance) v *= 1.25f;
  const std::string reference =
      scratch().write("error_reference.npy", prt_test::npy_f32_bytes(radiance, 3));

  const std::string png = scratch().file("error.png");
  const prt_test::CommandResult run =
      run_viewer(quote(blob) + " --env " + quote(sky) + " --reference " + quote(reference) +
                     " --backend cpu --exposure 0 --size 320x240 --screenshot " + quote(png),
                 "error");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::size_t at = run.output.find("relative RMSE ");
  ASSERT_NE(at, std::string::npos) << run.output;
  EXPECT_NEAR(std::stod(run.output.substr(at + 14)), 0.2, 1e-4);
  // The right half is the heat map over prt-view's mid-grey backdrop (byte 64).
  const Picture p = read_picture(png);
  ASSERT_EQ(p.width, 320);
  const std::array<int, 3> corner = p.at(318, 1);
  EXPECT_EQ(corner[0], 64);
  EXPECT_EQ(corner[1], 64);
  EXPECT_EQ(corner[2], 64);
  // The left half is the blob as a half-frame view shows it.
  const Picture single =
      screenshot(blob, sky, "error_single", "--backend cpu --exposure 0", false, "160x240");
  Picture left;
  left.width = 160, left.height = 240;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 160; ++x)
      for (int c = 0; c < 3; ++c) left.rgb.push_back(p.at(x, y)[c]);
  EXPECT_LE(difference(left, single).largest, 1);
}

}  // namespace
