// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s surface-radiance basis and source radiance fields
// (docs/shadowfield/design.md): how an object, lit by others, glows onto them.
//
// Both bakes take a ShadowfieldObject whose mesh (positions, normals, indices), albedo,
// material and order are filled, and an EmbreeScene whose mesh 0 is that object in its own
// frame (same vertices, same triangles in the same order). Other meshes of the scene, if any,
// block rays but never glow (a hit on them sees no radiance).
//
// The object's bounding sphere (centre c, radius r) is oof_shells' when that is set
// (radius > 0), else the centre of the box around its vertices and the largest distance from
// it to a vertex.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/shadowfield/shadowfield_object.hpp"

namespace prt::bake {

// ---- Surface-radiance basis --------------------------------------------------------------------

// The training lights are `lights` point lights on a sphere of radius light_distance * r about
// c, spread evenly (a spherical Fibonacci lattice, so deterministic). The paper puts them on
// the bounding sphere; there a light can sit on a vertex, where 1/d^2 is unbounded, so
// light_distance must be above 1: every vertex is then at least (light_distance - 1) r away.
struct ShadowfieldBasisSettings {
  std::uint32_t size = 16;      // N basis functions, 1..samples (lights x BRDF terms), <= vertices
  std::uint32_t lights = 256;   // >= 1
  double light_distance = 2.0;  // x r, > 1
};
// Throws Error naming the bad setting.
void check_basis_settings(const ShadowfieldBasisSettings& settings);

// The training lights: `count` points at distance `distance` from `centre`, the Fibonacci
// lattice's point i at height 1 - (2 i + 1) / count.
std::vector<glm::vec3> shadowfield_light_positions(std::uint32_t count, const glm::vec3& centre,
                                                   float distance);

// W: a third of the area of the triangles around each vertex (0 for a vertex no triangle uses).
std::vector<float> shadowfield_vertex_weights(const ShadowfieldObject& object);

// The training samples, one row per (light l, BRDF term k), row l K + k, one column per vertex:
//   r_lk(v) = luminance(albedo(v)) I V(v, l) h_k(w_l) max(0, n.w_l) / d^2
// with w_l the unit direction from the vertex to the light at distance d, read in the vertex's
// tangent frame (Frame(normal) of prt/baker/sampling.hpp), h = 1/pi for a diffuse material,
// luminance with the Rec. 709 weights, and V the light's visibility: the ray from the vertex
// moved off the surface by the scene's ray-offset policy to the light. A vertex without a usable
// normal gets 0.
struct ShadowfieldRadianceSamples {
  std::size_t rows = 0, vertices = 0;
  std::vector<double> values;  // rows x vertices, row-major
  std::uint64_t rays_traced = 0;
  double at(std::size_t row, std::size_t vertex) const { return values[row * vertices + vertex]; }
};
ShadowfieldRadianceSamples shadowfield_radiance_samples(const ShadowfieldObject& object,
                                                        const EmbreeScene& scene,
                                                        const std::vector<glm::vec3>& lights,
                                                        double intensity, const Context& ctx);

struct ShadowfieldBasisReport {
  std::size_t samples = 0;              // lights x BRDF terms
  std::vector<double> singular_values;  // of the weighted sample matrix, all, descending
  double energy_kept = 0.0;             // energy_kept_by(N)
  std::uint64_t rays_traced = 0;
  double seconds = 0.0;
  // The fraction of the samples' energy (sum of squared W-norms) the first n functions keep:
  // sum of the first n squared singular values over all of them (1 when there is none).
  double energy_kept_by(std::size_t n) const;
};

// Fills vertex_weights, basis_size, basis and basis_inverse. The lights have intensity
// I = (light_distance r)^2, so one facing a vertex at the centre would give it irradiance 1.
// The basis is the uncentred PCA of the samples in the W inner product: with
// M' = samples diag(sqrt(W)) = U S V^T (Eigen's BDCSVD), B_i = V_i / sqrt(W) for the N leading
// singular values (0 where W = 0), the sign making each function's largest entry positive, so
// B W B^T = I up to rounding. basis_inverse is A^-1, A = B W B^T, computed in double from the
// stored float basis. Throws Error for bad settings, an object with no area or N above the
// vertex count; Error("cancelled") when ctx's progress says stop.
ShadowfieldBasisReport bake_surface_basis(ShadowfieldObject& object, const EmbreeScene& scene,
                                          const ShadowfieldBasisSettings& settings,
                                          const Context& ctx);

// ---- Source radiance fields --------------------------------------------------------------------

// The SRF's shell grid (prt/format/shadowfield_shells.h, about the bounding sphere) and its
// quadrature: `directions` unit directions uniform on the sphere (the Owen-scrambled Sobol stream
// of `seed`, mapped by an area-preserving map), the same at every point, each of weight
// 4 pi / directions. With one shell, the grid stores `inner` as its outer radius too.
struct SrfSettings {
  std::uint32_t shells = 8;         // 1..256
  std::uint32_t face_size = 8;      // 1..256
  float inner = 0.2f;               // x r, > 0
  float outer = 8.0f;               // x r, >= inner
  std::uint32_t directions = 1024;  // 1..2^20
  std::uint32_t seed = 0;
};
void check_srf_settings(const SrfSettings& settings);

struct SrfReport {
  std::uint64_t points = 0;  // shell points
  std::size_t floats = 0;    // srf.size()
  std::uint64_t rays_traced = 0;
  double seconds = 0.0;
};

// Fills srf_shells and srf from the basis (basis_size, basis). For basis function i and term k,
// at shell point p: the order-n SH projection of S(w) = g_k(wo) B_i(x), where x is the nearest
// hit of the ray from p along w (tnear 0), B_i is interpolated with the hit's barycentrics and
// wo = -w in x's tangent frame (Frame of the interpolated normal); g = 1 for a diffuse material.
// S = 0 when the ray misses, hits another mesh, or reaches the back of the surface (the side the
// interpolated normal turns away from: a surface glows only from its front, as it is lit only
// there). Points are spread over TBB tasks on ctx.thread_count() threads; each point's sum is in
// a fixed order, so the result is bitwise the same for any thread count. Throws Error for bad
// settings, an object without a basis or an order outside 2..6; Error("cancelled") when ctx's
// progress says stop.
SrfReport bake_source_radiance_fields(ShadowfieldObject& object, const EmbreeScene& scene,
                                      const SrfSettings& settings, const Context& ctx);

// The same bake by shells, for a bake split into shards (docs/farm.md): every point is sampled on
// its own, so a range is, bit for bit, the whole bake's values there. The grid the bake stores
// in srf_shells (after the same checks, size limit included):
prt_sf_shells source_radiance_field_grid(const ShadowfieldObject& object,
                                         const SrfSettings& settings);
// The fields at the points of shells [first_shell, first_shell + shell_count), laid out as
// object.srf over those points only: srf[(f * P + p) * n^2 + c], f = i K + k, P = shell_count x
// 6 F^2, p from the first shell's first point. Error for shells beyond the grid.
std::vector<float> bake_source_radiance_shells(const ShadowfieldObject& object,
                                               const EmbreeScene& scene,
                                               const SrfSettings& settings,
                                               std::uint32_t first_shell, std::uint32_t shell_count,
                                               const Context& ctx);

}  // namespace prt::bake
