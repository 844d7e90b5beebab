// SPDX-License-Identifier: MIT
// prt-view on `sh` blobs (the frozen golden bake, and blobs built here) under maps written here,
// and the options and failures every blob shares. Expected values come from elsewhere:
// per-vertex radiance recomputed here from the decoded transfer (dot products written out, not
// prt_sh_shade) with the runtime's projection of the map as stored, or with the SH coefficients
// of a linear sky worked out by hand; image sizes from the request; and properties (a full turn
// is no turn, backends agree, a reference of itself has no error, a quarter turn equals a
// quarter shift of the map's columns).
#include <gtest/gtest.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <prt/prt.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sh/sh_blob_test_util.hpp"
#include "viewer/viewer_test_util.hpp"

namespace {

using namespace prt_view_test;

const std::string kBlob = golden("sh_quad.prtk");  // order 3, 8 vertices, 4 triangles

// Decoded transfer . light per vertex and channel, summed in double. `light`: order² RGB
// coefficients, or empty for the runtime's projection of the lat-long file `map` as stored.
std::vector<float> shade_independently(const std::string& blob, std::vector<float> light,
                                       const std::string& map = "") {
  auto [context, made] = prt::create_context();
  EXPECT_EQ(made, PRT_OK);
  auto [asset, loaded] = prt::load_asset_file(context.get(), blob.c_str(), PRT_VALIDATE_FULL);
  EXPECT_EQ(loaded, PRT_OK) << blob;
  if (!asset) return {};
  prt_sh_info info = prt::sized<prt_sh_info>();
  EXPECT_EQ(prt_sh_get_info(asset.get(), &info), PRT_OK);
  const std::uint32_t n2 = info.order * info.order;
  if (light.empty()) {
    int width = 0, height = 0;
    const std::vector<float> pixels = read_hdr(map, &width, &height);
    light.resize(3 * n2);
    const prt_env_image env = prt::latlong_env(width, height, pixels.data());
    EXPECT_EQ(prt_sh_project(info.order, &env, light.data()), PRT_OK);
  }
  EXPECT_EQ(light.size(), 3u * n2);
  std::vector<float> transfer(std::size_t(info.vertex_count) * info.channels * n2);
  EXPECT_EQ(prt_sh_decode_transfer(asset.get(), 0, info.vertex_count, transfer.data()), PRT_OK);
  std::vector<float> radiance(3 * std::size_t(info.vertex_count));
  for (std::size_t v = 0; v < info.vertex_count; ++v) {
    for (std::uint32_t ch = 0; ch < 3; ++ch) {
      const float* t = &transfer[(v * info.channels + (info.channels == 3 ? ch : 0)) * n2];
      double sum = 0.0;
      for (std::uint32_t k = 0; k < n2; ++k) sum += double(t[k]) * light[3 * k + ch];
      radiance[3 * v + ch] = float(sum);
    }
  }
  return radiance;
}

// A sky linear in the direction, L_c(d) = a_c + b_c . d: positive everywhere, and its SH
// projection is known in closed form (below).
const double kLinearA[3] = {1.0, 0.8, 1.2};
const double kLinearB[3][3] = {{0.5, 0.2, -0.3}, {-0.2, 0.4, 0.1}, {0.1, -0.3, 0.6}};

void linear_sky(const double d[3], float rgb[3]) {
  for (int c = 0; c < 3; ++c)
    rgb[c] =
        float(kLinearA[c] + kLinearB[c][0] * d[0] + kLinearB[c][1] * d[1] + kLinearB[c][2] * d[2]);
}

// The linear sky's SH coefficients: Y00 is constant, so c00 = 4 pi a Y00; each band-1 function
// is linear, Y1m(d) = g_m . d with g_m its values on the axes, and the integral of d_i d_j over
// the sphere is 4 pi/3 delta_ij, so c1m = 4 pi/3 b . g_m; higher bands are orthogonal to both.
// The basis values come from prt_sh_eval (the runtime's basis, tested on its own).
std::vector<float> linear_sky_sh(std::uint32_t order) {
  std::vector<float> light(3u * order * order, 0.0f);
  const float axes[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  float basis[3][4];
  for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(prt_sh_eval(2, axes[axis], basis[axis]), PRT_OK);
  for (int c = 0; c < 3; ++c) {
    light[c] = float(4.0 * kPi * kLinearA[c] * basis[0][0]);
    for (int m = 1; m < 4; ++m) {
      double dot = 0.0;
      for (int axis = 0; axis < 3; ++axis) dot += kLinearB[c][axis] * basis[axis][m];
      light[3 * m + c] = float(4.0 * kPi / 3.0 * dot);
    }
  }
  return light;
}

// An `sh` blob built here (order 4, 37 vertices: not a multiple of any SIMD width), so the
// backends also shade a partial last group.
std::string odd_sh_blob() {
  const prt_test::Transfer t = prt_test::random_transfer(4, 37, 3, 8, 11);
  return write_blob("odd_sh.prtk", prt_test::make_blob(prt_test::encode(t), t.vertices));
}

TEST(PrtView, WritesPngOfRequestedSize) {
  const std::string png = scratch().file("size.png");
  const prt_test::CommandResult run =
      run_view(quote(kBlob) + " --env " + quote(write_test_sky()) +
                   " --headless --size 160x90 --backend cpu --out " + quote(png),
               "size");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  int w = 0, h = 0, c = 0;
  ASSERT_TRUE(stbi_info(png.c_str(), &w, &h, &c)) << run.output;
  EXPECT_EQ(w, 160);
  EXPECT_EQ(h, 90);
  EXPECT_NE(run.output.find("wrote " + png), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("sh_quad.prtk: 8 vertices, 4 triangles, sh order 3, shadowed transfer, "
                            "3 channel(s)"),
            std::string::npos)
      << run.output;
}

TEST(PrtView, VertexOutMatchesDotProductsOfDecodedTransfer) {
  const std::string sky = write_test_sky();
  for (const std::string& blob : {kBlob, odd_sh_blob()}) {
    const std::vector<float> shaded = view_vertices(blob, sky, "cpu", "--backend cpu");
    const std::vector<float> expected = shade_independently(blob, {}, sky);
    ASSERT_EQ(shaded.size(), expected.size()) << blob;
    ASSERT_FALSE(shaded.empty());
    // Float shading against double sums: rounding only.
    EXPECT_LT(relative_difference(shaded, expected), 1e-5) << blob;
  }
}

// The same linear sky as a lat-long, a vertical cross and a probe file: prt-view reads each in
// its own mapping (the cross and the probe resampled to cube faces), and the shaded radiance
// matches the closed-form light to the discretisation error of each map: the midpoint rule over
// the lat-long's 32 rows (the largest), bilinear resampling of the probe, RGBE rounding. A cross
// face or the probe's axis taken the wrong way round fails by far.
TEST(PrtView, EveryMappingOfALinearSkyGivesItsClosedFormLight) {
  struct Case {
    std::string map;
    const char* mapping;
    double tolerance;  // about twice the measured difference
  };
  const Case cases[] = {
      {write_hdr("linear_latlong.hdr", 64, 32, latlong_map(linear_sky, 64, 32)), "latlong", 1e-3},
      {write_hdr("linear_cross.hdr", 48, 64, cross_map(linear_sky, 16)), "cross", 1.5e-4},
      {write_hdr("linear_probe.hdr", 64, 64, probe_map(linear_sky, 64)), "probe", 6e-4}};
  const std::vector<float> expected = shade_independently(kBlob, linear_sky_sh(3));
  for (const Case& c : cases) {
    const std::string name = std::string("linear_") + c.mapping;
    const std::vector<float> shaded = view_vertices(kBlob, c.map, name, "--backend cpu");
    ASSERT_EQ(shaded.size(), expected.size()) << c.mapping;
    const double difference = relative_difference(shaded, expected);
    std::printf("%s: relative RMS difference %.2e\n", c.mapping, difference);
    EXPECT_LT(difference, c.tolerance) << c.mapping;
    const std::string log = prt_test::read_text(scratch().file(name + ".log"));
    EXPECT_NE(log.find(std::string(" ") + c.mapping + " map"), std::string::npos) << log;
  }
}

TEST(PrtView, FullTurnEqualsNoTurn) {
  const std::string sky = write_test_sky();
  const std::vector<float> a = view_vertices(kBlob, sky, "turn0", "--backend cpu --rotate 0");
  const std::vector<float> b = view_vertices(kBlob, sky, "turn360", "--backend cpu --rotate 360");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  EXPECT_LT(relative_difference(b, a), 1e-5);
}

// Turning the light a quarter about +Y equals shifting the lat-long columns by W/4
// (formats/SPEC.md): turned(x) = original(x + W/4).
TEST(PrtView, QuarterTurnEqualsQuarterColumnShiftOfTheMap) {
  const std::string sky = write_test_sky();
  int width = 0, height = 0;
  const std::vector<float> pixels = read_hdr(sky, &width, &height);
  ASSERT_EQ(width % 4, 0);
  const std::string shifted =
      write_hdr("sky_shifted.hdr", width, height, quarter_turned(pixels, width, height));
  const std::vector<float> turned =
      view_vertices(kBlob, sky, "turn90", "--backend cpu --rotate 90");
  const std::vector<float> expected = view_vertices(kBlob, shifted, "shifted", "--backend cpu");
  ASSERT_EQ(turned.size(), expected.size());
  // The SH of a turned light vary smoothly with the turn: rounding only, as for the full turn.
  EXPECT_LT(relative_difference(turned, expected), 1e-5);
  const std::vector<float> unturned = view_vertices(kBlob, sky, "turn0b", "--backend cpu");
  EXPECT_GT(relative_difference(unturned, expected), 1e-2);  // the turn does something
}

TEST(PrtView, CpuAndAutoBackendsAgree) {
  const std::string sky = write_test_sky();
  for (const std::string& blob : {kBlob, odd_sh_blob()}) {
    const std::vector<float> cpu = view_vertices(blob, sky, "agree_cpu", "--backend cpu");
    const std::vector<float> best = view_vertices(blob, sky, "agree_auto", "--backend auto");
    ASSERT_EQ(cpu.size(), best.size());
    // SIMD sums in float (prt_sh_asset.h): rounding of a 16-term dot product.
    EXPECT_LT(relative_difference(best, cpu), 1e-5) << blob;
  }
}

TEST(PrtView, GlBackendAgreesWithCpu) {
  if (!PRT_VIEW_HAS_GL) GTEST_SKIP() << "built without the headless GL helper";
  const std::string sky = write_test_sky();
  for (const std::string& blob : {kBlob, odd_sh_blob()}) {
    const std::vector<float> cpu = view_vertices(blob, sky, "gl_cpu", "--backend cpu");
    const std::vector<float> gl = view_vertices(blob, sky, "gl_gl", "--backend gl --frames 3");
    ASSERT_EQ(cpu.size(), gl.size());
    EXPECT_LT(relative_difference(gl, cpu), 1e-5) << blob;
  }
}

TEST(PrtView, ReferenceOfItselfHasZeroErrorAndDrawsAHeatMap) {
  const std::string sky = write_test_sky();
  view_vertices(kBlob, sky, "self", "--backend cpu");
  const std::string heat = scratch().file("heat.png");
  const prt_test::CommandResult run =
      run_view(quote(kBlob) + " --env " + quote(sky) + " --headless --backend cpu --size 64x48 " +
                   "--reference " + quote(scratch().file("self.npy")) + " --error-out " +
                   quote(heat) + " --frames 3",
               "self_compare");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("relative RMSE 0.00000 (0.00 %)"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("3 frame(s), median"), std::string::npos) << run.output;
  int w = 0, h = 0, c = 0;
  EXPECT_TRUE(stbi_info(heat.c_str(), &w, &h, &c));
  EXPECT_EQ(w, 64);
}

TEST(PrtView, ReferenceOfAnotherSizeFailsNamingBoth) {
  const std::string sky = write_test_sky();
  view_vertices(odd_sh_blob(), sky, "odd", "--backend cpu");
  const prt_test::CommandResult run =
      run_view(quote(kBlob) + " --env " + quote(sky) + " --headless --reference " +
                   quote(scratch().file("odd.npy")),
               "wrong_reference");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("odd.npy: 37 vertices, the blob has 8"), std::string::npos)
      << run.output;
}

TEST(PrtView, BadBlobFailsNamingTheFile) {
  const std::string not_blob = scratch().write("not_a_blob.prtk", "hello");
  const prt_test::CommandResult run =
      run_view(quote(not_blob) + " --env " + quote(write_test_sky()) + " --headless --out x.png",
               "bad_blob");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("not_a_blob.prtk: "), std::string::npos) << run.output;
}

