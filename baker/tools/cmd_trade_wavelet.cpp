// SPDX-License-Identifier: MIT
// prt-bake trade-wavelet SCENE --env MAP ... --out-dir DIR: the measured speed/accuracy trade of
// technique `wavelet` against `sh` (docs/wavelet/trade.md). One bake per parameterisation and
// size at the largest K swept; smaller K are the same rows truncated (the bake keeps the K
// largest |c|, so the K' < K largest of those are what a bake at K' keeps). Sweeps:
//   N   cube face size at K = 4 % of the coefficients, the default quantiser, every light term;
//   K   kept coefficients at the base N: float rows (no quantisation) and both quantisers;
//   M   light detail coefficients kept (prt_wavelet_select_light) at the base N and K;
//   param  the dual paraboloid at sizes P (K = 4 %) next to the cube;
//   sh  orders at 256 rays, 8 and 16 bits, grey transfer: the equal-bytes comparison.
// Each map is turned into a light by the runtime (resample -> transform -> select -> prepare),
// each quantised setting written to a blob, loaded at full validation and shaded by the runtime
// on the CPU and SIMD backends; errors are against the reference renderer's direct light with
// shadows (cached, the same key scheme as prt-bake trade). Writes DIR/trade.csv and trade.md.
#include <prt/prt.h>
#include <prt/prt_sh.h>
#include <prt/prt_sh_asset.h>
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "command.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "prt/baker/wavelet/wavelet_blob.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"
#include "prt/io/envmap.hpp"
#include "prt/io/radiance_error.hpp"
#include "trade_common.hpp"

namespace prt::bake::cli {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kAllTerms = std::numeric_limits<std::uint32_t>::max();
// Face size of the cube a non-lat-long map is handed to the runtime as (the game's cube map).
constexpr int kProbeFaceSize = 256;

struct WaveletTradeOptions {
  std::string scene, out_dir, cache_dir, albedo, quantizer = "band";
  std::vector<std::string> envs, light_terms{"0", "10", "30", "100", "300", "1000", "3000", "all"};
  std::vector<std::uint32_t> sizes{16, 32, 64}, keeps{50, 100, 250, 500, 1000, 2000, 4000},
      paraboloid_sizes{64, 128}, sh_orders{2, 4, 6, 8, 12, 16}, sh_bits{8, 16};
  std::uint32_t base_size = 64, base_keep = 0, samples = 1, sh_rays = 256, ref_spp = 2048, seed = 0;
  std::uint32_t vertex_stride = 1;  // bake and measure every n-th vertex only (quick runs)
  int frames = 10;
  bool no_paraboloid = false;
};

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

  double clean_error() const { return noise_removed(error, ref_noise); }
};

// An environment as both techniques' runtimes take it: lat-long maps as they are, other
// mappings as cube faces the baker resamples once (what a game would hold).
struct TradeLight {
  ShLight sh;
  Reference reference;
  bool latlong = false;
  int face_size = 0;
  std::vector<float> faces;  // 6 faces back to back, RGB
};

std::string terms_text(std::uint32_t m) {
  return m == kAllTerms ? "all" : std::to_string(m);
}

std::uint32_t parse_terms(const std::string& text) {
  if (text == "all") return kAllTerms;
  try {
    std::size_t used = 0;
    const unsigned long value = std::stoul(text, &used);
    if (used == text.size() && value < kAllTerms) return static_cast<std::uint32_t>(value);
  } catch (const std::exception&) {
  }
  throw Error("--light-terms: '" + text + "' is neither a count nor 'all'");
}

// The relative RMSE over the measured vertices (every `stride`-th).
double subset_rmse(const std::vector<glm::vec3>& estimate, const std::vector<glm::vec3>& reference,
                   std::uint32_t stride) {
  if (stride <= 1) return io::relative_rmse(estimate, reference);
  std::vector<glm::vec3> a, b;
  for (std::size_t v = 0; v < estimate.size() && v < reference.size(); v += stride) {
    a.push_back(estimate[v]);
    b.push_back(reference[v]);
  }
  return io::relative_rmse(a, b);
}

bool is_power_of_two(std::uint32_t n) {
  return n != 0 && (n & (n - 1)) == 0;
}

void check_options(const WaveletTradeOptions& o) {
  if (o.envs.empty()) throw Error("trade-wavelet: give at least one --env MAP");
  auto check_size = [](std::uint32_t s, const char* flag) {
    if (!is_power_of_two(s) || s < PRT_WAVELET_MIN_SIZE || s > PRT_WAVELET_MAX_SIZE)
      throw Error(std::string(flag) + ": " + std::to_string(s) + " is not a power of two in " +
                  std::to_string(PRT_WAVELET_MIN_SIZE) + ".." +
                  std::to_string(PRT_WAVELET_MAX_SIZE));
  };
  for (std::uint32_t s : o.sizes) check_size(s, "--sizes");
  for (std::uint32_t s : o.paraboloid_sizes) check_size(s, "--paraboloid-sizes");
  check_size(o.base_size, "--base-size");
  for (std::uint32_t k : o.keeps) {
    if (k < 1) throw Error("--keeps: every value must be >= 1");
  }
  for (std::uint32_t order : o.sh_orders) {
    if (order < 1 || order > PRT_SH_MAX_ORDER)
      throw Error("--sh-orders: " + std::to_string(order) + " is outside 1.." +
                  std::to_string(PRT_SH_MAX_ORDER));
  }
  for (std::uint32_t bits : o.sh_bits) {
    if (bits != 8 && bits != 16)
      throw Error("--sh-bits: " + std::to_string(bits) + " is not 8 or 16");
  }
  for (const std::string& m : o.light_terms) parse_terms(m);
  parse_wavelet_quantizer(o.quantizer.c_str());
  const std::uint32_t k = static_cast<std::uint32_t>(std::lround(std::sqrt(double(o.samples))));
  if (o.samples < 1 || k * k != o.samples)
    throw Error("--samples: must be a square (1, 4, 9, ...)");
  if (o.frames < 1) throw Error("--frames: must be >= 1");
}

