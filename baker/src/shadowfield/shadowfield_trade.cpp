// SPDX-License-Identifier: MIT
// prt-bake trade shadowfield SCENE --env MAP ... --out-dir DIR: the measured speed/accuracy trade
// of technique `shadowfield` (docs/shadowfield/trade.md), in two modes.
// - SCENE a mesh file: one object alone, measured here. Sweeps around a base setting (order, BRDF
//   terms, bits, transfer rays): each setting is baked in-process, written to a blob and loaded
//   through the runtime, then the object is turned about +Y through its centre to a few angles
//   (so the view and the light fall differently on it) and shaded by the runtime (0 bounces, a
//   fixed eye) against the reference renderer's radiance of the same placement towards the same
//   eye (0 bounces, the same BRDF; cached).
// - SCENE a preset's name: every knob of the technique swept on the preset's objects and
//   placements (shadowfield_scene_trade.cpp).
// Writes DIR/trade.csv and DIR/trade.md.
#include <prt/prt.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "prt/baker/instances.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"
#include "prt/io/image_io.hpp"
#include "prt/io/radiance_error.hpp"

#include "../common/trade_common.hpp"
#include "shadowfield_scene_trade.hpp"
#include "shadowfield_technique.hpp"
#include "shadowfield_trade_shared.hpp"

namespace prt::bake {
namespace {

using namespace trade;
using sf_trade::SceneSweep;
using sf_trade::SceneSweepOptions;
using sf_trade::SfTradeSettings;

struct Setting {
  std::uint32_t order = 0, terms = 0, rays = 0;
  int bits = 0;
  std::string sweeps;
};

struct ShadowfieldTradeRow {
  std::string map, sweeps;
  Setting setting;
  double degrees = 0.0;
  double error = 0.0, bias = 0.0, ref_noise = 0.0, cpu_ms = 0.0, bake_seconds = 0.0;
  std::size_t blob_bytes = 0, compared = 0;  // compared: vertices facing the eye
};

// Order sweep at the base terms, rays and bits; terms (glossy only), rays and bits at the base
// order. A setting in several sweeps is baked once.
std::vector<Setting> sweep_settings(const SfTradeSettings& o, bool glossy) {
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, int>, std::string> sweeps;
  const std::uint32_t base_terms = glossy ? o.base_terms : 1;
  auto add = [&](std::uint32_t order, std::uint32_t terms, std::uint32_t rays, int bits,
                 const char* sweep) {
    std::string& names = sweeps[{order, terms, rays, bits}];
    const std::string name = sweep;
    // A value given twice to one sweep names it once.
    if (("+" + names + "+").find("+" + name + "+") != std::string::npos) return;
    names += (names.empty() ? "" : "+") + name;
  };
  for (std::uint32_t order : o.orders) add(order, base_terms, o.base_rays, o.base_bits, "order");
  if (glossy) {
    for (std::uint32_t terms : o.terms) add(o.base_order, terms, o.base_rays, o.base_bits, "terms");
  }
  for (std::uint32_t rays : o.rays) add(o.base_order, base_terms, rays, o.base_bits, "rays");
  for (int bits : o.bits) add(o.base_order, base_terms, o.base_rays, bits, "bits");
  std::vector<Setting> settings;
  for (const auto& [key, names] : sweeps)
    settings.push_back(
        {std::get<0>(key), std::get<1>(key), std::get<2>(key), std::get<3>(key), names});
  return settings;
}

void check_settings(const SfTradeSettings& o) {
  if (o.orders.empty() || o.terms.empty() || o.rays.empty() || o.bits.empty())
    throw Error("trade: --orders, --terms, --rays and --bits need at least one value each");
  for (std::uint32_t order : o.orders) {
    if (order < 2 || order > 6)
      throw Error("--orders: " + std::to_string(order) + " is outside 2..6");
  }
  for (std::uint32_t terms : o.terms) {
    if (terms < 1 || terms > 8)
      throw Error("--terms: " + std::to_string(terms) + " is outside 1..8");
  }
  for (std::uint32_t rays : o.rays) {
    if (rays < 1 || rays > 65536)
      throw Error("--rays: " + std::to_string(rays) + " is outside 1..65536");
  }
  for (int bits : o.bits) {
    if (bits != 8 && bits != 16) throw Error("--bits: " + std::to_string(bits) + " is not 8 or 16");
  }
  parse_brdf_option(o.brdf);
}

// The object's turns: evenly spread over a full turn about +Y.
double turn_degrees(std::uint32_t index, std::uint32_t count) {
  return 360.0 * index / count;
}

glm::mat3 turn(double degrees) {
  return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(float(degrees)), {0.0f, 1.0f, 0.0f}));
}

