// SPDX-License-Identifier: MIT
// prt-bake bake SCENE --technique sh -o OUT.prtk: bakes per-vertex SH transfer, quantises it,
// writes the blob, then loads it back through the runtime and checks it (prt/baker/sh_blob.hpp).
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "command.hpp"
#include "prt/baker/sh_blob.hpp"
#include "prt/baker/sh_transfer.hpp"

namespace prt::bake::cli {
namespace {

struct BakeOptions {
  std::string scene, technique = "sh", transfer = "shadowed", albedo, output, report;
  ShTransferSettings settings;
  int bits = 16;
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

void run_bake(const BakeOptions& options, CommandEnv& env) {
  if (options.technique != "sh") {
    throw Error("--technique: '" + options.technique + "' is not available (only 'sh' for now)");
  }
  const Context ctx = env.context();
  ShTransferSettings settings = options.settings;
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

}  // namespace

void add_bake_command(CLI::App& app, CommandEnv& env) {
  auto options = std::make_shared<BakeOptions>();
  ShTransferSettings& s = options->settings;
  s.order = 6;
  s.kind = ShTransferKind::Shadowed;
  s.rays = 1024;
  auto* cmd = app.add_subcommand("bake", "Bake a technique's transfer into a runtime blob");
  cmd->add_option("SCENE", options->scene, "Scene file (.gltf, .glb, .obj)")->required();
  cmd->add_option("--technique", options->technique, "Technique (only 'sh' for now)")
      ->capture_default_str();
  cmd->add_option("--order", s.order, "SH order n (n*n coefficients)")
      ->check(CLI::Range(1u, 16u))
      ->capture_default_str();
  cmd->add_option("--transfer", options->transfer, "unshadowed|shadowed|interreflected")
      ->check(CLI::IsMember({"unshadowed", "shadowed", "interreflected"}))
      ->capture_default_str();
  cmd->add_option("--rays", s.rays, "Directions per vertex")
      ->check(CLI::Range(1u, 1u << 24))
      ->capture_default_str();
  cmd->add_option("--bounces", s.bounces, "Bounce passes (interreflected only)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  cmd->add_option("--bits", options->bits, "Quantisation bits per value: 8 or 16")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  cmd->add_option("--albedo", options->albedo,
                  "Diffuse albedo r,g,b for every surface (default: from the materials)");
  cmd->add_option("--seed", s.seed, "Random seed (same seed, same blob, any thread count)")
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output, "Output blob (.prtk)")->required();
  cmd->add_option("--report", options->report,
                  "Write a JSON report (settings, rays, seconds, blob bytes, quantisation error, "
                  "self-check)");
  cmd->callback([&env, options] { run_bake(*options, env); });
}

}  // namespace prt::bake::cli