// --- the sweep design ---------------------------------------------------------------------------

// One measurement of a bake: K kept, quantiser, light terms M; `sweeps` names its sweeps.
struct Measurement {
  std::uint32_t keep = 0, terms = kAllTerms;
  std::string quantizer, sweeps;
};

// One wavelet bake (at the largest K its measurements use) and what is measured on it.
struct WaveletBake {
  std::uint32_t param = PRT_WAVELET_PARAM_CUBE, size = 0, keep = 0;
  std::vector<Measurement> measurements;
};

std::uint32_t base_keep(const WaveletTradeOptions& o) {
  return o.base_keep ? o.base_keep : default_wavelet_keep(PRT_WAVELET_PARAM_CUBE, o.base_size);
}

std::vector<WaveletBake> wavelet_bakes(const WaveletTradeOptions& o) {
  // (param, size) -> (keep, quantiser, terms) -> sweep names; a measurement in several sweeps is
  // made once.
  std::map<std::pair<std::uint32_t, std::uint32_t>,
           std::map<std::tuple<std::uint32_t, std::string, std::uint32_t>, std::string>>
      plan;
  auto add = [&](std::uint32_t param, std::uint32_t size, std::uint32_t keep, const std::string& q,
                 std::uint32_t terms, const char* sweep) {
    std::string& names = plan[{param, size}][{keep, q, terms}];
    if (names.find(sweep) == std::string::npos)
      names += (names.empty() ? "" : "+") + std::string(sweep);
  };
  const std::uint32_t cube = PRT_WAVELET_PARAM_CUBE, paraboloid = PRT_WAVELET_PARAM_DUAL_PARABOLOID;
  for (std::uint32_t n : o.sizes)
    add(cube, n, default_wavelet_keep(cube, n), o.quantizer, kAllTerms, "N");
  for (std::uint32_t k : o.keeps) {
    for (const char* q : {"float", "vertex", "band"}) add(cube, o.base_size, k, q, kAllTerms, "K");
  }
  for (const std::string& m : o.light_terms)
    add(cube, o.base_size, base_keep(o), o.quantizer, parse_terms(m), "M");
  if (!o.no_paraboloid) {
    for (std::uint32_t p : o.paraboloid_sizes) {
      add(paraboloid, p, default_wavelet_keep(paraboloid, p), o.quantizer, kAllTerms, "param");
      // The cube next to it at the same face size and at half of it (about as many
      // coefficients: 6 (P/2)^2 against 2 P^2), when the N sweep bakes those anyway.
      for (std::uint32_t n : o.sizes) {
        if (n == p || 2 * n == p)
          add(cube, n, default_wavelet_keep(cube, n), o.quantizer, kAllTerms, "param");
      }
    }
  }
  std::vector<WaveletBake> bakes;
  for (const auto& [key, measurements] : plan) {
    WaveletBake bake;
    bake.param = key.first;
    bake.size = key.second;
    for (const auto& [m, sweeps] : measurements) {
      bake.keep = std::max(bake.keep, std::get<0>(m));
      bake.measurements.push_back({std::get<0>(m), std::get<2>(m), std::get<1>(m), sweeps});
    }
    bakes.push_back(std::move(bake));
  }
  // Cheapest first: the coefficient count decides the bake's cost.
  std::stable_sort(bakes.begin(), bakes.end(), [](const WaveletBake& a, const WaveletBake& b) {
    return prt_wavelet_coefficient_count(a.param, a.size) <
           prt_wavelet_coefficient_count(b.param, b.size);
  });
  return bakes;
}

// --- lights -------------------------------------------------------------------------------------

TradeLight load_trade_light(const std::string& path, const Scene& scene,
                            const WaveletTradeOptions& o, const Context& ctx) {
  std::uint32_t max_order = 1;
  for (std::uint32_t order : o.sh_orders) max_order = std::max(max_order, order);
  TradeLight light;
  light.sh = load_sh_light(path, max_order, ctx);
  const io::EnvMap& map = *light.sh.map;
  light.latlong = map.mapping() == io::EnvMapping::LatLong;
  if (!light.latlong) {
    light.face_size =
        map.mapping() == io::EnvMapping::VerticalCross ? map.face_size() : kProbeFaceSize;
    for (const std::vector<float>& face : io::resample_to_cube(map, light.face_size))
      light.faces.insert(light.faces.end(), face.begin(), face.end());
  }
  ReferenceRequest request;
  request.scene_path = o.scene;
  request.map_name = light.sh.name;
  request.albedo = o.albedo;
  request.cache_dir = o.cache_dir;
  request.bounces = 0;
  request.spp = o.ref_spp;
  request.seed = o.seed;
  light.reference = cached_reference(scene, map, request, ctx);
  return light;
}

// The map's texel values on a parameterisation (prt_wavelet_resample_*), RGBA.
prt_result resample(const TradeLight& light, std::uint32_t param, std::uint32_t size, float* rgba) {
  const io::EnvMap& map = *light.sh.map;
  if (light.latlong)
    return prt_wavelet_resample_latlong(param, size, map.pixels().data(), map.width(), map.height(),
                                        nullptr, rgba);
  return prt_wavelet_resample_cube(param, size, light.faces.data(), light.face_size, nullptr, rgba);
}

