// SPDX-License-Identifier: MIT
// The accuracy `wavelet` promises on a real scene (docs/wavelet/trade.md): the Stanford bunny
// under spiaggia_di_mondello_1k.hdr (a small, very bright sun), a cube bake at N = 64 keeping 1000
// coefficients (about 4 %) with the default quantiser, written to a blob, loaded at full
// validation and shaded by the runtime (light: resample -> transform -> select all -> prepare ->
// prt_wavelet_shade), against the reference renderer's per-vertex radiance (direct light with
// shadows). The targets:
// - relative RMSE, with the reference's noise removed, below 5 %;
// - at most 0.35 x the same error of sh at order 6 and at the highest order, 16 (shadowed, 256
//   rays, 16 bits), each baked and shaded through the runtime here under the same map: a sun is
//   what SH cannot represent and the wavelet basis can, so losing that advantage is a defect.
// With the texel solid angle in the transfer instead of the light (SPEC §14 before the change)
// the wavelet error roughly doubles, which the 0.35 ratio rejects.
// Both sides are measured against one independent reference (the Monte Carlo renderer, which
// uses no PRT approximation). To keep the run short the wavelet bake covers every 8th vertex
// (WaveletTransferSettings::vertex_stride) and all errors are taken over those vertices; the
// reference (512 spp over the whole bunny) gives its noise as VertexRadiance::relative_rmse, an
// estimate of the same figure, independent of the PRT errors, so squares add and
// sqrt(error^2 - noise^2) estimates the error against the exact radiance.
#include <gtest/gtest.h>

#include <prt/prt_sh_asset.h>
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "prt/baker/reference.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "prt/baker/wavelet/wavelet_blob.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"
#include "prt/io/envmap.hpp"
#include "prt/io/radiance_error.hpp"

