// SPDX-License-Identifier: MIT
// Technique wavelet at its extremes, end to end (bake -> truncate -> quantise -> blob -> runtime
// load at full validation -> runtime shading), each against an independent expectation:
// - a vertex inside a closed sphere: an empty row, shading exactly 0;
// - kept coefficients all equal: decoded exactly (both quantisers);
// - N = 16 and N = 128: the unoccluded vertex's scaling coefficients sum to 1/S (integral of
//   cos/pi = 1), the self-check passes;
// - a 10^5:1 sun on a dim sky: an unoccluded vertex against the analytic
//   rho (L_sky (1 - F) + sum over sun texels L_sun dw cos / pi), F the blocker's exact
//   form factor (Lambert's polygon formula), and a vertex under the blocker against the sky term
//   alone: the sharp shadow SH cannot give;
// - determinism: the blob from 1 and 2 threads bit for bit.
#include <gtest/gtest.h>

#include <prt/prt.h>
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>

#include <cmath>
#include <vector>

#include "prt/baker/wavelet/wavelet_blob.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"
#include "sh/sh_test_scenes.hpp"
#include "support/render_test_scenes.hpp"
#include "wavelet/wavelet_test_util.hpp"

namespace prt::bake {
namespace {

using test::kPi;

struct Baked {
  WaveletTransfer transfer;
  QuantizedWavelet quantized;
  std::vector<std::uint8_t> blob;
};

Baked bake(const Scene& scene, const WaveletTransferSettings& s,
           WaveletQuantizer mode = WaveletQuantizer::Band, unsigned threads = 2) {
  Context ctx;
  ctx.threads = threads;
  Baked b;
  b.transfer = compute_wavelet_transfer(scene, nullptr, s, ctx);
  b.quantized = quantize_wavelet_transfer(b.transfer, mode, s.keep);
  b.blob = build_wavelet_blob(scene, b.quantized, "");
  return b;
}

TEST(WaveletExtremes, VertexInsideAClosedSphereShadesToExactlyZero) {
  Scene scene;
  scene.meshes.push_back(test::make_plane(0.3f, 2));
  scene.meshes.push_back(test::make_icosphere(2, 2.0f));
  WaveletTransferSettings s;
  s.size = 16;
  s.keep = 100;
  s.vertex_list = {4};  // the plane's centre
  const Baked b = bake(scene, s);
  EXPECT_EQ(b.transfer.row_size(4), 0u);
  EXPECT_GT(b.transfer.rays_traced, 0u);
  test::RuntimeAsset a;
  ASSERT_EQ(a.load(b.blob), PRT_OK) << a.message();
  std::vector<float> light(6 * 256 * 4, 1e6f);
  const std::vector<glm::vec3> shaded = test::runtime_shade(a, light);
  EXPECT_EQ(shaded[4], glm::vec3(0.0f));
  EXPECT_TRUE(check_wavelet_blob(b.blob, b.transfer, b.quantized).passed);
}

TEST(WaveletExtremes, AllEqualKeptCoefficientsDecodeExactly) {
  WaveletTransfer t;
  t.param = PRT_WAVELET_PARAM_CUBE;
  t.size = 16;
  t.vertex_count = 3;
  t.coefficient_count = 1536;
  const float value = 127.0f * std::ldexp(1.0f, -9);  // m/127 = 2^-9, exact
  for (std::uint32_t j : {3u, 40u, 700u, 1200u, 1535u}) {
    t.index.push_back(j);
    t.value.push_back(j % 2 ? value : -value);
  }
  t.row_start = {0, 0, 5, 5};
  t.albedo = {glm::vec3(1.0f), glm::vec3(0.5f, 1.0f, 0.25f), glm::vec3(1.0f)};
  t.baked = {1, 1, 1};
  Scene scene;
  scene.meshes.push_back(test::make_plane(1.0f, 1));
  scene.meshes[0].positions.pop_back();  // three vertices
  scene.meshes[0].normals.pop_back();
  scene.meshes[0].indices = {0, 1, 2};
  for (WaveletQuantizer mode : {WaveletQuantizer::Vertex, WaveletQuantizer::Band}) {
    const QuantizedWavelet q = quantize_wavelet_transfer(t, mode, 5);
    test::RuntimeAsset a;
    ASSERT_EQ(a.load(build_wavelet_blob(scene, q, "")), PRT_OK) << a.message();
    std::vector<float> row(1536 * 3);
    ASSERT_EQ(prt_wavelet_decode_transfer(a.asset, 1, 1, row.data()), PRT_OK);
    for (std::size_t p = 0; p < 5; ++p) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(row[t.index[p] * 3 + c], t.value[p] * t.albedo[1][c]) << p;
      }
    }
  }
}