TEST(PrtView, MissingMapFailsNamingTheFile) {
  const prt_test::CommandResult run =
      run_view(quote(kBlob) + " --env " + quote(scratch().file("no_such_sky.hdr")) +
                   " --headless --out x.png",
               "missing_map");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("no_such_sky.hdr: cannot open file"), std::string::npos) << run.output;
}

// A backend the context may not use (limited here through PRT_BACKEND, as on a CPU without
// SSE4.1) fails with the runtime's result and reason, not a crash or a silent fallback.
TEST(PrtView, UnusableBackendFailsWithTheRuntimesReason) {
  const std::string sky = write_test_sky();
  for (const char* backend : {"simd", "gl"}) {
    if (!PRT_VIEW_HAS_GL && std::string(backend) == "gl") continue;
    const prt_test::CommandResult run = run_view(
        quote(kBlob) + " --env " + quote(sky) + " --headless --frames 2 --backend " + backend,
        std::string("limited_") + backend, "PRT_BACKEND=cpu");
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find(std::string("backend ") + backend + ": "), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("PRT_ERROR_UNSUPPORTED_BACKEND"), std::string::npos) << run.output;
  }
}

TEST(PrtView, BadArgumentsExitTwo) {
  const std::string sky = quote(write_test_sky()), blob = quote(kBlob);
  EXPECT_EQ(
      run_view(blob + " --env " + sky + " --headless --backend vulkan --out x.png", "bad_backend")
          .exit_code,
      2);
  EXPECT_EQ(run_view(blob + " --env " + sky + " --out x.png", "no_headless").exit_code, 2);
  EXPECT_EQ(run_view(blob + " --headless --out x.png", "no_env").exit_code, 2);
  EXPECT_EQ(
      run_view(blob + " --env " + sky + " --headless --size 12 --out x.png", "bad_size").exit_code,
      2);
  EXPECT_EQ(run_view(blob + " --env " + sky + " --headless", "nothing_to_do").exit_code, 2);
  EXPECT_EQ(run_view(blob + " --env " + sky + " --headless --out x.png --error-out e.png",
                     "error_out_alone")
                .exit_code,
            2);
}

TEST(PrtView, MontageTilesImages) {
  const std::string a = scratch().file("tile_a.png"), b = scratch().file("tile_b.png");
  const std::string out = scratch().file("tiles.png");
  const unsigned char red[3 * 4 * 2] = {255, 0, 0, 255, 0, 0, 255, 0, 0, 255, 0, 0,
                                        255, 0, 0, 255, 0, 0, 255, 0, 0, 255, 0, 0};
  ASSERT_TRUE(stbi_write_png(a.c_str(), 4, 2, 3, red, 12));
  ASSERT_TRUE(stbi_write_png(b.c_str(), 4, 2, 3, red, 12));
  const prt_test::CommandResult run = run_view(
      "--montage " + quote(out) + " --montage-columns 1 " + quote(a) + " " + quote(b), "montage");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  int w = 0, h = 0, c = 0;
  ASSERT_TRUE(stbi_info(out.c_str(), &w, &h, &c));
  EXPECT_EQ(w, 4);
  EXPECT_EQ(h, 2 + 4 + 2);  // two tiles and a 4-pixel gap
}

}  // namespace
