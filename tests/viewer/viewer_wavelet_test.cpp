// SPDX-License-Identifier: MIT
// prt-view on `wavelet` blobs (the frozen golden bake on a 16-texel cube, and a blob built here)
// under maps written here. Expected values come from elsewhere: per-vertex radiance recomputed
// here as dot products of the decoded rows (prt_wavelet_decode_transfer, which applies the band
// and vertex scales) with the light's Haar coefficients, and properties (a full turn is no turn,
// a quarter turn is a quarter shift of the map's columns, backends agree, fewer light
// coefficients change the result, the three mappings of one sky give one light).
#include <gtest/gtest.h>
#include <prt/prt.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "viewer/viewer_test_util.hpp"
#include "wavelet/wavelet_blob_test_util.hpp"

namespace {

using namespace prt_view_test;

const std::string kBlob = golden("wavelet_quad.prtk");  // cube 16, 8 vertices, 4 triangles

// A `wavelet` blob built here (37 vertices: not a multiple of any SIMD width).
std::string odd_wavelet_blob() {
  const prt_test::WvltTransfer t = prt_test::wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 37, 40, 3);
  return write_blob("odd_wavelet.prtk", prt_test::wvlt_make_blob(prt_test::wvlt_encode(t), 37));
}

// Decoded rows . Haar coefficients of the sky (resampled and transformed by the runtime, all
// kept), summed in double here.
std::vector<float> shade_independently(const std::string& blob, const std::string& map) {
  int width = 0, height = 0;
  const std::vector<float> pixels = read_hdr(map, &width, &height);
  auto [context, made] = prt::create_context();
  EXPECT_EQ(made, PRT_OK);
  auto [owned, loaded] = prt::load_asset_file(context.get(), blob.c_str(), PRT_VALIDATE_FULL);
  EXPECT_EQ(loaded, PRT_OK) << blob;
  if (!owned) return {};
  const prt_asset* asset = owned.get();
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  EXPECT_EQ(prt_wavelet_get_info(asset, &info), PRT_OK);
  std::vector<float> light(4u * info.coefficient_count);
  const prt_env_image env = prt::latlong_env(width, height, pixels.data());
  EXPECT_EQ(prt_wavelet_resample(info.param, info.size, &env, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_transform_light(info.param, info.size, light.data()), PRT_OK);
  std::vector<float> row(3u * info.coefficient_count), radiance(3u * info.vertex_count);
  for (std::uint32_t v = 0; v < info.vertex_count; ++v) {
    EXPECT_EQ(prt_wavelet_decode_transfer(asset, v, 1, row.data()), PRT_OK);
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (std::uint32_t j = 0; j < info.coefficient_count; ++j)
        sum += double(row[3 * j + c]) * light[4 * j + c];
      radiance[3 * v + c] = float(sum);
    }
  }
  return radiance;
}

TEST(PrtViewWavelet, VertexOutMatchesDotProductsOfDecodedRows) {
  const std::string sky = write_test_sky();
  for (const std::string& blob : {kBlob, odd_wavelet_blob()}) {
    const std::vector<float> shaded = view_vertices(blob, sky, "cpu", "--backend cpu");
    const std::vector<float> expected = shade_independently(blob, sky);
    ASSERT_EQ(shaded.size(), expected.size()) << blob;
    ASSERT_FALSE(shaded.empty());
    EXPECT_LT(relative_difference(shaded, expected), 1e-5) << blob;  // float sums vs double
  }
}

TEST(PrtViewWavelet, PrintsTheBlobsWaveletHeader) {
  const prt_test::CommandResult run = run_view(
      quote(kBlob) + " --env " + quote(write_test_sky()) + " --headless --frames 2", "header");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("wavelet_quad.prtk: 8 vertices, 4 triangles, wavelet cube 16, 24.0 "
                            "non-zeros per vertex (48 bytes), per face and level quantiser"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("64x32 latlong map, resampled onto the blob's 1536 coefficients by "
                            "the runtime, rotated 0 deg about +Y, 6 + 1530 light coefficients "
                            "kept (area-weighted)"),
            std::string::npos)
      << run.output;
}