// The light in Haar coefficients with every term (resample + transform). Its power, the sum of
// its texels (SPEC §14: power per texel), is checked against the SH light's DC term (integral of
// L = L_00 / Y_00), which the SH projection computes by separate code: a wrong face or
// orientation shows there.
std::vector<float> wavelet_light(const TradeLight& light, std::uint32_t param, std::uint32_t size,
                                 const Context& ctx, std::vector<std::string>* notes) {
  const std::uint32_t count = prt_wavelet_coefficient_count(param, size);
  std::vector<float> rgba(std::size_t(count) * 4);
  check_runtime(resample(light, param, size, rgba.data()), "prt_wavelet_resample");
  double power = 0.0;
  for (std::size_t j = 0; j < count; ++j) {
    power += (double(rgba[4 * j]) + rgba[4 * j + 1] + rgba[4 * j + 2]) / 3.0;
  }
  const double y00 = 0.28209479177387814;
  const std::vector<float>& sh = light.sh.rgb;
  const double expected = (sh[0] + sh[1] + sh[2]) / 3.0 / y00;
  const double relative = expected > 0.0 ? std::abs(power - expected) / expected : 0.0;
  if (relative > 0.02) {
    const std::string note = light.sh.name + ": the " + wavelet_param_name(param) + " " +
                             std::to_string(size) + " light's power differs from the SH " +
                             "projection's by " + format("%.2g %%", 100 * relative);
    ctx.warn(note);
    notes->push_back(note);
  }
  check_runtime(prt_wavelet_transform_light(param, size, rgba.data()),
                "prt_wavelet_transform_light");
  return rgba;
}

std::vector<float> selected(const std::vector<float>& light, std::uint32_t param,
                            std::uint32_t size, std::uint32_t terms) {
  std::vector<float> out = light;
  check_runtime(prt_wavelet_select_light(param, size, terms, out.data()),
                "prt_wavelet_select_light");
  return out;
}

// --- wavelet measurements -----------------------------------------------------------------------

// The rows truncated to their `keep` largest |c| (ties: the lower index), as a bake at `keep`
// would have kept them.
WaveletTransfer truncated(const WaveletTransfer& t, std::uint32_t keep) {
  WaveletTransfer out = t;  // everything but the rows
  out.index.clear();
  out.value.clear();
  out.row_start.assign(1, 0);
  std::vector<float> row;
  for (std::size_t v = 0; v < t.vertex_count; ++v) {
    row.assign(t.value.begin() + t.row_start[v], t.value.begin() + t.row_start[v + 1]);
    for (std::uint32_t i : select_wavelet_coefficients(row, keep, 0.0)) {
      out.index.push_back(t.index[t.row_start[v] + i]);
      out.value.push_back(row[i]);
    }
    out.row_start.push_back(out.index.size());
  }
  return out;
}

Row wavelet_row(const WaveletTransfer& t, const Measurement& m, const TradeLight& light) {
  Row row;
  row.technique = "wavelet";
  row.map = light.sh.name;
  row.sweeps = m.sweeps;
  row.param = wavelet_param_name(t.param);
  row.quantizer = m.quantizer;
  row.size = t.size;
  row.keep = m.keep;
  row.terms = m.terms;
  row.ref_noise = light.reference.noise;
  row.bake_seconds = t.seconds;
  row.rays_traced = double(t.rays_traced);
  return row;
}

// Median ms of one light update: resample, transform, select M, prepare for the asset.
double time_light_update(const TradeLight& light, const prt_asset* asset, std::uint32_t param,
                         std::uint32_t size, std::uint32_t terms, int frames) {
  std::vector<float> rgba(std::size_t(prt_wavelet_coefficient_count(param, size)) * 4);
  return median_frame_ms(frames, "light update", [&] {
    prt_result r = resample(light, param, size, rgba.data());
    if (r == PRT_OK) r = prt_wavelet_transform_light(param, size, rgba.data());
    if (r == PRT_OK) r = prt_wavelet_select_light(param, size, terms, rgba.data());
    if (r == PRT_OK) r = prt_wavelet_prepare_light(asset, rgba.data(), rgba.data());
    return r;
  });
}

double time_wavelet_shading(const prt_asset* asset, prt_backend backend,
                            const std::vector<float>& prepared, std::uint32_t vertices, int frames,
                            std::vector<float>* out) {
  out->resize(std::size_t(vertices) * 3);
  return median_frame_ms(
      frames, std::string("prt_wavelet_shade_on(") + prt_backend_name(backend) + ")", [&] {
        return prt_wavelet_shade_on(asset, backend, prepared.data(), 0, vertices, out->data());
      });
}

