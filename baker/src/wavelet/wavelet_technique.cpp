// SPDX-License-Identifier: MIT
// Technique `wavelet` for prt-bake: `bake wavelet SCENE -o OUT.prtk` bakes per-vertex sparse Haar
// transfer (prt/baker/wavelet/wavelet_transfer.hpp), quantises it to 8 bits, writes the blob
// (prt/baker/wavelet/wavelet_blob.hpp), then loads it back through the runtime and checks it.
// `bake wavelet --shard i/N` bakes the direct pass of a range of vertices; merge_shards joins
// the ranges and runs the bounces (wavelet_transfer.hpp).
#include <prt/prt_wavelet.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/scene_bake.hpp"
#include "prt/baker/text.hpp"
#include "prt/baker/wavelet/wavelet_blob.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"

#include "../common/shard_payload.hpp"
#include "wavelet_technique.hpp"

namespace prt::bake {
namespace {

// A shard's payload: this header, then the range's direct pass (WaveletTransfer), per vertex of
// the range baked (u8), albedo (vec3), energy_kept (f64), nonzeros_before (u32) and row size
// (u32), then the rows' indices (u32) and values (f32), `pairs` of each. Native byte order.
constexpr std::uint32_t kWaveletShardMagic = 0x44535657;  // "WVSD"
constexpr std::uint32_t kWaveletShardVersion = 1;
struct WaveletShardHeader {
  std::uint32_t magic = kWaveletShardMagic, version = kWaveletShardVersion;
  std::uint32_t param = 0, size = 0, samples = 0, keep = 0;  // keep as resolved
  double keep_energy = 0.0;
  std::int32_t bounces = 0;
  std::uint32_t seed = 0, override_albedo = 0, vertex_stride = 1;
  glm::vec3 albedo{0.0f};         // when override_albedo
  std::uint32_t reserved = 0;     // no padding: every byte of a payload is written
  std::uint64_t vertex_list = 0;  // FNV-1a of WaveletTransferSettings::vertex_list; 0: empty
  std::uint64_t scene = 0;        // shard_scene_fingerprint
  std::uint64_t vertices = 0, first = 0, count = 0;
  std::uint64_t without_normal = 0, rays_traced = 0;
  double seconds = 0.0;
  std::uint64_t pairs = 0;
};
static_assert(sizeof(WaveletShardHeader) == 136, "WaveletShardHeader has padding");

std::uint64_t wavelet_vertex_list_hash(const std::vector<std::uint32_t>& list) {
  if (list.empty()) return 0;
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::uint32_t v : list)
    for (int b = 0; b < 4; ++b) h = (h ^ ((v >> (8 * b)) & 0xFFu)) * 0x100000001b3ull;
  return h;
}

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
    resolve(input);
    transfer_ = compute_wavelet_transfer(scene, nullptr, settings_, ctx);
  }

  std::size_t shard_units(const Scene& scene) const override { return scene.vertex_count(); }

  std::vector<std::uint8_t> bake_shard(const Scene& scene, const BakeInput& input,
                                       std::size_t first, std::size_t count,
                                       const Context& ctx) override {
    resolve(input);
    const WaveletTransfer part =
        compute_wavelet_direct_range(scene, nullptr, settings_, first, count, ctx);
    WaveletShardHeader h = shard_header(scene);
    h.first = first;
    h.count = count;
    h.without_normal = part.vertices_without_normal;
    h.rays_traced = part.rays_traced;
    h.seconds = part.seconds;
    h.pairs = part.index.size();
    std::vector<std::uint32_t> row_size(count);
    for (std::size_t v = 0; v < count; ++v)
      row_size[v] = static_cast<std::uint32_t>(part.row_size(v));
    ShardPayloadWriter out;
    out.put(h);
    out.put_vector(part.baked);
    out.put_vector(part.albedo);
    out.put_vector(part.energy_kept);
    out.put_vector(part.nonzeros_before);
    out.put_vector(row_size);
    out.put_vector(part.index);
    out.put_vector(part.value);
    return std::move(out).bytes();
  }

  void merge_shards(const Scene& scene, const BakeInput& input,
                    const std::vector<std::vector<std::uint8_t>>& parts,
                    const Context& ctx) override {
    resolve(input);
    const WaveletShardHeader expected = shard_header(scene);
    const std::uint32_t coefficients = prt_wavelet_coefficient_count(
        static_cast<prt_wavelet_param>(settings_.param), settings_.size);
    std::vector<WaveletTransfer> ranges;
    std::vector<ShardPartRange> spans;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      ShardPayloadReader in(parts[i], "wavelet merge: shard " + std::to_string(i));
      const WaveletShardHeader h = read_shard_header(in, expected);
      spans.push_back({h.first, h.count, h.vertices});
      ranges.push_back(read_shard_rows(in, h, coefficients));
    }
    check_shard_ranges("wavelet", shard_unit(), spans, scene.vertex_count());
    transfer_ = join_wavelet_ranges(settings_, std::move(ranges));
    add_wavelet_bounces(scene, nullptr, settings_, transfer_, ctx);
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
  // The settings as every bake step takes them: from the options and the shared flags.
  void resolve(const BakeInput& input) {
    WaveletTransferSettings& settings = settings_;
    settings.seed = input.seed;
    settings.param = parse_wavelet_param(param_.c_str());
    if (!keep_given_) settings.keep = default_wavelet_keep(settings.param, settings.size);
    if (settings.keep_energy > 0.0) settings.keep = 0;
    if (!input.albedo.empty()) {
      settings.override_albedo = true;
      settings.albedo = parse_albedo(input.albedo);
    }
  }

  // What a shard of this bake states about it, the range left 0.
  WaveletShardHeader shard_header(const Scene& scene) const {
    const WaveletTransferSettings& s = settings_;
    WaveletShardHeader h;
    h.param = s.param;
    h.size = s.size;
    h.samples = s.samples;
    h.keep = s.keep;
    h.keep_energy = s.keep_energy;
    h.bounces = s.bounces;
    h.seed = s.seed;
    h.override_albedo = s.override_albedo ? 1 : 0;
    if (s.override_albedo) h.albedo = s.albedo;
    h.vertex_stride = s.vertex_stride;
    h.vertex_list = wavelet_vertex_list_hash(s.vertex_list);
    h.scene = shard_scene_fingerprint(scene);
    h.vertices = scene.vertex_count();
    return h;
  }

  // Reads a part's header; Error naming what differs from `expected` (this merge's bake).
  static WaveletShardHeader read_shard_header(ShardPayloadReader& in,
                                              const WaveletShardHeader& expected) {
    const auto h = in.get<WaveletShardHeader>();
    if (h.magic != kWaveletShardMagic)
      throw Error(in.who() + " is not a shard of technique wavelet");
    if (h.version != kWaveletShardVersion) {
      throw Error(in.who() + " has wavelet shard version " + std::to_string(h.version) +
                  ", this baker reads " + std::to_string(kWaveletShardVersion));
    }
    const auto albedo = [](const WaveletShardHeader& x) {
      return x.override_albedo ? shard_value_text(x.albedo) : std::string("from the materials");
    };
    ShardSettingsDiff diff;
    diff.compare<std::string>("--param", wavelet_param_name(h.param),
                              wavelet_param_name(expected.param));
    diff.compare("--cube", h.size, expected.size);
    diff.compare("--samples", h.samples, expected.samples);
    diff.compare("--keep", h.keep, expected.keep);
    diff.compare("--keep-energy", h.keep_energy, expected.keep_energy);
    diff.compare("--bounces", h.bounces, expected.bounces);
    diff.compare("--seed", h.seed, expected.seed);
    diff.compare("--albedo", albedo(h), albedo(expected));
    diff.compare("--vertex-stride", h.vertex_stride, expected.vertex_stride);
    diff.compare("the vertex list (hash)", h.vertex_list, expected.vertex_list);
    diff.check(in.who());
    if (h.scene != expected.scene && h.vertices == expected.vertices)
      throw Error(in.who() + " was baked from another scene (its geometry or materials differ)");
    return h;
  }

  // The range's direct pass after its header, as compute_wavelet_direct_range returned it.
  WaveletTransfer read_shard_rows(ShardPayloadReader& in, const WaveletShardHeader& h,
                                  std::uint32_t coefficients) const {
    WaveletTransfer part;
    part.param = settings_.param;
    part.size = settings_.size;
    part.coefficient_count = coefficients;
    part.vertex_count = h.count;
    part.baked = in.get_vector<unsigned char>(h.count);
    part.albedo = in.get_vector<glm::vec3>(h.count);
    part.energy_kept = in.get_vector<double>(h.count);
    part.nonzeros_before = in.get_vector<std::uint32_t>(h.count);
    const std::vector<std::uint32_t> row_size = in.get_vector<std::uint32_t>(h.count);
    part.index = in.get_vector<std::uint32_t>(h.pairs);
    part.value = in.get_vector<float>(h.pairs);
    in.finish();
    part.row_start.assign(h.count + 1, 0);
    for (std::size_t v = 0; v < h.count; ++v)
      part.row_start[v + 1] = part.row_start[v] + row_size[v];
    // Checked, since quantising and writing index by these: a damaged part must not read out
    // of bounds.
    bool fits = part.row_start.back() == h.pairs;
    for (std::uint32_t j : part.index) fits = fits && j < coefficients;
    if (!fits) throw Error(in.who() + ": its rows do not fit its header");
    part.vertices_without_normal = h.without_normal;
    part.rays_traced = h.rays_traced;
    part.seconds = h.seconds;
    return part;
  }

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
  ObjectFit fit(const Scene& scene, int node) const override {
    return static_diffuse_fit(scene, node);
  }
  std::vector<Rung> ladder(int bounces) const override { return wavelet_scene_ladder(bounces); }
  std::vector<glm::vec3> shade(const std::vector<std::uint8_t>& blob, const io::EnvMap& light,
                               const Context& ctx) const override {
    return wavelet_scene_shade(blob, light, ctx);
  }
};

}  // namespace

const Technique& wavelet_technique() {
  static const WaveletTechnique technique;
  return technique;
}

}  // namespace prt::bake
