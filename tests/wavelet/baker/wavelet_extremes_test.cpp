// SPDX-License-Identifier: MIT
// Technique wavelet at its extremes, end to end (bake -> truncate -> quantise -> blob -> runtime
// load at full validation -> runtime shading), each against an independent expectation:
// - a vertex inside a closed sphere: an empty row, shading exactly 0;
// - kept coefficients all equal: decoded exactly (both quantisers);
// - N = 16 and N = 128: a blocker's form factor from the bake against its exact value
//   (Lambert's polygon formula) within the sampling bound, the truncated row's lit fraction
//   within the Cauchy-Schwarz bound of the full row's, the self-check passes;
// - a 10^5:1 sun on a dim sky: an unoccluded vertex against the analytic
//   rho (L_sky (1 - F) + sum over sun texels L_sun dw cos / pi), F the blocker's exact
//   form factor (Lambert's polygon formula), and a vertex under the blocker against the sky term
//   alone plus the bound on what truncation and quantisation leak of the sun: the sharp shadow
//   SH cannot give;
// - determinism: the blob from 1 and 2 threads bit for bit.
#include <gtest/gtest.h>

#include <prt/prt.h>
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>

#include <algorithm>
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

// A vertex's lit fraction under a sky of radiance 1: the light's texels are their solid angles
// (SPEC §14), so the row's dot product with their Haar transform is the cosine-weighted
// unoccluded fraction of the sky.
class SkyFraction {
 public:
  explicit SkyFraction(std::uint32_t size) : sky_(6u * size * size) {
    for (std::uint32_t f = 0; f < 6; ++f) {
      for (std::uint32_t y = 0; y < size; ++y)
        for (std::uint32_t x = 0; x < size; ++x)
          sky_[(f * size + y) * size + x] =
              float(prt_wavelet_texel_solid_angle(PRT_WAVELET_PARAM_CUBE, size, f, x, y));
      EXPECT_EQ(prt_haar_forward(size, 1, sky_.data() + f * size * size), PRT_OK);
    }
  }
  double lit(const WaveletTransfer& t, std::size_t v) const {
    double sum = 0.0;
    for (std::uint64_t p = t.row_start[v]; p < t.row_start[v + 1]; ++p)
      sum += double(t.value[p]) * sky_[t.index[p]];
    return sum;
  }
  // Cauchy-Schwarz bound on what truncating `full` to `kept` (one vertex's rows, the same
  // coefficients) can change of lit(): the dropped coefficients' norm times the sky's there.
  double truncation_bound(const WaveletTransfer& full, const WaveletTransfer& kept,
                          std::size_t v) const {
    std::vector<bool> is_kept(sky_.size(), false);
    for (std::uint64_t p = kept.row_start[v]; p < kept.row_start[v + 1]; ++p)
      is_kept[kept.index[p]] = true;
    double row = 0.0, sky = 0.0;
    for (std::uint64_t p = full.row_start[v]; p < full.row_start[v + 1]; ++p) {
      if (is_kept[full.index[p]]) continue;
      row += double(full.value[p]) * full.value[p];
      sky += double(sky_[full.index[p]]) * sky_[full.index[p]];
    }
    return std::sqrt(row * sky);
  }

 private:
  std::vector<float> sky_;
};

// Standard deviation bound of the one-ray-per-texel estimate of a convex blocker's form factor
// from the origin (normal +Y), taken as the difference of bakes without and with it (the same
// seed and vertex trace the same rays, so texels the blocker cannot reach cancel exactly). A
// texel that can meet the blocker (within the cap of its circumscribed sphere) contributes
// w V cos / pi at one jittered point, which spans at most w cos_max / pi, variance at most a
// quarter of its square (Popoviciu); inside the cap of the inscribed sphere V is 1 throughout
// and only the cosine varies, by at most the texel's angular diameter.
double blocker_form_factor_sigma(std::uint32_t size, const Mesh& blocker, glm::dvec3 centre,
                                 double radius) {
  double inradius = radius;
  for (std::size_t i = 0; i < blocker.indices.size(); i += 3) {
    const glm::dvec3 a(blocker.positions[blocker.indices[i]]),
        b(blocker.positions[blocker.indices[i + 1]]), c(blocker.positions[blocker.indices[i + 2]]);
    inradius = std::min(inradius,
                        std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), a - centre)));
  }
  const double distance = glm::length(centre);
  const double outer = std::asin(radius / distance), inner = std::asin(inradius / distance);
  const glm::dvec3 towards = centre / distance, up(0, 1, 0);
  auto angle = [](glm::dvec3 a, glm::dvec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0));
  };
  double variance = 0.0;
  for (std::uint32_t f = 0; f < 6; ++f) {
    for (std::uint32_t y = 0; y < size; ++y) {
      for (std::uint32_t x = 0; x < size; ++x) {
        const std::vector<glm::dvec3> corners = test::cube_texel(size, f, x, y);
        const glm::dvec3 mid =
            test::cube_point(f, (2.0 * x + 1.0) / size - 1.0, (2.0 * y + 1.0) / size - 1.0);
        double reach = 0.0, diameter = 0.0;
        for (const glm::dvec3& a : corners) {
          reach = std::max(reach, angle(mid, a));
          for (const glm::dvec3& b : corners) diameter = std::max(diameter, angle(a, b));
        }
        const double from_blocker = angle(mid, towards);
        if (from_blocker - reach > outer) continue;
        const double omega = prt_wavelet_texel_solid_angle(PRT_WAVELET_PARAM_CUBE, size, f, x, y);
        const double cos_max = std::cos(std::max(0.0, angle(mid, up) - reach));
        const double span = from_blocker + reach < inner ? diameter : cos_max;
        variance += std::pow(omega * span / kPi, 2) / 4.0;
      }
    }
  }
  return std::sqrt(variance);
}