// Rows of one (keep, quantiser) on every light and each of its light terms.
void measure_quantized(const Scene& scene, const WaveletTransfer& t, const std::string& quantizer,
                       const std::vector<const Measurement*>& ms,
                       const std::vector<TradeLight>& lights,
                       const std::vector<std::vector<float>>& full_lights,
                       const WaveletTradeOptions& o, const Context& ctx, std::vector<Row>* rows) {
  const std::uint32_t keep = ms.front()->keep;
  const QuantizedWavelet q =
      quantize_wavelet_transfer(t, parse_wavelet_quantizer(quantizer.c_str()), keep);
  const std::size_t section = encode_wvlt_section(q).size();
  const std::vector<std::uint8_t> blob =
      build_wavelet_blob(scene, q, "prtkit wavelet trade: " + o.scene);
  const RuntimeAsset runtime = load_runtime_asset(blob);
  const prt_asset* asset = runtime.asset.get();
  const std::uint32_t vertices = static_cast<std::uint32_t>(t.vertex_count);
  for (std::size_t l = 0; l < lights.size(); ++l) {
    for (const Measurement* m : ms) {
      const std::vector<float> light = selected(full_lights[l], t.param, t.size, m->terms);
      std::vector<float> prepared(light.size());
      check_runtime(prt_wavelet_prepare_light(asset, light.data(), prepared.data()),
                    "prt_wavelet_prepare_light");
      Row row = wavelet_row(t, *m, lights[l]);
      std::vector<float> shaded, simd_shaded;
      row.simd_ms =
          time_wavelet_shading(asset, PRT_BACKEND_SIMD, prepared, vertices, o.frames, &simd_shaded);
      row.cpu_ms =
          time_wavelet_shading(asset, PRT_BACKEND_CPU, prepared, vertices, o.frames, &shaded);
      row.light_ms = time_light_update(lights[l], asset, t.param, t.size, m->terms, o.frames);
      const std::vector<glm::vec3> radiance = as_vec3(shaded);
      row.error = subset_rmse(radiance, lights[l].reference.radiance, o.vertex_stride);
      row.quant_error = subset_rmse(radiance, shade_wavelet_transfer(t, light), o.vertex_stride);
      // Per measured vertex: with a vertex stride the other rows are empty, so the pairs count
      // over the measured vertices, the rest of the section (SPEC §7.2) over all.
      const double measured = double((vertices + o.vertex_stride - 1) / o.vertex_stride);
      const double pair_bytes = 2.0 * double(q.pair_count());
      row.bytes_per_vertex = (double(section) - pair_bytes) / vertices + pair_bytes / measured;
      row.pairs_per_vertex = double(q.pair_count()) / measured;
      row.blob_bytes = blob.size();
      rows->push_back(row);
      ctx.info("  " + row.map + " " + row.param + " " + std::to_string(row.size) + ", K " +
               std::to_string(row.keep) + ", " + quantizer + ", M " + terms_text(row.terms) +
               format(": error %.3f %%", 100 * row.error) +
               format(" (%.3f %% without noise)", 100 * row.clean_error()) +
               format(", %.0f B/vertex", row.bytes_per_vertex) + ", CPU " + ms_text(row.cpu_ms) +
               " ms, SIMD " + ms_text(row.simd_ms) + " ms");
    }
  }
}

void measure_float(const WaveletTransfer& t, const std::vector<const Measurement*>& ms,
                   const std::vector<TradeLight>& lights,
                   const std::vector<std::vector<float>>& full_lights, const WaveletTradeOptions& o,
                   const Context& ctx, std::vector<Row>* rows) {
  for (std::size_t l = 0; l < lights.size(); ++l) {
    for (const Measurement* m : ms) {
      Row row = wavelet_row(t, *m, lights[l]);
      const std::vector<float> light = selected(full_lights[l], t.param, t.size, m->terms);
      row.error = subset_rmse(shade_wavelet_transfer(t, light), lights[l].reference.radiance,
                              o.vertex_stride);
      row.pairs_per_vertex =
          double(t.index.size()) / double((t.vertex_count + o.vertex_stride - 1) / o.vertex_stride);
      rows->push_back(row);
      ctx.info("  " + row.map + " " + row.param + " " + std::to_string(row.size) + ", K " +
               std::to_string(row.keep) + ", float rows, M " + terms_text(row.terms) +
               format(": error %.3f %%", 100 * row.error));
    }
  }
}

void run_wavelet_bake(const Scene& scene, const EmbreeScene& rays, const WaveletBake& bake,
                      const std::vector<TradeLight>& lights, const WaveletTradeOptions& o,
                      const Context& ctx, std::vector<Row>* rows, std::vector<std::string>* notes) {
  WaveletTransferSettings settings;
  settings.param = bake.param;
  settings.size = bake.size;
  settings.samples = o.samples;
  settings.keep = bake.keep;
  settings.seed = o.seed;
  settings.vertex_stride = o.vertex_stride;
  if (!o.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(o.albedo);
  }
  const WaveletTransfer full = compute_wavelet_transfer(scene, &rays, settings, ctx);
  ctx.info(format("  baked in %.1f s, ", full.seconds) +
           format("%.1f Mrays/s", 1e-6 * double(full.rays_traced) / std::max(full.seconds, 1e-9)));
  std::vector<std::vector<float>> full_lights;
  for (const TradeLight& light : lights)
    full_lights.push_back(wavelet_light(light, bake.param, bake.size, ctx, notes));
  // Group by (keep, quantiser): one truncation and one blob per group.
  std::map<std::pair<std::uint32_t, std::string>, std::vector<const Measurement*>> groups;
  for (const Measurement& m : bake.measurements) groups[{m.keep, m.quantizer}].push_back(&m);
  std::uint32_t truncated_keep = 0;
  WaveletTransfer rows_at_keep;
  for (const auto& [key, ms] : groups) {
    const bool whole = key.first >= bake.keep;
    if (!whole && truncated_keep != key.first) {
      rows_at_keep = truncated(full, key.first);
      truncated_keep = key.first;
    }
    const WaveletTransfer& t = whole ? full : rows_at_keep;
    if (key.second == "float") {
      measure_float(t, ms, lights, full_lights, o, ctx, rows);
    } else {
      measure_quantized(scene, t, key.second, ms, lights, full_lights, o, ctx, rows);
    }
  }
}

// --- sh measurements ----------------------------------------------------------------------------

