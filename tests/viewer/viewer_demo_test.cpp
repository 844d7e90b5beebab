// SPDX-License-Identifier: MIT
// prt-view on a real bake of the project's demo scene (thousands of vertices, `sh` order 4 and
// `wavelet` on a 16 cube, baked by the viewer_demo_bake fixture), built only with the baker: the
// per-vertex radiance equals dot products of the decoded transfer with the runtime's light, on
// every backend; and the published light probes, read by the viewer in their own mappings,
// shade as the baker's texel-by-texel projection (another method) says.
#include <gtest/gtest.h>
#include <prt/prt.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "prt/baker/sh/env_sh.hpp"
#include "prt/io/envmap.hpp"
#include "support/test_files.hpp"
#include "viewer/viewer_test_util.hpp"

namespace {

using namespace prt_view_test;

const std::string kDir = PRT_VIEW_DEMO_DIR;
const std::string kShBlob = kDir + "/demo_sh4.prtk";
const std::string kWaveletBlob = kDir + "/demo_wavelet16.prtk";
const std::string kSky = kDir + "/demo_sky.hdr";

// Decoded transfer . light, summed in double (light: order² RGB coefficients).
std::vector<float> shade_sh(const std::vector<float>& light) {
  auto [context, made] = prt::create_context();
  auto [asset, loaded] = prt::load_asset_file(context.get(), kShBlob.c_str(), PRT_VALIDATE_FULL);
  EXPECT_EQ(loaded, PRT_OK);
  if (!asset) return {};
  prt_sh_info info = prt::sized<prt_sh_info>();
  EXPECT_EQ(prt_sh_get_info(asset.get(), &info), PRT_OK);
  const std::uint32_t n2 = info.order * info.order;
  EXPECT_EQ(light.size(), 3u * n2);
  std::vector<float> transfer(std::size_t(info.vertex_count) * info.channels * n2);
  EXPECT_EQ(prt_sh_decode_transfer(asset.get(), 0, info.vertex_count, transfer.data()), PRT_OK);
  std::vector<float> radiance(3 * std::size_t(info.vertex_count));
  for (std::size_t v = 0; v < info.vertex_count; ++v)
    for (std::uint32_t c = 0; c < 3; ++c) {
      const float* t = &transfer[(v * info.channels + (info.channels == 3 ? c : 0)) * n2];
      double sum = 0.0;
      for (std::uint32_t k = 0; k < n2; ++k) sum += double(t[k]) * light[3 * k + c];
      radiance[3 * v + c] = float(sum);
    }
  return radiance;
}

// The runtime's projection of the demo sky as stored, order 4.
std::vector<float> demo_sky_light() {
  int width = 0, height = 0;
  const std::vector<float> pixels = read_hdr(kSky, &width, &height);
  std::vector<float> light(3 * 16);
  const prt_env_image env = prt::latlong_env(width, height, pixels.data());
  EXPECT_EQ(prt_sh_project(4, &env, light.data()), PRT_OK);
  return light;
}

// Decoded rows . the runtime's Haar light of the demo sky (all kept), summed in double.
std::vector<float> shade_wavelet() {
  int width = 0, height = 0;
  const std::vector<float> pixels = read_hdr(kSky, &width, &height);
  auto [context, made] = prt::create_context();
  auto [asset, loaded] =
      prt::load_asset_file(context.get(), kWaveletBlob.c_str(), PRT_VALIDATE_FULL);
  EXPECT_EQ(loaded, PRT_OK);
  if (!asset) return {};
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  EXPECT_EQ(prt_wavelet_get_info(asset.get(), &info), PRT_OK);
  std::vector<float> light(4u * info.coefficient_count);
  const prt_env_image env = prt::latlong_env(width, height, pixels.data());
  EXPECT_EQ(prt_wavelet_resample(info.param, info.size, &env, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_transform_light(info.param, info.size, light.data()), PRT_OK);
  std::vector<float> row(3u * info.coefficient_count), radiance(3u * info.vertex_count);
  for (std::uint32_t v = 0; v < info.vertex_count; ++v) {
    EXPECT_EQ(prt_wavelet_decode_transfer(asset.get(), v, 1, row.data()), PRT_OK);
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (std::uint32_t j = 0; j < info.coefficient_count; ++j)
        sum += double(row[3 * j + c]) * light[4 * j + c];
      radiance[3 * v + c] = float(sum);
    }
  }
  return radiance;
}

TEST(PrtViewDemo, ShVertexOutMatchesDotProductsOnEveryBackend) {
  const std::vector<float> expected = shade_sh(demo_sky_light());
  ASSERT_FALSE(expected.empty());
  std::vector<std::string> backends = {"cpu", "auto"};
  if (PRT_VIEW_HAS_GL) backends.push_back("gl");
  for (const std::string& backend : backends) {
    const std::vector<float> shaded =
        view_vertices(kShBlob, kSky, "demo_sh_" + backend, "--backend " + backend);
    ASSERT_EQ(shaded.size(), expected.size()) << backend;
    EXPECT_LT(relative_difference(shaded, expected), 1e-5) << backend;
  }
}

TEST(PrtViewDemo, WaveletVertexOutMatchesDotProductsOnEveryBackend) {
  const std::vector<float> expected = shade_wavelet();
  ASSERT_FALSE(expected.empty());
  std::vector<std::string> backends = {"cpu", "auto"};
  if (PRT_VIEW_HAS_GL) backends.push_back("gl");
  for (const std::string& backend : backends) {
    const std::vector<float> shaded =
        view_vertices(kWaveletBlob, kSky, "demo_wavelet_" + backend, "--backend " + backend);
    ASSERT_EQ(shaded.size(), expected.size()) << backend;
    EXPECT_LT(relative_difference(shaded, expected), 1e-5) << backend;
  }
}

// Cross and probe maps go through a cube resampling and prt_sh_project; the baker projects the
// same file texel by texel with each texel's exact solid angle (another method): the shaded
// radiance agrees to a few times the resampling error (the probe's, the larger); a resampling
// turned by half a probe texel differs by far more.
TEST(PrtViewDemo, PublishedCrossAndProbeMatchTheBakersTexelProjection) {
  for (const char* name : {"rnl_cross.hdr", "rnl_probe.hdr"}) {
    const std::string map = prt_test::shared_asset(std::string("envmaps/") + name);
    if (map.empty()) GTEST_SKIP() << "shared/assets/envmaps/" << name << " not found";
    const std::vector<float> shaded =
        view_vertices(kShBlob, map, std::string("demo_") + name, "--backend cpu");
    const prt::io::EnvMap env = prt::io::load_envmap(map, prt::io::EnvMapping::Auto);
    const std::vector<float> expected = shade_sh(prt::bake::project_env_sh(env, 4).to_float());
    ASSERT_EQ(shaded.size(), expected.size());
    const double difference = relative_difference(shaded, expected);
    std::printf("%s: relative RMS difference %.5f\n", name, difference);
    EXPECT_LT(difference, 1e-4) << name;
  }
}

}  // namespace
