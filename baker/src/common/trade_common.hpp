// SPDX-License-Identifier: MIT
// What every technique's trade shares (private to the baker): the cached reference radiance, the
// SH light as the runtime projects it, blobs loaded through the runtime, a shading timer, the
// machine description, and the CSV and markdown table writing.
#pragma once

#include <prt/prt.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/technique.hpp"
#include "prt/baker/text.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake::trade {

// Empty for a negative value (not measured), else the value in `fmt`.
std::string optional_number(double value, const char* fmt);
// "n/a" for a negative time (backend not available), else milliseconds to 3 decimals.
std::string ms_text(double ms);
std::string stem(const std::string& path);
std::string joined(const std::vector<std::uint32_t>& values);

// Throws Error("what: <result string>") unless result is PRT_OK.
void check_runtime(prt_result result, const std::string& what);

// An environment and its SH light as the runtime projects it, at the largest order swept (lower
// orders are its leading coefficients: each coefficient's projection does not depend on the
// order). Lat-long maps and vertical crosses (as cube faces) go through prt_sh_project (checked
// against the baker's projection); other mappings are
// projected by the baker.
struct ShLight {
  std::string name;
  std::unique_ptr<io::EnvMap> map;
  std::string projection;  // which projection made `rgb`
  std::vector<float> rgb;  // coefficient-major RGB

  // The leading order^2 coefficients.
  std::vector<float> at_order(std::uint32_t order) const;
};
ShLight load_sh_light(const std::string& path, std::uint32_t order, const Context& ctx);

// The reference renderer's per-vertex radiance under `map` (named `map_name`) with `bounces`,
// at the trade's samples, seed and albedo, cached in input.cache_dir as
// <scene stem>_<map>_b<bounces>_spp<spp>_seed<seed>_albedo-<albedo>.npy and its noise estimate
// in the same name + ".noise"; rendered and written when missing.
struct Reference {
  std::vector<glm::vec3> radiance;
  double noise = 0.0;  // the renderer's own relative RMSE estimate
};
Reference cached_reference(const Scene& scene, const io::EnvMap& map, const std::string& map_name,
                           int bounces, const TradeInput& input, const Context& ctx);

// The error with the reference's noise taken out: the two are independent, so their squares add.
double noise_removed(double error, double noise);

// A blob loaded through the runtime at full validation, with its own context.
struct RuntimeAsset {
  prt::ContextPtr context;
  prt::AssetPtr asset;
};
RuntimeAsset load_runtime_asset(const std::vector<std::uint8_t>& blob);

// Median milliseconds of `frames` calls of `frame` (after one warm-up call, which decides:
// when it returns PRT_ERROR_UNSUPPORTED_BACKEND the result is -1; another error throws).
double median_frame_ms(int frames, const std::string& what,
                       const std::function<prt_result()>& frame);

// Median milliseconds of `frames` prt_sh_shade calls over every vertex of an sh asset on
// `backend` (median_frame_ms: -1 when the backend is not available); `out` receives the
// radiance. The sh light is in the runtime's layout, `light` at the asset's order.
double time_sh_shading(const prt_asset* asset, prt_backend backend, const std::vector<float>& light,
                       std::uint32_t vertices, int frames, std::vector<float>* out);

std::vector<glm::vec3> as_vec3(const std::vector<float>& rgb);

// A map as the runtime's environment image: lat-long as it is, any other mapping as six cube
// faces (a vertical cross at its own face size, others at `face_size`) held in `faces`.
prt_env_image runtime_env_image(const io::EnvMap& map, int face_size, std::vector<float>* faces);

// "Scene `<file name>`: V vertices, T triangles", the first words of every trade.md.
std::string scene_description(const std::string& path, const Scene& scene);
// "<CPU model>, N hardware threads; bakes on T threads; SIMD backend: <what the runtime says>".
std::string machine_description(unsigned bake_threads);

// Tables: every cell is formatted by the caller; a row has one cell per column.
struct Column {
  std::string title;
  bool numeric = true;  // right-aligned in markdown
};
void write_csv_row(std::ostream& out, const std::vector<std::string>& cells);
void write_markdown_header(std::ostream& out, const std::vector<Column>& columns);
void write_markdown_row(std::ostream& out, const std::vector<std::string>& cells);
// Throws Error naming the file when a stream that writes it has failed.
void check_written(const std::ostream& out, const std::string& path);

}  // namespace prt::bake::trade
