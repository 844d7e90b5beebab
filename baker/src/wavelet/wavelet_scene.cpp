// SPDX-License-Identifier: MIT
// Technique `wavelet` in `prt-bake scene` (prt/baker/scene_bake.hpp): it suits static diffuse
// objects; its ladder climbs the coefficients kept per vertex, each at a coarse then a fine cube;
// its blobs are shaded through the runtime with every light term kept.
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>
#include <prt/prt.hpp>

#include <string>
#include <vector>

#include "prt/baker/scene_bake.hpp"

#include "../common/trade_common.hpp"
#include "wavelet_technique.hpp"

namespace prt::bake {

namespace {
// Cube faces of maps that are neither lat-long nor a cross, resampled before the runtime's own
// resampling to the asset's cube: finer than any cube the ladder bakes.
constexpr int kLightFaceSize = 256;
}  // namespace

std::vector<Rung> wavelet_scene_ladder(int bounces) {
  std::vector<Rung> ladder;
  // Bytes follow the kept coefficients; at the same count the coarser cube bakes four times
  // faster, so it is tried first.
  for (int keep : {64, 128, 256, 512, 1024, 2048}) {
    for (int cube : {32, 64}) {
      ladder.push_back({{"--keep", std::to_string(keep), "--cube", std::to_string(cube),
                         "--bounces", std::to_string(bounces)}});
    }
  }
  return ladder;
}

std::vector<glm::vec3> wavelet_scene_shade(const std::vector<std::uint8_t>& blob,
                                           const io::EnvMap& light, const Context&) {
  const trade::RuntimeAsset loaded = trade::load_runtime_asset(blob);
  const prt_asset* asset = loaded.asset.get();
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  trade::check_runtime(prt_wavelet_get_info(asset, &info), "prt_wavelet_get_info");
  std::vector<float> faces;
  const prt_env_image env = trade::runtime_env_image(light, kLightFaceSize, &faces);
  std::vector<float> rgba(std::size_t(info.coefficient_count) * 4);
  trade::check_runtime(prt_wavelet_resample(info.param, info.size, &env, rgba.data()),
                       "prt_wavelet_resample");
  trade::check_runtime(prt_wavelet_transform_light(info.param, info.size, rgba.data()),
                       "prt_wavelet_transform_light");
  trade::check_runtime(
      prt_wavelet_select_light(info.param, info.size, info.coefficient_count, rgba.data()),
      "prt_wavelet_select_light");
  trade::check_runtime(prt_wavelet_prepare_light(asset, rgba.data(), rgba.data(), nullptr),
                       "prt_wavelet_prepare_light");
  std::vector<float> shaded(std::size_t(info.vertex_count) * 3);
  trade::check_runtime(prt_wavelet_shade(asset, PRT_BACKEND_CPU, rgba.data(), nullptr, 0,
                                         info.vertex_count, shaded.data()),
                       "prt_wavelet_shade");
  return trade::as_vec3(shaded);
}

}  // namespace prt::bake
