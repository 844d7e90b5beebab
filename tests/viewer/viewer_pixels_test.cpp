// SPDX-License-Identifier: MIT
// prt-view's pixels, read back with stb (not the viewer's code): the tone mapping of a known
// radiance (shaded, or given with --radiance-in) and the heat map's colours at known errors; box
// framing, the turning light's frames and the animated PNG of tiled frames.
//
// The blobs are flat quads facing the camera (+Z) whose every vertex has the same order-1 `sh`
// transfer t (offset t, scale 0), lit by a constant map m: the radiance is t * L00 with
// L00 = 4 pi Y00 m = 2 sqrt(pi) m, so every covered pixel shows that radiance and the background
// shows m. The expected bytes are worked out here from the published formulas: exposure 2^EV,
// the ACES filmic fit of K. Narkowicz (2015) and the sRGB transfer function (IEC 61966-2-1).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sh/sh_blob_test_util.hpp"
#include "support/command.hpp"
#include "support/mesh_blob.hpp"
#include "support/picture.hpp"
#include "viewer/viewer_test_util.hpp"

namespace {

using namespace prt_view_test;

// An axis-aligned rectangle in the z = 0 plane: [x0, x1] x [y0, y1].
struct Rect {
  float x0, y0, x1, y1;
};

// A blob of `rects` (four vertices and two triangles each) whose every vertex has the order-1
// RGB transfer `t` (stored exactly: offset t, scale 0, q 0).
std::string flat_blob(const std::string& name, const std::vector<Rect>& rects,
                      const std::array<float, 3>& t) {
  const std::uint32_t vertices = 4 * static_cast<std::uint32_t>(rects.size());
  std::vector<float> positions;
  std::vector<std::uint32_t> triangles;
  for (const Rect& r : rects) {
    const std::uint32_t base = static_cast<std::uint32_t>(positions.size() / 3);
    positions.insert(positions.end(),
                     {r.x0, r.y0, 0.0f, r.x1, r.y0, 0.0f, r.x1, r.y1, 0.0f, r.x0, r.y1, 0.0f});
    triangles.insert(triangles.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  prt_test::Transfer transfer;
  transfer.order = 1, transfer.vertices = vertices, transfer.channels = 3, transfer.kind = 0;
  transfer.offset.assign(t.begin(), t.end());
  transfer.scale.assign(3, 0.0f);
  transfer.q.assign(3u * vertices, 0u);
  return write_blob(name, prt_test::mesh_blob(positions, triangles, PRT_BLOB_TAG_SHTR,
                                              prt_test::encode(transfer)));
}

// A constant lat-long map (64 x 32) of `m`; RGBE stores these values exactly.
const std::array<float, 3> kConstant = {0.75f, 0.5f, 1.0f};

std::string constant_map() {
  std::vector<float> rgb;
  for (int i = 0; i < 64 * 32; ++i) rgb.insert(rgb.end(), kConstant.begin(), kConstant.end());
  return write_hdr("constant.hdr", 64, 32, rgb);
}

// The published formulas, in double.
double aces_narkowicz(double x) {
  x = std::max(x, 0.0);
  return std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}
int display_byte(double radiance, double exposure_ev) {
  return static_cast<int>(
      std::lround(srgb_encode(aces_narkowicz(radiance * std::exp2(exposure_ev))) * 255.0));
}

// float32 [V, 3] .npy, format 1.0, written here; returns the path.
std::string write_npy(const std::string& name, const std::vector<float>& rgb) {
  return scratch().write(name, prt_test::npy_f32_bytes(rgb, 3));
}

using Png = prt_test::Picture;

Png read_png(const std::string& path) {
  return prt_test::read_picture(path);
}

// Every pixel of the block [x0, x1) x [y0, y1) within one 8-bit step of `expected`.
void expect_block(const Png& png, int x0, int y0, int x1, int y1,
                  const std::array<int, 3>& expected, const std::string& what) {
  int worst = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(png.at(x, y)[c] - expected[c]));
  const std::array<int, 3> seen = png.at((x0 + x1) / 2, (y0 + y1) / 2);
  EXPECT_LE(worst, 1) << what << ": expected " << expected[0] << " " << expected[1] << " "
                      << expected[2] << ", e.g. " << seen[0] << " " << seen[1] << " " << seen[2];
}

TEST(PrtViewPixels, ToneMappingOfAKnownRadianceAndOfTheBackground) {
  const std::array<float, 3> t = {0.1f, 0.3f, 0.45f};
  const std::string blob = flat_blob("tone.prtk", {{-1.0f, -1.0f, 1.0f, 1.0f}}, t);
  const std::string png_path = scratch().file("tone.png");
  const double ev = 0.75;
  const prt_test::CommandResult run = run_view(
      quote(blob) + " --env " + quote(constant_map()) +
          " --headless --backend cpu --size 200x200 --exposure 0.75 --out " + quote(png_path),
      "tone");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("exposure +0.75 EV"), std::string::npos) << run.output;
  const Png png = read_png(png_path);
  ASSERT_EQ(png.width, 200);
  std::array<int, 3> surface, background;
  for (int c = 0; c < 3; ++c) {
    surface[c] = display_byte(t[c] * 2.0 * std::sqrt(kPi) * kConstant[c], ev);
    background[c] = display_byte(kConstant[c], ev);
  }
  std::printf("surface %d %d %d, background %d %d %d\n", surface[0], surface[1], surface[2],
              background[0], background[1], background[2]);
  // The quad fills the middle of the frame (the camera frames its bounding sphere); the corners
  // see the map.
  expect_block(png, 80, 80, 120, 120, surface, "the quad");
  for (const auto& [x, y] :
       {std::pair{0, 0}, std::pair{190, 0}, std::pair{0, 190}, std::pair{190, 190}})
    expect_block(png, x, y, x + 10, y + 10, background, "a corner");
}

// The heat map's ramp as the viewer documents it (samples/viewer/README.md): sRGB display
// colours at e / scale = 0, 0.2, 0.4, 0.6, 0.8, 1, linear in between, white beyond.
const double kRamp[6][3] = {{0.0, 0.0, 0.0}, {0.15, 0.1, 0.6}, {0.7, 0.15, 0.6},
                            {1.0, 0.5, 0.1}, {1.0, 0.9, 0.2},  {1.0, 1.0, 1.0}};

std::array<int, 3> ramp_byte(double t) {
  t = std::clamp(t, 0.0, 1.0) * 5.0;
  const int i = std::min(static_cast<int>(t), 4);
  std::array<int, 3> rgb;
  for (int c = 0; c < 3; ++c)
    rgb[c] = static_cast<int>(
        std::lround((kRamp[i][c] + (t - i) * (kRamp[i + 1][c] - kRamp[i][c])) * 255.0));
  return rgb;
}

// Runs of pixels along row y that differ from `backdrop` (more than one step in a channel):
// [begin, end) pairs, left to right.
std::vector<std::pair<int, int>> runs_off(const Png& png, int y,
                                          const std::array<int, 3>& backdrop) {
  std::vector<std::pair<int, int>> runs;
  for (int x = 0; x < png.width; ++x) {
    const std::array<int, 3> p = png.at(x, y);
    bool off = false;
    for (int c = 0; c < 3; ++c) off = off || std::abs(p[c] - backdrop[c]) > 1;
    if (!off) continue;
    if (runs.empty() || runs.back().second != x)
      runs.push_back({x, x + 1});
    else
      runs.back().second = x + 1;
  }
  return runs;
}

// Twelve quads in a row, left to right at ramp positions 0, 0.1, ..., 1 and 1.5 (beyond the
// scale). Every vertex shades the same radiance x; the reference of quad k is x (1 + s_k), so
// its error |x - ref| / mean |ref| is s_k / (1 + mean s) exactly, and --error-scale puts it at
// its ramp position.
TEST(PrtViewPixels, HeatMapShowsTheDocumentedRampAtKnownErrors) {
  std::vector<double> ramp_at;
  for (int k = 0; k <= 10; ++k) ramp_at.push_back(0.1 * k);
  ramp_at.push_back(1.5);
  std::vector<Rect> rects;
  for (std::size_t k = 0; k < ramp_at.size(); ++k)
    rects.push_back({1.5f * k, 0.0f, 1.5f * k + 1.0f, 3.0f});
  const std::string blob = flat_blob("heat.prtk", rects, {0.2f, 0.25f, 0.3f});
  const std::string map = constant_map();
  const std::vector<float> shaded = view_vertices(blob, map, "heat_x", "--backend cpu");
  ASSERT_EQ(shaded.size(), 3 * 4 * ramp_at.size());

  const double sigma = 0.5;
  double mean_s = 0.0;
  for (double t : ramp_at) mean_s += sigma * t / ramp_at.size();
  std::vector<float> reference(shaded.size());
  for (std::size_t i = 0; i < shaded.size(); ++i)
    reference[i] = float(1.0 + sigma * ramp_at[i / 12]) * shaded[i];  // 12 floats per quad
  const std::string reference_path = scratch().file("heat_reference.npy");
  write_npy("heat_reference.npy", reference);
  char scale[32];
  std::snprintf(scale, sizeof scale, "%.9g", sigma / (1.0 + mean_s));
  const std::string heat = scratch().file("heat.png");
  const prt_test::CommandResult run =
      run_view(quote(blob) + " --env " + quote(map) + " --headless --backend cpu --size 480x480 " +
                   "--reference " + quote(reference_path) + " --error-out " + quote(heat) +
                   " --error-scale " + scale,
               "heat");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Png png = read_png(heat);
  ASSERT_EQ(png.width, 480);

  const std::array<int, 3> backdrop = {64, 64, 64};  // mid grey 0.25: "no surface"
  expect_block(png, 0, 0, 10, 10, backdrop, "the backdrop");
  // The camera looks at the row's centre with no roll: the middle image row crosses every quad.
  const std::vector<std::pair<int, int>> runs = runs_off(png, png.height / 2, backdrop);
  ASSERT_EQ(runs.size(), ramp_at.size()) << "one run of colour per quad along the middle row";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const int x = (runs[k].first + runs[k].second) / 2;
    ASSERT_GE(runs[k].second - runs[k].first, 12) << "quad " << k;
    expect_block(png, x - 3, png.height / 2 - 3, x + 4, png.height / 2 + 4, ramp_byte(ramp_at[k]),
                 "quad " + std::to_string(k) + " at ramp position " + std::to_string(ramp_at[k]));
  }
}