// A vertex at the centre of an empty plane at face size S, under a sky of radiance 1: the light's
// texels are their solid angles (SPEC §14), so the row's dot product with their Haar transform is
// the cosine-weighted unoccluded fraction of the sky, 1 minus the sphere's form factor.
void check_size(std::uint32_t size) {
  Scene scene;
  scene.meshes.push_back(test::make_plane(1.0f, 2));
  scene.meshes.push_back(test::make_icosphere(1, 0.2f, {0.6f, 0.5f, 0.0f}));
  WaveletTransferSettings s;
  s.size = size;
  s.keep = default_wavelet_keep(PRT_WAVELET_PARAM_CUBE, size);
  s.vertex_list = {4, 0, 8};
  const Baked b = bake(scene, s);
  std::vector<float> sky(6u * size * size);
  for (std::uint32_t f = 0; f < 6; ++f) {
    for (std::uint32_t y = 0; y < size; ++y)
      for (std::uint32_t x = 0; x < size; ++x)
        sky[(f * size + y) * size + x] =
            float(prt_wavelet_texel_solid_angle(PRT_WAVELET_PARAM_CUBE, size, f, x, y));
    ASSERT_EQ(prt_haar_forward(size, 1, sky.data() + f * size * size), PRT_OK);
  }
  double lit = 0.0;
  for (std::uint64_t p = b.transfer.row_start[4]; p < b.transfer.row_start[5]; ++p) {
    lit += double(b.transfer.value[p]) * sky[b.transfer.index[p]];
  }
  // The sphere (radius 0.2 at distance 0.78) hides less than (0.2/0.78)^2 of the cosine-weighted
  // sky from the centre vertex: 0.9 < lit <= 1 (plus the sampling bound of the transfer test
  // and the truncation to 4 % of the coefficients).
  EXPECT_LE(lit, 1.0 + 0.01) << size;
  EXPECT_GE(lit, 0.9) << size;
  EXPECT_LE(b.transfer.row_size(4), s.keep);
  const WaveletBlobCheck check = check_wavelet_blob(b.blob, b.transfer, b.quantized);
  EXPECT_TRUE(check.passed) << check.message;
  test::RuntimeAsset a;
  ASSERT_EQ(a.load(b.blob), PRT_OK);
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  ASSERT_EQ(prt_wavelet_get_info(a.asset, &info), PRT_OK);
  EXPECT_EQ(info.size, size);
  EXPECT_EQ(info.coefficient_count, 6u * size * size);
}

TEST(WaveletExtremes, FaceSize16) {
  check_size(16);
}
TEST(WaveletExtremes, FaceSize128) {
  check_size(128);
}

// The sun: radius 1.5 deg at elevation 60 deg towards +X, 10^5 times the sky's radiance 1.
constexpr float kSun = 1e5f, kSunRadius = 1.5f * float(kPi) / 180.0f;
const glm::vec3 kSunDir(0.5f, 0.8660254f, 0.0f);

io::EnvMap sun_map() {
  return test::make_function_map(1024, [](glm::vec3 d) {
    return glm::dot(d, kSunDir) >= std::cos(kSunRadius) ? glm::vec3(kSun) : glm::vec3(1.0f);
  });
}

// rho/pi * sum over the map's sun texels of L dw max(0, n.w), visible ones only (none when the
// blocker hides the sun), plus rho L_sky (1 - blocker form factor).
double expected_radiance(const io::EnvMap& map, const std::vector<glm::dvec3>& blocker_from_vertex,
                         bool sun_visible) {
  double sun = 0.0;
  for (int y = 0; y < map.height() && sun_visible; ++y) {
    for (int x = 0; x < map.width(); ++x) {
      glm::vec3 d;
      float omega;
      if (!map.texel(x, y, &d, &omega) || map.texel_value(x, y).r < 2.0f) continue;
      sun += double(kSun - 1.0f) * omega * std::max(0.0f, d.y) / kPi;
    }
  }
  const double form_factor = test::clamped_cosine_integral(blocker_from_vertex, {0, 1, 0}) / kPi;
  return 0.8 * (sun + 1.0 * (1.0 - form_factor));
}

