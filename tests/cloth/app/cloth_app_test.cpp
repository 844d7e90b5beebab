// SPDX-License-Identifier: MIT
// prt-cloth headless on the six presets baked here by prt-bake bake cloth on small grids (over a
// quad the app does not draw: it draws its built-in draped sheet), under a sky of constant radiance
// 1 and a fixed exposure with the linear tone map, so that a picture's bytes decode to radiance:
// the sky is the one radiance the background has, and the cloth is what differs from it. Checked
// against what is known without the app: white light keeps the albedo's order of channels; with eta
// 1 (no surface term) the radiance is linear in the albedo; the split screen is the runtime left of
// the divider and the reference right of it, and its error figure is the one the two pictures give;
// the heat map is the ramp at the error a side-by-side picture gives; the gallery's tiles are
// single pictures of each fabric.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "compare.hpp"
#include "support/command.hpp"
#include "support/picture.hpp"
#include "support/shared_bake.hpp"
#include "support/test_files.hpp"

namespace {

const prt_test::TempDir& scratch() {
  static const prt_test::TempDir dir("cloth_app");
  return dir;
}

// A 32 x 16 lat-long map of constant radiance 1 (RGBE 128 128 128 129), flat scanlines.
const std::string& constant_sky() {
  static const std::string path = [] {
    std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 32\n";
    for (int i = 0; i < 32 * 16; ++i) bytes += std::string("\x80\x80\x80\x81", 4);
    return scratch().write("constant.hdr", bytes);
  }();
  return path;
}

const char* const kFabrics[6] = {"linen_plain",
                                 "silk_crepe_de_chine",
                                 "polyester_satin_charmeuse",
                                 "polyester_satin_charmeuse_back",
                                 "silk_shot",
                                 "velvet"};

// Bakes the six presets on small grids (quick, coarse) over a quad, into `dir`/presets.prtk.
bool bake_presets(const std::string& dir) {
  const std::string quad = dir + "/quad.obj";
  std::ofstream(quad) << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nf 1 3 2\nf 1 4 3\n";
  const prt_test::CommandResult run = prt_test::run_command(
      PRT_BAKE_EXE,
      "bake cloth " + prt_test::shell_quote(quad) +
          " --fabric all --xi-size 8 --levels 4 --view-theta 6 --view-phi 6 -o " +
          prt_test::shell_quote(dir + "/presets.prtk"),
      scratch().file("bake.log"));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return run.exit_code == 0;
}

// Where the presets are baked: under ctest, in the folder PRT_CLOTH_APP_BAKE names, by the
// fixture test ClothAppBake (tests/cloth/app/CMakeLists.txt); by hand, in the scratch folder.
const char* const kBakeVariable = "PRT_CLOTH_APP_BAKE";

// The six presets' blob, made once.
const std::string& presets_blob() {
  static const std::string path =
      prt_test::shared_bake_folder(kBakeVariable, scratch().dir(), bake_presets) + "/presets.prtk";
  return path;
}

TEST(ClothAppBake, MakesTheBlobTheOtherTestsShare) {
  prt_test::make_shared_bake(kBakeVariable, bake_presets);
}

constexpr int kWidth = 128, kHeight = 96;

// prt-cloth on the presets' blob under the constant sky at `ev`, its picture into `name`.png.
prt_test::CommandResult cloth(const std::string& name, const std::string& extra, double ev = -1.0) {
  return prt_test::run_command(
      PRT_CLOTH_EXE,
      prt_test::shell_quote(presets_blob()) + " --env " + prt_test::shell_quote(constant_sky()) +
          " --headless --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight) +
          " --tonemap linear --exposure " + std::to_string(ev) +
          " --mesh patch --reference-size 16x8 --screenshot " +
          prt_test::shell_quote(scratch().file(name + ".png")) + " " + extra,
      scratch().file(name + ".log"));
}

prt_test::Picture picture(const std::string& name) {
  return prt_test::read_picture(scratch().file(name + ".png"));
}

// An sRGB byte back to linear light, over 2^ev: the radiance the picture shows.
double radiance(int byte, double ev) {
  const double v = byte / 255.0;
  const double linear = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  return linear / std::exp2(ev);
}

// Whether pixel (x, y) shows cloth: it differs from the sky's colour, the picture's top left
// (where the framed sheet never reaches).
bool is_cloth(const prt_test::Picture& p, int x, int y) {
  return p.at(x, y) != p.at(0, 0);
}

// The figure of the line "... relative RMSE X (...) over N pixels", or NaN.
double printed_rmse(const std::string& output) {
  const std::size_t at = output.find("relative RMSE ");
  return at == std::string::npos ? std::nan("") : std::atof(output.c_str() + at + 14);
}

struct Rgb {
  double c[3] = {0.0, 0.0, 0.0};
};

Rgb radiance_at(const prt_test::Picture& p, int x, int y, double ev) {
  const std::array<int, 3> b = p.at(x, y);
  Rgb r;
  for (int k = 0; k < 3; ++k) r.c[k] = radiance(b[k], ev);
  return r;
}

TEST(ClothApp, TheClothIsLitInTheAlbedosOrderOfChannels) {
  const prt_test::CommandResult run = cloth("lit", "");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const prt_test::Picture p = picture("lit");
  ASSERT_EQ(p.width, kWidth);
  ASSERT_EQ(p.height, kHeight);
  // The sky: radiance 1 at EV -1 is 0.5 (sRGB 188), within a byte's rounding.
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(radiance(p.at(0, 0)[k], -1.0), 1.0, 0.01);
  std::size_t cloth_pixels = 0, black = 0;
  Rgb sum;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      if (!is_cloth(p, x, y)) continue;
      ++cloth_pixels;
      const Rgb r = radiance_at(p, x, y, -1.0);
      if (r.c[0] + r.c[1] + r.c[2] == 0.0) ++black;
      for (int k = 0; k < 3; ++k) sum.c[k] += r.c[k];
    }
  // The framed sheet fills a good part of the frame; none of it is black (a NaN would leave the
  // sky showing through, a zero black).
  EXPECT_GT(cloth_pixels, std::size_t(kWidth * kHeight / 5));
  EXPECT_EQ(black, 0u);
  // linen_plain's albedo is blue over green over red in both threads; the surface term is
  // white: under white light the mean radiance keeps that order.
  EXPECT_GT(sum.c[2], sum.c[1]);
  EXPECT_GT(sum.c[1], sum.c[0]);
  EXPECT_GT(sum.c[0], 0.0);
}

