// SPDX-License-Identifier: MIT
// Technique `shadowfield` in `prt-bake scene` (prt/baker/scene_bake.hpp): it suits rigid objects
// that move; its ladder climbs the SH order with the occlusion field's shells and points, the
// source fields and basis, and the bits (docs/shadowfield/trade.md); its measurement places the
// object above a floor it shadows, at a few placements of its own motion, and compares the
// runtime's shading of both with the path tracer's (docs/shadowfield/design.md, "In a scene
// bake").
#include <prt/prt_shadowfield.h>
#include <prt/prt_shadowfield_asset.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "prt/baker/animation.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/scene_bake.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "prt/baker/shadowfield/shadowfield_bake.hpp"
#include "prt/baker/shadowfield/shadowfield_measure.hpp"
#include "prt/io/radiance_error.hpp"

#include "../common/trade_common.hpp"
#include "shadowfield_technique.hpp"

namespace prt::bake {
namespace {

// Directions per field point and rays per vertex of every rung: enough that the fields' own
// noise stays below the order's truncation (the trade bakes at this count).
constexpr const char* kSfSceneRays = "1024";

// The floor the measurement's object shadows: a square of this half side (x the object's
// bounding radius, wide enough for the shadow under a high sky), this many cells a side, this
// far below the object's lowest point (x the radius: near contact, as an object moving over the
// ground is, where its shadow is sharpest, yet clear of the bake's ray offsets).
constexpr float kSfProbeFloorHalf = 2.0f;
constexpr int kSfProbeFloorCells = 20;
constexpr float kSfProbeFloorGap = 0.05f;
constexpr float kSfProbeFloorAlbedo = 0.6f;
// Placements of the object's own clip measured (or fixed ones without a clip).
constexpr int kSfPlacements = 3;
// The light's SH order given to the runtime: the largest a blob has; it takes the leading ones.
constexpr std::uint32_t kSfLightOrder = 6;

struct SfSceneRungSpec {
  int order, oof_shells, oof_face, srf_shells, srf_face, basis, bits;
};

Rung sf_scene_rung(const SfSceneRungSpec& s) {
  return {{"--order", std::to_string(s.order), "--shells", std::to_string(s.oof_shells),
           "--face-size", std::to_string(s.oof_face), "--srf-shells", std::to_string(s.srf_shells),
           "--srf-face-size", std::to_string(s.srf_face), "--basis", std::to_string(s.basis),
           "--bits", std::to_string(s.bits), "--field-rays", kSfSceneRays, "--transfer-rays",
           kSfSceneRays}};
}

// --- The placements -------------------------------------------------------------------------

// The first clip whose channels move `node` (or an ancestor), or null.
const Animation* sf_clip_moving(const Scene& scene, int node) {
  std::vector<int> chain;
  for (int n = node; n >= 0; n = scene.nodes[std::size_t(n)].parent) chain.push_back(n);
  for (const Animation& clip : scene.animations) {
    for (const AnimationChannel& channel : clip.channels) {
      if (channel.path == AnimationChannel::Path::Weights) continue;
      if (std::find(chain.begin(), chain.end(), channel.node) != chain.end()) return &clip;
    }
  }
  return nullptr;
}

// The similarity nearest `m` (world = s R x + t): s the cube root of |det|, R the rotation of
// the scaled columns. A shadow field is placed by a similarity only: a clip that shears or
// scales unevenly is measured at this nearest one, on both sides.
ShadowfieldPlacement sf_similarity_of(const glm::mat4& m) {
  const glm::mat3 linear(m);
  const float scale = std::cbrt(std::abs(glm::determinant(linear)));
  ShadowfieldPlacement p;
  p.translation = glm::vec3(m[3]);
  p.scale = scale > 0.0f && std::isfinite(scale) ? scale : 1.0f;
  p.rotation = glm::normalize(glm::quat_cast(linear / p.scale));
  return p;
}

// Where the object is measured, relative to the pose it was baked in (its node's rest world
// transform): the clip's pose at instants spread over it, or, for an object that only says it
// moves, its rest pose, a quarter turn about +Y and a tilt about +X (its field read from other
// directions), each turned about its centre.
std::vector<ShadowfieldPlacement> sf_measured_placements(const Scene& object, int node,
                                                         const glm::vec3& centre, float radius) {
  std::vector<ShadowfieldPlacement> placements;
  if (const Animation* clip = sf_clip_moving(object, node)) {
    const glm::mat4 rest_inverse = glm::inverse(object.nodes[std::size_t(node)].world);
    for (int i = 0; i < kSfPlacements; ++i) {
      ScenePose pose(object);
      pose.apply(*clip, clip->duration * (float(i) + 0.5f) / float(kSfPlacements));
      placements.push_back(
          sf_similarity_of(pose.world_matrices()[std::size_t(node)] * rest_inverse));
    }
    return placements;
  }
  const float quarter = 0.5f * glm::pi<float>();
  const glm::quat turns[kSfPlacements] = {glm::quat(1.0f, 0.0f, 0.0f, 0.0f),
                                          glm::angleAxis(quarter, glm::vec3(0.0f, 1.0f, 0.0f)),
                                          glm::angleAxis(0.4f * quarter, glm::vec3(1, 0, 0))};
  const glm::vec3 shifts[kSfPlacements] = {glm::vec3(0.0f), glm::vec3(0.5f * radius, 0.0f, 0.0f),
                                           glm::vec3(0.0f, 0.0f, -0.5f * radius)};
  for (int i = 0; i < kSfPlacements; ++i) {
    ShadowfieldPlacement p;
    p.rotation = turns[i];
    p.translation = centre + shifts[i] - turns[i] * centre;
    placements.push_back(p);
  }
  return placements;
}

// The floor under the object at `placement`: level whatever the object's turn, centred under its
// bounding sphere, scaled with it, its top kSfProbeFloorGap radii below the lowest vertex.
ShadowfieldPlacement sf_floor_under(const Scene& object, const ShadowfieldPlacement& placement,
                                    const glm::vec3& centre, float radius) {
  float lowest = HUGE_VALF;
  for (const Mesh& mesh : object.meshes)
    for (const glm::vec3& p : mesh.positions) lowest = std::min(lowest, placement.apply(p).y);
  const glm::vec3 placed_centre = placement.apply(centre);
  ShadowfieldPlacement floor;
  floor.scale = placement.scale;
  floor.translation =
      glm::vec3(placed_centre.x, lowest - kSfProbeFloorGap * radius * floor.scale, placed_centre.z);
  return floor;
}

ShadowfieldPath sf_still(const ShadowfieldPlacement& placement) {
  ShadowfieldPath path;
  path.keyframes.push_back({0.0f, placement});
  return path;
}

Scene sf_probe_floor(float radius) {
  Scene floor;
  floor.source = "generated: shadowfield probe floor";
  Material grey;
  grey.name = "probe floor";
  grey.base_color = glm::vec4(glm::vec3(kSfProbeFloorAlbedo), 1.0f);
  floor.materials.push_back(grey);
  const float half = kSfProbeFloorHalf * radius;
  floor.meshes.push_back(
      make_plane_mesh("probe floor", 0, half, half, kSfProbeFloorCells, kSfProbeFloorCells));
  return floor;
}

// --- The measurement ------------------------------------------------------------------------

// The settings of a blob that a receiver baked alongside must share (the runtime's scene takes
// one SH order) or that make it part of the same candidate.
using SfReceiverKey = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t, float,
                                 float, std::uint32_t, std::uint32_t, float, float, std::uint32_t>;

prt_shadowfield_info sf_blob_info(const std::vector<std::uint8_t>& blob) {
  const trade::RuntimeAsset loaded = trade::load_runtime_asset(blob);
  prt_shadowfield_info info = prt::sized<prt_shadowfield_info>();
  trade::check_runtime(prt_shadowfield_get_info(loaded.asset.get(), &info),
                       "prt_shadowfield_get_info");
  return info;
}

// One reference render's figures over two sets of probes rendered apart: the radiance in turn,
// the noise as the RMSE over both against their RMS over both.
VertexRadiance sf_joined(const VertexRadiance& a, const VertexRadiance& b) {
  const auto sum_of_squares = [](const std::vector<glm::vec3>& values) {
    double sum = 0.0;
    for (const glm::vec3& v : values) sum += double(glm::dot(v, v));
    return sum;
  };
  const double squares_a = sum_of_squares(a.radiance), squares_b = sum_of_squares(b.radiance);
  VertexRadiance joined;
  joined.radiance = a.radiance;
  joined.radiance.insert(joined.radiance.end(), b.radiance.begin(), b.radiance.end());
  const double squares = squares_a + squares_b;
  joined.relative_rmse = squares > 0.0 ? std::sqrt((a.relative_rmse * a.relative_rmse * squares_a +
                                                    b.relative_rmse * b.relative_rmse * squares_b) /
                                                   squares)
                                       : 0.0;
  return joined;
}

// Two runtime scenes per placement, each against the reference of the same: the object alone
// (its own probes: its self transfer, turned as the placement turns it), and the object above
// the floor (the floor's probes: the shadow the object's occlusion field casts and, with
// bounces, the light its source fields send). The floor's own fields are a probe's, not the
// candidate's, so they are kept out of the object's probes; the floor does not shadow itself.
class ShadowfieldObjectMeasure final : public ObjectMeasure {
 public:
  explicit ShadowfieldObjectMeasure(const ObjectMeasureInput& input) : input_(input) {
    std::vector<glm::vec3> positions;
    for (const Mesh& mesh : input.object->meshes)
      positions.insert(positions.end(), mesh.positions.begin(), mesh.positions.end());
    const BoundingSphere sphere = bounding_sphere(positions);
    alone_.name = "object alone";
    alone_.objects.push_back({"object", *input.object, {}});
    over_floor_.name = "object over a probe floor";
    over_floor_.objects = alone_.objects;
    over_floor_.objects.push_back({"probe floor", sf_probe_floor(sphere.radius), {}});
    for (const ShadowfieldPlacement& p :
         sf_measured_placements(*input.object, input.node, sphere.centre, sphere.radius)) {
      placements_.push_back(
          {{0, sf_still(p)},
           {1, sf_still(sf_floor_under(*input.object, p, sphere.centre, sphere.radius))}});
      // Lambertian on both sides, so the eye only has to be outside: above and in front.
      eyes_.push_back(p.apply(sphere.centre) + p.scale * sphere.radius * glm::vec3(0, 3, 6));
    }
    // As many probes on the floor as on the object, so that the shadow it casts weighs as much
    // as its own shading.
    const std::size_t per_side = std::max<std::size_t>(input.probe_vertices / 2, 1);
    object_probes_ = spread_vertices(input.object->vertex_count(), per_side);
    floor_probes_ =
        spread_vertices(over_floor_.objects[1].mesh.vertex_count(), object_probes_.size());
    references_.resize(input.lights.size() * placements_.size());
    light_sh_.resize(input.lights.size());
  }