TEST(PrtViewPixels, RadianceInDrawsTheGivenRadianceLikeShading) {
  const std::string blob = flat_blob("given.prtk", {{-1.0f, -1.0f, 1.0f, 1.0f}}, {0, 0, 0});
  const std::array<float, 3> given = {0.4f, 1.1f, 2.5f};
  std::vector<float> rgb;
  for (int v = 0; v < 4; ++v) rgb.insert(rgb.end(), given.begin(), given.end());
  const std::string npy = write_npy("given.npy", rgb);
  const std::string png_path = scratch().file("given.png");
  const std::string common = quote(blob) + " --env " + quote(constant_map()) +
                             " --headless --size 200x200 --exposure -0.5 --out " + quote(png_path) +
                             " --radiance-in ";
  const prt_test::CommandResult run = run_view(common + quote(npy), "given");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.find("shading:"), std::string::npos) << "no runtime shading";
  const Png png = read_png(png_path);
  ASSERT_EQ(png.width, 200);
  std::array<int, 3> surface, background;
  for (int c = 0; c < 3; ++c) {
    surface[c] = display_byte(given[c], -0.5);
    background[c] = display_byte(kConstant[c], -0.5);
  }
  expect_block(png, 80, 80, 120, 120, surface, "the quad");
  expect_block(png, 0, 0, 10, 10, background, "a corner");

  rgb.resize(3 * 3);  // one vertex short
  const prt_test::CommandResult short_run =
      run_view(common + quote(write_npy("short.npy", rgb)), "given_short");
  EXPECT_EQ(short_run.exit_code, 1) << short_run.output;
  EXPECT_NE(short_run.output.find("3 vertices, the blob has 4"), std::string::npos)
      << short_run.output;
}