// One channel instead of three when R, G and B are the same (a grey albedo): SPEC §7.1's C = 1,
// the grey transfer the wavelet rows also store.
QuantizedShTransfer grey_if_possible(QuantizedShTransfer q) {
  const std::size_t n2 = q.coefficient_count();
  for (std::uint32_t c = 1; c < 3; ++c) {
    for (std::size_t k = 0; k < n2; ++k) {
      if (q.offsets[c * n2 + k] != q.offsets[k] || q.scales[c * n2 + k] != q.scales[k]) return q;
    }
  }
  for (std::size_t v = 0; v < q.vertex_count; ++v) {
    for (std::size_t k = 0; k < n2; ++k) {
      const std::uint16_t r = q.q[(v * 3) * n2 + k];
      if (q.q[(v * 3 + 1) * n2 + k] != r || q.q[(v * 3 + 2) * n2 + k] != r) return q;
    }
  }
  std::vector<std::uint16_t> grey(q.vertex_count * n2);
  for (std::size_t v = 0; v < q.vertex_count; ++v)
    std::copy_n(q.q.begin() + (v * 3) * n2, n2, grey.begin() + v * n2);
  q.q = std::move(grey);
  q.offsets.resize(n2);
  q.scales.resize(n2);
  q.channels = 1;
  return q;
}

double time_sh_projection(const TradeLight& light, std::uint32_t order, int frames) {
  const io::EnvMap& map = *light.sh.map;
  std::vector<float> rgb(std::size_t(order) * order * 3);
  const float* faces[6];
  const std::size_t face_floats = std::size_t(light.face_size) * light.face_size * 3;
  for (int f = 0; f < 6 && !light.latlong; ++f) faces[f] = light.faces.data() + f * face_floats;
  return median_frame_ms(frames, "SH projection", [&] {
    if (light.latlong)
      return prt_sh_project_latlong(order, map.width(), map.height(), map.pixels().data(),
                                    std::size_t(map.width()) * 3, rgb.data());
    return prt_sh_project_cube(order, light.face_size, faces, rgb.data());
  });
}

void run_sh_bake(const Scene& scene, const EmbreeScene& rays, std::uint32_t order,
                 const std::vector<TradeLight>& lights, const WaveletTradeOptions& o,
                 const Context& ctx, std::vector<Row>* rows) {
  ShTransferSettings settings;
  settings.order = order;
  settings.rays = o.sh_rays;
  settings.kind = ShTransferKind::Shadowed;
  settings.seed = o.seed;
  if (!o.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(o.albedo);
  }
  const ShTransfer transfer = compute_sh_transfer(scene, &rays, settings, ctx);
  const std::uint32_t vertices = static_cast<std::uint32_t>(transfer.vertex_count);
  for (std::uint32_t bits : o.sh_bits) {
    const QuantizedShTransfer q = grey_if_possible(quantize_sh_transfer(transfer, int(bits)));
    const std::size_t section = encode_shtr_section(q).size();
    const std::vector<std::uint8_t> blob = build_sh_blob(scene, q, "prtkit wavelet trade (sh)");
    const RuntimeAsset runtime = load_runtime_asset(blob);
    for (const TradeLight& light : lights) {
      const std::vector<float> l(light.sh.rgb.begin(),
                                 light.sh.rgb.begin() + std::size_t(order) * order * 3);
      Row row;
      row.technique = "sh";
      row.map = light.sh.name;
      row.sweeps = "sh";
      row.quantizer = std::to_string(bits) + "-bit" + (q.channels == 1 ? " grey" : " rgb");
      row.order = order;
      row.rays = o.sh_rays;
      row.ref_noise = light.reference.noise;
      std::vector<float> shaded(std::size_t(vertices) * 3), simd_shaded(shaded.size());
      auto timed = [&](prt_backend backend, std::vector<float>* out) {
        return median_frame_ms(o.frames, "prt_sh_shade_on", [&] {
          return prt_sh_shade_on(runtime.asset.get(), backend, l.data(), 0, vertices, out->data());
        });
      };
      row.simd_ms = timed(PRT_BACKEND_SIMD, &simd_shaded);
      row.cpu_ms = timed(PRT_BACKEND_CPU, &shaded);
      row.light_ms = time_sh_projection(light, order, o.frames);
      const std::vector<glm::vec3> radiance = as_vec3(shaded);
      row.error = subset_rmse(radiance, light.reference.radiance, o.vertex_stride);
      std::vector<glm::vec3> light_vec(std::size_t(order) * order);
      for (std::size_t k = 0; k < light_vec.size(); ++k)
        light_vec[k] = glm::vec3(l[3 * k], l[3 * k + 1], l[3 * k + 2]);
      row.quant_error =
          subset_rmse(radiance, shade_sh_transfer(transfer, light_vec), o.vertex_stride);
      row.bytes_per_vertex = double(section) / vertices;
      row.blob_bytes = blob.size();
      row.bake_seconds = transfer.seconds;
      row.rays_traced = double(transfer.rays_traced);
      rows->push_back(row);
      ctx.info("  " + row.map + " sh order " + std::to_string(order) + ", " + row.quantizer +
               format(": error %.3f %%", 100 * row.error) +
               format(" (%.3f %% without noise)", 100 * row.clean_error()) +
               format(", %.0f B/vertex", row.bytes_per_vertex));
    }
  }
}

// --- output -------------------------------------------------------------------------------------

std::string opt(double value, const char* fmt) {
  return value < 0.0 ? "" : format(fmt, value);
}