TEST(WaveletExtremes, SunOfTenToTheFiveCastsASharpShadow) {
  // Plane y = 0, 9 x 9 vertices 0.5 apart; a square blocker of half-size 0.25 at height 0.866
  // centred on the sun's direction from the plane's centre (vertex 40), so the sun (1.5 deg) is
  // hidden with more than 10 deg to spare; vertex 37 at x = -1.5 sees the sun past it.
  Scene scene;
  scene.meshes.push_back(test::make_plane(2.0f, 8));
  const float h = 0.8660254f;
  const std::vector<glm::vec3> quad = {
      {0.25f, h, -0.25f}, {0.75f, h, -0.25f}, {0.75f, h, 0.25f}, {0.25f, h, 0.25f}};
  Mesh blocker;
  blocker.name = "blocker";
  blocker.positions = quad;
  blocker.normals.assign(4, glm::vec3(0, -1, 0));
  blocker.indices = {0, 2, 1, 0, 3, 2};
  scene.meshes.push_back(blocker);
  WaveletTransferSettings s;
  s.size = 64;
  s.keep = 1000;
  s.override_albedo = true;
  s.albedo = glm::vec3(0.8f);
  s.vertex_list = {37, 40};
  const Baked b = bake(scene, s);
  test::RuntimeAsset a;
  ASSERT_EQ(a.load(b.blob), PRT_OK) << a.message();
  const io::EnvMap map = sun_map();
  const std::vector<glm::vec3> shaded =
      test::runtime_shade(a, test::runtime_light(map, PRT_WAVELET_PARAM_CUBE, 64));
  auto relative_to = [&](const glm::vec3& p) {
    std::vector<glm::dvec3> out;
    for (const glm::vec3& q : quad) out.push_back(glm::dvec3(q - p));
    return out;
  };
  const double lit = expected_radiance(map, relative_to({-1.5f, 0, 0}), true);
  const double dark = expected_radiance(map, relative_to({0, 0, 0}), false);
  ASSERT_GT(lit, 30.0 * dark);  // the sun dominates
  // Lit: K = 1000 of 24,576 coefficients and 8 bits, within 3 %. Shadowed: the sky alone within
  // 5 %, plus what truncation leaks of the sun (its ringing around the blocker's edge): less than
  // 0.2 % of the lit vertex's light.
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(shaded[37][c], lit, 0.03 * lit) << c;
    EXPECT_NEAR(shaded[40][c], dark, 0.05 * dark + 0.002 * lit) << c;
  }
  // Every coefficient kept, in float: the grid alone, within 2 % for both.
  s.keep = 0;
  Context ctx;
  const WaveletTransfer all = compute_wavelet_transfer(scene, nullptr, s, ctx);
  const std::vector<glm::vec3> exact =
      shade_wavelet_transfer(all, test::runtime_light(map, PRT_WAVELET_PARAM_CUBE, 64));
  EXPECT_NEAR(exact[37].g, lit, 0.02 * lit);
  EXPECT_NEAR(exact[40].g, dark, 0.02 * dark);
}

TEST(WaveletExtremes, SameBlobForOneAndTwoThreads) {
  Scene scene;
  scene.meshes.push_back(test::make_plane(1.0f, 6));
  scene.meshes.push_back(test::make_icosphere(1, 0.4f, {0.0f, 0.5f, 0.0f}));
  WaveletTransferSettings s;
  s.size = 16;
  s.keep = 60;
  s.seed = 11;
  EXPECT_EQ(bake(scene, s, WaveletQuantizer::Band, 1).blob,
            bake(scene, s, WaveletQuantizer::Band, 2).blob);
  s.param = PRT_WAVELET_PARAM_DUAL_PARABOLOID;
  s.size = 32;
  EXPECT_EQ(bake(scene, s, WaveletQuantizer::Vertex, 1).blob,
            bake(scene, s, WaveletQuantizer::Vertex, 2).blob);
}

}  // namespace
}  // namespace prt::bake