TEST(PrtViewWavelet, FullTurnEqualsNoTurn) {
  const std::string sky = write_test_sky();
  const std::vector<float> a = view_vertices(kBlob, sky, "turn0", "--backend cpu");
  const std::vector<float> b = view_vertices(kBlob, sky, "turn360", "--backend cpu --rotate 360");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  EXPECT_LT(relative_difference(b, a), 1e-4);
}

// A quarter turn about +Y moves every lat-long texel centre onto the centre of the texel W/4
// columns over (formats/SPEC.md), so the splat lands the same power in the same cube texels:
// equal up to rounding of the rotated directions at texel boundaries.
TEST(PrtViewWavelet, QuarterTurnEqualsQuarterColumnShiftOfTheMap) {
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
  EXPECT_LT(relative_difference(turned, expected), 1e-3);
  const std::vector<float> unturned = view_vertices(kBlob, sky, "turn0b", "--backend cpu");
  EXPECT_GT(relative_difference(unturned, expected), 1e-2);  // the turn does something
}

TEST(PrtViewWavelet, BackendsAgree) {
  const std::string sky = write_test_sky();
  for (const std::string& blob : {kBlob, odd_wavelet_blob()}) {
    const std::vector<float> cpu = view_vertices(blob, sky, "agree_cpu", "--backend cpu");
    const std::vector<float> best = view_vertices(blob, sky, "agree_auto", "--backend auto");
    ASSERT_EQ(cpu.size(), best.size());
    EXPECT_LT(relative_difference(best, cpu), 1e-5) << blob;
    if (!PRT_VIEW_HAS_GL) continue;
    const std::vector<float> gl = view_vertices(blob, sky, "agree_gl", "--backend gl --frames 2");
    ASSERT_EQ(cpu.size(), gl.size());
    EXPECT_LT(relative_difference(gl, cpu), 1e-5) << blob;
  }
  if (!PRT_VIEW_HAS_GL) GTEST_SKIP() << "built without the headless GL helper";
}

// Keeping only the faces' scaling coefficients (M = 0) shades with each face's mean power: a
// different, blurrier result than keeping all of them.
TEST(PrtViewWavelet, FewerLightCoefficientsChangeTheResult) {
  const std::string sky = write_test_sky();
  const std::vector<float> all = view_vertices(kBlob, sky, "m_all", "--backend cpu");
  const std::vector<float> none =
      view_vertices(kBlob, sky, "m_0", "--backend cpu --light-coefficients 0");
  ASSERT_EQ(all.size(), none.size());
  EXPECT_GT(relative_difference(none, all), 1e-2);
}

// One sky as a lat-long, a vertical cross and a probe file: each is read in its own mapping (the
// cross and the probe resampled to cube faces before prt_wavelet_resample), and all three give
// the same shading to the resampling error (the bands are about twice the measured difference).
TEST(PrtViewWavelet, EveryMappingOfOneSkyGivesTheSameLight) {
  const auto smooth_sky = [](const double d[3], float rgb[3]) {
    rgb[0] = float(1.0 + 0.5 * d[0] + 0.3 * d[1] * d[1]);
    rgb[1] = float(0.8 + 0.4 * d[1] - 0.2 * d[2]);
    rgb[2] = float(1.2 - 0.3 * d[0] * d[2] + 0.5 * d[2]);
  };
  const std::string latlong =
      write_hdr("smooth_latlong.hdr", 256, 128, latlong_map(smooth_sky, 256, 128));
  const std::string cross = write_hdr("smooth_cross.hdr", 96, 128, cross_map(smooth_sky, 32));
  const std::string probe = write_hdr("smooth_probe.hdr", 128, 128, probe_map(smooth_sky, 128));
  const std::vector<float> expected =
      view_vertices(kBlob, latlong, "smooth_latlong", "--backend cpu");
  for (const auto& [map, mapping] : {std::pair{cross, "cross"}, std::pair{probe, "probe"}}) {
    const std::vector<float> shaded =
        view_vertices(kBlob, map, std::string("smooth_") + mapping, "--backend cpu");
    ASSERT_EQ(shaded.size(), expected.size()) << mapping;
    const double difference = relative_difference(shaded, expected);
    std::printf("%s: relative RMS difference %.2e\n", mapping, difference);
    EXPECT_LT(difference, 1.5e-3) << mapping;
  }
}

}  // namespace
