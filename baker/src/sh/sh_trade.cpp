// SPDX-License-Identifier: MIT
// prt-bake trade sh SCENE --env MAP ... --out-dir DIR: the measured speed/accuracy trade of
// technique `sh` (docs/sh/trade.md). Three sweeps around a base setting (order, rays, bounces):
// each setting is baked in-process, quantised, written to a blob and loaded through the runtime;
// each map is projected to SH by the runtime and the blob shaded by the runtime on the CPU and
// SIMD backends; the result is compared with the reference renderer's per-vertex radiance for the
// same bounces (cached). Each light is also measured de-ringed at each --dering strength
// (prt_sh_dering_light; 0 = as projected). Writes DIR/trade.csv and DIR/trade.md.
#include <prt/prt.h>
#include <prt/prt_sh.h>
#include <prt/prt_sh_asset.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "prt/io/radiance_error.hpp"

#include "../common/trade_common.hpp"
#include "sh_technique.hpp"

namespace prt::bake {
namespace {

using namespace trade;

// The sweeps' own flags (the shared ones are TradeInput).
struct ShTradeSettings {
  std::vector<std::uint32_t> orders{2, 3, 4, 5, 6, 7, 8}, rays{64, 256, 1024};
  std::vector<int> bounces{0, 1};
  std::uint32_t base_rays = 256, base_order = 6;
  int bits = 16;
  std::vector<std::string> dering{"0"};  // strengths, parsed by dering_strengths
};

// One bake setting of the sweeps; `sweeps` names the sweeps it belongs to.
struct Setting {
  std::uint32_t order = 0, rays = 0;
  int bounces = 0;
  std::string sweeps;
};

struct ShTradeRow {
  std::string map, projection, sweeps;
  std::uint32_t order = 0, rays = 0;
  int bounces = 0;
  float dering = 0.0f;  // de-ringing strength of the light
  double error = 0.0, ref_noise = 0.0, quant_shading_error = 0.0;
  double negative_share = 0.0;           // vertices shaded below zero in some channel (ringing)
  double cpu_ms = -1.0, simd_ms = -1.0;  // < 0: backend not available
  std::size_t blob_bytes = 0;
  double bake_seconds = 0.0, rays_traced = 0.0;
  double quant_max_abs = 0.0, quant_rms_abs = 0.0, transfer_max_abs = 0.0;

