// SPDX-License-Identifier: MIT
// prt-bake trade wavelet SCENE --env MAP ... --out-dir DIR: the measured speed/accuracy trade of
// technique `wavelet` against `sh` (docs/wavelet/trade.md). One bake per parameterisation and
// size at the largest K swept; smaller K are the same rows truncated (the bake keeps the K
// largest |c|, so the K' < K largest of those are what a bake at K' keeps). Sweeps:
//   N   cube face size at K = 4 % of the coefficients, the default quantiser, every light term;
//   K   kept coefficients at the base N: float rows (no quantisation) and both quantisers;
//   M   light detail coefficients kept (prt_wavelet_select_light) at the base N and K;
//   param  the dual paraboloid at sizes P (K = 4 %) next to the cube;
//   sh  orders at 256 rays, 8 and 16 bits, grey transfer: the equal-bytes comparison
//       (wavelet_trade_sh.cpp).
// Each map is turned into a light by the runtime (resample -> transform -> select -> prepare),
// each quantised setting written to a blob, loaded at full validation and shaded by the runtime
// on the CPU and SIMD backends; errors are against the reference renderer's direct light with
// shadows (cached, the key scheme every trade shares). Writes DIR/trade.csv and trade.md
// (wavelet_trade_tables.cpp).
#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "prt/baker/wavelet/wavelet_blob.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"
#include "prt/io/envmap.hpp"
#include "prt/io/radiance_error.hpp"

#include "wavelet_technique.hpp"
#include "wavelet_trade.hpp"

