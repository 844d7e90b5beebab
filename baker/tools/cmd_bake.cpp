// SPDX-License-Identifier: MIT
// prt-bake bake SCENE --technique sh|wavelet -o OUT.prtk: bakes per-vertex transfer (SH vectors,
// prt/baker/sh/sh_blob.hpp; or sparse Haar rows, prt/baker/wavelet/wavelet_blob.hpp), quantises it, writes
// the blob, then loads it back through the runtime and checks it.
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "prt/baker/wavelet/wavelet_blob.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"

namespace prt::bake::cli {
namespace {

struct BakeOptions {
  std::string scene, technique = "sh", transfer = "shadowed", albedo, output, report;
  ShTransferSettings settings;
  int bits = 16;
  WaveletTransferSettings wavelet;
  std::string param = "cube", quantizer = "band";
  // Options given on the command line that belong to one technique only.
  std::vector<CLI::Option*> sh_only, wavelet_only;
  CLI::Option* keep = nullptr;
  CLI::Option* bounces = nullptr;
  std::uint32_t seed = 0;
};

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream file(path, std::ios::binary);
  if (!file || !file.write(reinterpret_cast<const char*>(bytes.data()),
                           static_cast<std::streamsize>(bytes.size()))) {
    throw Error(path + ": cannot write the blob");
  }
}

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c);
  return buffer;
}

// Rejects options of the other technique, naming them.
void check_applicable(const std::vector<CLI::Option*>& others, const std::string& technique) {
  for (const CLI::Option* option : others) {
    if (option->count() > 0) {
      throw Error(option->get_name() + " does not apply to --technique " + technique);
    }
  }
}

void run_sh_bake(const BakeOptions& options, CommandEnv& env) {
  const Context ctx = env.context();
  ShTransferSettings settings = options.settings;
  settings.seed = options.seed;
  settings.kind = parse_sh_transfer_kind(options.transfer.c_str());
  if (!options.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(options.albedo);
  }
  const Scene scene = import_scene(options.scene, ctx);
  const ShTransfer transfer = compute_sh_transfer(scene, nullptr, settings, ctx);
  const int bounces = settings.kind == ShTransferKind::Interreflected ? settings.bounces : 0;
  const QuantizedShTransfer quantized = quantize_sh_transfer(transfer, options.bits, bounces);
  const std::string info = "prtkit sh bake: " + options.scene + ", order " +
                           std::to_string(settings.order) + ", " +
                           sh_transfer_kind_name(settings.kind);
  const std::vector<std::uint8_t> blob = build_sh_blob(scene, quantized, info);
  write_bytes(options.output, blob);
  ctx.info(
      std::to_string(scene.vertex_count()) + " vertices, order " + std::to_string(settings.order) +
      ", " + sh_transfer_kind_name(settings.kind) + ": " +
      format("%.3g rays in %.1f s; ", static_cast<double>(transfer.rays_traced), transfer.seconds) +
      std::to_string(options.bits) + "-bit " +
      format("quantisation error max %.3g, RMS %.3g; ", quantized.max_abs_error,
             quantized.rms_abs_error) +
      "wrote " + options.output + " (" + std::to_string(blob.size()) + " bytes)");

  ShBakeReport report;
  report.scene = options.scene;
  report.vertices = scene.vertex_count();
  report.triangles = scene.triangle_count();
  report.settings = settings;
  report.bits = options.bits;
  report.threads = ctx.thread_count();
  report.transfer = &transfer;
  report.quantized = &quantized;
  report.output = options.output;
  report.blob_bytes = blob.size();
  report.check = check_sh_blob(blob, transfer, quantized);
  if (!options.report.empty()) {
    write_sh_bake_report(options.report, report);
    ctx.info("wrote " + options.report);
  }
  if (!report.check.passed)
    throw Error("self-check of " + options.output + ": " + report.check.message);
  ctx.info("self-check passed: " + report.check.message);
}