  double clean_error() const { return noise_removed(error, ref_noise); }
  double rays_per_second() const { return bake_seconds > 0 ? rays_traced / bake_seconds : 0.0; }
};

// --- settings -----------------------------------------------------------------------------------

// Order sweep at (base rays, 0 bounces); ray sweep at (base order, 0 bounces); bounce sweep at
// (base order, base rays). A setting in several sweeps is baked once.
std::vector<Setting> sweep_settings(const ShTradeSettings& o) {
  std::map<std::tuple<std::uint32_t, std::uint32_t, int>, std::string> sweeps;
  auto add = [&](std::uint32_t order, std::uint32_t rays, int bounces, const char* sweep) {
    std::string& names = sweeps[{order, rays, bounces}];
    names += (names.empty() ? "" : "+") + std::string(sweep);
  };
  for (std::uint32_t order : o.orders) add(order, o.base_rays, 0, "order");
  for (std::uint32_t rays : o.rays) add(o.base_order, rays, 0, "rays");
  for (int bounces : o.bounces) add(o.base_order, o.base_rays, bounces, "bounces");
  std::vector<Setting> settings;
  for (const auto& [key, names] : sweeps) {
    settings.push_back({std::get<0>(key), std::get<1>(key), std::get<2>(key), names});
  }
  // Bounce count first, then order, then rays: the table reads in sweep order.
  std::stable_sort(settings.begin(), settings.end(), [](const Setting& a, const Setting& b) {
    return std::tie(a.bounces, a.order, a.rays) < std::tie(b.bounces, b.order, b.rays);
  });
  return settings;
}

// The --dering strengths: each a finite number >= 0, as prt_sh_dering_light takes.
std::vector<float> dering_strengths(const ShTradeSettings& o) {
  std::vector<float> strengths;
  for (const std::string& text : o.dering) {
    char* end = nullptr;
    const float value = std::strtof(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(value) || value < 0.0f)
      throw Error("--dering: '" + text + "' is not a strength (a number >= 0)");
    strengths.push_back(value);
  }
  if (strengths.empty()) throw Error("trade: --dering needs at least one value");
  return strengths;
}

std::string joined_strengths(const std::vector<float>& strengths) {
  std::string text;
  for (float s : strengths) text += (text.empty() ? "" : ",") + format("%g", s);
  return text;
}

void check_settings(const ShTradeSettings& o) {
  if (o.orders.empty() || o.rays.empty() || o.bounces.empty())
    throw Error("trade: --orders, --rays and --bounces need at least one value each");
  for (std::uint32_t order : o.orders) {
    if (order < 1 || order > PRT_SH_MAX_ORDER)
      throw Error("--orders: " + std::to_string(order) + " is outside 1.." +
                  std::to_string(PRT_SH_MAX_ORDER));
  }
  if (o.base_order < 1 || o.base_order > PRT_SH_MAX_ORDER)
    throw Error("--base-order: outside 1.." + std::to_string(PRT_SH_MAX_ORDER));
  for (std::uint32_t r : o.rays) {
    if (r < 1) throw Error("--rays: every value must be >= 1");
  }
  for (int b : o.bounces) {
    if (b < 0 || b > 64) throw Error("--bounces: every value must be in 0..64");
  }
  dering_strengths(o);
}

// --- one setting --------------------------------------------------------------------------------

struct Baked {
  ShTransfer transfer;
  QuantizedShTransfer quantized;
  std::vector<std::uint8_t> blob;
};

Baked bake_setting(const Scene& scene, const EmbreeScene& rays, const Setting& s,
                   const ShTradeSettings& o, const TradeInput& input, const Context& ctx) {
  ShTransferSettings settings;
  settings.order = s.order;
  settings.rays = s.rays;
  settings.bounces = s.bounces;
  settings.kind = s.bounces > 0 ? ShTransferKind::Interreflected : ShTransferKind::Shadowed;
  settings.seed = input.seed;
  if (!input.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(input.albedo);
  }
  Baked baked;
  baked.transfer = compute_sh_transfer(scene, &rays, settings, ctx);
  baked.quantized = quantize_sh_transfer(baked.transfer, o.bits, s.bounces);
  baked.blob = build_sh_blob(scene, baked.quantized, "prtkit sh trade: " + input.scene);
  return baked;
}

// The light at the setting's order, windowed by prt_sh_dering_light at `dering`.
std::vector<float> dering_light(const ShLight& light, std::uint32_t order, float dering) {
  std::vector<float> l = light.at_order(order);
  if (prt_sh_dering_light(order, dering, l.data(), l.data()) != PRT_OK)
    throw Error("trade: prt_sh_dering_light refused strength " + format("%g", dering));
  return l;
}

// The share of vertices with a negative channel: radiance never is, SH ringing makes it so.
double negative_share(const std::vector<glm::vec3>& radiance) {
  const auto negative = std::count_if(radiance.begin(), radiance.end(), [](const glm::vec3& c) {
    return c.r < 0.0f || c.g < 0.0f || c.b < 0.0f;
  });
  return radiance.empty() ? 0.0 : static_cast<double>(negative) / radiance.size();
}

ShTradeRow measure(const Baked& baked, const prt_asset* asset, const Setting& s,
                   const ShLight& light, float dering, const Reference& ref, int frames) {
  const std::uint32_t vertices = static_cast<std::uint32_t>(baked.transfer.vertex_count);
  const std::vector<float> l = dering_light(light, s.order, dering);
  ShTradeRow row;
  row.map = light.name;
  row.projection = light.projection;
  row.sweeps = s.sweeps;
  row.order = s.order;
  row.rays = s.rays;
  row.bounces = s.bounces;
  row.dering = dering;
  std::vector<float> shaded, simd_shaded;
  row.simd_ms = time_sh_shading(asset, PRT_BACKEND_SIMD, l, vertices, frames, &simd_shaded);
  row.cpu_ms = time_sh_shading(asset, PRT_BACKEND_CPU, l, vertices, frames, &shaded);
  const std::vector<glm::vec3> radiance = as_vec3(shaded);
  row.error = io::relative_rmse(radiance, ref.radiance);
  row.ref_noise = ref.noise;
  row.negative_share = negative_share(radiance);
  // What 16/8-bit storage costs in radiance: runtime shading vs the float transfer's.
  row.quant_shading_error =
      io::relative_rmse(radiance, shade_sh_transfer(baked.transfer, as_vec3(l)));
  row.blob_bytes = baked.blob.size();
  row.bake_seconds = baked.transfer.seconds;
  row.rays_traced = static_cast<double>(baked.transfer.rays_traced);
  row.quant_max_abs = baked.quantized.max_abs_error;
  row.quant_rms_abs = baked.quantized.rms_abs_error;
  row.transfer_max_abs = baked.quantized.max_abs_value;
  return row;
}

// --- output -------------------------------------------------------------------------------------

const std::vector<std::string> kCsvColumns = {"scene",
                                              "map",
                                              "light_projection",
                                              "sweeps",
                                              "order",
                                              "rays",
                                              "bounces",
                                              "dering",
                                              "transfer",
                                              "bits",
                                              "vertices",
                                              "rel_rmse",
                                              "ref_noise",
                                              "rel_rmse_noise_removed",
                                              "ref_spp",
                                              "shade_cpu_ms",
                                              "shade_simd_ms",
                                              "blob_bytes",
                                              "bake_seconds",
                                              "rays_traced",
                                              "rays_per_second",
                                              "quant_max_abs",
                                              "quant_rms_abs",
                                              "transfer_max_abs",
                                              "quant_shading_rel_rmse",
                                              "negative_vertex_share"};

std::vector<std::string> csv_cells(const ShTradeRow& r, const ShTradeSettings& o,
                                   const TradeInput& input, std::size_t vertices) {
  return {stem(input.scene),
          r.map,
          r.projection,
          r.sweeps,
          std::to_string(r.order),
          std::to_string(r.rays),
          std::to_string(r.bounces),
          format("%g", r.dering),
          r.bounces > 0 ? "interreflected" : "shadowed",
          std::to_string(o.bits),
          std::to_string(vertices),
          format("%.6g", r.error),
          format("%.6g", r.ref_noise),
          format("%.6g", r.clean_error()),
          std::to_string(input.ref_spp),
          ms_text(r.cpu_ms),
          ms_text(r.simd_ms),
          std::to_string(r.blob_bytes),
          format("%.4g", r.bake_seconds),
          format("%.0f", r.rays_traced),
          format("%.4g", r.rays_per_second()),
          format("%.4g", r.quant_max_abs),
          format("%.4g", r.quant_rms_abs),
          format("%.4g", r.transfer_max_abs),
          format("%.4g", r.quant_shading_error),
          format("%.4g", r.negative_share)};
}

void write_csv(const std::string& path, const std::vector<ShTradeRow>& rows,
               const ShTradeSettings& o, const TradeInput& input, std::size_t vertices) {
  std::ofstream csv(path);
  write_csv_row(csv, kCsvColumns);
  for (const ShTradeRow& r : rows) write_csv_row(csv, csv_cells(r, o, input, vertices));
  check_written(csv, path);
}

const std::vector<Column> kMarkdownColumns = {{"sweep", false},
                                              {"order"},
                                              {"rays"},
                                              {"bounces"},
                                              {"dering"},
                                              {"error %"},
                                              {"ref noise %"},
                                              {"error, noise removed %"},
                                              {"CPU ms"},
                                              {"SIMD ms"},
                                              {"blob KiB"},
                                              {"bake s"},
                                              {"Mrays/s"},
                                              {"quant. %"},
                                              {"negative vertices %"}};

std::vector<std::string> markdown_cells(const ShTradeRow& r) {
  return {r.sweeps,
          std::to_string(r.order),
          std::to_string(r.rays),
          std::to_string(r.bounces),
          format("%g", r.dering),
          format("%.2f", 100 * r.error),
          format("%.2f", 100 * r.ref_noise),
          format("%.2f", 100 * r.clean_error()),
          ms_text(r.cpu_ms),
          ms_text(r.simd_ms),
          format("%.0f", r.blob_bytes / 1024.0),
          format("%.2f", r.bake_seconds),
          format("%.1f", 1e-6 * r.rays_per_second()),
          format("%.3f", 100 * r.quant_shading_error),
          format("%.2f", 100 * r.negative_share)};
}

void write_markdown(const std::string& path, const std::vector<ShTradeRow>& rows,
                    const std::vector<ShLight>& lights, const ShTradeSettings& o,
                    const TradeInput& input, const Scene& scene, unsigned threads) {
  std::ofstream md(path);
  md << "# Technique sh: speed versus accuracy (prt-bake trade sh)\n\n";
  md << scene_description(input.scene, scene) << ". Transfer quantised to " << o.bits
     << " bits; albedo " << (input.albedo.empty() ? "from the materials" : input.albedo) << ".\n\n";
  md << "Sweeps: order " << joined(o.orders) << " at " << o.base_rays << " rays, shadowed; rays "
     << joined(o.rays) << " at order " << o.base_order << ", shadowed; bounces";
  for (int b : o.bounces) md << ' ' << b;
  md << " at order " << o.base_order << ", " << o.base_rays
     << " rays (0 = shadowed, more = interreflected). Light de-ringed at strengths "
     << joined_strengths(dering_strengths(o))
     << " (prt_sh_dering_light: 0 = as projected, 1 = the default window). Reference: "
     << input.ref_spp << " samples per vertex, the same bounces; seed " << input.seed << ".\n\n";
  md << "Error = relative RMSE of per-vertex RGB radiance against the reference, "
        "sqrt(mean |x - ref|^2) / sqrt(mean |ref|^2); ref noise = the reference's own estimate "
        "of the same figure; "
        "error with noise removed = sqrt(error^2 - noise^2), the error with the reference's "
        "independent noise taken out. Shading time = median of "
     << input.frames << " frames of prt_sh_shade over all vertices, one thread. "
     << "Quant. = the relative RMSE that " << o.bits
     << "-bit storage adds to the shading (runtime vs float transfer). Negative vertices = "
        "the share of vertices shaded below zero in some channel (SH ringing; light never is "
        "negative).\n\n";
  md << "Machine: " << machine_description(threads) << ".\n";
  for (const ShLight& light : lights) {
    md << "\n## " << light.name << " (" << io::env_mapping_name(light.map->mapping()) << ", "
       << light.map->width() << "x" << light.map->height() << ", light by " << light.projection
       << ")\n\n";
    write_markdown_header(md, kMarkdownColumns);
    for (const ShTradeRow& r : rows) {
      if (r.map == light.name) write_markdown_row(md, markdown_cells(r));
    }
  }
  check_written(md, path);
}

// --- the sweep ----------------------------------------------------------------------------------

class ShTrade final : public TechniqueTrade {
 public:
  TradeInput defaults() const override {
    TradeInput input;
    input.ref_spp = 4096;
    input.frames = 20;
    return input;
  }