  // The worst over lights and placements: the budget is a promise for every frame the object is
  // seen in, and a placement whose shadow is misread is not made good by others.
  Measurement measure(const Technique&, const std::vector<std::uint8_t>& blob,
                      const Context& ctx) override {
    const std::vector<std::uint8_t>& floor = floor_blob(blob, ctx);
    Measurement worst;
    bool first = true;
    for (std::size_t l = 0; l < input_.lights.size(); ++l) {
      for (std::size_t p = 0; p < placements_.size(); ++p) {
        const VertexRadiance& ref = reference(l, p, ctx);
        double error = trade::noise_removed(
            io::relative_rmse(runtime_at_probes(blob, floor, l, p), ref.radiance),
            ref.relative_rmse);
        if (!std::isfinite(error)) error = HUGE_VAL;
        if (first || error > worst.error) worst = {error, ref.relative_rmse};
        first = false;
      }
    }
    return worst;
  }

 private:
  // The floor's blob, baked with the candidate's settings as its SFLD header states them (the
  // rays are the ladder's). The floor is only a probe: its bytes are not the candidate's.
  const std::vector<std::uint8_t>& floor_blob(const std::vector<std::uint8_t>& blob,
                                              const Context& ctx) {
    const prt_shadowfield_info info = sf_blob_info(blob);
    if (info.glossy)
      throw Error("shadowfield measure: a glossy blob; the scene's reference is diffuse");
    if (info.vertex_count != input_.object->vertex_count())
      throw Error("shadowfield measure: the blob has " + std::to_string(info.vertex_count) +
                  " vertices, the object " + std::to_string(input_.object->vertex_count()));
    const prt_shadowfield_shells& oof = info.oof_shells;
    const prt_shadowfield_shells& srf = info.srf_shells;
    const SfReceiverKey key{info.order, info.bits, oof.shells,     oof.face_size,
                            oof.inner,  oof.outer, srf.shells,     srf.face_size,
                            srf.inner,  srf.outer, info.basis_size};
    auto found = floors_.find(key);
    if (found != floors_.end()) return found->second;
    ShadowfieldBakeSettings s;
    s.fields.order = info.order;
    s.fields.oof_shells = oof.shells;
    s.fields.oof_face_size = oof.face_size;
    s.fields.inner = oof.inner;
    s.fields.outer = oof.outer;
    s.srf.shells = srf.shells;
    s.srf.face_size = srf.face_size;
    s.srf.inner = srf.inner;
    s.srf.outer = srf.outer;
    s.basis.size = info.basis_size;
    s.bits = int(info.bits);
    s.fields.seed = s.srf.seed = input_.seed;
    const ShadowfieldBakeResult floor =
        bake_shadowfield_object(over_floor_.objects[1].mesh, ShadowfieldMaterial{}, s, ctx);
    return floors_
        .emplace(key, shadowfield_blob_of(floor.object, s.bits, "prt-bake scene: probe floor"))
        .first->second;
  }