// The bounding sphere's centre stays put: t = c - R c.
Instance turned_instance(double degrees, const glm::vec3& centre) {
  Instance instance;
  instance.rotation = turn(degrees);
  instance.translation = centre - instance.rotation * centre;
  return instance;
}

// The camera: in front of the object, a little above it.
glm::vec3 trade_eye(const BoundingSphere& sphere) {
  return sphere.centre + sphere.radius * glm::vec3(0.0f, 1.0f, 3.0f);
}

// Whether each vertex (scene order) faces `eye` once placed: the camera sees its front. The
// others are not compared: the reference reflects nothing towards an eye below the surface,
// while the runtime reads the BRDF's g at the horizon there.
std::vector<bool> facing_eye(const Scene& scene, const Instance& placed, const glm::vec3& eye) {
  std::vector<bool> facing;
  for (const Mesh& mesh : scene.meshes) {
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::vec3 normal = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f);
      facing.push_back(glm::dot(placed.rotation * normal, eye - placed.place(mesh.positions[v])) >
                       0.0f);
    }
  }
  return facing;
}

std::vector<glm::vec3> masked(const std::vector<glm::vec3>& values, const std::vector<bool>& keep) {
  std::vector<glm::vec3> kept;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (keep[i]) kept.push_back(values[i]);
  }
  return kept;
}

const std::vector<std::string> kCsvColumns = {"scene",
                                              "map",
                                              "brdf",
                                              "sweeps",
                                              "order",
                                              "terms",
                                              "transfer_rays",
                                              "bits",
                                              "rotation_deg",
                                              "vertices",
                                              "vertices_compared",
                                              "rel_rmse",
                                              "bias",
                                              "ref_noise",
                                              "rel_rmse_noise_removed",
                                              "ref_spp",
                                              "shade_cpu_ms",
                                              "blob_bytes",
                                              "bake_seconds"};

std::vector<std::string> csv_cells(const ShadowfieldTradeRow& r, const SfTradeSettings& o,
                                   const TradeInput& input, std::size_t vertices) {
  const Setting& s = r.setting;
  std::string brdf = o.brdf;  // its commas would split the cell
  std::replace(brdf.begin(), brdf.end(), ',', ';');
  return {stem(input.scene),
          r.map,
          brdf,
          r.sweeps,
          std::to_string(s.order),
          std::to_string(s.terms),
          std::to_string(s.rays),
          std::to_string(s.bits),
          format("%g", r.degrees),
          std::to_string(vertices),
          std::to_string(r.compared),
          format("%.6g", r.error),
          format("%.6g", r.bias),
          format("%.6g", r.ref_noise),
          format("%.6g", noise_removed(r.error, r.ref_noise)),
          std::to_string(input.ref_spp),
          ms_text(r.cpu_ms),
          std::to_string(r.blob_bytes),
          format("%.4g", r.bake_seconds)};
}

const std::vector<Column> kMarkdownColumns = {
    {"sweep", false}, {"order"},  {"terms"},       {"rays"},   {"bits"},     {"turn deg"},
    {"error %"},      {"bias %"}, {"ref noise %"}, {"CPU ms"}, {"blob KiB"}, {"bake s"}};

std::vector<std::string> markdown_cells(const ShadowfieldTradeRow& r) {
  const Setting& s = r.setting;
  return {r.sweeps,
          std::to_string(s.order),
          std::to_string(s.terms),
          std::to_string(s.rays),
          std::to_string(s.bits),
          format("%g", r.degrees),
          format("%.2f", 100 * r.error),
          format("%+.2f", 100 * r.bias),
          format("%.2f", 100 * r.ref_noise),
          ms_text(r.cpu_ms),
          format("%.0f", r.blob_bytes / 1024.0),
          format("%.2f", r.bake_seconds)};
}