void write_csv(const std::string& path, const std::vector<Row>& rows, const WaveletTradeOptions& o,
               std::size_t vertices) {
  std::ofstream csv(path);
  csv << "scene,technique,map,sweeps,param,size,keep,quantizer,light_terms,sh_order,sh_rays,"
         "samples,vertices,rel_rmse,ref_noise,rel_rmse_noise_removed,ref_spp,"
         "transfer_bytes_per_vertex,pairs_per_vertex,blob_bytes,shade_cpu_ms,shade_simd_ms,"
         "light_update_ms,bake_seconds,rays_traced,rays_per_second,quant_shading_rel_rmse\n";
  for (const Row& r : rows) {
    const bool wavelet = r.technique == "wavelet";
    csv << stem(o.scene) << ',' << r.technique << ',' << r.map << ',' << r.sweeps << ',' << r.param
        << ',' << (wavelet ? std::to_string(r.size) : "") << ','
        << (wavelet ? std::to_string(r.keep) : "") << ',' << r.quantizer << ','
        << (wavelet ? terms_text(r.terms) : "") << ',' << (wavelet ? "" : std::to_string(r.order))
        << ',' << (wavelet ? "" : std::to_string(r.rays)) << ','
        << (wavelet ? std::to_string(o.samples) : "") << ',' << vertices << ','
        << format("%.6g", r.error) << ',' << format("%.6g", r.ref_noise) << ','
        << format("%.6g", r.clean_error()) << ',' << o.ref_spp << ','
        << opt(r.bytes_per_vertex, "%.2f") << ',' << opt(r.pairs_per_vertex, "%.2f") << ','
        << (r.blob_bytes ? std::to_string(r.blob_bytes) : "") << ',' << opt(r.cpu_ms, "%.3f") << ','
        << opt(r.simd_ms, "%.3f") << ',' << opt(r.light_ms, "%.3f") << ','
        << format("%.4g", r.bake_seconds) << ',' << format("%.0f", r.rays_traced) << ','
        << format("%.4g", r.bake_seconds > 0 ? r.rays_traced / r.bake_seconds : 0.0) << ','
        << opt(r.quant_error, "%.4g") << '\n';
  }
  if (!csv) throw Error(path + ": cannot write");
}

std::string joined(const std::vector<std::uint32_t>& values) {
  std::string text;
  for (std::uint32_t v : values) text += (text.empty() ? "" : ",") + std::to_string(v);
  return text;
}

std::string pct(double fraction) {
  return format("%.2f", 100 * fraction);
}

void table_header(std::ofstream& md) {
  md << "| technique | param | size | K | quantiser | M | sh order | error % | error, noise "
        "removed % | B/vertex | pairs/vertex | blob KiB | CPU ms | SIMD ms | light ms | bake s | "
        "Mrays/s | quant. % |\n";
  md << "|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
        "\n";
}

void table_row(std::ofstream& md, const Row& r) {
  const bool wavelet = r.technique == "wavelet";
  md << "| " << r.technique << " | " << r.param << " | " << (wavelet ? std::to_string(r.size) : "")
     << " | " << (wavelet ? std::to_string(r.keep) : "") << " | " << r.quantizer << " | "
     << (wavelet ? terms_text(r.terms) : "") << " | " << (wavelet ? "" : std::to_string(r.order))
     << " | " << pct(r.error) << " | " << pct(r.clean_error()) << " | "
     << opt(r.bytes_per_vertex, "%.0f") << " | " << opt(r.pairs_per_vertex, "%.0f") << " | "
     << (r.blob_bytes ? format("%.0f", r.blob_bytes / 1024.0) : "") << " | "
     << opt(r.cpu_ms, "%.2f") << " | " << opt(r.simd_ms, "%.2f") << " | " << opt(r.light_ms, "%.2f")
     << " | " << format("%.1f", r.bake_seconds) << " | "
     << format("%.1f", r.bake_seconds > 0 ? 1e-6 * r.rays_traced / r.bake_seconds : 0.0) << " | "
     << (r.quant_error < 0 ? "" : format("%.3f", 100 * r.quant_error)) << " |\n";
}

bool in_sweep(const Row& r, const std::string& sweep) {
  std::string names = "+" + r.sweeps + "+";
  return names.find("+" + sweep + "+") != std::string::npos;
}