  std::vector<glm::vec3> runtime_at_probes(const std::vector<std::uint8_t>& blob,
                                           const std::vector<std::uint8_t>& floor,
                                           std::size_t light, std::size_t placement) {
    place(placement);
    if (light_sh_[light].empty())
      light_sh_[light] = project_env_sh(*input_.lights[light], kSfLightOrder).to_float();
    const std::vector<std::uint32_t> bounces = {std::min<std::uint32_t>(
        std::uint32_t(std::max(input_.bounces, 0)), PRT_SHADOWFIELD_MAX_BOUNCES)};
    const glm::vec3& eye = eyes_[placement];
    const std::vector<glm::vec3> alone = shade_shadowfield_scene(
        alone_, {blob}, light_sh_[light], kSfLightOrder, 0.0f, bounces, eye)[0];
    const std::vector<glm::vec3> with_floor = shade_shadowfield_scene(
        over_floor_, {blob, floor}, light_sh_[light], kSfLightOrder, 0.0f, bounces, eye)[0];
    std::vector<glm::vec3> at_probes;
    const std::size_t floor_first = input_.object->vertex_count();
    for (const std::size_t v : object_probes_) at_probes.push_back(alone.at(v));
    for (const std::size_t v : floor_probes_) at_probes.push_back(with_floor.at(floor_first + v));
    return at_probes;
  }

