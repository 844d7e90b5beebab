// SPDX-License-Identifier: MIT
// Technique `shadowfield` for prt-bake: `bake shadowfield SCENE -o OUT.prtk` bakes the scene's
// meshes as one object (prt/baker/shadowfield/shadowfield_bake.hpp), quantises and writes it,
// loads it back through the runtime and shades it alone against the float object.
#include "shadowfield_technique.hpp"

#include <prt/prt_shadowfield.h>
#include <prt/prt_shadowfield_asset.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "prt/baker/text.hpp"

#include "../common/numbers.hpp"
#include "../common/technique_blob.hpp"

namespace prt::bake {
namespace {

// The scene with every mesh's material replaced by one of base colour `albedo` (--albedo).
Scene with_albedo(const Scene& scene, const glm::vec3& albedo) {
  Scene out = scene;
  Material material;
  material.name = "--albedo";
  material.base_color = glm::vec4(albedo, 1.0f);
  out.materials.push_back(material);
  for (Mesh& mesh : out.meshes) mesh.material = static_cast<int>(out.materials.size() - 1);
  return out;
}

// --inner and --outer, named as the command spells them (the stages name their settings).
void check_shells_options(double inner, double outer) {
  if (!std::isfinite(inner) || inner <= 0.0)
    throw Error(format("--inner: %g must be finite and > 0", inner));
  if (!std::isfinite(outer) || outer < inner)
    throw Error(format("--outer: %g must be finite and at least --inner (%g)", outer, inner));
}

nlohmann::json block_json(const QuantizedShadowfieldBlock& block) {
  return {{"values", block.q.size()},
          {"rows", block.offsets.size()},
          {"max_abs_error", block.max_abs_error},
          {"max_abs_value", block.max_abs_value}};
}

nlohmann::json shells_json(const prt_sf_shells& shells) {
  return {{"shells", shells.shells},
          {"face_size", shells.face_size},
          {"inner", shells.inner},
          {"outer", shells.outer},
          {"radius", shells.radius}};
}

class ShadowfieldBake final : public TechniqueBake {
 public:
  OptionList options() override {
    ShadowfieldBakeSettings& s = settings_;
    OptionList list;
    list.add("--brdf", &brdf_, "lambert, phong:N[,ks[,kd]] or ggx:ALPHA[,F0]");
    list.add("--order", &s.fields.order, "SH order n of the fields and transfer").range(2, 6);
    list.add("--terms", &s.brdf.terms, "Separable BRDF terms K; a pair is completed (glossy only)")
        .range(1, 8);
    list.add("--brdf-grid", &s.brdf.grid_size, "The BRDF table's hemisphere grid G (G x G)")
        .range(4, 64);
    list.add("--shells", &s.fields.oof_shells, "Occlusion field shells").range(1, 64);
    list.add("--face-size", &s.fields.oof_face_size, "Occlusion field cube face size").range(1, 64);
    list.add("--srf-shells", &s.srf.shells, "Source radiance field shells").range(1, 64);
    list.add("--srf-face-size", &s.srf.face_size, "Source radiance field cube face size")
        .range(1, 64);
    list.add("--inner", &inner_, "Innermost shell / bounding radius (both grids)");
    list.add("--outer", &outer_, "Outermost shell / bounding radius (both grids)");
    list.add("--basis", &s.basis.size, "Surface-radiance basis functions N").range(1, 64);
    list.add("--lights", &s.basis.lights, "Training lights of the basis").range(1, 1u << 16);
    list.add("--field-rays", &s.fields.field_directions, "Directions per occlusion field point")
        .range(1, 65536);
    list.add("--transfer-rays", &s.fields.transfer_rays, "Rays per vertex of the transfer")
        .range(1, 65536);
    list.add("--srf-rays", &s.srf.directions, "Directions per source radiance field point")
        .range(1, 1u << 20);
    list.add("--bits", &s.bits, "Quantisation bits per value: 8 or 16").choices({8, 16});
    return list;
  }

  void bake(const Scene& scene, const BakeInput& input, const Context& ctx) override {
    const auto start = std::chrono::steady_clock::now();
    resolve(input);
    seconds_brdf_ = seconds_since(start);
    result_ = input.albedo.empty()
                  ? bake_shadowfield_object(scene, material_, settings_, ctx)
                  : bake_shadowfield_object(with_albedo(scene, parse_albedo(input.albedo)),
                                            material_, settings_, ctx);
    end_bake(start, ctx);
  }

  // Shards (shadowfield_shards.cpp): the fields' shells and the transfer's vertex blocks.
  const char* shard_unit() const override { return kShadowfieldShardUnit; }
  std::size_t shard_units(const Scene& scene) const override {
    return shadowfield_shard_units(scene, settings_);
  }

