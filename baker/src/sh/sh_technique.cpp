// SPDX-License-Identifier: MIT
// Technique `sh` for prt-bake: `bake sh SCENE -o OUT.prtk` bakes per-vertex SH transfer
// (prt/baker/sh/sh_transfer.hpp), quantises it, writes the blob (prt/baker/sh/sh_blob.hpp), then
// loads it back through the runtime and checks it.
#include <prt/prt_sh.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "prt/baker/text.hpp"

#include "sh_technique.hpp"

namespace prt::bake {
namespace {

class ShBake final : public TechniqueBake {
 public:
  ShBake() {
    settings_.order = 6;
    settings_.kind = ShTransferKind::Shadowed;
    settings_.rays = 1024;
  }

  OptionList options() override {
    ShTransferSettings& s = settings_;
    OptionList list;
    list.add("--order", &s.order, "SH order n (n*n coefficients)").range(1, PRT_SH_MAX_ORDER);
    list.add("--transfer", &kind_, "unshadowed|shadowed|interreflected")
        .choices({"unshadowed", "shadowed", "interreflected"});
    list.add("--rays", &s.rays, "Directions per vertex").range(1, 1u << 24);
    list.add("--bounces", &s.bounces, "Bounce passes of the interreflected transfer").range(0, 64);
    list.add("--bits", &bits_, "Quantisation bits per value: 8 or 16").choices({8, 16});
    return list;
  }

  void bake(const Scene& scene, const BakeInput& input, const Context& ctx) override {
    settings_.seed = input.seed;
    settings_.kind = parse_sh_transfer_kind(kind_.c_str());
    if (!input.albedo.empty()) {
      settings_.override_albedo = true;
      settings_.albedo = parse_albedo(input.albedo);
    }
    transfer_ = compute_sh_transfer(scene, nullptr, settings_, ctx);
  }

  void quantize() override {
    const int bounces = settings_.kind == ShTransferKind::Interreflected ? settings_.bounces : 0;
    quantized_ = quantize_sh_transfer(transfer_, bits_, bounces);
  }

  std::vector<std::uint8_t> write(const Scene& scene, const BakeInput& input) const override {
    const std::string info = "prtkit sh bake: " + input.scene + ", order " +
                             std::to_string(settings_.order) + ", " +
                             sh_transfer_kind_name(settings_.kind);
    return build_sh_blob(scene, quantized_, info);
  }

  std::string summary(const Scene& scene, const BakeInput& input,
                      std::size_t blob_bytes) const override {
    return std::to_string(scene.vertex_count()) + " vertices, order " +
           std::to_string(settings_.order) + ", " + sh_transfer_kind_name(settings_.kind) + ": " +
           format("%.3g rays in %.1f s; ", static_cast<double>(transfer_.rays_traced),
                  transfer_.seconds) +
           std::to_string(bits_) + "-bit " +
           format("quantisation error max %.3g, RMS %.3g; ", quantized_.max_abs_error,
                  quantized_.rms_abs_error) +
           "wrote " + input.output + " (" + std::to_string(blob_bytes) + " bytes)";
  }

  SelfCheck self_check(const std::vector<std::uint8_t>& blob) override {
    check_ = check_sh_blob(blob, transfer_, quantized_);
    return {check_.passed, check_.message};
  }

  void write_report(const std::string& path, const BakeInput& input,
                    const BakeFacts& facts) const override {
    ShBakeReport report;
    report.scene = input.scene;
    report.vertices = facts.vertices;
    report.triangles = facts.triangles;
    report.settings = settings_;
    report.bits = bits_;
    report.threads = facts.threads;
    report.transfer = &transfer_;
    report.quantized = &quantized_;
    report.output = input.output;
    report.blob_bytes = facts.blob_bytes;
    report.check = check_;
    write_sh_bake_report(path, report);
  }

 private:
  ShTransferSettings settings_;
  std::string kind_ = "shadowed";
  int bits_ = 16;
  ShTransfer transfer_;
  QuantizedShTransfer quantized_;
  ShBlobCheck check_;
};

class ShTechnique final : public Technique {
 public:
  const char* name() const override { return "sh"; }
  const char* summary() const override {
    return "Bake per-vertex SH transfer (unshadowed, shadowed or interreflected) into a blob";
  }
  const char* trade_summary() const override {
    return "Measure technique sh's speed/accuracy trade: sweep order, rays and bounces";
  }
  std::unique_ptr<TechniqueBake> make_bake() const override { return std::make_unique<ShBake>(); }
  std::unique_ptr<TechniqueTrade> make_trade() const override { return make_sh_trade(); }
};

}  // namespace

const Technique& sh_technique() {
  static const ShTechnique technique;
  return technique;
}

}  // namespace prt::bake