  OptionList options() override {
    OptionList list;
    list.add("--orders", &o_.orders, "SH orders of the order sweep");
    list.add("--rays", &o_.rays, "Rays per vertex of the ray sweep");
    list.add("--bounces", &o_.bounces, "Bounces of the bounce sweep (0 = shadowed)");
    list.add("--base-rays", &o_.base_rays, "Rays of the order and bounce sweeps")
        .range(1, 1u << 24);
    list.add("--base-order", &o_.base_order, "Order of the ray and bounce sweeps");
    list.add("--bits", &o_.bits, "Quantisation bits: 8 or 16").choices({8, 16});
    list.add("--dering", &o_.dering,
             "De-ringing strengths of the light, each measured at every setting "
             "(prt_sh_dering_light: 0 = none, 1 = the default window)");
    return list;
  }

  void check(const TradeInput&) const override { check_settings(o_); }

  // The maps at the largest order swept, then a reference per map and bounce count.
  void prepare(const Scene& scene, const TradeInput& input, const Context& ctx) override {
    settings_ = sweep_settings(o_);
    dering_ = dering_strengths(o_);
    std::uint32_t max_order = 0;
    std::set<int> bounce_counts;
    for (const Setting& s : settings_) {
      max_order = std::max(max_order, s.order);
      bounce_counts.insert(s.bounces);
    }
    for (const std::string& path : input.envs)
      lights_.push_back(load_sh_light(path, max_order, ctx));
    for (const ShLight& light : lights_) {
      for (int b : bounce_counts) {
        references_[{light.name, b}] =
            cached_reference(scene, *light.map, light.name, b, input, ctx);
      }
    }
  }

