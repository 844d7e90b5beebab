// SPDX-License-Identifier: MIT
// Technique `cloth` in `prt-bake scene` (prt/baker/scene_bake.hpp): it suits nodes with a cloth
// material that no skin deforms; its ladder climbs the tables' grid, rank and bits
// (docs/cloth/trade.md); its measurement shades the blob's own vertex frames, each seen from a
// few views, through the runtime under the static spherical-Gaussian fit of each light, against
// the brute-force reference of the material's fabric over the map's texels
// (docs/cloth/trade.md#in-a-scene-bake).
#include <prt/prt_cloth_asset.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/cloth/cloth_light.hpp"
#include "prt/baker/cloth/fabrics.hpp"
#include "prt/baker/scene_bake.hpp"
#include "prt/io/radiance_error.hpp"

#include "../common/trade_common.hpp"
#include "cloth_technique.hpp"
#include "cloth_trade_measure.hpp"

namespace prt::bake {
namespace {

// The default fabric of `prt-bake bake cloth`, for a cloth material that names no preset.
constexpr const char* kClothSceneDefaultFabric = "linen_plain";

// The light's lobes. K is the app's choice, not the blob's, and no bake setting changes the
// light's own error, so the measurement takes the most accurate light the trade measures (its
// K 64 row, the app's largest K): fewer lobes add the light's error to every rung alike, up to
// most of satin's error at K 10 (docs/cloth/trade.md).
constexpr std::uint32_t kClothSceneLobes = 64;
// Views per probe vertex: one at each of the trade's four elevations (cloth_trade::frame_views),
// the azimuth turning from vertex to vertex so that the probes cover all of them.
constexpr std::size_t kClothSceneViewsPerVertex = 4;
// The reference integrates over at most about this many texels (blocks of texels merged, a power
// of two on a side); the same reference over blocks twice as wide states its own error.
constexpr std::size_t kClothSceneReferenceTexels = 8192;

bool cloth_scene_material(const Material& m) {
  return m.sheen || m.cloth;
}

// The cloth materials the node's meshes use, in mesh order (each once).
std::vector<const Material*> cloth_scene_materials_of(const Scene& scene, int node) {
  std::vector<const Material*> materials;
  for (const Mesh& mesh : scene.meshes) {
    if ((node >= 0 && mesh.node != node) || mesh.material < 0) continue;
    const Material& m = scene.materials[static_cast<std::size_t>(mesh.material)];
    if (cloth_scene_material(m) &&
        std::find(materials.begin(), materials.end(), &m) == materials.end())
      materials.push_back(&m);
  }
  return materials;
}

// The fabric of node `node`'s cloth (every mesh of the scene for node -1), and why.
struct ClothSceneFabric {
  const ClothPreset* preset = nullptr;
  std::string why;
};

ClothSceneFabric cloth_scene_fabric_of(const Scene& scene, int node) {
  const std::vector<const Material*> materials = cloth_scene_materials_of(scene, node);
  for (const Material* m : materials)
    if (const ClothPreset* preset = find_cloth_fabric(m->name))
      return {preset, "material '" + m->name + "' names the preset"};
  return {&cloth_fabric(kClothSceneDefaultFabric),
          materials.empty()
              ? "no cloth material: the default"
              : "material '" + materials.front()->name + "' names no preset: the default"};
}

// The blocks of texels the reference merges: the smallest power of two on a side that leaves at
// most kClothSceneReferenceTexels of them.
int cloth_scene_reference_block(const io::EnvMap& map) {
  int block = 1;
  const std::size_t texels = std::size_t(map.width()) * std::size_t(map.height());
  while (texels / (std::size_t(block) * std::size_t(block)) > kClothSceneReferenceTexels)
    block *= 2;
  return block;
}

// The probe vertices' frames and views, as prt_cloth_pixels takes them.
cloth_trade::Samples cloth_scene_samples(const std::vector<float>& normals,
                                         const std::vector<float>& warps,
                                         const std::vector<std::size_t>& probes) {
  cloth_trade::Samples samples;
  for (std::size_t p = 0; p < probes.size(); ++p) {
    const std::size_t v = probes[p];
    const glm::vec3 n(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
    const glm::vec3 w(warps[3 * v], warps[3 * v + 1], warps[3 * v + 2]);
    // frame_views lists 8 azimuths at each of 4 elevations.
    const std::vector<glm::vec3> views = cloth_trade::frame_views({n, w});
    for (std::size_t e = 0; e < kClothSceneViewsPerVertex; ++e) {
      const glm::vec3 view = views[8 * (e % 4) + (p + 3 * e) % 8];
      samples.normals.insert(samples.normals.end(), {n.x, n.y, n.z});
      samples.warps.insert(samples.warps.end(), {w.x, w.y, w.z});
      samples.views.insert(samples.views.end(), {view.x, view.y, view.z});
    }
  }
  return samples;
}

// A blob's VNRM or VTAN section as floats; Error when absent or of the wrong size.
std::vector<float> cloth_scene_section_floats(const prt_asset* asset, std::uint32_t tag,
                                              const char* what, std::size_t vertices) {
  const void* data = nullptr;
  std::size_t size = 0;
  if (prt_asset_section_data(asset, tag, &data, &size) != PRT_OK)
    throw Error(std::string("the cloth blob has no ") + what + " section");
  if (size != vertices * 3 * sizeof(float))
    throw Error(std::string("the cloth blob's ") + what + " holds " +
                std::to_string(size / (3 * sizeof(float))) + " vertices, not " +
                std::to_string(vertices));
  std::vector<float> values(vertices * 3);
  if (size > 0) std::memcpy(values.data(), data, size);
  return values;
}

// One light: its static SG fit (what the runtime shades under), the reference and its own error.
struct ClothSceneLight {
  std::vector<prt_cloth_lobe> lobes;
  std::vector<glm::vec3> reference;
  double reference_error = 0.0;
};

class ClothObjectMeasure final : public ObjectMeasure {
 public:
  explicit ClothObjectMeasure(const ObjectMeasureInput& input)
      : input_(input),
        fabric_(*cloth_scene_fabric_of(*input.object, -1).preset),
        probes_(spread_vertices(input.object->vertex_count(), input.probe_vertices)),
        lights_(input.lights.size()) {
    const ClothMesh mesh = cloth_mesh_of(*input.object);
    reference_samples_ = cloth_scene_samples(mesh.normals, mesh.tangents, probes_);
  }

  Measurement measure(const Technique&, const std::vector<std::uint8_t>& blob,
                      const Context& ctx) override {
    const trade::RuntimeAsset runtime = trade::load_runtime_asset(blob);
    const cloth_trade::Samples samples = blob_samples(runtime.asset.get());
    const std::uint32_t fabric = blob_fabric(runtime.asset.get());
    Measurement worst;
    for (std::size_t l = 0; l < lights_.size(); ++l) {
      const ClothSceneLight& light = prepared(l, ctx);
      const std::vector<glm::vec3> shaded = shade(runtime, fabric, samples, light.lobes, ctx);
      double error =
          trade::noise_removed(io::relative_rmse(shaded, light.reference), light.reference_error);
      if (!std::isfinite(error)) error = HUGE_VAL;
      if (l == 0 || error > worst.error) worst = {error, light.reference_error};
    }
    return worst;
  }

 private:
  // The probes' frames as the blob stores them (what an app draws the cloth with), seen from the
  // reference's views.
  cloth_trade::Samples blob_samples(const prt_asset* asset) const {
    const std::size_t vertices = input_.object->vertex_count();
    const std::vector<float> normals =
        cloth_scene_section_floats(asset, PRT_SECTION_VNRM, "VNRM", vertices);
    const std::vector<float> warps =
        cloth_scene_section_floats(asset, PRT_SECTION_VTAN, "VTAN", vertices);
    cloth_trade::Samples samples = cloth_scene_samples(normals, warps, probes_);
    // The views are the reference's: a blob whose frames are off is seen where they should be.
    samples.views = reference_samples_.views;
    return samples;
  }

  // The object's fabric in the blob (by name), or the blob's only one when it has another.
  std::uint32_t blob_fabric(const prt_asset* asset) const {
    std::uint32_t index = 0;
    if (prt_cloth_find_fabric(asset, fabric_.name.c_str(), &index) == PRT_OK) return index;
    prt_cloth_info info = prt::sized<prt_cloth_info>();
    trade::check_runtime(prt_cloth_get_info(asset, &info), "prt_cloth_get_info");
    if (info.fabric_count == 0) throw Error("the cloth blob has no fabric");
    return 0;
  }

  std::vector<glm::vec3> shade(const trade::RuntimeAsset& runtime, std::uint32_t fabric,
                               const cloth_trade::Samples& samples,
                               const std::vector<prt_cloth_lobe>& lobes, const Context& ctx) const {
    prt_workers_desc desc = prt::sized<prt_workers_desc>();
    desc.thread_count = ctx.thread_count();
    prt_workers* workers = nullptr;
    trade::check_runtime(prt_workers_create(runtime.context.get(), &desc, &workers),
                         "prt_workers_create");
    const std::unique_ptr<prt_workers, void (*)(prt_workers*)> owned(workers, prt_workers_destroy);
    prt_cloth_light light = prt::sized<prt_cloth_light>();
    light.lobe_count = static_cast<std::uint32_t>(lobes.size());
    light.lobes = lobes.data();
    const prt_cloth_pixels pixels = samples.pixels();
    std::vector<float> rgb(3 * std::size_t(samples.count()));
    trade::check_runtime(
        prt_cloth_shade_workers(workers, runtime.asset.get(), PRT_BACKEND_AUTO, fabric, nullptr,
                                &light, nullptr, &pixels, 0, samples.count(), rgb.data()),
        "prt_cloth_shade");
    return trade::as_vec3(rgb);
  }

  // The light's fit and reference, made on first need.
  const ClothSceneLight& prepared(std::size_t l, const Context& ctx) {
    if (!lights_[l]) {
      const io::EnvMap& map = *input_.lights[l];
      auto light = std::make_unique<ClothSceneLight>();
      SgLightOptions options;
      options.lobe_count = kClothSceneLobes;
      light->lobes = fit_sg_light(map, options, ctx).lobes;
      const int block = cloth_scene_reference_block(map);
      light->reference = trade::as_vec3(cloth_trade::reference(
          fabric_, reference_samples_, cloth_trade::env_texels(map, block), ctx));
      const std::vector<glm::vec3> coarse = trade::as_vec3(cloth_trade::reference(
          fabric_, reference_samples_, cloth_trade::env_texels(map, 2 * block), ctx));
      light->reference_error = io::relative_rmse(coarse, light->reference);
      lights_[l] = std::move(light);
    }
    return *lights_[l];
  }

  ObjectMeasureInput input_;
  const ClothPreset& fabric_;
  std::vector<std::size_t> probes_;
  cloth_trade::Samples reference_samples_;
  std::vector<std::unique_ptr<ClothSceneLight>> lights_;
};

}  // namespace

const ClothPreset& cloth_scene_fabric(const Scene& scene) {
  return *cloth_scene_fabric_of(scene, -1).preset;
}

ObjectFit cloth_scene_fit(const Scene& scene, int node) {
  const NodeKind kind = node_kind(scene, node);
  if (!kind.has_mesh) return {false, "no mesh"};
  if (!kind.cloth) return {false, "no cloth material (KHR_materials_sheen or extras.prt.cloth)"};
  if (kind.skinned)
    return {false,
            "skinned: the blob's mesh is the bind pose, whose frames a skin deforms (the "
            "tables alone would still shade any frame an app gives)"};
  const ClothSceneFabric fabric = cloth_scene_fabric_of(scene, node);
  std::string reason = "woven cloth, fabric " + fabric.preset->name + " (" + fabric.why + ")";
  if (kind.moves)
    reason +=
        "; it moves, which cloth allows: the tables do not depend on the pose and the runtime "
        "shades whatever frames it is given";
  return {true, reason};
}

std::vector<Rung> cloth_scene_ladder(int) {
  // The fabric is the scene's; the rank follows the energy. From the coarsest grid and the
  // loosest rank to the trade's default grid with a tighter rank, in the order of the bytes
  // they store. All at 8 bits: 16 bits cost more than twice the bytes and buy no measurable
  // accuracy (docs/cloth/trade.md).
  struct Setting {
    const char *xi, *levels, *views, *energy;
  };
  const Setting settings[] = {
      {"16", "6", "8", "1e-3"},  {"16", "6", "8", "1e-4"},   {"16", "6", "16", "1e-4"},
      {"32", "6", "16", "1e-4"}, {"32", "10", "16", "1e-4"}, {"32", "10", "16", "1e-5"},
  };
  std::vector<Rung> ladder;
  for (const Setting& s : settings) {
    ladder.push_back({{"--fabric", "scene", "--xi-size", s.xi, "--levels", s.levels, "--view-theta",
                       s.views, "--view-phi", s.views, "--energy", s.energy, "--bits", "8"}});
  }
  return ladder;
}

std::unique_ptr<ObjectMeasure> make_cloth_measure(const ObjectMeasureInput& input) {
  return std::make_unique<ClothObjectMeasure>(input);
}

}  // namespace prt::bake