// The centre vertex of an empty plane at face size S, beside a blocker (an icosphere: its exact
// form factor is Lambert's formula over its faces): the blocker's form factor from the
// difference of bakes with and without it, within 4 sigma of its sampling bound (and not 0,
// the blocker ignored: the error is a sum of many independent bounded terms and sigma bounds
// its spread from above); the truncated row's lit fraction within the Cauchy-Schwarz bound of
// the full row's; the self-check and the runtime's view of the size.
void check_size(std::uint32_t size) {
  const glm::vec3 centre(0.6f, 0.5f, 0.0f);
  const float radius = 0.2f;
  Scene open;
  open.meshes.push_back(test::make_plane(1.0f, 2));
  Scene scene = open;
  scene.meshes.push_back(test::make_icosphere(1, radius, centre));
  WaveletTransferSettings s;
  s.size = size;
  s.keep = default_wavelet_keep(PRT_WAVELET_PARAM_CUBE, size);
  s.vertex_list = {4, 0, 8};
  const Baked b = bake(scene, s);
  WaveletTransferSettings every = s;
  every.keep = 0;
  Context ctx;
  const WaveletTransfer full = compute_wavelet_transfer(scene, nullptr, every, ctx);
  const WaveletTransfer without = compute_wavelet_transfer(open, nullptr, every, ctx);
  const SkyFraction sky(size);
  const double form_factor =
      test::convex_mesh_clamped_cosine_integral(scene.meshes[1], {0, 0, 0}, {0, 1, 0}) / kPi;
  const double sigma = blocker_form_factor_sigma(size, scene.meshes[1], centre, radius);
  EXPECT_NEAR(sky.lit(without, 4) - sky.lit(full, 4), form_factor, 4.0 * sigma) << size;
  EXPECT_NEAR(sky.lit(b.transfer, 4), sky.lit(full, 4), sky.truncation_bound(full, b.transfer, 4))
      << size;
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

// What truncating vertex v's full row to `kept` and quantising it can change of its shading
// under `light` (Haar coefficients, 4 floats each; grey, before the albedo): the dropped
// coefficients' |t L| plus half a quantisation step times |L| for each kept one.
double leak_bound(const WaveletTransfer& full, const WaveletTransfer& kept,
                  const QuantizedWavelet& quantized, const std::vector<float>& light,
                  std::size_t v) {
  std::vector<bool> is_kept(full.coefficient_count, false);
  for (std::uint64_t p = kept.row_start[v]; p < kept.row_start[v + 1]; ++p)
    is_kept[kept.index[p]] = true;
  double bound = 0.0;
  for (std::uint64_t p = full.row_start[v]; p < full.row_start[v + 1]; ++p) {
    if (!is_kept[full.index[p]]) bound += std::abs(full.value[p] * light[full.index[p] * 4 + 1]);
  }
  for (std::uint32_t p = quantized.row_start[v]; p < quantized.row_start[v + 1]; ++p) {
    const std::uint32_t j = quantized.index[p];
    const double step = quantized.band_scale[wavelet_band(quantized.param, quantized.size, j)] *
                        quantized.grey_step[v];
    bound += 0.5 * step * std::abs(light[j * 4 + 1]);
  }
  return bound;
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
  // Every coefficient kept, in float: the one jittered ray per texel alone, whose error is the
  // cosine's variation over the sun's few texels for the lit vertex and the blocker's edge
  // texels for the shadowed one; a few times its spread over seeds.
  s.keep = 0;
  Context ctx;
  const WaveletTransfer all = compute_wavelet_transfer(scene, nullptr, s, ctx);
  const std::vector<float> light = test::runtime_light(map, PRT_WAVELET_PARAM_CUBE, 64);
  const std::vector<glm::vec3> exact = shade_wavelet_transfer(all, light);
  EXPECT_NEAR(exact[37].g, lit, 0.01 * lit);
  EXPECT_NEAR(exact[40].g, dark, 0.005 * dark);
  // K = 1000 of 24,576 coefficients in 8 bits: the lit vertex within 3 %. The shadowed vertex
  // gets the sky alone, plus what truncation and quantisation leak of the sun: at most the
  // dropped coefficients' and half the quantisation steps' products with the light (the band
  // scale is set by the lit vertices, so those steps are coarse for a dark row).
  const double leak = 0.8 * leak_bound(all, b.transfer, b.quantized, light, 40);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(shaded[37][c], lit, 0.03 * lit) << c;
    EXPECT_NEAR(shaded[40][c], dark, 0.005 * dark + leak) << c;
  }
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