  void sweep(const Scene& scene, const EmbreeScene& rays, const TradeInput& input,
             const Context& ctx) override {
    std::vector<ShTradeRow> rows;
    for (std::size_t i = 0; i < settings_.size(); ++i) {
      const Setting& s = settings_[i];
      ctx.info("setting " + std::to_string(i + 1) + "/" + std::to_string(settings_.size()) +
               ": order " + std::to_string(s.order) + ", " + std::to_string(s.rays) + " rays, " +
               std::to_string(s.bounces) + " bounces");
      const Baked baked = bake_setting(scene, rays, s, o_, input, ctx);
      const RuntimeAsset runtime = load_runtime_asset(baked.blob);
      for (const ShLight& light : lights_) {
        for (float dering : dering_) {
          rows.push_back(measure(baked, runtime.asset.get(), s, light, dering,
                                 references_.at({light.name, s.bounces}), input.frames));
          const ShTradeRow& r = rows.back();
          ctx.info("  " + light.name + (dering > 0 ? format(", dering %g", dering) : "") +
                   format(": error %.3f %%", 100 * r.error) + format(", CPU %.3f ms", r.cpu_ms) +
                   ", SIMD " + ms_text(r.simd_ms) + " ms");
        }
      }
    }
    write_csv(input.out_dir + "/trade.csv", rows, o_, input, scene.vertex_count());
    write_markdown(input.out_dir + "/trade.md", rows, lights_, o_, input, scene,
                   ctx.thread_count());
  }

 private:
  ShTradeSettings o_;
  std::vector<Setting> settings_;
  std::vector<float> dering_;
  std::vector<ShLight> lights_;
  std::map<std::pair<std::string, int>, Reference> references_;
};

}  // namespace

std::unique_ptr<TechniqueTrade> make_sh_trade() {
  return std::make_unique<ShTrade>();
}

}  // namespace prt::bake
