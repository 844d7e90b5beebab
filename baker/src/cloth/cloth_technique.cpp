// SPDX-License-Identifier: MIT
// Technique `cloth` for prt-bake: `bake cloth SCENE --fabric NAME -o OUT.prtk` bakes the named
// fabrics' shadowing/masking tables (prt/baker/cloth/cloth_tables.hpp), writes them with the
// scene's mesh and its warps (the cloth's thread directions) and checks the blob through the
// runtime.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/cloth/fabrics.hpp"
#include "prt/baker/text.hpp"

#include "cloth_technique.hpp"

namespace prt::bake {

std::vector<ClothFabricSource> cloth_fabric_sources(const std::vector<std::string>& names) {
  std::vector<std::string> wanted;
  for (const std::string& name : names) {
    if (name == "all") {
      for (const std::string& preset : cloth_fabric_names()) wanted.push_back(preset);
    } else {
      wanted.push_back(name);
    }
  }
  std::vector<ClothFabricSource> sources;
  for (const std::string& name : wanted) {
    const ClothPreset& preset = cloth_fabric(name);  // Error naming the presets
    for (const ClothFabricSource& s : sources)
      if (s.name == name) throw Error("--fabric " + name + " is named twice");
    sources.push_back({preset.name, preset.params, preset.weave});
  }
  return sources;
}

namespace {

// --fabric's name for the fabric the scene's cloth material names (cloth_scene_fabric).
constexpr const char* kSceneFabric = "scene";

class ClothBake final : public TechniqueBake {
 public:
  OptionList options() override {
    ClothGrid& g = options_.grid;
    OptionList list;
    list.add("--fabric", &fabrics_,
             "Fabrics to bake, presets by name (comma-separated or repeated), all, or scene "
             "(the preset the scene's cloth material is named after, else linen_plain)")
        .choices(fabric_choices());
    list.add("--xi-size", &g.xi_size, "Lobe-direction nodes per side of the octahedral grid")
        .range(2, 256);
    list.add("--levels", &g.lambda_levels, "Lobe-sharpness levels from 0.25 to 1e4").range(1, 64);
    list.add("--view-theta", &g.view_theta, "View nodes over the elevation").range(2, 256);
    list.add("--view-phi", &g.view_phi, "View nodes over the azimuth (half circle)").range(2, 256);
    list.add("--energy", &options_.factor.energy,
             "Share of each table's squared norm its truncated SVD may leave out")
        .range(0.0, 1.0);
    list.add("--rank", &options_.factor.fixed_rank, "Rank of every table; 0: by --energy")
        .range(0, 64);
    list.add("--bits", &bits_, "Bits per stored factor value: 8 or 16").choices({8, 16});
    return list;
  }

  void bake(const Scene& scene, const BakeInput&, const Context& ctx) override {
    bake_ = bake_cloth_tables(fabric_sources(scene), options_, ctx);
  }

  // Shards take views of the tables' grid (cloth_shards.cpp).
  const char* shard_unit() const override { return "views"; }
  std::size_t shard_units(const Scene&) const override { return options_.grid.columns(); }
  std::vector<std::uint8_t> bake_shard(const Scene& scene, const BakeInput&, std::size_t first,
                                       std::size_t count, const Context& ctx) override {
    return bake_cloth_shard(scene, shard_settings(scene), first, count, ctx);
  }
  void merge_shards(const Scene& scene, const BakeInput&,
                    const std::vector<std::vector<std::uint8_t>>& parts,
                    const Context& ctx) override {
    bake_ = merge_cloth_shards(scene, shard_settings(scene), parts, ctx);
  }

  void quantize() override {
    section_bytes_ = encode_clth_section(bake_.section, bits_);
    const DecodedClothSection stored =
        decode_clth_section(section_bytes_.data(), section_bytes_.size());
    quantization_ = measure_cloth_quantization(bake_.section, stored);
    quantization_.bits = bits_;
  }

  std::vector<std::uint8_t> write(const Scene& scene, const BakeInput& input) const override {
    const ClothMesh mesh = cloth_mesh_of(scene);
    std::string info = "prtkit cloth bake: " + input.scene + ", fabrics";
    for (const ClothFabric& f : bake_.section.fabrics) info += " " + f.name;
    return write_cloth_blob(bake_.section, bits_, &mesh, info);
  }

  std::string summary(const Scene& scene, const BakeInput& input,
                      std::size_t blob_bytes) const override {
    std::string names;
    for (const ClothFabric& f : bake_.section.fabrics)
      names += (names.empty() ? "" : ", ") + f.name;
    std::uint32_t max_rank = 0;
    for (const ClothTableReport& t : bake_.tables)
      max_rank = std::max({max_rank, t.full.rank, t.cone.rank});
    return std::to_string(scene.vertex_count()) + " vertices; " + names + ": " +
           std::to_string(bake_.tables.size()) + " tables, ranks up to " +
           std::to_string(max_rank) +
           format(", %zu table bytes, quantisation error %.2g; ", section_bytes_.size(),
                  quantization_.max_abs_error) +
           "wrote " + input.output + " (" + std::to_string(blob_bytes) + " bytes)";
  }

  SelfCheck self_check(const std::vector<std::uint8_t>& blob) override {
    check_ = check_cloth_blob(blob, bake_.section);
    return {check_.passed, check_.message};
  }

  void write_report(const std::string& path, const BakeInput& input,
                    const BakeFacts& facts) const override {
    write_cloth_bake_report(path, input, facts, bake_, options_, quantization_, check_);
  }

 private:
  // The fabrics --fabric names, "scene" as the scene's cloth material names it.
  std::vector<ClothFabricSource> fabric_sources(const Scene& scene) const {
    std::vector<std::string> names = fabrics_;
    for (std::string& name : names)
      if (name == kSceneFabric) name = cloth_scene_fabric(scene).name;
    return cloth_fabric_sources(names);
  }

  ClothShardSettings shard_settings(const Scene& scene) const {
    return {fabrics_, fabric_sources(scene), options_, bits_};
  }

  static std::vector<std::string> fabric_choices() {
    std::vector<std::string> names = cloth_fabric_names();
    names.push_back("all");
    names.push_back(kSceneFabric);
    return names;
  }

  std::vector<std::string> fabrics_{"linen_plain"};
  ClothTablesOptions options_;
  int bits_ = 16;
  ClothTablesBake bake_;
  std::vector<std::uint8_t> section_bytes_;
  ClothQuantization quantization_;
  ClothBlobCheck check_;
};

class ClothTechnique final : public Technique {
 public:
  const char* name() const override { return "cloth"; }
  const char* summary() const override {
    return "Bake woven fabrics' shadowing/masking tables for per-pixel cloth shading with live "
           "fabric parameters";
  }
  const char* trade_summary() const override {
    return "Measure technique cloth's trade against the brute-force reference: lobes, rank, "
           "table resolution, quadrature, the paper's method and each fix";
  }
  std::unique_ptr<TechniqueBake> make_bake() const override {
    return std::make_unique<ClothBake>();
  }
  std::unique_ptr<TechniqueTrade> make_trade() const override { return make_cloth_trade(); }

  ObjectFit fit(const Scene& scene, int node) const override {
    return cloth_scene_fit(scene, node);
  }
  std::vector<Rung> ladder(int bounces) const override { return cloth_scene_ladder(bounces); }
  ObjectMeasureFactory measure() const override { return make_cloth_measure; }
};

}  // namespace

const Technique& cloth_technique() {
  static const ClothTechnique technique;
  return technique;
}

}  // namespace prt::bake