  std::vector<std::uint8_t> bake_shard(const Scene& scene, const BakeInput& input,
                                       std::size_t first, std::size_t count,
                                       const Context& ctx) override {
    resolve(input);
    return input.albedo.empty()
               ? bake_shadowfield_shard(scene, material_, shard_bake(input), first, count, ctx)
               : bake_shadowfield_shard(with_albedo(scene, parse_albedo(input.albedo)), material_,
                                        shard_bake(input), first, count, ctx);
  }

  void merge_shards(const Scene& scene, const BakeInput& input,
                    const std::vector<std::vector<std::uint8_t>>& parts,
                    const Context& ctx) override {
    const auto start = std::chrono::steady_clock::now();
    resolve(input);
    seconds_brdf_ = seconds_since(start);
    result_ = input.albedo.empty()
                  ? merge_shadowfield_shards(scene, material_, shard_bake(input), parts, ctx)
                  : merge_shadowfield_shards(with_albedo(scene, parse_albedo(input.albedo)),
                                             material_, shard_bake(input), parts, ctx);
    end_bake(start, ctx);
  }

  void quantize() override { quantized_ = quantize_shadowfield(result_.object, settings_.bits); }

  std::vector<std::uint8_t> write(const Scene&, const BakeInput& input) const override {
    const std::string info = "prtkit shadowfield bake: " + input.scene + ", order " +
                             std::to_string(settings_.fields.order) + ", " + brdf_;
    return build_shadowfield_blob(result_.object, quantized_, info);
  }

  std::string summary(const Scene& scene, const BakeInput& input,
                      std::size_t blob_bytes) const override {
    return std::to_string(scene.vertex_count()) + " vertices, order " +
           std::to_string(settings_.fields.order) + ", " + brdf_ + ", " +
           std::to_string(result_.object.material.terms()) + " term(s), basis " +
           std::to_string(result_.object.basis_size) +
           format(" (%.1f %% energy kept); baked in %.1f s; ", 100 * result_.basis.energy_kept,
                  seconds_) +
           std::to_string(settings_.bits) + "-bit; wrote " + input.output + " (" +
           std::to_string(blob_bytes) + " bytes)";
  }

  SelfCheck self_check(const std::vector<std::uint8_t>& blob) override {
    check_ = check_shadowfield_blob(blob, result_.object, quantized_);
    return {check_.passed, check_.message};
  }

  void write_report(const std::string& path, const BakeInput& input,
                    const BakeFacts& facts) const override {
    std::ofstream file(path);
    if (!file || !(file << report_json(input, facts).dump(2) << '\n'))
      throw Error(path + ": cannot write the report");
  }

 private:
  // The settings and material every bake step takes, from the options and the shared flags.
  void resolve(const BakeInput& input) {
    settings_.fields.inner = settings_.srf.inner = static_cast<float>(inner_);
    settings_.fields.outer = settings_.srf.outer = static_cast<float>(outer_);
    settings_.fields.seed = settings_.srf.seed = input.seed;
    check_shells_options(inner_, outer_);
    check_shadowfield_bake_settings(settings_);
    surface_ = parse_brdf_option(brdf_);
    material_ = shadowfield_material_of(surface_, settings_.brdf);
  }

  ShadowfieldShardBake shard_bake(const BakeInput& input) const {
    ShadowfieldShardBake bake{settings_, surface_brdf_name(surface_), inner_, outer_};
    bake.override_albedo = !input.albedo.empty();
    if (bake.override_albedo) bake.albedo = parse_albedo(input.albedo);
    return bake;
  }

  // The bake's time and its warning, after bake() or merge_shards().
  void end_bake(std::chrono::steady_clock::time_point start, const Context& ctx) {
    seconds_ = seconds_since(start);
    if (result_.vertices_without_transfer > 0)
      ctx.warn(std::to_string(result_.vertices_without_transfer) +
               " vertices without a usable normal get zero transfer");
  }

