// SPDX-License-Identifier: MIT
// prt-bake trade SCENE --env MAP ... --out-dir DIR: the measured speed/accuracy trade of technique
// `sh` (docs/sh/trade.md). Three sweeps around a base setting (order, rays, bounces): each
// setting is baked in-process, quantised, written to a blob and loaded through the runtime; each
// map is projected to SH by the runtime and the blob shaded by the runtime on the CPU and SIMD
// backends; the result is compared with the reference renderer's per-vertex radiance for the same
// bounces (cached in DIR/cache). Writes DIR/trade.csv and DIR/trade.md.
#include <prt/prt.h>
#include <prt/prt_sh.h>
#include <prt/prt_sh_asset.h>

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "command.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "prt/io/envmap.hpp"
#include "prt/io/image_io.hpp"
#include "prt/io/radiance_error.hpp"
#include "trade_common.hpp"

namespace prt::bake::cli {
namespace {

namespace fs = std::filesystem;

struct TradeOptions {
  std::string scene, out_dir, cache_dir, albedo;
  std::vector<std::string> envs;
  std::vector<std::uint32_t> orders{2, 3, 4, 5, 6, 7, 8}, rays{64, 256, 1024};
  std::vector<int> bounces{0, 1};
  std::uint32_t base_rays = 256, base_order = 6, ref_spp = 4096, seed = 0;
  int bits = 16, frames = 20;
};

// One bake setting of the sweeps; `sweeps` names the sweeps it belongs to.
struct Setting {
  std::uint32_t order = 0, rays = 0;
  int bounces = 0;
  std::string sweeps;
};

struct Row {
  std::string map, projection, sweeps;
  std::uint32_t order = 0, rays = 0;
  int bounces = 0;
  double error = 0.0, ref_noise = 0.0, quant_shading_error = 0.0;
  double cpu_ms = -1.0, simd_ms = -1.0;  // < 0: backend not available
  std::size_t blob_bytes = 0;
  double bake_seconds = 0.0, rays_traced = 0.0;
  double quant_max_abs = 0.0, quant_rms_abs = 0.0, transfer_max_abs = 0.0;
};

// --- settings -----------------------------------------------------------------------------------

// Order sweep at (base rays, 0 bounces); ray sweep at (base order, 0 bounces); bounce sweep at
// (base order, base rays). A setting in several sweeps is baked once.
std::vector<Setting> sweep_settings(const TradeOptions& o) {
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

void check_options(const TradeOptions& o) {
  if (o.envs.empty()) throw Error("trade: give at least one --env MAP");
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
  if (o.frames < 1) throw Error("--frames: must be >= 1");
}

// --- reference cache ----------------------------------------------------------------------------

Reference reference_for(const Scene& scene, const ShLight& light, int bounces,
                        const TradeOptions& o, const Context& ctx) {
  ReferenceRequest request;
  request.scene_path = o.scene;
  request.map_name = light.name;
  request.albedo = o.albedo;
  request.cache_dir = o.cache_dir;
  request.bounces = bounces;
  request.spp = o.ref_spp;
  request.seed = o.seed;
  return cached_reference(scene, *light.map, request, ctx);
}

// --- runtime shading ----------------------------------------------------------------------------

// Median milliseconds of `frames` shadings of every vertex on `backend` (after one warm-up), or
// -1 when the backend is not available. `out` receives the last frame's radiance.
double time_shading(const prt_asset* asset, prt_backend backend, const float* light,
                    std::uint32_t vertices, int frames, std::vector<float>* out) {
  out->resize(std::size_t(vertices) * 3);
  return median_frame_ms(
      frames, std::string("prt_sh_shade_on(") + prt_backend_name(backend) + ")",
      [&] { return prt_sh_shade_on(asset, backend, light, 0, vertices, out->data()); });
}

// The leading order^2 coefficients of a light projected at a higher order.
std::vector<float> truncated(const std::vector<float>& rgb, std::uint32_t order) {
  return std::vector<float>(rgb.begin(), rgb.begin() + std::size_t(order) * order * 3);
}

std::vector<glm::vec3> as_light(const std::vector<float>& rgb) {
  return as_vec3(rgb);
}

// --- one setting --------------------------------------------------------------------------------

struct Baked {
  ShTransfer transfer;
  QuantizedShTransfer quantized;
  std::vector<std::uint8_t> blob;
};

Baked bake_setting(const Scene& scene, const EmbreeScene& rays, const Setting& s,
                   const TradeOptions& o, const Context& ctx) {
  ShTransferSettings settings;
  settings.order = s.order;
  settings.rays = s.rays;
  settings.bounces = s.bounces;
  settings.kind = s.bounces > 0 ? ShTransferKind::Interreflected : ShTransferKind::Shadowed;
  settings.seed = o.seed;
  if (!o.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(o.albedo);
  }
  Baked baked;
  baked.transfer = compute_sh_transfer(scene, &rays, settings, ctx);
  baked.quantized = quantize_sh_transfer(baked.transfer, o.bits, s.bounces);
  baked.blob = build_sh_blob(scene, baked.quantized, "prtkit sh trade: " + o.scene);
  return baked;
}

Row measure(const Baked& baked, const prt_asset* asset, const Setting& s, const ShLight& light,
            const Reference& ref, const TradeOptions& o) {
  const std::uint32_t vertices = static_cast<std::uint32_t>(baked.transfer.vertex_count);
  const std::vector<float> l = truncated(light.rgb, s.order);
  Row row;
  row.map = light.name;
  row.projection = light.projection;
  row.sweeps = s.sweeps;
  row.order = s.order;
  row.rays = s.rays;
  row.bounces = s.bounces;
  std::vector<float> shaded, simd_shaded;
  row.simd_ms = time_shading(asset, PRT_BACKEND_SIMD, l.data(), vertices, o.frames, &simd_shaded);
  row.cpu_ms = time_shading(asset, PRT_BACKEND_CPU, l.data(), vertices, o.frames, &shaded);
  const std::vector<glm::vec3> radiance = as_vec3(shaded);
  row.error = io::relative_rmse(radiance, ref.radiance);
  row.ref_noise = ref.noise;
  // What 16/8-bit storage costs in radiance: runtime shading vs the float transfer's.
  row.quant_shading_error =
      io::relative_rmse(radiance, shade_sh_transfer(baked.transfer, as_light(l)));
  row.blob_bytes = baked.blob.size();
  row.bake_seconds = baked.transfer.seconds;
  row.rays_traced = static_cast<double>(baked.transfer.rays_traced);
  row.quant_max_abs = baked.quantized.max_abs_error;
  row.quant_rms_abs = baked.quantized.rms_abs_error;
  row.transfer_max_abs = baked.quantized.max_abs_value;
  return row;
}

// --- output -------------------------------------------------------------------------------------

double without_noise(const Row& r) {
  return noise_removed(r.error, r.ref_noise);
}

void write_csv(const std::string& path, const std::vector<Row>& rows, const TradeOptions& o,
               std::size_t vertices) {
  std::ofstream csv(path);
  csv << "scene,map,light_projection,sweeps,order,rays,bounces,transfer,bits,vertices,"
         "rel_rmse,ref_noise,rel_rmse_noise_removed,ref_spp,shade_cpu_ms,shade_simd_ms,blob_bytes,"
         "bake_seconds,"
         "rays_traced,rays_per_second,quant_max_abs,quant_rms_abs,transfer_max_abs,"
         "quant_shading_rel_rmse\n";
  for (const Row& r : rows) {
    csv << stem(o.scene) << ',' << r.map << ',' << r.projection << ',' << r.sweeps << ',' << r.order
        << ',' << r.rays << ',' << r.bounces << ','
        << (r.bounces > 0 ? "interreflected" : "shadowed") << ',' << o.bits << ',' << vertices
        << ',' << format("%.6g", r.error) << ',' << format("%.6g", r.ref_noise) << ','
        << format("%.6g", without_noise(r)) << ',' << o.ref_spp << ',' << ms_text(r.cpu_ms) << ','
        << ms_text(r.simd_ms) << ',' << r.blob_bytes << ',' << format("%.4g", r.bake_seconds) << ','
        << format("%.0f", r.rays_traced) << ','
        << format("%.4g", r.bake_seconds > 0 ? r.rays_traced / r.bake_seconds : 0.0) << ','
        << format("%.4g", r.quant_max_abs) << ',' << format("%.4g", r.quant_rms_abs) << ','
        << format("%.4g", r.transfer_max_abs) << ',' << format("%.4g", r.quant_shading_error)
        << '\n';
  }
  if (!csv) throw Error(path + ": cannot write");
}

std::string joined(const std::vector<std::uint32_t>& values) {
  std::string text;
  for (std::uint32_t v : values) text += (text.empty() ? "" : ",") + std::to_string(v);
  return text;
}

void write_markdown(const std::string& path, const std::vector<Row>& rows,
                    const std::vector<ShLight>& lights, const TradeOptions& o, const Scene& scene,
                    unsigned threads, const std::string& simd_note) {
  std::ofstream md(path);
  md << "# Technique sh: speed versus accuracy (prt-bake trade)\n\n";
  md << "Scene `" << fs::path(o.scene).filename().string() << "`: " << scene.vertex_count()
     << " vertices, " << scene.triangle_count() << " triangles. Transfer quantised to " << o.bits
     << " bits; albedo " << (o.albedo.empty() ? "from the materials" : o.albedo) << ".\n\n";
  md << "Sweeps: order " << joined(o.orders) << " at " << o.base_rays << " rays, shadowed; rays "
     << joined(o.rays) << " at order " << o.base_order << ", shadowed; bounces";
  for (int b : o.bounces) md << ' ' << b;
  md << " at order " << o.base_order << ", " << o.base_rays
     << " rays (0 = shadowed, more = interreflected). Reference: " << o.ref_spp
     << " samples per vertex, the same bounces; seed " << o.seed << ".\n\n";
  md << "Error = relative RMSE of per-vertex RGB radiance against the reference, "
        "sqrt(mean |x - ref|^2) / sqrt(mean |ref|^2); ref noise = the reference's own estimate "
        "of the same figure; "
        "error with noise removed = sqrt(error^2 - noise^2), the error with the reference's "
        "independent noise taken out. Shading time = median of "
     << o.frames << " frames of prt_sh_shade_on over all vertices, one thread. "
     << "Quant. = the relative RMSE that " << o.bits
     << "-bit storage adds to the shading (runtime vs float transfer).\n\n";
  md << "Machine: " << cpu_model() << ", " << std::thread::hardware_concurrency()
     << " hardware threads; bake on " << threads << " threads; SIMD backend: " << simd_note
     << ".\n";
  for (const ShLight& light : lights) {
    md << "\n## " << light.name << " (" << io::env_mapping_name(light.map->mapping()) << ", "
       << light.map->width() << "x" << light.map->height() << ", light by " << light.projection
       << ")\n\n";
    md << "| sweep | order | rays | bounces | error % | ref noise % | error, noise removed % | CPU "
          "ms | SIMD ms | blob KiB "
          "| bake s | Mrays/s | quant. % |\n";
    md << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows) {
      if (r.map != light.name) continue;
      md << "| " << r.sweeps << " | " << r.order << " | " << r.rays << " | " << r.bounces << " | "
         << format("%.2f", 100 * r.error) << " | " << format("%.2f", 100 * r.ref_noise) << " | "
         << format("%.2f", 100 * without_noise(r)) << " | " << ms_text(r.cpu_ms) << " | "
         << ms_text(r.simd_ms) << " | " << format("%.0f", r.blob_bytes / 1024.0) << " | "
         << format("%.2f", r.bake_seconds) << " | "
         << format("%.1f", r.bake_seconds > 0 ? 1e-6 * r.rays_traced / r.bake_seconds : 0.0)
         << " | " << format("%.3f", 100 * r.quant_shading_error) << " |\n";
    }
  }
  if (!md) throw Error(path + ": cannot write");
}

// --- the command --------------------------------------------------------------------------------

void run_trade(TradeOptions o, const CommandEnv& env) {
  check_options(o);
  const Context ctx = env.context();
  if (o.cache_dir.empty()) o.cache_dir = o.out_dir + "/cache";
  fs::create_directories(o.out_dir);
  fs::create_directories(o.cache_dir);
  const std::vector<Setting> settings = sweep_settings(o);
  std::uint32_t max_order = 0;
  for (const Setting& s : settings) max_order = std::max(max_order, s.order);

  const Scene scene = import_scene(o.scene, ctx);
  std::vector<ShLight> lights;
  for (const std::string& path : o.envs) lights.push_back(load_sh_light(path, max_order, ctx));
  std::set<std::string> names;
  for (const ShLight& light : lights) {
    if (!names.insert(light.name).second)
      throw Error("--env: two maps are named '" + light.name + "'");
  }
  std::set<int> bounce_counts;
  for (const Setting& s : settings) bounce_counts.insert(s.bounces);
  std::map<std::pair<std::string, int>, Reference> references;
  for (const ShLight& light : lights) {
    for (int b : bounce_counts)
      references[{light.name, b}] = reference_for(scene, light, b, o, ctx);
  }

  const EmbreeScene rays(scene, ctx);
  std::vector<Row> rows;
  for (std::size_t i = 0; i < settings.size(); ++i) {
    const Setting& s = settings[i];
    ctx.info("setting " + std::to_string(i + 1) + "/" + std::to_string(settings.size()) +
             ": order " + std::to_string(s.order) + ", " + std::to_string(s.rays) + " rays, " +
             std::to_string(s.bounces) + " bounces");
    const Baked baked = bake_setting(scene, rays, s, o, ctx);
    const RuntimeAsset runtime = load_runtime_asset(baked.blob);
    for (const ShLight& light : lights) {
      rows.push_back(
          measure(baked, runtime.asset.get(), s, light, references.at({light.name, s.bounces}), o));
      const Row& r = rows.back();
      ctx.info("  " + light.name + format(": error %.3f %%", 100 * r.error) +
               format(", CPU %.3f ms", r.cpu_ms) + ", SIMD " + ms_text(r.simd_ms) + " ms");
    }
  }
  write_csv(o.out_dir + "/trade.csv", rows, o, scene.vertex_count());
  write_markdown(o.out_dir + "/trade.md", rows, lights, o, scene, ctx.thread_count(),
                 simd_description());
  ctx.info("wrote " + o.out_dir + "/trade.csv and trade.md");
}

}  // namespace

void add_trade_command(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<TradeOptions>();
  TradeOptions& o = *options;
  auto* cmd = app.add_subcommand(
      "trade", "Measure technique sh's speed/accuracy trade: sweep order, rays and bounces");
  cmd->add_option("SCENE", o.scene, "Scene file (.gltf, .glb, .obj)")->required();
  cmd->add_option("--env", o.envs, "Environment map (.hdr); repeat for several")
      ->required()
      ->allow_extra_args(false);
  cmd->add_option("--out-dir", o.out_dir, "Where trade.csv and trade.md go")->required();
  cmd->add_option("--cache-dir", o.cache_dir,
                  "Where reference radiance is cached (default: OUT_DIR/cache)");
  cmd->add_option("--orders", o.orders, "SH orders of the order sweep")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--rays", o.rays, "Rays per vertex of the ray sweep")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--bounces", o.bounces, "Bounces of the bounce sweep (0 = shadowed)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--base-rays", o.base_rays, "Rays of the order and bounce sweeps")
      ->check(CLI::Range(1u, 1u << 24))
      ->capture_default_str();
  cmd->add_option("--base-order", o.base_order, "Order of the ray and bounce sweeps")
      ->capture_default_str();
  cmd->add_option("--ref-spp", o.ref_spp, "Reference samples per vertex")
      ->check(CLI::Range(2u, 1u << 30))
      ->capture_default_str();
  cmd->add_option("--bits", o.bits, "Quantisation bits: 8 or 16")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  cmd->add_option("--frames", o.frames, "Timed shading frames per measurement (median)")
      ->capture_default_str();
  cmd->add_option("--albedo", o.albedo,
                  "Diffuse albedo r,g,b for every surface (default: from the materials)");
  cmd->add_option("--seed", o.seed, "Seed of the bakes and references")->capture_default_str();
  cmd->callback([&env, options] { run_trade(*options, env); });
}

}  // namespace prt::bake::cli