// With eta 1 there is no surface term and the volume term is the albedo times the rest: half the
// albedo at one EV more is the same picture on the cloth.
TEST(ClothApp, TheFabricOptionsReachTheShadingLinearlyInTheAlbedo) {
  const std::string eta = " --warp-eta 1 --weft-eta 1";
  const prt_test::CommandResult full =
      cloth("albedo_full", eta + " --warp-albedo 0.8,0.8,0.8 --weft-albedo 0.6,0.6,0.6", -1.0);
  const prt_test::CommandResult half =
      cloth("albedo_half", eta + " --warp-albedo 0.4,0.4,0.4 --weft-albedo 0.3,0.3,0.3", 0.0);
  ASSERT_EQ(full.exit_code, 0) << full.output;
  ASSERT_EQ(half.exit_code, 0) << half.output;
  const prt_test::Picture a = picture("albedo_full"), b = picture("albedo_half");
  ASSERT_EQ(a.width, b.width);
  std::size_t cloth_pixels = 0, differing = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!is_cloth(a, x, y)) continue;
      ++cloth_pixels;
      for (int k = 0; k < 3; ++k) differing += std::abs(a.at(x, y)[k] - b.at(x, y)[k]) > 1;
    }
  EXPECT_GT(cloth_pixels, std::size_t(kWidth * kHeight / 5));
  EXPECT_EQ(differing, 0u);
  // And the albedo does reach it: the same eta at the fabric's own albedo is another picture.
  const prt_test::CommandResult own = cloth("albedo_own", eta, -1.0);
  ASSERT_EQ(own.exit_code, 0) << own.output;
  EXPECT_NE(prt_test::read_bytes(scratch().file("albedo_own.png")),
            prt_test::read_bytes(scratch().file("albedo_full.png")));
}