// The options only the scene mode reads.
const std::set<std::string> kSceneOnly = {
    "--shared",          "--times",         "--oof-shells", "--oof-faces",       "--srf-shells",
    "--srf-faces",       "--basis-sizes",   "--bounces",    "--base-oof-shells", "--base-oof-face",
    "--base-srf-shells", "--base-srf-face", "--base-basis", "--base-bounces",    "--lights"};

class ShadowfieldTrade final : public TechniqueTrade {
 public:
  ShadowfieldTrade() {
    // Small fields by default: the trade measures the object alone (no OOF or SRF read).
    o_.bake.fields.oof_shells = 4;
    o_.bake.fields.oof_face_size = 4;
    o_.bake.fields.field_directions = 256;
    o_.bake.srf.shells = 2;
    o_.bake.srf.face_size = 2;
    o_.bake.srf.directions = 256;
    o_.bake.basis.size = 4;
    o_.bake.basis.lights = 32;
  }

  TradeInput defaults() const override {
    TradeInput input;
    input.ref_spp = 1024;
    input.frames = 10;
    return input;
  }

  OptionList options() override {
    OptionList list;
    // Every option records whether it was given: the modes refuse each other's.
    auto add = [&](const std::string& name, auto* value, const std::string& help) -> OptionSpec& {
      return list.add(name, value, help).record_given(&given_[name]);
    };
    add("--brdf", &o_.brdf, "The object's BRDF: lambert, phong:N[,ks[,kd]], ggx:A[,F0]");
    add("--orders", &o_.orders, "SH orders of the order sweep (2..6)");
    add("--terms", &o_.terms, "BRDF terms K of the terms sweep (glossy only)");
    add("--rays", &o_.rays, "Transfer rays per vertex of the rays sweep");
    add("--bits", &o_.bits, "Quantisation bits of the bits sweep (8, 16)");
    add("--base-order", &o_.base_order, "Order of the other sweeps").range(2, 6);
    add("--base-terms", &o_.base_terms, "Terms of the other sweeps").range(1, 8);
    add("--base-rays", &o_.base_rays, "Transfer rays of the other sweeps").range(1, 65536);
    add("--base-bits", &o_.base_bits, "Bits of the other sweeps").choices({8, 16});
    add("--rotations", &o_.rotations, "Turns of the object about +Y, over a full turn")
        .range(1, 64);
    add("--brdf-grid", &o_.bake.brdf.grid_size, "The BRDF table's grid").range(4, 64);
    // Scene mode (SCENE names a preset): the fields, the basis and the bounces swept as well.
    add("--shared", &s_.shared, "Scene mode: the shared assets folder");
    add("--times", &s_.times, "Scene mode: seconds on the paths of the placements shaded");
    add("--oof-shells", &s_.oof_shells, "Scene mode: OOF shells of the oof_shells sweep");
    add("--oof-faces", &s_.oof_faces,
        "Scene mode: OOF cube face sizes (6 F^2 points a shell) of the oof_face sweep");
    add("--srf-shells", &s_.srf_shells, "Scene mode: SRF shells of the srf_shells sweep");
    add("--srf-faces", &s_.srf_faces, "Scene mode: SRF cube face sizes of the srf_face sweep");
    add("--basis-sizes", &s_.basis, "Scene mode: basis sizes N of the basis sweep");
    add("--bounces", &s_.bounces, "Scene mode: bounce counts of the bounces sweep");
    add("--base-oof-shells", &s_.base_oof_shells, "Scene mode: OOF shells of the others")
        .range(1, 64);
    add("--base-oof-face", &s_.base_oof_face, "Scene mode: OOF face size of the others")
        .range(1, 64);
    add("--base-srf-shells", &s_.base_srf_shells, "Scene mode: SRF shells of the others")
        .range(1, 256);
    add("--base-srf-face", &s_.base_srf_face, "Scene mode: SRF face size of the others")
        .range(1, 64);
    add("--base-basis", &s_.base_basis, "Scene mode: basis size N of the others").range(1, 256);
    add("--base-bounces", &s_.base_bounces, "Scene mode: bounces of the others")
        .range(0, PRT_SHADOWFIELD_MAX_BOUNCES);
    add("--lights", &s_.lights, "Scene mode: the basis's training lights").range(1, 65536);
    return list;
  }