// The share of the middle image column a surface covers (pixels that are not the background).
double covered_rows(const Png& png, const std::array<int, 3>& background) {
  int covered = 0;
  for (int y = 0; y < png.height; ++y) {
    const std::array<int, 3> p = png.at(png.width / 2, y);
    int diff = 0;
    for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(p[c] - background[c]));
    covered += diff > 2 ? 1 : 0;
  }
  return double(covered) / png.height;
}

TEST(PrtViewPixels, FrameBoundsFramesTheGivenBoxNotTheWholeMesh) {
  // A unit square at the origin and a large rectangle far to the side, as objects beside a
  // large ground plane are.
  const std::string blob =
      flat_blob("framed.prtk", {{-0.5f, -0.5f, 0.5f, 0.5f}, {20.0f, -10.0f, 60.0f, 10.0f}},
                {0.3f, 0.3f, 0.3f});
  const std::string map = constant_map();
  std::array<int, 3> background;
  for (int c = 0; c < 3; ++c) background[c] = display_byte(kConstant[c], 0.0);
  double share[2] = {0.0, 0.0};
  for (int framed = 0; framed < 2; ++framed) {
    const std::string png_path = scratch().file("framed" + std::to_string(framed) + ".png");
    const prt_test::CommandResult run =
        run_view(quote(blob) + " --env " + quote(map) +
                     " --headless --backend cpu --size 200x200 " + "--exposure 0 --out " +
                     quote(png_path) + (framed ? " --frame-bounds -0.5,-0.5,0,0.5,0.5,0" : ""),
                 "framed" + std::to_string(framed));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    share[framed] = covered_rows(read_png(png_path), background);
  }
  // Framed, the square spans the height but for the 5 % margins (its far edge is seen a little
  // smaller); framed with the whole mesh, it is a small patch.
  EXPECT_GT(share[1], 0.8);
  EXPECT_LT(share[1], 0.95);
  EXPECT_LT(share[0], 0.4);

  const prt_test::CommandResult bad =
      run_view(quote(blob) + " --env " + quote(map) + " --headless --out x.png --frame-bounds " +
                   "1,0,0,0,1,1",
               "framed_bad");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
}

