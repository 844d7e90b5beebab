// SPDX-License-Identifier: MIT
// Technique `shadowfield` (paper 000), per object and alone: the object from a scene, its
// occlusion field (OOF) and its self-shadowed transfer (docs/shadowfield/design.md). Everything is
// in the object's frame with the SH conventions of prt/prt_sh.h; the layouts are
// ShadowfieldObject's (shadowfield_object.hpp).
//
// Sampling, both bakes, deterministic for any thread count:
// - OOF: one fixed set of M = field_directions unit directions over the whole sphere, the same for
//   every shell point: an Owen-scrambled Sobol stream keyed by the seed, mapped by the
//   area-preserving z = 1 - 2u, phi = 2 pi v, so equal weights 4 pi / M are right and the points
//   stay stratified. A shell point's coefficient i is (4 pi / M) sum over escaping rays of
//   y_i(w). Rays leave the point itself (tnear 0): a shell point is not on the surface. A point
//   inside the object gets whatever its rays say: inside a closed mesh every ray hits a face
//   (Embree culls no back faces), so the field is 0 there.
// - Transfer: per vertex, transfer_rays cosine-weighted directions about its normal from a Sobol
//   stream keyed by (seed, vertex), cast from EmbreeScene::offset_origin as the `sh` bake casts
//   them. With pdf cos / pi, T_k,i = (pi / M) sum over unblocked directions of h_k(w_local)
//   y_i(w), w_local the direction in Frame(normal) coordinates; a diffuse surface (h = 1/pi) gets
//   the mean of V y_i, so an unoccluded vertex's band 0 is exact. Vertices with a zero or
//   non-finite normal (or a non-finite position) get zero transfer and one warning counts them.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/shadowfield/shadowfield_object.hpp"

namespace prt::bake {

struct ShadowfieldFieldSettings {
  std::uint32_t order = 4;           // SH order n, 2..6
  std::uint32_t oof_shells = 16;     // S, 1..64
  float inner = 0.2f;                // innermost shell / bounding radius, finite, > 0
  float outer = 8.0f;                // outermost / bounding radius, > inner when S > 1
  std::uint32_t oof_face_size = 16;  // F, 1..128: 6 F^2 points per shell
  // Directions per shell point (M) and per vertex, each 1..65536; powers of two suit Sobol.
  std::uint32_t field_directions = 1024;
  std::uint32_t transfer_rays = 1024;
  std::uint32_t seed = 0;
};

// Throws Error naming the first bad value and its valid range.
void check_shadowfield_field_settings(const ShadowfieldFieldSettings& settings);

struct BoundingSphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};

// The centre of the axis-aligned bounds of the finite positions and the largest distance from it
// to one of them: it depends on the set of points only, not their order or count (Ritter's
// depends on the order), and is within sqrt(3) of the smallest sphere. The radius is at least
// 1e-5 x max(1, largest |coordinate|), so a single point (or coincident points) still gets shells
// that float positions can tell apart. Throws Error when no position is finite.
BoundingSphere bounding_sphere(const std::vector<glm::vec3>& positions);

// The object of a scene: its meshes concatenated in order (positions and normals as the scene
// holds them: an OBJ's, or a glTF's world placement, taken as the object frame), indices offset
// by the vertices before each mesh, albedo from Scene::vertex_albedo. Fields stay empty. Throws
// Error for a bad order (2..6), a glossy material without terms, or a scene without vertices.
ShadowfieldObject make_shadowfield_object(const Scene& scene, const ShadowfieldMaterial& material,
                                          std::uint32_t order);

// Fills object.oof_shells (the bounding sphere of object.positions, settings' shells) and
// object.oof. `rays` must hold the object's triangles (e.g. built from the scene it came from).
// object.order must equal settings.order. Runs on ctx.thread_count() threads with progress under
// "shadowfield: occlusion field"; throws Error("cancelled") when progress says stop.
void bake_occlusion_field(ShadowfieldObject& object, const EmbreeScene& rays,
                          const ShadowfieldFieldSettings& settings, const Context& ctx);

// Fills object.transfer (vertex x term x n^2). Same threading and progress ("shadowfield:
// transfer"). Returns the vertices given zero transfer for a bad normal or position.
std::size_t bake_self_transfer(ShadowfieldObject& object, const EmbreeScene& rays,
                               const ShadowfieldFieldSettings& settings, const Context& ctx);

// Ranges of the two bakes above, for a bake split into shards (docs/farm.md). Every shell point
// and every vertex is sampled on its own (a direction set per seed, a stream per vertex), so a
// range is, bit for bit, the whole bake's values for it, however the work is split.
// The grid bake_occlusion_field stores in object.oof_shells.
prt_sf_shells occlusion_field_grid(const ShadowfieldObject& object,
                                   const ShadowfieldFieldSettings& settings);
// The occlusion field of shells [first_shell, first_shell + shell_count): shell_count x 6 F^2
// points x n^2, from the first shell's first point. Error for shells beyond the grid.
std::vector<float> bake_occlusion_shells(const ShadowfieldObject& object, const EmbreeScene& rays,
                                         const ShadowfieldFieldSettings& settings,
                                         std::uint32_t first_shell, std::uint32_t shell_count,
                                         const Context& ctx);
// The transfer of vertices [first, first + count) into `transfer` (count x term x n^2); returns
// how many of them get zero transfer. Error for vertices beyond the object.
std::size_t bake_self_transfer_range(const ShadowfieldObject& object, const EmbreeScene& rays,
                                     const ShadowfieldFieldSettings& settings, std::size_t first,
                                     std::size_t count, std::vector<float>* transfer,
                                     const Context& ctx);

// The OOF's direction set (see above): M unit directions for a seed.
std::vector<glm::vec3> occlusion_field_directions(std::uint32_t count, std::uint32_t seed);

}  // namespace prt::bake