  void check(const TradeInput& input) const override {
    check_settings(o_);
    const bool scene_mode = is_preset(input.scene);
    for (const auto& [name, given] : given_) {
      if (!given) continue;
      const bool object_only = name == "--brdf" || name == "--rotations";
      if (scene_mode && object_only)
        throw Error(name + ": a scene preset has its own placements and materials");
      if (!scene_mode && kSceneOnly.count(name))
        throw Error(name + ": only with a scene preset (" + preset_list() + ") as SCENE");
    }
    if (!scene_mode) return;
    if (!input.albedo.empty()) throw Error("--albedo: a scene preset has its own materials");
    sf_trade::check_scene_sweep_options(s_);
  }

  Scene load_scene(const TradeInput& input, const Context& ctx) override {
    if (!is_preset(input.scene)) return TechniqueTrade::load_scene(input, ctx);
    scene_ = sf_trade::make_scene_sweep(input.scene, s_, o_, given("--rays"), given("--base-rays"));
    return scene_->scene();
  }

  void prepare(const Scene& scene, const TradeInput& input, const Context& ctx) override {
    if (scene_) {
      scene_->prepare(input, ctx);
      return;
    }
    surface_ = parse_brdf_option(o_.brdf);
    settings_ = sweep_settings(o_, surface_.model != SurfaceBrdf::Model::Lambert);
    std::uint32_t max_order = 0;
    for (const Setting& s : settings_) max_order = std::max(max_order, s.order);
    std::vector<glm::vec3> positions;
    for (const Mesh& mesh : scene.meshes)
      positions.insert(positions.end(), mesh.positions.begin(), mesh.positions.end());
    sphere_ = bounding_sphere(positions);
    for (std::uint32_t i = 0; i < o_.rotations; ++i)
      facing_.push_back(facing_eye(scene,
                                   turned_instance(turn_degrees(i, o_.rotations), sphere_.centre),
                                   trade_eye(sphere_)));
    for (const std::string& path : input.envs) {
      lights_.push_back(load_sh_light(path, max_order, ctx));
      for (std::uint32_t i = 0; i < o_.rotations; ++i)
        references_[{lights_.back().name, i}] = reference(scene, lights_.back(), i, input, ctx);
    }
  }

  void sweep(const Scene& scene, const EmbreeScene&, const TradeInput& input,
             const Context& ctx) override {
    if (scene_) {
      scene_->sweep(input, ctx);
      return;
    }
    std::vector<ShadowfieldTradeRow> rows;
    for (std::size_t i = 0; i < settings_.size(); ++i) {
      const Setting& s = settings_[i];
      ctx.info("setting " + std::to_string(i + 1) + "/" + std::to_string(settings_.size()) +
               ": order " + std::to_string(s.order) + ", " + std::to_string(s.terms) + " terms, " +
               std::to_string(s.rays) + " rays, " + std::to_string(s.bits) + " bits");
      measure_setting(scene, s, input, ctx, rows);
    }
    write_tables(scene, rows, input, ctx.thread_count());
  }