void run_wavelet_bake(const BakeOptions& options, CommandEnv& env) {
  const Context ctx = env.context();
  WaveletTransferSettings settings = options.wavelet;
  settings.seed = options.seed;
  settings.param = parse_wavelet_param(options.param.c_str());
  if (options.keep->count() == 0)
    settings.keep = default_wavelet_keep(settings.param, settings.size);
  if (settings.keep_energy > 0.0) settings.keep = 0;
  settings.bounces = options.bounces->count() > 0 ? options.settings.bounces : 0;
  if (!options.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(options.albedo);
  }
  const WaveletQuantizer quantizer = parse_wavelet_quantizer(options.quantizer.c_str());
  const Scene scene = import_scene(options.scene, ctx);
  const WaveletTransfer transfer = compute_wavelet_transfer(scene, nullptr, settings, ctx);
  std::uint32_t most = 0;
  for (std::size_t v = 0; v < transfer.vertex_count; ++v)
    most = std::max<std::uint32_t>(most, static_cast<std::uint32_t>(transfer.row_size(v)));
  QuantizedWavelet quantized = quantize_wavelet_transfer(
      transfer, quantizer, settings.keep_energy > 0.0 ? most : settings.keep);
  quantized.bounces = static_cast<std::uint32_t>(settings.bounces);
  const std::string info = "prtkit wavelet bake: " + options.scene + ", " +
                           wavelet_param_name(settings.param) + " " +
                           std::to_string(settings.size) + ", keep " +
                           std::to_string(quantized.keep) + ", quantizer " + options.quantizer;
  const std::vector<std::uint8_t> blob = build_wavelet_blob(scene, quantized, info);
  write_bytes(options.output, blob);
  const double vertices = double(std::max<std::size_t>(1, scene.vertex_count()));
  ctx.info(std::to_string(scene.vertex_count()) + " vertices, " +
           wavelet_param_name(settings.param) + " " + std::to_string(settings.size) + ": " +
           format("%.3g rays in %.1f s; ", double(transfer.rays_traced), transfer.seconds) +
           format("%.0f non-zeros/vertex (%.1f %% of the energy kept); ",
                  double(quantized.pair_count()) / vertices, 100.0 * transfer.mean_energy_kept) +
           options.quantizer +
           format(" quantiser RMS error %.3g of the largest coefficient; ",
                  quantized.max_abs_value > 0 ? quantized.rms_abs_error / quantized.max_abs_value
                                              : 0.0) +
           "wrote " + options.output + " (" + std::to_string(blob.size()) + " bytes, " +
           format("%.0f per vertex)", double(blob.size()) / vertices));

  WaveletBakeReport report;
  report.scene = options.scene;
  report.output = options.output;
  report.vertices = scene.vertex_count();
  report.triangles = scene.triangle_count();
  report.settings = settings;
  report.threads = ctx.thread_count();
  report.transfer = &transfer;
  report.quantized = &quantized;
  report.blob_bytes = blob.size();
  report.check = check_wavelet_blob(blob, transfer, quantized, settings.seed + 1);
  if (!options.report.empty()) {
    write_wavelet_bake_report(options.report, report);
    ctx.info("wrote " + options.report);
  }
  if (!report.check.passed)
    throw Error("self-check of " + options.output + ": " + report.check.message);
  ctx.info("self-check passed: " + report.check.message);
}

void run_bake(const BakeOptions& options, CommandEnv& env) {
  if (options.technique == "sh") {
    check_applicable(options.wavelet_only, "sh");
    run_sh_bake(options, env);
  } else if (options.technique == "wavelet") {
    check_applicable(options.sh_only, "wavelet");
    run_wavelet_bake(options, env);
  } else {
    throw Error("--technique: '" + options.technique + "' is not available (sh or wavelet)");
  }
}