namespace prt::bake {
namespace wavelet_trade {

using namespace trade;

std::string terms_text(std::uint32_t m) {
  return m == kAllTerms ? "all" : std::to_string(m);
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

std::uint32_t base_keep(const Settings& o) {
  return o.base_keep ? o.base_keep : default_wavelet_keep(PRT_WAVELET_PARAM_CUBE, o.base_size);
}

namespace {

// Face size of the cube a non-lat-long map is handed to the runtime as (the game's cube map).
constexpr int kProbeFaceSize = 256;

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

bool is_power_of_two(std::uint32_t n) {
  return n != 0 && (n & (n - 1)) == 0;
}

void check_settings(const Settings& o) {
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

std::vector<WaveletBake> wavelet_bakes(const Settings& o) {
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
    return prt_wavelet_coefficient_count(static_cast<prt_wavelet_param>(a.param), a.size) <
           prt_wavelet_coefficient_count(static_cast<prt_wavelet_param>(b.param), b.size);
  });
  return bakes;
}

// --- lights -------------------------------------------------------------------------------------

TradeLight load_trade_light(const std::string& path, const Scene& scene, const Settings& o,
                            const TradeInput& input, const Context& ctx) {
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
  light.reference = cached_reference(scene, map, light.sh.name, 0, input, ctx);
  return light;
}

// The map's texel values on a parameterisation (prt_wavelet_resample), RGBA.
prt_result resample(const TradeLight& light, std::uint32_t param, std::uint32_t size, float* rgba) {
  const prt_env_image env = env_image(light);
  return prt_wavelet_resample(static_cast<prt_wavelet_param>(param), size, &env, rgba);
}

// The light in Haar coefficients with every term (resample + transform). Its power, the sum of
// its texels (SPEC §14: power per texel), is checked against the SH light's DC term (integral of
// L = L_00 / Y_00), which the SH projection computes by separate code: a wrong face or
// orientation shows there.
std::vector<float> wavelet_light(const TradeLight& light, std::uint32_t param, std::uint32_t size,
                                 const Context& ctx, std::vector<std::string>* notes) {
  const auto domain = static_cast<prt_wavelet_param>(param);
  const std::uint32_t count = prt_wavelet_coefficient_count(domain, size);
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
  check_runtime(prt_wavelet_transform_light(domain, size, rgba.data()),
                "prt_wavelet_transform_light");
  return rgba;
}

std::vector<float> selected(const std::vector<float>& light, std::uint32_t param,
                            std::uint32_t size, std::uint32_t terms) {
  std::vector<float> out = light;
  check_runtime(
      prt_wavelet_select_light(static_cast<prt_wavelet_param>(param), size, terms, out.data()),
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
  const auto domain = static_cast<prt_wavelet_param>(param);
  const std::uint32_t count = prt_wavelet_coefficient_count(domain, size);
  std::vector<float> rgba(std::size_t(count) * 4);
  std::vector<std::uint8_t> zero_blocks(count / 256);
  return median_frame_ms(frames, "light update", [&] {
    prt_result r = resample(light, param, size, rgba.data());
    if (r == PRT_OK) r = prt_wavelet_transform_light(domain, size, rgba.data());
    if (r == PRT_OK) r = prt_wavelet_select_light(domain, size, terms, rgba.data());
    if (r == PRT_OK)
      r = prt_wavelet_prepare_light(asset, rgba.data(), rgba.data(), zero_blocks.data());
    return r;
  });
}

double time_wavelet_shading(const prt_asset* asset, prt_backend backend,
                            const std::vector<float>& prepared,
                            const std::vector<std::uint8_t>& zero_blocks, std::uint32_t vertices,
                            int frames, std::vector<float>* out) {
  out->resize(std::size_t(vertices) * 3);
  return median_frame_ms(frames,
                         std::string("prt_wavelet_shade(") + prt_backend_name(backend) + ")", [&] {
                           return prt_wavelet_shade(asset, backend, prepared.data(),
                                                    zero_blocks.data(), 0, vertices, out->data());
                         });
}

// Rows of one (keep, quantiser) on every light and each of its light terms.
void measure_quantized(const Scene& scene, const WaveletTransfer& t, const std::string& quantizer,
                       const std::vector<const Measurement*>& ms,
                       const std::vector<TradeLight>& lights,
                       const std::vector<std::vector<float>>& full_lights, const Settings& o,
                       const TradeInput& input, const Context& ctx, std::vector<Row>* rows) {
  const std::uint32_t keep = ms.front()->keep;
  const QuantizedWavelet q =
      quantize_wavelet_transfer(t, parse_wavelet_quantizer(quantizer.c_str()), keep);
  const std::size_t section = encode_wvlt_section(q).size();
  const std::vector<std::uint8_t> blob =
      build_wavelet_blob(scene, q, "prtkit wavelet trade: " + input.scene);
  const RuntimeAsset runtime = load_runtime_asset(blob);
  const prt_asset* asset = runtime.asset.get();
  const std::uint32_t vertices = static_cast<std::uint32_t>(t.vertex_count);
  for (std::size_t l = 0; l < lights.size(); ++l) {
    for (const Measurement* m : ms) {
      const std::vector<float> light = selected(full_lights[l], t.param, t.size, m->terms);
      std::vector<float> prepared(light.size());
      std::vector<std::uint8_t> zero_blocks(light.size() / 4 / 256);
      check_runtime(
          prt_wavelet_prepare_light(asset, light.data(), prepared.data(), zero_blocks.data()),
          "prt_wavelet_prepare_light");
      Row row = wavelet_row(t, *m, lights[l]);
      std::vector<float> shaded, simd_shaded;
      row.simd_ms = time_wavelet_shading(asset, PRT_BACKEND_SIMD, prepared, zero_blocks, vertices,
                                         input.frames, &simd_shaded);
      row.cpu_ms = time_wavelet_shading(asset, PRT_BACKEND_CPU, prepared, zero_blocks, vertices,
                                        input.frames, &shaded);
      row.light_ms = time_light_update(lights[l], asset, t.param, t.size, m->terms, input.frames);
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
                   const std::vector<std::vector<float>>& full_lights, const Settings& o,
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
                      const std::vector<TradeLight>& lights, const Settings& o,
                      const TradeInput& input, const Context& ctx, std::vector<Row>* rows,
                      std::vector<std::string>* notes) {
  WaveletTransferSettings settings;
  settings.param = bake.param;
  settings.size = bake.size;
  settings.samples = o.samples;
  settings.keep = bake.keep;
  settings.seed = input.seed;
  settings.vertex_stride = o.vertex_stride;
  if (!input.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(input.albedo);
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
      measure_quantized(scene, t, key.second, ms, lights, full_lights, o, input, ctx, rows);
    }
  }
}

// --- the sweep ----------------------------------------------------------------------------------

class WaveletTrade final : public TechniqueTrade {
 public:
  TradeInput defaults() const override {
    TradeInput input;
    input.ref_spp = 2048;
    input.frames = 10;
    return input;
  }

  OptionList options() override {
    OptionList list;
    list.add("--sizes", &o_.sizes,
             "Cube sizes N of the N sweep (the bake time grows with N squared)");
    list.add("--base-size", &o_.base_size, "Cube size of the K and M sweeps");
    list.add("--keeps", &o_.keeps, "Kept coefficients K of the K sweep");
    list.add("--base-keep", &o_.base_keep, "K of the M sweep (0 = 4 % of the coefficients)");
    list.add("--light-terms", &o_.light_terms,
             "Light detail coefficients M of the M sweep (a count or 'all')");
    list.add("--paraboloid-sizes", &o_.paraboloid_sizes,
             "Dual-paraboloid sizes P compared with the cube");
    list.add("--no-paraboloid", &o_.no_paraboloid, "Skip the parameterisation sweep");
    list.add("--quantizer", &o_.quantizer,
             "Quantiser of the N, M and param sweeps: vertex or band");
    list.add("--samples", &o_.samples, "Rays per texel of the wavelet bakes (a square)");
    list.add("--sh-orders", &o_.sh_orders, "SH orders compared");
    list.add("--sh-rays", &o_.sh_rays, "Rays per vertex of the SH bakes").range(1, 1u << 24);
    list.add("--sh-bits", &o_.sh_bits, "SH quantisation bits (8, 16)");
    list.add("--vertex-stride", &o_.vertex_stride,
             "Bake and measure every n-th vertex only (quick runs; the sh bakes and the "
             "reference still cover all)")
        .range(1, 1u << 20);
    return list;
  }

  void check(const TradeInput&) const override { check_settings(o_); }

  void prepare(const Scene& scene, const TradeInput& input, const Context& ctx) override {
    bakes_ = wavelet_bakes(o_);
    for (const std::string& path : input.envs)
      lights_.push_back(load_trade_light(path, scene, o_, input, ctx));
  }

  // The tables are rewritten after every bake, so a long run that stops still leaves its rows.
  void sweep(const Scene& scene, const EmbreeScene& rays, const TradeInput& input,
             const Context& ctx) override {
    std::vector<Row> rows;
    std::vector<std::string> notes;  // light checks that failed, for trade.md
    const std::size_t total = bakes_.size() + o_.sh_orders.size();
    std::size_t done = 0;
    auto write_tables = [&] {
      write_csv(input.out_dir + "/trade.csv", rows, o_, input, scene.vertex_count());
      write_markdown(input.out_dir + "/trade.md", rows, lights_, o_, input, scene,
                     ctx.thread_count(), notes);
    };
    for (std::uint32_t order : o_.sh_orders) {
      ctx.info("bake " + std::to_string(++done) + "/" + std::to_string(total) + ": sh order " +
               std::to_string(order) + ", " + std::to_string(o_.sh_rays) + " rays");
      measure_sh(scene, rays, order, lights_, o_, input, ctx, &rows);
      write_tables();
    }
    for (const WaveletBake& bake : bakes_) {
      ctx.info("bake " + std::to_string(++done) + "/" + std::to_string(total) + ": wavelet " +
               wavelet_param_name(bake.param) + " " + std::to_string(bake.size) + ", K " +
               std::to_string(bake.keep) + ", " + std::to_string(bake.measurements.size()) +
               " measurement(s) per map");
      run_wavelet_bake(scene, rays, bake, lights_, o_, input, ctx, &rows, &notes);
      write_tables();
    }
  }

 private:
  Settings o_;
  std::vector<WaveletBake> bakes_;
  std::vector<TradeLight> lights_;
};

}  // namespace
}  // namespace wavelet_trade

std::unique_ptr<TechniqueTrade> make_wavelet_trade() {
  return std::make_unique<wavelet_trade::WaveletTrade>();
}

}  // namespace prt::bake