 private:
  Reference reference(const Scene& scene, const ShLight& light, std::uint32_t rotation,
                      const TradeInput& input, const Context& ctx) const {
    std::string brdf_key = o_.brdf;
    std::replace(brdf_key.begin(), brdf_key.end(), ',', '-');
    std::replace(brdf_key.begin(), brdf_key.end(), ':', '-');
    std::string albedo_key = input.albedo.empty() ? "material" : input.albedo;
    std::replace(albedo_key.begin(), albedo_key.end(), ',', '-');
    const std::string key = stem(input.scene) + "_" + light.name + "_" + brdf_key + "_turn" +
                            std::to_string(rotation) + "of" + std::to_string(o_.rotations) +
                            "_spp" + std::to_string(input.ref_spp) + "_seed" +
                            std::to_string(input.seed) + "_albedo-" + albedo_key;
    const std::string npy = input.cache_dir + "/" + key + ".npy", noise_file = npy + ".noise";
    Reference ref;
    std::ifstream noise_in(noise_file);
    if (noise_in >> ref.noise && std::filesystem::exists(npy)) {
      ref.radiance = io::read_npy_vec3(npy);
      if (ref.radiance.size() == scene.vertex_count()) {
        ctx.info("reference " + key + ": from the cache");
        return ref;
      }
    }
    ctx.info("reference " + key + ": rendering");
    const PlacedScene placed = place_instances(
        {scene}, {turned_instance(turn_degrees(rotation, o_.rotations), sphere_.centre)});
    ReferenceSettings settings;
    settings.bounces = 0;
    settings.spp = input.ref_spp;
    settings.seed = input.seed;
    settings.brdf = surface_;
    if (!input.albedo.empty()) {
      settings.override_albedo = true;
      settings.albedo = parse_albedo(input.albedo);
    }
    const ReferenceRenderer renderer(placed.scene, *light.map, settings, ctx);
    VertexRadiance result = renderer.render_vertices(ctx, trade_eye(sphere_));
    io::write_npy_vec3(npy, result.radiance);
    std::ofstream noise_out(noise_file);
    noise_out.precision(17);
    noise_out << result.relative_rmse << "\n";
    if (!noise_out) throw Error(noise_file + ": cannot write");
    ref.radiance = std::move(result.radiance);
    ref.noise = result.relative_rmse;
    return ref;
  }

  void measure_setting(const Scene& scene, const Setting& s, const TradeInput& input,
                       const Context& ctx, std::vector<ShadowfieldTradeRow>& rows) const {
    ShadowfieldBakeSettings settings = o_.bake;
    settings.fields.order = s.order;
    settings.fields.transfer_rays = s.rays;
    settings.fields.seed = settings.srf.seed = input.seed;
    settings.brdf.terms = s.terms;
    settings.bits = s.bits;
    settings.basis.size = std::min<std::uint32_t>(
        settings.basis.size,
        std::uint32_t(std::min<std::size_t>(scene.vertex_count(),
                                            std::size_t(settings.basis.lights) * s.terms)));
    Scene object_scene = scene;
    if (!input.albedo.empty()) {
      Material material;
      material.base_color = glm::vec4(parse_albedo(input.albedo), 1.0f);
      object_scene.materials.push_back(material);
      for (Mesh& mesh : object_scene.meshes) mesh.material = int(object_scene.materials.size() - 1);
    }
    const auto start = std::chrono::steady_clock::now();
    const ShadowfieldBakeResult baked = bake_shadowfield_object(
        object_scene, shadowfield_material_of(surface_, settings.brdf), settings, ctx);
    const double bake_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::vector<std::uint8_t> blob =
        shadowfield_blob_of(baked.object, s.bits, "prtkit shadowfield trade: " + input.scene);
    const RuntimeAsset runtime = load_runtime_asset(blob);
    const glm::vec3 eye = trade_eye(sphere_);
    for (const ShLight& light : lights_) {
      const std::vector<float> l = light.at_order(s.order);
      for (std::uint32_t i = 0; i < o_.rotations; ++i) {
        const double degrees = turn_degrees(i, o_.rotations);
        const Instance placed = turned_instance(degrees, sphere_.centre);
        const prt_shadowfield_transform transform =
            shadowfield_transform(placed.rotation, placed.translation);
        LoneShadowfieldScene lone(runtime.asset.get(), transform);
        std::vector<float> shaded;
        ShadowfieldTradeRow row;
        row.cpu_ms = median_frame_ms(input.frames, "prt_shadowfield_shade", [&] {
          lone.shade(l, eye, &shaded);
          return PRT_OK;
        });
        const Reference& ref = references_.at({light.name, i});
        const std::vector<bool>& keep = facing_.at(i);
        const std::vector<glm::vec3> radiance = masked(as_vec3(shaded), keep);
        const std::vector<glm::vec3> expected = masked(ref.radiance, keep);
        row.map = light.name;
        row.sweeps = s.sweeps;
        row.setting = s;
        row.degrees = degrees;
        row.compared = radiance.size();
        row.error = io::relative_rmse(radiance, expected);
        row.bias = sf_trade::mean_bias(radiance, expected);
        row.ref_noise = ref.noise;
        row.blob_bytes = blob.size();
        row.bake_seconds = bake_seconds;
        ctx.info("  " + light.name + format(", turn %g: error %.3f %%", degrees, 100 * row.error));
        rows.push_back(row);
      }
    }
  }