void add_sh_options(CLI::App* cmd, BakeOptions& options) {
  ShTransferSettings& s = options.settings;
  s.order = 6;
  s.kind = ShTransferKind::Shadowed;
  s.rays = 1024;
  options.bounces = cmd->add_option("--bounces", s.bounces,
                                    "Bounce passes: sh interreflected (default 1), wavelet "
                                    "(default 0, at most 8)")
                        ->check(CLI::Range(0, 64));
  options.sh_only = {
      cmd->add_option("--order", s.order, "sh: SH order n (n*n coefficients)")
          ->check(CLI::Range(1u, 16u))
          ->capture_default_str(),
      cmd->add_option("--transfer", options.transfer, "sh: unshadowed|shadowed|interreflected")
          ->check(CLI::IsMember({"unshadowed", "shadowed", "interreflected"}))
          ->capture_default_str(),
      cmd->add_option("--rays", s.rays, "sh: directions per vertex")
          ->check(CLI::Range(1u, 1u << 24))
          ->capture_default_str(),
      cmd->add_option("--bits", options.bits, "sh: quantisation bits per value: 8 or 16")
          ->check(CLI::IsMember({8, 16}))
          ->capture_default_str()};
}

void add_wavelet_options(CLI::App* cmd, BakeOptions& options) {
  WaveletTransferSettings& w = options.wavelet;
  w.size = 64;
  w.samples = 1;
  options.keep = cmd->add_option("--keep", w.keep,
                                 "wavelet: coefficients kept per vertex (default 1000 at a cube "
                                 "of 64, the same fraction for other sizes; 0 = all)");
  CLI::Option* energy =
      cmd->add_option("--keep-energy", w.keep_energy,
                      "wavelet: keep the fewest coefficients holding this fraction of each "
                      "vertex's squared norm instead of --keep")
          ->check(CLI::Range(1e-9, 1.0));
  energy->excludes(options.keep);
  options.wavelet_only = {
      cmd->add_option("--cube", w.size,
                      "wavelet: face size S (cube N or paraboloid P), a power of two in 16..128")
          ->check(CLI::IsMember({16u, 32u, 64u, 128u}))
          ->capture_default_str(),
      cmd->add_option("--param", options.param, "wavelet: cube|dual-paraboloid")
          ->check(CLI::IsMember({"cube", "dual-paraboloid"}))
          ->capture_default_str(),
      options.keep,
      energy,
      cmd->add_option("--quantizer", options.quantizer,
                      "wavelet: band (a scale per face and wavelet level) or vertex (a scale per "
                      "vertex, the paper's)")
          ->check(CLI::IsMember({"band", "vertex"}))
          ->capture_default_str(),
      cmd->add_option("--samples", w.samples,
                      "wavelet: jittered rays per texel, a square k*k (1, 4, 9, 16, ...)")
          ->check(CLI::IsMember({1u, 4u, 9u, 16u, 25u, 36u, 49u, 64u}))
          ->capture_default_str(),
      cmd->add_option("--vertex-stride", w.vertex_stride,
                      "wavelet: bake every k-th vertex only (the others get empty rows; for "
                      "quick measurements)")
          ->check(CLI::Range(1u, 1u << 30))
          ->capture_default_str()};
}

}  // namespace

void add_bake_command(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<BakeOptions>();
  auto* cmd = app.add_subcommand("bake", "Bake a technique's transfer into a runtime blob");
  cmd->add_option("SCENE", options->scene, "Scene file (.gltf, .glb, .obj)")->required();
  cmd->add_option("--technique", options->technique, "Technique: sh or wavelet")
      ->check(CLI::IsMember({"sh", "wavelet"}))
      ->capture_default_str();
  add_sh_options(cmd, *options);
  add_wavelet_options(cmd, *options);
  cmd->add_option("--albedo", options->albedo,
                  "Diffuse albedo r,g,b for every surface (default: from the materials)");
  cmd->add_option("--seed", options->seed, "Random seed (same seed, same blob, any thread count)")
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output, "Output blob (.prtk)")->required();
  cmd->add_option("--report", options->report,
                  "Write a JSON report (settings, rays, seconds, blob bytes, quantisation error, "
                  "self-check)");
  cmd->callback([&env, options] { run_bake(*options, env); });
}

}  // namespace prt::bake::cli
