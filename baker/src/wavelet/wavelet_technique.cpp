// SPDX-License-Identifier: MIT
// Technique `wavelet` for prt-bake: `bake wavelet SCENE -o OUT.prtk` bakes per-vertex sparse Haar
// transfer (prt/baker/wavelet/wavelet_transfer.hpp), quantises it to 8 bits, writes the blob
// (prt/baker/wavelet/wavelet_blob.hpp), then loads it back through the runtime and checks it.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/text.hpp"
#include "prt/baker/wavelet/wavelet_blob.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"

#include "wavelet_technique.hpp"

namespace prt::bake {
namespace {

class WaveletBake final : public TechniqueBake {
 public:
  WaveletBake() {
    settings_.size = 64;
    settings_.samples = 1;
  }

  OptionList options() override {
    WaveletTransferSettings& w = settings_;
    OptionList list;
    list.add("--bounces", &w.bounces, "Interreflection passes (0 = direct light with shadows)")
        .range(0, 8);
    list.add("--keep", &w.keep,
             "Coefficients kept per vertex (default 1000 at a cube of 64, the same fraction for "
             "other sizes; 0 = all)")
        .no_default()
        .record_given(&keep_given_);
    list.add("--keep-energy", &w.keep_energy,
             "Keep the fewest coefficients holding this fraction of each vertex's squared norm "
             "instead of --keep")
        .range(1e-9, 1.0)
        .no_default()
        .excludes("--keep");
    list.add("--cube", &w.size, "Face size S (cube N or paraboloid P), a power of two in 16..128")
        .choices({16, 32, 64, 128});
    list.add("--param", &param_, "cube|dual-paraboloid").choices({"cube", "dual-paraboloid"});
    list.add("--quantizer", &quantizer_,
             "band (a scale per face and wavelet level) or vertex (a scale per vertex, the "
             "paper's)")
        .choices({"band", "vertex"});
    list.add("--samples", &w.samples, "Jittered rays per texel, a square k*k (1, 4, 9, 16, ...)")
        .choices({1, 4, 9, 16, 25, 36, 49, 64});
    list.add("--vertex-stride", &w.vertex_stride,
             "Bake every k-th vertex only (the others get empty rows; for quick measurements)")
        .range(1, 1u << 30);
    return list;
  }

  void bake(const Scene& scene, const BakeInput& input, const Context& ctx) override {
    WaveletTransferSettings& settings = settings_;
    settings.seed = input.seed;
    settings.param = parse_wavelet_param(param_.c_str());
    if (!keep_given_) settings.keep = default_wavelet_keep(settings.param, settings.size);
    if (settings.keep_energy > 0.0) settings.keep = 0;
    if (!input.albedo.empty()) {
      settings.override_albedo = true;
      settings.albedo = parse_albedo(input.albedo);
    }
    transfer_ = compute_wavelet_transfer(scene, nullptr, settings, ctx);
  }

  void quantize() override {
    std::uint32_t most = 0;
    for (std::size_t v = 0; v < transfer_.vertex_count; ++v)
      most = std::max<std::uint32_t>(most, static_cast<std::uint32_t>(transfer_.row_size(v)));
    quantized_ = quantize_wavelet_transfer(transfer_, parse_wavelet_quantizer(quantizer_.c_str()),
                                           settings_.keep_energy > 0.0 ? most : settings_.keep);
    quantized_.bounces = static_cast<std::uint32_t>(settings_.bounces);
  }

  std::vector<std::uint8_t> write(const Scene& scene, const BakeInput& input) const override {
    const std::string info = "prtkit wavelet bake: " + input.scene + ", " +
                             wavelet_param_name(settings_.param) + " " +
                             std::to_string(settings_.size) + ", keep " +
                             std::to_string(quantized_.keep) + ", quantizer " + quantizer_;
    return build_wavelet_blob(scene, quantized_, info);
  }

  std::string summary(const Scene& scene, const BakeInput& input,
                      std::size_t blob_bytes) const override {
    const double vertices = double(std::max<std::size_t>(1, scene.vertex_count()));
    const QuantizedWavelet& q = quantized_;
    return std::to_string(scene.vertex_count()) + " vertices, " +
           wavelet_param_name(settings_.param) + " " + std::to_string(settings_.size) + ": " +
           format("%.3g rays in %.1f s; ", double(transfer_.rays_traced), transfer_.seconds) +
           format("%.0f non-zeros/vertex (%.1f %% of the energy kept); ",
                  double(q.pair_count()) / vertices, 100.0 * transfer_.mean_energy_kept) +
           quantizer_ +
           format(" quantiser RMS error %.3g of the largest coefficient; ",
                  q.max_abs_value > 0 ? q.rms_abs_error / q.max_abs_value : 0.0) +
           "wrote " + input.output + " (" + std::to_string(blob_bytes) + " bytes, " +
           format("%.0f per vertex)", double(blob_bytes) / vertices);
  }

  SelfCheck self_check(const std::vector<std::uint8_t>& blob) override {
    check_ = check_wavelet_blob(blob, transfer_, quantized_, settings_.seed + 1);
    return {check_.passed, check_.message};
  }

  void write_report(const std::string& path, const BakeInput& input,
                    const BakeFacts& facts) const override {
    WaveletBakeReport report;
    report.scene = input.scene;
    report.output = input.output;
    report.vertices = facts.vertices;
    report.triangles = facts.triangles;
    report.settings = settings_;
    report.threads = facts.threads;
    report.transfer = &transfer_;
    report.quantized = &quantized_;
    report.blob_bytes = facts.blob_bytes;
    report.check = check_;
    write_wavelet_bake_report(path, report);
  }

 private:
  WaveletTransferSettings settings_;
  std::string param_ = "cube", quantizer_ = "band";
  bool keep_given_ = false;
  WaveletTransfer transfer_;
  QuantizedWavelet quantized_;
  WaveletBlobCheck check_;
};

class WaveletTechnique final : public Technique {
 public:
  const char* name() const override { return "wavelet"; }
  const char* summary() const override {
    return "Bake per-vertex sparse Haar transfer (all-frequency shadows) into a blob";
  }
  const char* trade_summary() const override {
    return "Measure technique wavelet's speed/accuracy trade (N, K, M, parameterisation) "
           "against sh at equal bytes per vertex";
  }
  std::unique_ptr<TechniqueBake> make_bake() const override {
    return std::make_unique<WaveletBake>();
  }
  std::unique_ptr<TechniqueTrade> make_trade() const override { return make_wavelet_trade(); }
};

}  // namespace

const Technique& wavelet_technique() {
  static const WaveletTechnique technique;
  return technique;
}

}  // namespace prt::bake
