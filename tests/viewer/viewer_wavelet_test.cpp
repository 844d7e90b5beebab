// SPDX-License-Identifier: MIT
// prt-view on a `wavelet` blob (the demo scene baked on a 16-texel cube by the
// viewer_bake_demo_blob fixture). Expected values come from elsewhere: per-vertex radiance
// recomputed here as dot products of the decoded rows (prt_wavelet_decode_transfer, which applies the
// band and vertex scales) with the light's Haar coefficients, and properties (a full turn is no
// turn, a quarter turn is a quarter shift of the map's columns, backends agree, fewer light
// coefficients change the result).
#include <gtest/gtest.h>
#include <prt/prt.hpp>
#include <stb_image.h>
#include <stb_image_write.h>

#include <sys/wait.h>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

const std::string kDir = PRT_VIEW_TEST_DIR;
const std::string kBlob = kDir + "/demo_wavelet16.prtk";
const std::string kSky = kDir + "/demo_sky.hdr";

// Runs prt-view with `arguments`; returns its exit code, output in *output.
int run_view(const std::string& arguments, const std::string& name, std::string* output) {
  const std::string log = kDir + "/wavelet_" + name + ".log";
  const std::string command =
      "\"" + std::string(PRT_VIEW_EXE) + "\" " + arguments + " > \"" + log + "\" 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  output->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// float32 [N,3] .npy (read without the viewer's code).
std::vector<float> read_npy(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (bytes.size() < 10 || bytes[6] != 1) return {};
  const std::size_t header = bytes[8] | (bytes[9] << 8);
  std::vector<float> values((bytes.size() - 10 - header) / 4);
  std::memcpy(values.data(), bytes.data() + 10 + header, values.size() * 4);
  return values;
}

// Per-vertex radiance of `blob_map` (a lat-long file) through prt-view with extra options.
std::vector<float> view_vertices(const std::string& map, const std::string& name,
                                 const std::string& extra) {
  const std::string out = kDir + "/wavelet_" + name + ".npy";
  std::string output;
  EXPECT_EQ(run_view(kBlob + " --env " + map + " --headless --vertex-out " + out + " " + extra,
                     name, &output),
            0)
      << output;
  return read_npy(out);
}

double relative_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double diff = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    diff += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    norm += double(b[i]) * b[i];
  }
  return std::sqrt(diff / norm);
}

std::vector<float> load_sky(int* width, int* height) {
  int channels = 0;
  float* data = stbi_loadf(kSky.c_str(), width, height, &channels, 3);
  EXPECT_NE(data, nullptr);
  std::vector<float> pixels(data, data + std::size_t(*width) * *height * 3);
  stbi_image_free(data);
  return pixels;
}

// Decoded rows . Haar coefficients of the sky (resampled and transformed by the runtime, all
// kept), summed in double here.
std::vector<float> shade_independently() {
  int width = 0, height = 0;
  const std::vector<float> pixels = load_sky(&width, &height);
  prt_context* context = nullptr;
  prt_asset* asset = nullptr;
  EXPECT_EQ(prt_context_create(nullptr, &context), PRT_OK);
  EXPECT_EQ(prt_asset_load_file(context, kBlob.c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK);
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
  prt_asset_destroy(asset);
  prt_context_destroy(context);
  return radiance;
}

TEST(PrtViewWavelet, VertexOutMatchesDotProductsOfDecodedRows) {
  const std::vector<float> shaded = view_vertices(kSky, "cpu", "--backend cpu");
  const std::vector<float> expected = shade_independently();
  ASSERT_EQ(shaded.size(), expected.size());
  ASSERT_FALSE(shaded.empty());
  EXPECT_LT(relative_difference(shaded, expected), 1e-5);  // float sums vs double: rounding
}

TEST(PrtViewWavelet, PrintsTheBlobsWaveletHeader) {
  std::string output;
  ASSERT_EQ(run_view(kBlob + " --env " + kSky + " --headless --frames 2", "header", &output), 0)
      << output;
  EXPECT_NE(output.find("wavelet cube 16"), std::string::npos) << output;
  EXPECT_NE(output.find("light coefficients kept"), std::string::npos) << output;
}

TEST(PrtViewWavelet, FullTurnEqualsNoTurn) {
  const std::vector<float> a = view_vertices(kSky, "turn0", "--backend cpu");
  const std::vector<float> b = view_vertices(kSky, "turn360", "--backend cpu --rotate 360");
  ASSERT_EQ(a.size(), b.size());
  EXPECT_LT(relative_difference(b, a), 1e-4);
}

// A quarter turn about +Y moves every lat-long texel centre onto the centre of the texel W/4
// columns over (tests/baker/render/env_rotation_test.cpp), so the splat lands the same power in
// the same cube texels: equal up to rounding of the rotated directions at texel boundaries.
TEST(PrtViewWavelet, QuarterTurnEqualsQuarterColumnShiftOfTheMap) {
  int width = 0, height = 0;
  const std::vector<float> pixels = load_sky(&width, &height);
  ASSERT_EQ(width % 4, 0);
  std::vector<float> shifted(pixels.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int from = (x + width / 4) % width;
      for (int c = 0; c < 3; ++c)
        shifted[(y * width + x) * 3 + c] = pixels[(y * width + from) * 3 + c];
    }
  }
  const std::string shifted_path = kDir + "/wavelet_sky_shifted.hdr";
  ASSERT_TRUE(stbi_write_hdr(shifted_path.c_str(), width, height, 3, shifted.data()));
  const std::vector<float> turned = view_vertices(kSky, "turn90", "--backend cpu --rotate 90");
  const std::vector<float> expected = view_vertices(shifted_path, "shifted", "--backend cpu");
  ASSERT_EQ(turned.size(), expected.size());
  EXPECT_LT(relative_difference(turned, expected), 1e-3);
  const std::vector<float> unturned = view_vertices(kSky, "turn0b", "--backend cpu");
  EXPECT_GT(relative_difference(unturned, expected), 1e-2);  // the turn does something
}

TEST(PrtViewWavelet, BackendsAgree) {
  const std::vector<float> cpu = view_vertices(kSky, "agree_cpu", "--backend cpu");
  const std::vector<float> best = view_vertices(kSky, "agree_auto", "--backend auto");
  ASSERT_EQ(cpu.size(), best.size());
  EXPECT_LT(relative_difference(best, cpu), 1e-5);
  if (!PRT_VIEW_HAS_GL) GTEST_SKIP() << "built without the headless GL helper";
  const std::vector<float> gl = view_vertices(kSky, "agree_gl", "--backend gl --frames 2");
  ASSERT_EQ(cpu.size(), gl.size());
  EXPECT_LT(relative_difference(gl, cpu), 1e-5);
}

// Keeping only the faces' scaling coefficients (M = 0) shades with each face's mean power: a
// different, blurrier result than keeping all of them.
TEST(PrtViewWavelet, FewerLightCoefficientsChangeTheResult) {
  const std::vector<float> all = view_vertices(kSky, "m_all", "--backend cpu");
  const std::vector<float> none =
      view_vertices(kSky, "m_0", "--backend cpu --light-coefficients 0");
  ASSERT_EQ(all.size(), none.size());
  EXPECT_GT(relative_difference(none, all), 1e-2);
}

}  // namespace
