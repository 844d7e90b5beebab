// SPDX-License-Identifier: MIT
// What the trade commands (prt-bake trade, prt-bake trade-wavelet) share: the cached reference
// radiance, the SH light as the runtime projects it, blobs loaded through the runtime, a shading
// timer, the machine description and number formatting.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake::cli {

std::string format(const char* fmt, double value);
std::string stem(const std::string& path);
// "n/a" for a negative time (backend not available), else milliseconds to 3 decimals.
std::string ms_text(double ms);

// Throws Error("what: <result string>") unless result is PRT_OK.
void check_runtime(prt_result result, const std::string& what);

// An environment and its SH light as the runtime projects it, at the largest order swept (lower
// orders are its leading coefficients: each coefficient's projection does not depend on the
// order). Lat-long maps go through prt_sh_project_latlong, vertical crosses through
// prt_sh_project_cube (both checked against the baker's projection); other mappings are
// projected by the baker.
struct ShLight {
  std::string name;
  std::unique_ptr<io::EnvMap> map;
  std::string projection;  // which projection made `rgb`
  std::vector<float> rgb;  // coefficient-major RGB
};
ShLight load_sh_light(const std::string& path, std::uint32_t order, const Context& ctx);

// The reference renderer's per-vertex radiance (direct light plus `bounces`), cached in
// cache_dir as <scene stem>_<map>_b<bounces>_spp<spp>_seed<seed>_albedo-<albedo>.npy and its
// noise estimate in the same name + ".noise"; rendered and written when missing.
struct ReferenceRequest {
  std::string scene_path, map_name, albedo, cache_dir;  // albedo "r,g,b" or "" (materials)
  int bounces = 0;
  std::uint32_t spp = 2048, seed = 0;
};
struct Reference {
  std::vector<glm::vec3> radiance;
  double noise = 0.0;  // the renderer's own relative RMSE estimate
};
Reference cached_reference(const Scene& scene, const io::EnvMap& map,
                           const ReferenceRequest& request, const Context& ctx);

// The error with the reference's noise taken out: the two are independent, so their squares add.
double noise_removed(double error, double noise);

// A blob loaded through the runtime at full validation, with its own context.
struct RuntimeAsset {
  std::unique_ptr<prt_context, decltype(&prt_context_destroy)> context{nullptr,
                                                                       &prt_context_destroy};
  std::unique_ptr<prt_asset, decltype(&prt_asset_destroy)> asset{nullptr, &prt_asset_destroy};
};
RuntimeAsset load_runtime_asset(const std::vector<std::uint8_t>& blob);

// Median milliseconds of `frames` calls of `frame` (after one warm-up call, which decides:
// when it returns PRT_ERROR_UNSUPPORTED_BACKEND the result is -1; another error throws).
double median_frame_ms(int frames, const std::string& what,
                       const std::function<prt_result()>& frame);

std::vector<glm::vec3> as_vec3(const std::vector<float>& rgb);

// "model name" of /proc/cpuinfo, or "unknown".
std::string cpu_model();
// The SIMD backend as the runtime reports it: "usable, avx2" or "not usable (...)".
std::string simd_description();

}  // namespace prt::bake::cli