// Divider 1: the runtime everywhere (the single picture); 0: the reference everywhere; 0.5: the
// left half of one and the right half of the other. The printed figure is the relative RMSE of
// the two whole pictures.
TEST(ClothApp, TheSplitShowsTheReferenceRightOfTheDividerAndItsError) {
  const prt_test::CommandResult single = cloth("single", "--compare single");
  const prt_test::CommandResult runtime = cloth("split1", "--compare split --divider 1");
  const prt_test::CommandResult reference = cloth("split0", "--compare split --divider 0");
  const prt_test::CommandResult half = cloth("split", "--compare split --divider 0.5");
  for (const prt_test::CommandResult* r : {&single, &runtime, &reference, &half})
    ASSERT_EQ(r->exit_code, 0) << r->output;
  const prt_test::Picture s = picture("single"), p1 = picture("split1"), p0 = picture("split0"),
                          ph = picture("split");
  EXPECT_EQ(s.rgb, p1.rgb);
  std::size_t wrong_side = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      wrong_side += ph.at(x, y) != (x < kWidth / 2 ? p1.at(x, y) : p0.at(x, y));
  EXPECT_EQ(wrong_side, 0u);

  double diff = 0.0, norm = 0.0;
  std::size_t cloth_pixels = 0, differing = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (!is_cloth(p1, x, y) && !is_cloth(p0, x, y)) continue;
      ++cloth_pixels;
      differing += p1.at(x, y) != p0.at(x, y);
      const Rgb a = radiance_at(p1, x, y, -1.0), b = radiance_at(p0, x, y, -1.0);
      for (int k = 0; k < 3; ++k) {
        diff += (a.c[k] - b.c[k]) * (a.c[k] - b.c[k]);
        norm += b.c[k] * b.c[k];
      }
    }
  // The method is not the exact model: the two differ on much of the cloth.
  EXPECT_GT(differing, cloth_pixels / 4);
  const double printed = printed_rmse(reference.output), from_pictures = std::sqrt(diff / norm);
  ASSERT_TRUE(std::isfinite(printed)) << reference.output;
  EXPECT_GT(printed, 0.0);
  // The pictures' bytes round each value by up to half an sRGB step.
  EXPECT_NEAR(from_pictures, printed, 0.02 * printed) << reference.output;
  EXPECT_NEAR(printed_rmse(half.output), printed, 1e-5) << half.output;
}

// A window's frame budget computes the pictures a share per frame, coarse to fine: a run with
// --frames goes on until they are whole, and ends on the picture and figure of one computed at
// once (each sample's value does not depend on how the samples are split).
TEST(ClothApp, TheProgressivePicturesEndAsTheWholeOnes) {
  const prt_test::CommandResult whole = cloth("whole", "--compare split");
  const prt_test::CommandResult progressive =
      cloth("progressive", "--compare split --frame-budget 20 --frames 1");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  ASSERT_EQ(progressive.exit_code, 0) << progressive.output;
  EXPECT_NE(whole.output.find("prt-cloth: 1 frame(s)"), std::string::npos) << whole.output;
  EXPECT_EQ(progressive.output.find("prt-cloth: 1 frame(s)"), std::string::npos)
      << progressive.output;
  EXPECT_EQ(printed_rmse(progressive.output), printed_rmse(whole.output)) << progressive.output;
  EXPECT_EQ(picture("progressive").rgb, picture("whole").rgb);
}

