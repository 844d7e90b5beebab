// SPDX-License-Identifier: MIT
// The pieces of prt-bake trade wavelet (private to the baker): its settings, the rows it
// measures, the lights as both techniques' runtimes take them, the sh rows it measures at equal
// bytes (wavelet_trade_sh.cpp) and its tables (wavelet_trade_tables.cpp).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/technique.hpp"

#include "../common/trade_common.hpp"

namespace prt::bake::wavelet_trade {

constexpr std::uint32_t kAllTerms = std::numeric_limits<std::uint32_t>::max();

// The sweeps' own flags (the shared ones are TradeInput).
struct Settings {
  std::string quantizer = "band";
  std::vector<std::string> light_terms{"0", "10", "30", "100", "300", "1000", "3000", "all"};
  std::vector<std::uint32_t> sizes{16, 32, 64}, keeps{50, 100, 250, 500, 1000, 2000, 4000},
      paraboloid_sizes{64, 128}, sh_orders{2, 4, 6, 8, 12, 16}, sh_bits{8, 16};
  std::uint32_t base_size = 64, base_keep = 0, samples = 1, sh_rays = 256;
  std::uint32_t vertex_stride = 1;  // bake and measure every n-th vertex only (quick runs)
  bool no_paraboloid = false;
};

// K of the M sweep: --base-keep, or 4 % of the base cube's coefficients.
std::uint32_t base_keep(const Settings& o);

// What a row measures. quantizer: "float" (no quantisation: the baker's float rows), "vertex" or
// "band" for wavelet; "8-bit"/"16-bit" for sh.
struct Row {
  std::string technique, map, sweeps, param, quantizer;
  std::uint32_t size = 0, keep = 0, terms = kAllTerms, order = 0, rays = 0;
  double error = 0.0, ref_noise = 0.0;
  double bytes_per_vertex = -1.0, pairs_per_vertex = -1.0, quant_error = -1.0;
  std::size_t blob_bytes = 0;
  double cpu_ms = -1.0, simd_ms = -1.0, light_ms = -1.0;
  double bake_seconds = 0.0, rays_traced = 0.0;

  double clean_error() const { return trade::noise_removed(error, ref_noise); }
  double rays_per_second() const { return bake_seconds > 0 ? rays_traced / bake_seconds : 0.0; }
};

// An environment as both techniques' runtimes take it: lat-long maps as they are, other
// mappings as cube faces the baker resamples once (what a game would hold).
struct TradeLight {
  trade::ShLight sh;
  trade::Reference reference;
  bool latlong = false;
  int face_size = 0;
  std::vector<float> faces;  // 6 faces back to back, RGB
};

// The light's map as the runtime's environment image: lat-long, or the six cube faces.
inline prt_env_image env_image(const TradeLight& light) {
  const io::EnvMap& map = *light.sh.map;
  if (light.latlong) return prt::latlong_env(map.width(), map.height(), map.pixels().data());
  return prt::cube_env(light.face_size, light.faces.data());
}

// "all" for every term, else the count.
std::string terms_text(std::uint32_t m);

// The relative RMSE over the measured vertices (every `stride`-th).
double subset_rmse(const std::vector<glm::vec3>& estimate, const std::vector<glm::vec3>& reference,
                   std::uint32_t stride);

// Bakes sh at `order` (shadowed, --sh-rays) and measures it at every --sh-bits on every light:
// the equal-bytes comparison.
void measure_sh(const Scene& scene, const EmbreeScene& rays, std::uint32_t order,
                const std::vector<TradeLight>& lights, const Settings& o, const TradeInput& input,
                const Context& ctx, std::vector<Row>* rows);

void write_csv(const std::string& path, const std::vector<Row>& rows, const Settings& o,
               const TradeInput& input, std::size_t vertices);
// `notes`: the light checks that failed.
void write_markdown(const std::string& path, const std::vector<Row>& rows,
                    const std::vector<TradeLight>& lights, const Settings& o,
                    const TradeInput& input, const Scene& scene, unsigned threads,
                    const std::vector<std::string>& notes);

}  // namespace prt::bake::wavelet_trade