// Where each technique wins at equal bytes per vertex: for every budget (the bytes per vertex
// of a quantised row), the lowest noise-removed error of each technique within that budget.
void write_comparison(std::ofstream& md, const std::vector<Row>& rows, const std::string& map) {
  std::vector<const Row*> candidates;
  for (const Row& r : rows) {
    if (r.map == map && r.bytes_per_vertex > 0 && r.terms == kAllTerms) candidates.push_back(&r);
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Row* a, const Row* b) { return a->bytes_per_vertex < b->bytes_per_vertex; });
  auto describe = [](const Row* r) {
    if (!r) return std::string("—");
    if (r->technique == "sh") return "order " + std::to_string(r->order) + ", " + r->quantizer;
    return r->param + " " + std::to_string(r->size) + ", K " + std::to_string(r->keep) + ", " +
           r->quantizer;
  };
  md << "\n### " << map << ": sh against wavelet at equal bytes per vertex\n\n";
  md << "For each budget (a measured row's transfer bytes per vertex), the lowest error "
        "(noise removed) each technique reaches within it.\n\n";
  md << "| budget B/vertex | best sh | error % | best wavelet | error % | wins |\n";
  md << "|---:|---|---:|---|---:|---|\n";
  const Row *best_sh = nullptr, *best_wavelet = nullptr;
  std::string last_winner, summary;
  double range_start = 0.0;
  for (const Row* r : candidates) {
    const Row*& best = r->technique == "sh" ? best_sh : best_wavelet;
    if (!best || r->clean_error() < best->clean_error()) best = r;
    std::string winner = "sh";
    if (!best_sh || (best_wavelet && best_wavelet->clean_error() < best_sh->clean_error()))
      winner = "wavelet";
    md << "| " << format("%.0f", r->bytes_per_vertex) << " | " << describe(best_sh) << " | "
       << (best_sh ? pct(best_sh->clean_error()) : "—") << " | " << describe(best_wavelet) << " | "
       << (best_wavelet ? pct(best_wavelet->clean_error()) : "—") << " | " << winner << " |\n";
    if (winner != last_winner) {
      if (!last_winner.empty())
        summary += last_winner + " from " + format("%.0f", range_start) + " B/vertex; ";
      last_winner = winner;
      range_start = r->bytes_per_vertex;
    }
  }
  if (!last_winner.empty())
    summary += last_winner + " from " + format("%.0f", range_start) + " B/vertex up.";
  md << "\nWinner by budget on " << map << ": " << summary << "\n";
  if (best_sh && best_wavelet) {
    md << "Best of each: sh " << describe(best_sh) << " at "
       << format("%.0f", best_sh->bytes_per_vertex) << " B/vertex, " << pct(best_sh->clean_error())
       << " %; wavelet " << describe(best_wavelet) << " at "
       << format("%.0f", best_wavelet->bytes_per_vertex) << " B/vertex, "
       << pct(best_wavelet->clean_error()) << " % (ratio "
       << format("%.2f", best_wavelet->clean_error() / best_sh->clean_error()) << ").\n";
  }
}

void write_markdown(const std::string& path, const std::vector<Row>& rows,
                    const std::vector<TradeLight>& lights, const WaveletTradeOptions& o,
                    const Scene& scene, unsigned threads, const std::vector<std::string>& notes) {
  std::ofstream md(path);
  md << "# Technique wavelet against sh: speed versus accuracy (prt-bake trade-wavelet)\n\n";
  md << "Scene `" << fs::path(o.scene).filename().string() << "`: " << scene.vertex_count()
     << " vertices, " << scene.triangle_count() << " triangles; albedo "
     << (o.albedo.empty() ? "from the materials" : o.albedo)
     << "; direct light with shadows (no bounces)."
     << (o.vertex_stride > 1 ? " Wavelet bakes and every error cover every " +
                                   std::to_string(o.vertex_stride) + "-th vertex only."
                             : std::string())
     << "\n\n";
  md << "Wavelet sweeps (" << o.samples << " ray(s) per texel, seed " << o.seed
     << "; the default quantiser is `" << o.quantizer << "`): **N** cube sizes " << joined(o.sizes)
     << " at K = 4 % of the coefficients; **K** " << joined(o.keeps) << " at N = " << o.base_size
     << ", float rows and both quantisers; **M** light terms";
  for (const std::string& m : o.light_terms) md << ' ' << m;
  md << " at N = " << o.base_size << ", K = " << base_keep(o) << "; **param** dual paraboloid P = "
     << (o.no_paraboloid ? std::string("none") : joined(o.paraboloid_sizes))
     << " against the cube at the same size and at half of it (about as many coefficients), "
        "each at K = 4 %. One bake per (param, size) at the largest K "
        "measured on it; smaller K are its rows truncated to the K largest |c|, exactly what a "
        "bake at that K keeps. **sh**: orders "
     << joined(o.sh_orders) << ", " << o.sh_rays << " rays, " << joined(o.sh_bits)
     << " bits, shadowed, one grey channel when the albedo is grey.\n\n";
  md << "Reference: " << o.ref_spp
     << " samples per vertex, direct light with visibility. Error = relative RMSE of per-vertex "
        "RGB radiance against it; error, noise removed = sqrt(error² − noise²) with the "
        "reference's own noise estimate. B/vertex = the raw WVLT or SHTR section bytes / "
        "vertices (the transfer a game holds; the blob adds the mesh). CPU / SIMD ms = median "
        "of "
     << o.frames
     << " shadings of every vertex on one thread; light ms = one light update (wavelet: resample, "
        "Haar transform, select M, prepare; sh: the runtime's SH projection). Quant. = what the "
        "quantisation adds: runtime shading against the float rows' under the same light.\n\n";
  md << "Machine: " << cpu_model() << ", " << std::thread::hardware_concurrency()
     << " hardware threads; bakes on " << threads
     << " threads; SIMD backend: " << simd_description() << ".\n";
  md << "\nLight check (power of the runtime's wavelet light, sum of its texels P_j, against the "
        "SH "
        "projection's DC term, beyond 2 %): "
     << (notes.empty() ? "every light passed.\n" : "\n\n");
  for (const std::string& note : notes) md << "- " << note << "\n";
  const std::vector<std::pair<std::string, std::string>> sections = {{"N", "cube size N (K = 4 %)"},
                                                                     {"K", "kept coefficients K"},
                                                                     {"M", "light terms M"},
                                                                     {"param", "parameterisation"},
                                                                     {"sh", "sh orders"}};
  for (const TradeLight& light : lights) {
    const std::string& name = light.sh.name;
    md << "\n## " << name << " (" << io::env_mapping_name(light.sh.map->mapping()) << ", "
       << light.sh.map->width() << "x" << light.sh.map->height() << "; reference noise "
       << pct(light.reference.noise) << " %)\n";
    for (const auto& [sweep, title] : sections) {
      md << "\n### " << name << ": " << title << "\n\n";
      table_header(md);
      for (const Row& r : rows) {
        if (r.map == name && in_sweep(r, sweep)) table_row(md, r);
      }
    }
    write_comparison(md, rows, name);
  }
  if (!md) throw Error(path + ": cannot write");
}