  void write_tables(const Scene& scene, const std::vector<ShadowfieldTradeRow>& rows,
                    const TradeInput& input, unsigned threads) const {
    const std::string csv_path = input.out_dir + "/trade.csv";
    std::ofstream csv(csv_path);
    write_csv_row(csv, kCsvColumns);
    for (const ShadowfieldTradeRow& r : rows)
      write_csv_row(csv, csv_cells(r, o_, input, scene.vertex_count()));
    check_written(csv, csv_path);

    const std::string md_path = input.out_dir + "/trade.md";
    std::ofstream md(md_path);
    md << "# Technique shadowfield: speed versus accuracy (prt-bake trade shadowfield)\n\n";
    md << scene_description(input.scene, scene) << ", baked as one object, BRDF " << o_.brdf
       << "; albedo " << (input.albedo.empty() ? "from the materials" : input.albedo) << ".\n\n";
    md << "Sweeps: order " << joined(o_.orders) << ", BRDF terms " << joined(o_.terms)
       << " (glossy only), transfer rays " << joined(o_.rays) << ", bits 8/16, around order "
       << o_.base_order << ", " << o_.base_terms << " terms, " << o_.base_rays << " rays, "
       << o_.base_bits << " bits. The object alone, turned about +Y through its centre to "
       << o_.rotations
       << " angles, 0 bounces, eye fixed in front of it; only the vertices facing the eye are "
          "compared (the reference reflects nothing towards an eye behind a surface). Reference: "
       << input.ref_spp << " samples per vertex, the same placement, BRDF and eye; seed "
       << input.seed << ".\n\n";
    md << "Error = relative RMSE of per-vertex RGB radiance against the reference; bias = "
          "(sum of runtime - reference) / sum of reference. Shading time = median of "
       << input.frames
       << " frames of prt_shadowfield_shade over the object's vertices, one thread.\n\n";
    md << "Machine: " << machine_description(threads) << ".\n";
    for (const ShLight& light : lights_) {
      md << "\n## " << light.name << "\n\n";
      write_markdown_header(md, kMarkdownColumns);
      for (const ShadowfieldTradeRow& r : rows) {
        if (r.map == light.name) write_markdown_row(md, markdown_cells(r));
      }
    }
    check_written(md, md_path);
  }

  bool given(const std::string& name) const {
    const auto found = given_.find(name);
    return found != given_.end() && found->second;
  }

  static bool is_preset(const std::string& scene) {
    const std::vector<std::string> names = shadowfield_scene_names();
    return std::find(names.begin(), names.end(), scene) != names.end();
  }

  static std::string preset_list() {
    std::string text;
    for (const std::string& name : shadowfield_scene_names())
      text += (text.empty() ? "" : ", ") + name;
    return text;
  }

  SfTradeSettings o_;
  SceneSweepOptions s_;
  std::map<std::string, bool> given_;  // by option name: whether the command line gave it
  std::unique_ptr<SceneSweep> scene_;  // scene mode
  SurfaceBrdf surface_;
  BoundingSphere sphere_;
  std::vector<Setting> settings_;
  std::vector<ShLight> lights_;
  std::vector<std::vector<bool>> facing_;  // per turn
  std::map<std::pair<std::string, std::uint32_t>, Reference> references_;
};

}  // namespace

std::unique_ptr<TechniqueTrade> make_shadowfield_trade() {
  return std::make_unique<ShadowfieldTrade>();
}

}  // namespace prt::bake