// A lat-long map bright in one half of the azimuths, so turning it changes the background.
std::string half_bright_map() {
  std::vector<float> rgb;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) rgb.insert(rgb.end(), 3, x < 32 ? 2.0f : 0.1f);
  return write_hdr("half.hdr", 64, 32, rgb);
}

TEST(PrtViewPixels, TurnFramesMatchSingleImagesAtTheSameTurns) {
  const std::string blob = flat_blob("turn.prtk", {{-1.0f, -1.0f, 1.0f, 1.0f}}, {0.2f, 0.2f, 0.2f});
  const std::string map = half_bright_map();
  const std::string common =
      quote(blob) + " --env " + quote(map) + " --headless --backend cpu --size 64x48 ";
  // One exposure for all frames (given here: a metered one is printed rounded).
  const std::string ev = "0.25";
  const prt_test::CommandResult run =
      run_view(common + "--rotate 30 --exposure " + ev + " --turn-frames 4 --out " +
                   quote(scratch().file("turn_%03d.png")),
               "turn");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::vector<Png> frames;
  for (int k = 0; k < 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "turn_%03d.png", k);
    frames.push_back(read_png(scratch().file(name)));
    const std::string single = scratch().file("single" + std::to_string(k) + ".png");
    const prt_test::CommandResult one =
        run_view(common + "--rotate " + std::to_string(30 + 90 * k) + " --exposure " + ev +
                     " --out " + quote(single),
                 "single" + std::to_string(k));
    ASSERT_EQ(one.exit_code, 0) << one.output;
    EXPECT_EQ(frames[k].rgb, read_png(single).rgb) << "frame " << k;
  }
  EXPECT_NE(frames[0].rgb, frames[2].rgb) << "the light turned half a circle";

  const prt_test::CommandResult no_pattern =
      run_view(common + "--turn-frames 4 --out " + quote(scratch().file("turn.png")), "turn_bad");
  EXPECT_EQ(no_pattern.exit_code, 2) << no_pattern.output;
}