namespace prt::bake {
namespace {

const std::string kShared = PRT_SHARED_DIR;
const std::string kBunny = kShared + "/assets/meshes/stanford-bunny.obj";
const std::string kSun = kShared + "/assets/envmaps/spiaggia_di_mondello_1k.hdr";
constexpr std::uint32_t kSize = 64, kKeep = 1000, kStride = 8, kSpp = 512, kShRays = 256;
const glm::vec3 kAlbedo(0.8f);

// A blob loaded at full validation in a context of its own.
struct Loaded {
  prt::ContextPtr context;
  prt::AssetPtr asset;
};

Loaded load(const std::vector<std::uint8_t>& blob) {
  Loaded loaded{prt::create_context().handle, nullptr};
  prt::Made<prt::AssetPtr> made =
      prt::load_asset_memory(loaded.context.get(), blob.data(), blob.size(), PRT_VALIDATE_FULL);
  EXPECT_EQ(made.result, PRT_OK) << prt_context_last_message(loaded.context.get());
  loaded.asset = std::move(made.handle);
  return loaded;
}

// The subset's values, in order.
std::vector<glm::vec3> subset(const std::vector<glm::vec3>& all) {
  std::vector<glm::vec3> out;
  for (std::size_t v = 0; v < all.size(); v += kStride) out.push_back(all[v]);
  return out;
}

double without_noise(double error, double noise) {
  return std::sqrt(std::max(0.0, error * error - noise * noise));
}

// The wavelet side: bake, quantise, blob, runtime light pipeline and scalar shading.
std::vector<glm::vec3> wavelet_radiance(const Scene& scene, const EmbreeScene& rays,
                                        const io::EnvMap& env, const Context& ctx) {
  WaveletTransferSettings settings;
  settings.param = PRT_WAVELET_PARAM_CUBE;
  settings.size = kSize;
  settings.keep = kKeep;
  settings.override_albedo = true;
  settings.albedo = kAlbedo;
  settings.vertex_stride = kStride;
  const WaveletTransfer transfer = compute_wavelet_transfer(scene, &rays, settings, ctx);
  // The default quantiser is the one `prt-bake bake wavelet` uses: band.
  const QuantizedWavelet quantized =
      quantize_wavelet_transfer(transfer, WaveletQuantizer::Band, kKeep);
  const std::vector<std::uint8_t> blob = build_wavelet_blob(scene, quantized, "accuracy test");
  const Loaded loaded = load(blob);
  if (!loaded.asset) return {};

  const std::uint32_t count = prt_wavelet_coefficient_count(PRT_WAVELET_PARAM_CUBE, kSize);
  std::vector<float> light(std::size_t(count) * 4);
  const prt_env_image image = prt::latlong_env(env.width(), env.height(), env.pixels().data());
  EXPECT_EQ(prt_wavelet_resample(PRT_WAVELET_PARAM_CUBE, kSize, &image, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_transform_light(PRT_WAVELET_PARAM_CUBE, kSize, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_select_light(PRT_WAVELET_PARAM_CUBE, kSize, count, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_prepare_light(loaded.asset.get(), light.data(), light.data(), nullptr),
            PRT_OK);
  std::vector<glm::vec3> radiance(scene.vertex_count());
  EXPECT_EQ(prt_wavelet_shade(loaded.asset.get(), PRT_BACKEND_CPU, light.data(), nullptr, 0,
                              static_cast<std::uint32_t>(radiance.size()), &radiance[0].x),
            PRT_OK);
  return radiance;
}

// The sh side at one order: bake every vertex, 16-bit blob, runtime scalar shading.
std::vector<glm::vec3> sh_radiance(const Scene& scene, const EmbreeScene& rays,
                                   const io::EnvMap& env, std::uint32_t order, const Context& ctx) {
  ShTransferSettings settings;
  settings.order = order;
  settings.kind = ShTransferKind::Shadowed;
  settings.rays = kShRays;
  settings.override_albedo = true;
  settings.albedo = kAlbedo;
  const ShTransfer transfer = compute_sh_transfer(scene, &rays, settings, ctx);
  const std::vector<std::uint8_t> blob =
      build_sh_blob(scene, quantize_sh_transfer(transfer, 16), "accuracy test");
  const Loaded loaded = load(blob);
  if (!loaded.asset) return {};
  const std::vector<float> light = project_env_sh(env, order).to_float();
  std::vector<glm::vec3> radiance(scene.vertex_count());
  EXPECT_EQ(prt_sh_shade(loaded.asset.get(), PRT_BACKEND_CPU, light.data(), 0,
                         static_cast<std::uint32_t>(radiance.size()), &radiance[0].x),
            PRT_OK);
  return radiance;
}

TEST(WaveletAccuracy, BunnyUnderTheSunAtN64Keep1000BeatsShAndTheMark) {
  if (!std::filesystem::exists(kBunny) || !std::filesystem::exists(kSun)) {
    GTEST_SKIP() << "shared assets missing (" << kBunny << ", " << kSun << ")";
  }
  const Context ctx;
  const Scene scene = import_scene(kBunny, ctx);
  const io::EnvMap env = io::load_envmap(kSun, io::EnvMapping::Auto, ctx.io_messages());
  ASSERT_EQ(env.mapping(), io::EnvMapping::LatLong);

  ReferenceSettings ref_settings;
  ref_settings.bounces = 0;
  ref_settings.spp = kSpp;
  ref_settings.override_albedo = true;
  ref_settings.albedo = kAlbedo;
  const ReferenceRenderer renderer(scene, env, ref_settings, ctx);
  const VertexRadiance reference = renderer.render_vertices(ctx);
  const double noise = reference.relative_rmse;
  // Well above the reference's noise at 512 spp under this map, and small enough that removing
  // it leaves the 5 % target meaningful.
  ASSERT_LE(noise, 0.03) << "reference noisier than this test allows for";
  const std::vector<glm::vec3> ref = subset(reference.radiance);

  const std::vector<glm::vec3> wavelet = wavelet_radiance(scene, renderer.embree_scene(), env, ctx);
  ASSERT_EQ(wavelet.size(), reference.radiance.size());
  for (const glm::vec3& l : wavelet) ASSERT_TRUE(std::isfinite(l.r + l.g + l.b));
  const double wavelet_error = io::relative_rmse(subset(wavelet), ref);
  const double wavelet_clean = without_noise(wavelet_error, noise);
  std::printf(
      "bunny / spiaggia, wavelet cube %u, K %u, band quantiser, every %u-th vertex: relative "
      "RMSE %.3f %%, %.3f %% with the reference's noise (%.3f %% at %u spp) removed\n",
      kSize, kKeep, kStride, 100 * wavelet_error, 100 * wavelet_clean, 100 * noise, kSpp);
  RecordProperty("wavelet_relative_rmse_noise_removed", std::to_string(wavelet_clean));
  EXPECT_LT(wavelet_clean, 0.05);

  for (const std::uint32_t order : {6u, 16u}) {
    const std::vector<glm::vec3> sh = sh_radiance(scene, renderer.embree_scene(), env, order, ctx);
    ASSERT_EQ(sh.size(), reference.radiance.size());
    const double sh_error = io::relative_rmse(subset(sh), ref);
    const double sh_clean = without_noise(sh_error, noise);
    std::printf(
        "sh order %u, %u rays, 16 bits: relative RMSE %.3f %%, %.3f %% noise removed; "
        "wavelet / sh = %.3f\n",
        order, kShRays, 100 * sh_error, 100 * sh_clean, wavelet_clean / sh_clean);
    RecordProperty("sh_order" + std::to_string(order) + "_relative_rmse_noise_removed",
                   std::to_string(sh_clean));
    EXPECT_LE(wavelet_clean, 0.35 * sh_clean) << "sh order " << order;
  }
}

}  // namespace
}  // namespace prt::bake