// The error view's right half is the heat ramp at |runtime - reference| / mean |reference|, which
// the side-by-side picture gives (runtime left, reference right, the same viewports).
TEST(ClothApp, TheHeatMapShowsTheErrorOfTheSideBySidePicture) {
  const float scale = 0.5f;
  const std::string s = " --error-scale " + std::to_string(scale);
  const prt_test::CommandResult side = cloth("side", "--compare side" + s);
  const prt_test::CommandResult error = cloth("error", "--compare error" + s);
  ASSERT_EQ(side.exit_code, 0) << side.output;
  ASSERT_EQ(error.exit_code, 0) << error.output;
  const prt_test::Picture a = picture("side"), h = picture("error");
  const int half = kWidth / 2;
  // The left halves are the same runtime picture.
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < half; ++x) ASSERT_EQ(a.at(x, y), h.at(x, y)) << x << ", " << y;
  std::vector<std::pair<int, int>> at;
  std::vector<glm::vec3> x_side, ref_side;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < half; ++x) {
      if (!is_cloth(a, x, y) || !is_cloth(a, x + half, y)) continue;
      const Rgb r = radiance_at(a, x, y, -1.0), q = radiance_at(a, x + half, y, -1.0);
      x_side.emplace_back(r.c[0], r.c[1], r.c[2]);
      ref_side.emplace_back(q.c[0], q.c[1], q.c[2]);
      at.emplace_back(x + half, y);
    }
  ASSERT_GT(at.size(), std::size_t(kWidth * kHeight / 10));
  const std::vector<float> e = prt::view::relative_vertex_error(x_side, ref_side);
  double sum_abs = 0.0, mean_expected = 0.0, mean_shown = 0.0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    const glm::vec3 c = prt::view::heat_colour(e[i], scale);
    const std::array<int, 3> shown = h.at(at[i].first, at[i].second);
    for (int k = 0; k < 3; ++k) {
      sum_abs += std::abs(shown[k] - 255.0 * c[k]);
      mean_expected += 255.0 * c[k];
      mean_shown += shown[k];
    }
  }
  const double n = 3.0 * double(at.size());
  // Quantised radiance moves a pixel's error by a little: on average the colours agree to a few
  // bytes, and the mean colour to within one.
  EXPECT_LT(sum_abs / n, 4.0);
  EXPECT_NEAR(mean_shown / n, mean_expected / n, 1.0);
  EXPECT_GT(mean_expected / n, 10.0) << "some error to show";
}

// Each tile of the gallery is the single picture of its fabric (the same fixed exposure), its
// name under it.
TEST(ClothApp, TheGalleryHoldsEveryFabricsPicture) {
  const std::string gallery = scratch().file("gallery.png");
  const prt_test::CommandResult run =
      cloth("gallery_run", "--gallery " + prt_test::shell_quote(gallery));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<std::string> names(kFabrics, kFabrics + 6);
  const prt_test::Picture g = prt_test::read_picture(gallery);
  ASSERT_GT(g.width, 0);
  const int gap = 4, columns = 3;  // ceil(sqrt(6)) columns, 4 pixels apart
  EXPECT_EQ(g.width, columns * kWidth + (columns - 1) * gap);
  for (std::size_t f = 0; f < names.size(); ++f) {
    EXPECT_NE(run.output.find("gallery " + std::to_string(f + 1) + "/6: " + names[f]),
              std::string::npos)
        << run.output;
    if (f != 0 && f != 5) continue;  // the first and the last: enough to place every tile
    const prt_test::CommandResult one = cloth("fabric" + std::to_string(f), "--fabric " + names[f]);
    ASSERT_EQ(one.exit_code, 0) << one.output;
    const prt_test::Picture p = picture("fabric" + std::to_string(f));
    // Column f % 3; the row's top is 0 for the first row, below the first row's labels for the
    // second: the first offset where the picture is found.
    const int ox = int(f % columns) * (kWidth + gap);
    int found = -1;
    for (int oy = f < 3 ? 0 : kHeight + gap; found < 0 && oy + kHeight <= g.height; ++oy) {
      bool same = true;
      for (int y = 0; same && y < kHeight; ++y)
        for (int x = 0; same && x < kWidth; ++x) same = p.at(x, y) == g.at(ox + x, oy + y);
      if (same) found = oy;
      if (f < 3) break;
    }
    EXPECT_GE(found, 0) << names[f] << ": its picture is not in the gallery's tile";
  }
}

// A fabric the blob lacks, and parameters it cannot take, are bad arguments that say why.
TEST(ClothApp, ArgumentsTheBlobCannotTakeFailNamingWhy) {
  const prt_test::CommandResult fabric = cloth("no_fabric", "--fabric wool");
  EXPECT_EQ(fabric.exit_code, 2) << fabric.output;
  EXPECT_NE(fabric.output.find("has no fabric 'wool'; it has: linen_plain, silk_crepe_de_chine,"),
            std::string::npos)
      << fabric.output;
  const prt_test::CommandResult coverage = cloth("coverage", "--warp-coverage 0.9");
  EXPECT_EQ(coverage.exit_code, 2) << coverage.output;
  EXPECT_NE(coverage.output.find("fabric linen_plain: coverages 0.9 (warp) and 0.33 (weft) add up "
                                 "to more than 1"),
            std::string::npos)
      << coverage.output;
}

}  // namespace