TEST(PrtViewPixels, AnimationTilesEachGroupOfInputsIntoOneFrame) {
  const std::string blob = flat_blob("anim.prtk", {{-1.0f, -1.0f, 1.0f, 1.0f}}, {0.2f, 0.2f, 0.2f});
  const std::string map = half_bright_map();
  const prt_test::CommandResult frames =
      run_view(quote(blob) + " --env " + quote(map) + " --headless --backend cpu --size 40x30 " +
                   "--turn-frames 4 --out " + quote(scratch().file("anim_%d.png")),
               "anim_frames");
  ASSERT_EQ(frames.exit_code, 0) << frames.output;
  std::string inputs;
  for (int k = 0; k < 4; ++k)
    inputs += " " + quote(scratch().file("anim_" + std::to_string(k) + ".png"));
  const std::string apng = scratch().file("anim.png");
  const prt_test::CommandResult run = run_view(
      "--animation " + quote(apng) + " --montage-columns 2 --frame-ms 40" + inputs, "anim");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("2 frames of 84x30, 40 ms each"), std::string::npos) << run.output;
  // The default image is the first frame: inputs 0 and 1 side by side, 4 black columns between.
  const Png still = read_png(apng);
  ASSERT_EQ(still.width, 84);
  const Png left = read_png(scratch().file("anim_0.png")),
            right = read_png(scratch().file("anim_1.png"));
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      ASSERT_EQ(still.at(x, y), left.at(x, y)) << x << "," << y;
      ASSERT_EQ(still.at(44 + x, y), right.at(x, y)) << x << "," << y;
    }
  }
  const prt_test::CommandResult odd =
      run_view("--animation " + quote(apng) + " --montage-columns 3" + inputs, "anim_odd");
  EXPECT_EQ(odd.exit_code, 1) << odd.output;

  // Labelled like a montage: a label row above every frame (30-pixel tiles: 12 rows at 1 pixel
  // per font pixel), the tiles unchanged below it.
  const std::string labelled = scratch().file("anim_labelled.png");
  const prt_test::CommandResult with_labels = run_view(
      "--animation " + quote(labelled) + " --montage-columns 2 --montage-labels a,b" + inputs,
      "anim_labelled");
  ASSERT_EQ(with_labels.exit_code, 0) << with_labels.output;
  EXPECT_NE(with_labels.output.find("2 frames of 84x42"), std::string::npos) << with_labels.output;
  const Png first = read_png(labelled);
  ASSERT_EQ(first.height, 42);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) ASSERT_EQ(first.at(x, 12 + y), left.at(x, y)) << x << "," << y;
}

TEST(PrtViewPixels, MontageLabelsAboveTheColumnsAndCaptionBelow) {
  const std::string blob =
      flat_blob("label.prtk", {{-1.0f, -1.0f, 1.0f, 1.0f}}, {0.2f, 0.2f, 0.2f});
  const std::string tile = scratch().file("label_tile.png");
  const prt_test::CommandResult made =
      run_view(quote(blob) + " --env " + quote(constant_map()) +
                   " --headless --size 90x180 --out " + quote(tile),
               "label_tile");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const std::string out = scratch().file("labelled.png");
  const prt_test::CommandResult run =
      run_view("--montage " + quote(out) + " --montage-columns 2 --montage-labels left,right " +
                   "--montage-caption 'one\\ntwo' " + quote(tile) + " " + quote(tile),
               "labelled");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Png png = read_png(out), single = read_png(tile);
  ASSERT_EQ(png.width, 90 + 4 + 90);
  // Text at 2 pixels per font pixel (a 180-pixel tile): a label row of 24, then the tiles, then two
  // caption lines.
  const int top = 24;
  ASSERT_GT(png.height, top + 180 + 2 * 2 * 10);
  for (int y = 0; y < 180; ++y)
    for (int x = 0; x < 90; ++x) ASSERT_EQ(png.at(94 + x, top + y), single.at(x, y));
  // White label pixels over each column's middle third, black elsewhere in the label row.
  for (int column = 0; column < 2; ++column) {
    int white = 0, other = 0;
    for (int y = 0; y < top; ++y) {
      for (int x = column * 94; x < column * 94 + 90; ++x) {
        const std::array<int, 3> p = png.at(x, y);
        const bool in_middle = x >= column * 94 + 20 && x < column * 94 + 70;
        if (p == std::array<int, 3>{255, 255, 255}) (in_middle ? white : other) += 1;
      }
    }
    EXPECT_GT(white, 20) << "column " << column;
    EXPECT_EQ(other, 0) << "column " << column;
  }
  int caption = 0;
  for (int y = top + 180; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) caption += png.at(x, y)[0] == 255 ? 1 : 0;
  EXPECT_GT(caption, 20);
}

}  // namespace
