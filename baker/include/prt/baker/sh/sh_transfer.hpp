// SPDX-License-Identifier: MIT
// Per-vertex SH radiance transfer for technique `sh` (Sloan, Kautz, Snyder 2002).
//
// For a vertex with unit normal n and albedo rho, the transfer vector t (one per colour channel)
// turns the SH projection L of the environment's radiance (L_k = integral of L(w) y_k(w) dw,
// prt_sh.h) into outgoing radiance: shading = sum_k t_k L_k, with
//   direct:         t_k = integral of V(w) max(0, n.w) (rho/pi) y_k(w) dw
// (V = 1 for kind Unshadowed, the scene's visibility for Shadowed), and for Interreflected the
// bounce passes of Sloan 2002 §5 added on top:
//   bounce b:       t^b_k(p) = (rho_p/pi) integral over occluded w of t^(b-1)_k(hit(p,w))
//   max(0,n.w) dw
// where the hit point's transfer is its vertices' transfer interpolated with the hit's
// barycentrics. Transfer is one-sided: a ray that hits the back of a surface (the side its vertex
// normals turn away from) gathers nothing in a bounce pass.
//
// Directions: per vertex, `rays` cosine-weighted directions about n from an Owen-scrambled Sobol
// stream keyed by (seed, vertex). Cosine sampling is importance sampling of the clamped cosine
// that every transfer coefficient carries, so t_k = rho * mean of V(w_i) y_k(w_i): no sample is
// wasted below the horizon and, for a vertex that sees the whole hemisphere, t_00 is exact
// (y_00 is constant), so a white furnace is reproduced without sampling error. The same
// directions are used in every pass; rays leave the vertex by the Embree scene's ray-offset
// policy (EmbreeScene::offset_origin along the vertex normal), as in the reference renderer.
//
// Vertices whose normal is zero or non-finite (or whose position is non-finite) get a zero
// transfer vector; they are counted and reported through the context as one warning.
// Results are bitwise deterministic for any thread count.
//
// Ranges (distributed bakes, docs/farm.md): a vertex's directions are keyed by its index in the
// scene, so the direct pass of a range of vertices gives, bit for bit, the rows the whole bake
// gives them. A bounce pass reads the previous pass of every vertex its rays hit, so an
// interreflected bake splits only its direct pass: the ranges are joined, then the bounces run
// over the whole (compute_sh_transfer is compute_sh_direct_range over every vertex followed by
// add_sh_bounces).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/scene.hpp"

namespace prt::bake {

enum class ShTransferKind { Unshadowed, Shadowed, Interreflected };

// "unshadowed" | "shadowed" | "interreflected"; parse throws Error on anything else.
const char* sh_transfer_kind_name(ShTransferKind kind);
ShTransferKind parse_sh_transfer_kind(const char* name);

struct ShTransferSettings {
  std::uint32_t order = 3;  // SH order n: bands 0..n-1, n*n coefficients; 1..PRT_SH_MAX_ORDER
  ShTransferKind kind = ShTransferKind::Shadowed;
  std::uint32_t rays = 1024;  // directions per vertex (>= 1); a power of two suits Sobol best
  int bounces = 1;            // bounce passes for Interreflected (>= 0; ignored otherwise)
  std::uint32_t seed = 0;
  bool override_albedo = false;  // true: every vertex has `albedo`; false: Scene::vertex_albedo
  glm::vec3 albedo{0.8f};        // linear RGB in [0,1]
};

struct ShTransfer {
  std::uint32_t order = 0;
  ShTransferKind kind = ShTransferKind::Shadowed;
  std::size_t vertex_count = 0;
  // vertex_count x 3 (R, G, B) x order^2 floats: vertex v, channel c, coefficient k at
  // (v * 3 + c) * order^2 + k. Vertices in Scene order.
  std::vector<float> coefficients;
  std::size_t vertices_without_normal = 0;  // given a zero vector
  std::uint64_t rays_traced = 0;            // occlusion and closest-hit queries
  double seconds = 0.0;

  std::size_t coefficient_count() const { return static_cast<std::size_t>(order) * order; }
  const float* vertex_channel(std::size_t vertex, int channel) const {
    return coefficients.data() +
           (vertex * 3 + static_cast<std::size_t>(channel)) * coefficient_count();
  }
};

// Computes the transfer of every scene vertex on ctx.thread_count() threads, reporting progress
// through ctx (stage names start with "sh transfer"); throws Error("cancelled") when the progress
// callback returns false, and Error on invalid settings. `rays` may be null: an Embree scene is
// then built for the kinds that need one; if given it must have been built from `scene`.
ShTransfer compute_sh_transfer(const Scene& scene, const EmbreeScene* rays,
                               const ShTransferSettings& settings, const Context& ctx);

// The direct pass (pass 0) of vertices [first, first + count) only: vertex_count = count, row i is
// vertex first + i's, bitwise the whole bake's; vertices_without_normal and rays_traced count
// these vertices only (the warning too). For Unshadowed and Shadowed this is the range's final
// transfer. Error when the range is not in the scene; `rays` as for compute_sh_transfer.
ShTransfer compute_sh_direct_range(const Scene& scene, const EmbreeScene* rays,
                                   const ShTransferSettings& settings, std::size_t first,
                                   std::size_t count, const Context& ctx);

// Consecutive ranges' direct passes, in vertex order, as one: rows concatenated, counts, rays
// and seconds summed. Error when they differ in order or kind.
ShTransfer join_sh_ranges(std::vector<ShTransfer> ranges);

// Finishes a whole bake from the direct pass of every vertex of `scene` (the settings' order and
// kind): adds the bounce passes when the kind is Interreflected (nothing otherwise), then warns
// once about the vertices without a usable normal. Adds the rays and seconds it spends. Error
// when `whole_direct` is not every vertex's pass with these settings.
void add_sh_bounces(const Scene& scene, const EmbreeScene* rays, const ShTransferSettings& settings,
                    ShTransfer& whole_direct, const Context& ctx);

// Outgoing radiance per vertex: sum_k t_k L_k per channel, with `light` the RGB SH projection of
// the environment (order^2 entries, the transfer's order). Throws Error on a size mismatch.
std::vector<glm::vec3> shade_sh_transfer(const ShTransfer& transfer,
                                         const std::vector<glm::vec3>& light);

}  // namespace prt::bake
