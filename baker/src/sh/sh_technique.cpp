// SPDX-License-Identifier: MIT
// Technique `sh` for prt-bake: `bake sh SCENE -o OUT.prtk` bakes per-vertex SH transfer
// (prt/baker/sh/sh_transfer.hpp), quantises it, writes the blob (prt/baker/sh/sh_blob.hpp), then
// loads it back through the runtime and checks it. `bake sh --shard i/N` bakes the direct pass
// of a range of vertices; merge_shards joins the ranges and runs the bounces (sh_transfer.hpp).
#include <prt/prt_sh.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/sh/sh_blob.hpp"
#include "prt/baker/sh/sh_transfer.hpp"
#include "prt/baker/scene_bake.hpp"
#include "prt/baker/text.hpp"

#include "../common/shard_payload.hpp"
#include "sh_technique.hpp"

namespace prt::bake {
namespace {

// A shard's payload: this header, then the range's direct pass (ShTransfer::coefficients,
// count x 3 x order^2 floats). Native byte order.
constexpr std::uint32_t kShShardMagic = 0x44534853;  // "SHSD"
constexpr std::uint32_t kShShardVersion = 1;
struct ShShardHeader {
  std::uint32_t magic = kShShardMagic, version = kShShardVersion;
  std::uint32_t order = 0, kind = 0, rays = 0, seed = 0;
  std::int32_t bounces = 0;  // the bounces the merge runs (0 unless interreflected)
  std::uint32_t override_albedo = 0;
  glm::vec3 albedo{0.0f};      // when override_albedo
  std::uint32_t reserved = 0;  // no padding: every byte of a payload is written
  std::uint64_t scene = 0;     // shard_scene_fingerprint
  std::uint64_t vertices = 0, first = 0, count = 0;
  std::uint64_t without_normal = 0, rays_traced = 0;
  double seconds = 0.0;
};
static_assert(sizeof(ShShardHeader) == 104, "ShShardHeader has padding");

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
    resolve(input);
    transfer_ = compute_sh_transfer(scene, nullptr, settings_, ctx);
  }

  std::size_t shard_units(const Scene& scene) const override { return scene.vertex_count(); }

  std::vector<std::uint8_t> bake_shard(const Scene& scene, const BakeInput& input,
                                       std::size_t first, std::size_t count,
                                       const Context& ctx) override {
    resolve(input);
    const ShTransfer part = compute_sh_direct_range(scene, nullptr, settings_, first, count, ctx);
    ShShardHeader h = shard_header(scene);
    h.first = first;
    h.count = count;
    h.without_normal = part.vertices_without_normal;
    h.rays_traced = part.rays_traced;
    h.seconds = part.seconds;
    ShardPayloadWriter out;
    out.put(h);
    out.put_vector(part.coefficients);
    return std::move(out).bytes();
  }

  void merge_shards(const Scene& scene, const BakeInput& input,
                    const std::vector<std::vector<std::uint8_t>>& parts,
                    const Context& ctx) override {
    resolve(input);
    const ShShardHeader expected = shard_header(scene);
    std::vector<ShTransfer> ranges;
    std::vector<ShardPartRange> spans;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      ShardPayloadReader in(parts[i], "sh merge: shard " + std::to_string(i));
      const ShShardHeader h = read_shard_header(in, expected);
      spans.push_back({h.first, h.count, h.vertices});
      ShTransfer part;
      part.order = settings_.order;
      part.kind = settings_.kind;
      part.vertex_count = h.count;
      part.coefficients = in.get_vector<float>(h.count * 3 * part.coefficient_count());
      in.finish();
      part.vertices_without_normal = h.without_normal;
      part.rays_traced = h.rays_traced;
      part.seconds = h.seconds;
      ranges.push_back(std::move(part));
    }
    check_shard_ranges("sh", shard_unit(), spans, scene.vertex_count());
    transfer_ = join_sh_ranges(std::move(ranges));
    add_sh_bounces(scene, nullptr, settings_, transfer_, ctx);
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
  // The settings as every bake step takes them: from the options and the shared flags.
  void resolve(const BakeInput& input) {
    settings_.seed = input.seed;
    settings_.kind = parse_sh_transfer_kind(kind_.c_str());
    if (!input.albedo.empty()) {
      settings_.override_albedo = true;
      settings_.albedo = parse_albedo(input.albedo);
    }
  }

  // What a shard of this bake states about it, the range left 0.
  ShShardHeader shard_header(const Scene& scene) const {
    ShShardHeader h;
    h.order = settings_.order;
    h.kind = static_cast<std::uint32_t>(settings_.kind);
    h.rays = settings_.rays;
    h.seed = settings_.seed;
    h.bounces = settings_.kind == ShTransferKind::Interreflected ? settings_.bounces : 0;
    h.override_albedo = settings_.override_albedo ? 1 : 0;
    if (settings_.override_albedo) h.albedo = settings_.albedo;
    h.scene = shard_scene_fingerprint(scene);
    h.vertices = scene.vertex_count();
    return h;
  }

  // Reads a part's header; Error naming what differs from `expected` (this merge's bake).
  static ShShardHeader read_shard_header(ShardPayloadReader& in, const ShShardHeader& expected) {
    const ShShardHeader h = in.get<ShShardHeader>();
    if (h.magic != kShShardMagic) throw Error(in.who() + " is not a shard of technique sh");
    if (h.version != kShShardVersion) {
      throw Error(in.who() + " has sh shard version " + std::to_string(h.version) +
                  ", this baker reads " + std::to_string(kShShardVersion));
    }
    const auto kind = [](std::uint32_t k) {
      return k <= 2 ? sh_transfer_kind_name(static_cast<ShTransferKind>(k)) : "unknown";
    };
    const auto albedo = [](const ShShardHeader& x) {
      return x.override_albedo ? shard_value_text(x.albedo) : std::string("from the materials");
    };
    ShardSettingsDiff diff;
    diff.compare("--order", h.order, expected.order);
    diff.compare<std::string>("--transfer", kind(h.kind), kind(expected.kind));
    diff.compare("--rays", h.rays, expected.rays);
    diff.compare("--bounces", h.bounces, expected.bounces);
    diff.compare("--seed", h.seed, expected.seed);
    diff.compare("--albedo", albedo(h), albedo(expected));
    diff.check(in.who());
    if (h.scene != expected.scene && h.vertices == expected.vertices)
      throw Error(in.who() + " was baked from another scene (its geometry or materials differ)");
    return h;
  }

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
  ObjectFit fit(const Scene& scene, int node) const override {
    return static_diffuse_fit(scene, node);
  }
  std::vector<Rung> ladder(int bounces) const override { return sh_scene_ladder(bounces); }
  std::vector<glm::vec3> shade(const std::vector<std::uint8_t>& blob, const io::EnvMap& light,
                               const Context& ctx) const override {
    return sh_scene_shade(blob, light, ctx);
  }
};

}  // namespace

const Technique& sh_technique() {
  static const ShTechnique technique;
  return technique;
}

}  // namespace prt::bake