  // The object probes of the object alone, then the floor probes of the object over the floor.
  const VertexRadiance& reference(std::size_t light, std::size_t placement, const Context& ctx) {
    std::unique_ptr<VertexRadiance>& slot = references_[light * placements_.size() + placement];
    if (!slot) {
      place(placement);
      const io::EnvMap& env = *input_.lights[light];
      const glm::vec3& eye = eyes_[placement];
      const VertexRadiance object = render_reference(alone_, 0, object_probes_, env, eye, ctx);
      const VertexRadiance floor = render_reference(over_floor_, 1, floor_probes_, env, eye, ctx);
      slot = std::make_unique<VertexRadiance>(sf_joined(object, floor));
    }
    return *slot;
  }

  VertexRadiance render_reference(const ShadowfieldSceneDescription& description,
                                  std::size_t instance, const std::vector<std::size_t>& probes,
                                  const io::EnvMap& env, const glm::vec3& eye,
                                  const Context& ctx) const {
    const PlacedScene placed = place_shadowfield_scene(description, 0.0f);
    const ReferenceSettings settings = shadowfield_reference_settings(
        description, placed, input_.bounces, input_.ref_spp, input_.seed);
    std::vector<std::size_t> world;
    for (const std::size_t v : probes) world.push_back(placed.world_vertex(instance, v));
    const ReferenceRenderer renderer(placed.scene, env, settings, ctx);
    return renderer.render_vertices(world, ctx, eye);
  }