  nlohmann::json report_json(const BakeInput& input, const BakeFacts& facts) const {
    const ShadowfieldBakeSettings& s = settings_;
    const ShadowfieldObject& o = result_.object;
    const double rays = static_cast<double>(result_.basis.rays_traced + result_.srf.rays_traced) +
                        double(o.oof.size() / (o.order * o.order)) * s.fields.field_directions +
                        double(o.positions.size()) * s.fields.transfer_rays;
    nlohmann::json json = {
        {"command", "bake"},
        {"technique", "shadowfield"},
        {"scene",
         {{"file", input.scene},
          {"vertices", facts.vertices},
          {"triangles", facts.triangles},
          {"vertices_without_transfer", result_.vertices_without_transfer}}},
        {"settings",
         {{"brdf", brdf_},
          {"order", s.fields.order},
          {"terms", o.material.terms()},
          {"terms_requested", o.material.glossy ? o.material.brdf.requested_terms : 1u},
          {"brdf_grid", s.brdf.grid_size},
          {"oof", shells_json(o.oof_shells)},
          {"srf", shells_json(o.srf_shells)},
          {"basis", s.basis.size},
          {"lights", s.basis.lights},
          {"field_rays", s.fields.field_directions},
          {"transfer_rays", s.fields.transfer_rays},
          {"srf_rays", s.srf.directions},
          {"bits", s.bits},
          {"seed", s.fields.seed},
          {"threads", facts.threads}}},
        {"bake",
         {{"seconds", seconds_},
          {"seconds_brdf", seconds_brdf_},
          {"seconds_fields", result_.seconds_fields},
          {"seconds_transfer", result_.seconds_transfer},
          {"seconds_basis", result_.basis.seconds},
          {"seconds_srf", result_.srf.seconds},
          {"rays", rays},
          {"basis_energy_kept", result_.basis.energy_kept},
          {"brdf_relative_error", o.material.glossy ? o.material.brdf.relative_error() : 0.0}}},
        {"blob",
         {{"file", input.output},
          {"bytes", facts.blob_bytes},
          {"values",
           {{"transfer", o.transfer.size()},
            {"oof", o.oof.size()},
            {"basis", o.basis.size()},
            {"srf", o.srf.size()}}}}},
        {"quantization",
         {{"bits", quantized_.bits},
          {"transfer", block_json(quantized_.transfer)},
          {"oof", block_json(quantized_.oof)},
          {"basis", block_json(quantized_.basis)},
          {"srf", block_json(quantized_.srf)}}},
        {"self_check",
         {{"passed", check_.passed},
          {"message", check_.message},
          {"max_abs_error", check_.max_abs_error},
          {"max_budget_ratio", check_.max_budget_ratio}}},
    };
    if (!input.albedo.empty()) json["settings"]["albedo"] = input.albedo;
    return json;
  }

  ShadowfieldBakeSettings settings_;
  std::string brdf_ = "lambert";
  double inner_ = 0.2, outer_ = 8.0;
  SurfaceBrdf surface_;
  ShadowfieldMaterial material_;
  ShadowfieldBakeResult result_;
  double seconds_ = 0.0, seconds_brdf_ = 0.0;  // the whole bake, the BRDF's separation
  QuantizedShadowfield quantized_;
  ShadowfieldBlobCheck check_;
};

class ShadowfieldTechnique final : public Technique {
 public:
  const char* name() const override { return "shadowfield"; }
  const char* summary() const override {
    return "Bake one rigid object's shadow field (occlusion and source radiance fields, "
           "self-shadowed transfer) into a blob";
  }
  const char* trade_summary() const override {
    return "Measure technique shadowfield's speed/accuracy trade: one object (SCENE a file; "
           "order, BRDF terms, bits, transfer rays) or a scene preset (SCENE teapot, bunny, room "
           "or procedural; also shells, points per shell, basis size and bounces)";
  }
  std::unique_ptr<TechniqueBake> make_bake() const override {
    return std::make_unique<ShadowfieldBake>();
  }
  std::unique_ptr<TechniqueTrade> make_trade() const override { return make_shadowfield_trade(); }

  ObjectFit fit(const Scene& scene, int node) const override {
    return shadowfield_scene_fit(scene, node);
  }
  std::vector<Rung> ladder(int bounces) const override { return shadowfield_scene_ladder(bounces); }
  ObjectMeasureFactory measure() const override { return &make_shadowfield_object_measure; }
};

}  // namespace

ShadowfieldMaterial shadowfield_material_of(const SurfaceBrdf& brdf,
                                            const SeparableBrdfOptions& options) {
  ShadowfieldMaterialDescription description;
  switch (brdf.model) {
    case SurfaceBrdf::Model::Lambert:
      break;
    case SurfaceBrdf::Model::Phong:
      description.model = ShadowfieldBrdfModel::Phong;
      description.phong = brdf.phong;
      break;
    case SurfaceBrdf::Model::Ggx:
      description.model = ShadowfieldBrdfModel::Ggx;
      description.ggx = brdf.ggx;
      break;
  }
  return make_shadowfield_material(description, options);
}

SurfaceBrdf parse_brdf_option(const std::string& text) {
  try {
    return parse_surface_brdf(text);
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.rfind("--brdf", 0) == 0) throw;
    throw Error("--brdf: " + message);
  }
}

const Technique& shadowfield_technique() {
  static const ShadowfieldTechnique technique;
  return technique;
}

}  // namespace prt::bake