// --- the command --------------------------------------------------------------------------------

void run_trade_wavelet(WaveletTradeOptions o, const CommandEnv& env) {
  check_options(o);
  const Context ctx = env.context();
  if (o.cache_dir.empty()) o.cache_dir = o.out_dir + "/cache";
  fs::create_directories(o.out_dir);
  fs::create_directories(o.cache_dir);
  const std::vector<WaveletBake> bakes = wavelet_bakes(o);

  const Scene scene = import_scene(o.scene, ctx);
  std::vector<TradeLight> lights;
  std::set<std::string> names;
  for (const std::string& path : o.envs) {
    lights.push_back(load_trade_light(path, scene, o, ctx));
    if (!names.insert(lights.back().sh.name).second)
      throw Error("--env: two maps are named '" + lights.back().sh.name + "'");
  }
  const EmbreeScene rays(scene, ctx);
  std::vector<Row> rows;
  std::vector<std::string> notes;  // light checks that failed, for trade.md
  const std::size_t total = bakes.size() + o.sh_orders.size();
  std::size_t done = 0;
  // The tables are rewritten after every bake, so a long run that stops still leaves its rows.
  auto write_tables = [&] {
    write_csv(o.out_dir + "/trade.csv", rows, o, scene.vertex_count());
    write_markdown(o.out_dir + "/trade.md", rows, lights, o, scene, ctx.thread_count(), notes);
  };
  for (std::uint32_t order : o.sh_orders) {
    ctx.info("bake " + std::to_string(++done) + "/" + std::to_string(total) + ": sh order " +
             std::to_string(order) + ", " + std::to_string(o.sh_rays) + " rays");
    run_sh_bake(scene, rays, order, lights, o, ctx, &rows);
    write_tables();
  }
  for (const WaveletBake& bake : bakes) {
    ctx.info("bake " + std::to_string(++done) + "/" + std::to_string(total) + ": wavelet " +
             wavelet_param_name(bake.param) + " " + std::to_string(bake.size) + ", K " +
             std::to_string(bake.keep) + ", " + std::to_string(bake.measurements.size()) +
             " measurement(s) per map");
    run_wavelet_bake(scene, rays, bake, lights, o, ctx, &rows, &notes);
    write_tables();
  }
  ctx.info("wrote " + o.out_dir + "/trade.csv and trade.md");
}

}  // namespace

void add_trade_wavelet_command(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<WaveletTradeOptions>();
  WaveletTradeOptions& o = *options;
  auto* cmd = app.add_subcommand("trade-wavelet",
                                 "Measure technique wavelet's speed/accuracy trade (N, K, M, "
                                 "parameterisation) against sh at equal bytes per vertex");
  cmd->add_option("SCENE", o.scene, "Scene file (.gltf, .glb, .obj)")->required();
  cmd->add_option("--env", o.envs, "Environment map (.hdr); repeat for several")
      ->required()
      ->allow_extra_args(false);
  cmd->add_option("--out-dir", o.out_dir, "Where trade.csv and trade.md go")->required();
  cmd->add_option("--cache-dir", o.cache_dir,
                  "Where reference radiance is cached (default: OUT_DIR/cache)");
  cmd->add_option("--sizes", o.sizes, "Cube sizes N of the N sweep (128 costs ~15 min)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--base-size", o.base_size, "Cube size of the K and M sweeps")
      ->capture_default_str();
  cmd->add_option("--keeps", o.keeps, "Kept coefficients K of the K sweep")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--base-keep", o.base_keep, "K of the M sweep (0 = 4 % of the coefficients)")
      ->capture_default_str();
  cmd->add_option("--light-terms", o.light_terms,
                  "Light detail coefficients M of the M sweep (a count or 'all')")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--paraboloid-sizes", o.paraboloid_sizes,
                  "Dual-paraboloid sizes P compared with the cube")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_flag("--no-paraboloid", o.no_paraboloid, "Skip the parameterisation sweep");
  cmd->add_option("--quantizer", o.quantizer,
                  "Quantiser of the N, M and param sweeps: vertex or band")
      ->capture_default_str();
  cmd->add_option("--samples", o.samples, "Rays per texel of the wavelet bakes (a square)")
      ->capture_default_str();
  cmd->add_option("--sh-orders", o.sh_orders, "SH orders compared")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--sh-rays", o.sh_rays, "Rays per vertex of the SH bakes")
      ->check(CLI::Range(1u, 1u << 24))
      ->capture_default_str();
  cmd->add_option("--sh-bits", o.sh_bits, "SH quantisation bits (8, 16)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--ref-spp", o.ref_spp, "Reference samples per vertex")
      ->check(CLI::Range(2u, 1u << 30))
      ->capture_default_str();
  cmd->add_option("--frames", o.frames, "Timed frames per measurement (median)")
      ->capture_default_str();
  cmd->add_option("--albedo", o.albedo,
                  "Diffuse albedo r,g,b for every surface (default: from the materials)");
  cmd->add_option("--seed", o.seed, "Seed of the bakes and references")->capture_default_str();
  cmd->add_option("--vertex-stride", o.vertex_stride,
                  "Bake and measure every n-th vertex only (quick runs; the sh bakes and the "
                  "reference still cover all)")
      ->check(CLI::Range(1u, 1u << 20))
      ->capture_default_str();
  cmd->callback([&env, options] { run_trade_wavelet(*options, env); });
}

}  // namespace prt::bake::cli