  void place(std::size_t placement) {
    alone_.instances = {placements_[placement][0]};
    over_floor_.instances = placements_[placement];
  }

  ObjectMeasureInput input_;
  // The object alone and the object over the floor; their instances set per placement.
  ShadowfieldSceneDescription alone_, over_floor_;
  std::vector<std::vector<ShadowfieldInstance>> placements_;  // the object's, then the floor's
  std::vector<glm::vec3> eyes_;
  std::vector<std::size_t> object_probes_, floor_probes_;
  std::vector<std::unique_ptr<VertexRadiance>> references_;  // light-major, then placement
  std::vector<std::vector<float>> light_sh_;
  std::map<SfReceiverKey, std::vector<std::uint8_t>> floors_;
};

}  // namespace

ObjectFit shadowfield_scene_fit(const Scene& scene, int node) {
  const NodeKind kind = node_kind(scene, node);
  if (kind.skinned) return {false, "skinned (a shadow field is baked for a rigid object)"};
  if (kind.cloth) return {false, "has a cloth material"};
  if (!kind.moves) return {false, "does not move (a static bake sees its surroundings)"};
  return {true, "rigid, moves"};
}

std::vector<Rung> shadowfield_scene_ladder(int bounces) {
  // Order first (the knob that matters most), the occlusion field's shells with it (4 shells
  // blur the shadow, past 16 nothing is gained), its points per shell little, the source fields
  // and N with them; 8 bits cost no error the trade measured, so 16 bits come last, at the top
  // order. Bytes follow order^2 x (occlusion points + source points x N) plus the transfer:
  // each rung's exceed the one before.
  std::vector<SfSceneRungSpec> specs = {{2, 4, 4, 2, 4, 4, 8},    {3, 8, 8, 4, 4, 8, 8},
                                        {4, 8, 8, 4, 4, 8, 8},    {4, 16, 8, 8, 8, 16, 8},
                                        {5, 16, 16, 8, 8, 16, 8}, {6, 16, 16, 8, 8, 16, 8},
                                        {6, 16, 16, 8, 8, 16, 16}};
  std::vector<Rung> ladder;
  for (SfSceneRungSpec spec : specs) {
    // Without bounces the runtime reads neither the source fields nor the basis: the smallest.
    if (bounces <= 0) spec.srf_shells = spec.srf_face = spec.basis = 1;
    ladder.push_back(sf_scene_rung(spec));
  }
  return ladder;
}

std::unique_ptr<ObjectMeasure> make_shadowfield_object_measure(const ObjectMeasureInput& input) {
  return std::make_unique<ShadowfieldObjectMeasure>(input);
}

}  // namespace prt::bake
