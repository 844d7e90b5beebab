// SPDX-License-Identifier: MIT
// Technique `shadowfield` behind the baker's Technique interface (private to the baker): what the
// bake's self-check and the trade share, and the trade itself (shadowfield_trade.cpp).
#pragma once

#include <prt/prt.h>
#include <prt/prt.hpp>

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/reference.hpp"
#include "prt/baker/shadowfield/shadowfield_bake.hpp"
#include "prt/baker/technique.hpp"

namespace prt::bake {

// prt-bake trade shadowfield (shadowfield_trade.cpp).
std::unique_ptr<TechniqueTrade> make_shadowfield_trade();

// prt-bake scene (shadowfield_scene.cpp): rigid objects that move; the settings ladder; the
// object measured above a floor it shadows, at placements of its own motion.
ObjectFit shadowfield_scene_fit(const Scene& scene, int node);
std::vector<Rung> shadowfield_scene_ladder(int bounces);
std::unique_ptr<ObjectMeasure> make_shadowfield_object_measure(const ObjectMeasureInput& input);

// The --brdf flag's text ("lambert", "phong:N[,ks[,kd]]", "ggx:A[,F0]") parsed and checked;
// every Error names the flag.
SurfaceBrdf parse_brdf_option(const std::string& text);

// The material a parsed --brdf bakes to: diffuse, or the model separated with `options`.
ShadowfieldMaterial shadowfield_material_of(const SurfaceBrdf& brdf,
                                            const SeparableBrdfOptions& options);

// A placement for prt_shadowfield_shade: world = rotation local + translation.
prt_shadowfield_transform shadowfield_transform(const glm::mat3& rotation,
                                                const glm::vec3& translation);

// A runtime scene of one object placed alone (its own context), shaded with 0 bounces on the CPU
// backend. Throws Error naming the failing call.
class LoneShadowfieldScene {
 public:
  LoneShadowfieldScene(const prt_asset* asset, const prt_shadowfield_transform& transform);
  // Outgoing radiance (vertex-major RGB) under `light_rgb` (world SH, the asset's order,
  // coefficient-major RGB) towards `eye`.
  void shade(const std::vector<float>& light_rgb, const glm::vec3& eye, std::vector<float>* rgb);

 private:
  prt::ContextPtr context_;
  std::unique_ptr<prt_shadowfield_scene, void (*)(prt_shadowfield_scene*)> scene_;
  std::uint32_t vertices_ = 0;
};

// LoneShadowfieldScene's radiance, once.
std::vector<float> shade_lone_shadowfield(const prt_asset* asset,
                                          const prt_shadowfield_transform& transform,
                                          const std::vector<float>& light_rgb,
                                          const glm::vec3& eye);

// The same radiance from the float object, unplaced (object frame = world), in double:
// albedo sum_k g_k(wo) (T_k . L), g read as the runtime reads it. `bound`, when not null,
// receives per vertex and channel how far the runtime may be from it: the quantisation steps of
// `quantized` (half a step per transfer value) carried through the same sum, and float rounding.
std::vector<double> shade_float_shadowfield(const ShadowfieldObject& object,
                                            const std::vector<float>& light_rgb,
                                            const glm::vec3& eye,
                                            const QuantizedShadowfield* quantized,
                                            std::vector<double>* bound);

// ---- Shards (shadowfield_shards.cpp, docs/farm.md) ---------------------------------------------
// A bake's units, numbered as one list: the occlusion field's shells, then the source radiance
// fields' shells, then the self transfer's vertex blocks (as many vertices as an occlusion shell
// has points, the last block shorter), so a unit of each kind traces about as many rays at the
// default settings. Every shell point and every vertex is sampled on its own, so a unit's values
// do not depend on the units baked with it.
inline constexpr const char* kShadowfieldShardUnit = "shells and vertex blocks";

// What a shard and the merge know of the bake besides the scene: its settings as bake() resolves
// them (inner, outer and seed set) and the options the settings do not hold.
struct ShadowfieldShardBake {
  const ShadowfieldBakeSettings& settings;
  std::string brdf;  // surface_brdf_name of --brdf
  double inner = 0.0, outer = 0.0;
  bool override_albedo = false;  // --albedo given
  glm::vec3 albedo{0.0f};
};

// How many units the bake of `scene` (its vertex count) with `settings` has.
std::size_t shadowfield_shard_units(const Scene& scene, const ShadowfieldBakeSettings& settings);

// Bakes units [first, first + count) of the object `scene` holds (--albedo applied) into a shard
// payload.
std::vector<std::uint8_t> bake_shadowfield_shard(const Scene& scene,
                                                 const ShadowfieldMaterial& material,
                                                 const ShadowfieldShardBake& bake,
                                                 std::size_t first, std::size_t count,
                                                 const Context& ctx);

// Joins every part's payload, in unit order, into the result bake_shadowfield_object gives for
// the whole object; Error naming the part and what does not fit.
ShadowfieldBakeResult merge_shadowfield_shards(const Scene& scene,
                                               const ShadowfieldMaterial& material,
                                               const ShadowfieldShardBake& bake,
                                               const std::vector<std::vector<std::uint8_t>>& parts,
                                               const Context& ctx);

// The bake's self-check: the blob loaded at full validation, its SFLD header against the bake,
// and the object shaded alone by the runtime under a few lights and eyes against
// shade_float_shadowfield, each vertex within its quantisation bound.
struct ShadowfieldBlobCheck {
  bool passed = false;
  std::string message;
  double max_abs_error = 0.0;     // runtime against float radiance, over every light and vertex
  double max_budget_ratio = 0.0;  // the largest error / bound
};
ShadowfieldBlobCheck check_shadowfield_blob(const std::vector<std::uint8_t>& blob,
                                            const ShadowfieldObject& object,
                                            const QuantizedShadowfield& quantized);

}  // namespace prt::bake
