// SPDX-License-Identifier: MIT
// Per-vertex sparse Haar transfer for technique `wavelet` (Ng, Ramamoorthi, Hanrahan 2003;
// formats/SPEC.md §7.2 and §14).
//
// For a vertex with unit normal n, the transfer of texel j of the parameterisation (the cube of
// 6 S x S faces or the dual paraboloid of 2) is the mean over the texel
//   T_j = (1 / dw_j) integral over texel j of V(w) max(0, n.w) / pi dw
// (grey: the albedo is kept per vertex and goes into the blob's vertex scale; the light texel is
// the power over the texel, §14). It is estimated with k x k jittered (stratified) rays per texel
// in the face's (u, v) coordinates, each sample weighted by the parameterisation's Jacobian:
// T_j = sum_i J_i f_i / sum_i J_i, so a texel that sees the sky everywhere gets exactly its
// mean cosine / pi. Texels entirely below the horizon (exact test: the sign of n.w over a cube
// texel is that of a linear function of (s, t), so its corners decide; for the paraboloid the
// separable quadratic is maximised exactly) get 0 and no rays. Rays leave the vertex by the Embree
// scene's offset policy, like the sh bake.
//
// Each face is then Haar-transformed (prt_haar_forward) and the row truncated to its largest
// coefficients: `keep` K largest |c| (ties: lower index), or, with keep_energy E in (0, 1], the
// fewest largest coefficients whose squared sum reaches E of the row's squared norm (Parseval:
// the row's energy in either basis). Rows are kept sparse (index ascending) so a 36k-vertex bake
// at N = 64 never holds the dense 6 x 64^2 rows of every vertex at once.
//
// Interreflection (bounces >= 1; Sloan 2002 §5 in the wavelet domain, as the report does it):
// each bounce gathers, along the same texel samples, where they hit the front of a surface, the
// previous pass's (truncated) rows of the hit triangle's vertices, interpolated by barycentrics
// and weighted by the sample's weight and the hit vertex's albedo:
//   B_j(p) = sum over hits of (dw cos / pi weight) * rho(hit) * T^(b-1)_j(hit)
// (the sample weights integrate over the hemisphere; the rows stay per unit of light power);
// the row stored is the truncation of direct + bounces. The rows are grey, so the hit's albedo
// is the mean of its RGB (exact for grey materials such as --albedo 0.8,0.8,0.8). Bounces read
// every vertex's rows: with a vertex subset, vertices outside it count as black.
//
// Deterministic: every random number is a hash of (seed, vertex, texel, sample), so 1 and N
// threads give the same rows bit for bit.
//
// Ranges (distributed bakes, docs/farm.md): the vertex in that hash is its index in the scene,
// so the direct pass of a range of vertices gives, bit for bit, the truncated rows the whole bake
// gives them. A bounce reads the previous pass's truncated rows of every vertex its rays hit
// (the direct pass's for the first bounce): with bounces, a bake splits only its direct pass;
// the ranges are joined, then the bounces run over the whole (compute_wavelet_transfer is
// compute_wavelet_direct_range over every vertex followed by add_wavelet_bounces).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/scene.hpp"

namespace prt::bake {

// "cube" | "dual-paraboloid" <-> PRT_WAVELET_PARAM_*; parse throws Error on anything else.
const char* wavelet_param_name(std::uint32_t param);
std::uint32_t parse_wavelet_param(const char* name);

// The default K for a face size: 1000 at the cube's N = 64 (about 4 % of 24,576), scaled with
// the coefficient count (the same fraction) for other sizes and parameterisations, at least 64.
std::uint32_t default_wavelet_keep(std::uint32_t param, std::uint32_t size);

struct WaveletTransferSettings {
  std::uint32_t param = 0;    // PRT_WAVELET_PARAM_CUBE or _DUAL_PARABOLOID
  std::uint32_t size = 64;    // face size S: power of two, 16..128
  std::uint32_t samples = 1;  // rays per texel, a square k*k: 1, since more rays measure no
                              // smaller error (docs/wavelet/trade.md)
  std::uint32_t keep = 1000;  // most coefficients kept per vertex; 0 = all (no truncation)
  double keep_energy = 0.0;   // in (0, 1]: keep by energy instead of `keep`; 0 = use keep
  int bounces = 0;            // interreflection passes, 0..8 (0 = direct light with shadows)
  std::uint32_t seed = 0;
  bool override_albedo = false;  // true: every vertex has `albedo`; false: Scene::vertex_albedo
  glm::vec3 albedo{0.8f};
  // Vertex subset for fast tests and measurements: only vertices v with v % vertex_stride == 0,
  // or (when non-empty) the listed ones, are baked; the others get empty rows.
  std::uint32_t vertex_stride = 1;
  std::vector<std::uint32_t> vertex_list;
};

struct WaveletTransfer {
  std::uint32_t param = 0, size = 0;
  std::size_t vertex_count = 0;
  std::uint32_t coefficient_count = 0;  // faces * size^2
  // Sparse rows: vertex v's coefficients are index/value[row_start[v] .. row_start[v+1]),
  // indices ascending, values never 0 (a truncated row drops its zeros).
  std::vector<std::uint64_t> row_start;
  std::vector<std::uint32_t> index;
  std::vector<float> value;
  std::vector<glm::vec3> albedo;     // per vertex (RGB)
  std::vector<unsigned char> baked;  // per vertex: 1 when in the subset and usable
  std::size_t vertices_without_normal = 0;
  std::uint64_t rays_traced = 0;
  double seconds = 0.0;
  // Over the baked vertices: the mean fraction of each row's squared norm the truncation kept,
  // and the mean count of non-zero coefficients before truncation.
  double mean_energy_kept = 1.0;
  double mean_nonzeros_before = 0.0;
  // Per vertex (0 where not baked): that fraction and that count, so that the means of joined
  // ranges are summed as the whole bake sums them.
  std::vector<double> energy_kept;
  std::vector<std::uint32_t> nonzeros_before;

  std::size_t row_size(std::size_t v) const { return row_start[v + 1] - row_start[v]; }
};

// Bakes every vertex of the subset on ctx.thread_count() threads, reporting progress through ctx
// (stages "wavelet transfer: ..."); Error("cancelled") when the callback says stop, Error on
// invalid settings. `rays` may be null (a scene is built); if given it must come from `scene`.
WaveletTransfer compute_wavelet_transfer(const Scene& scene, const EmbreeScene* rays,
                                         const WaveletTransferSettings& settings,
                                         const Context& ctx);

// The direct pass of the subset's vertices in [first, first + count) only: vertex_count = count,
// row i (and albedo, baked, the statistics) is vertex first + i's, bitwise the whole bake's
// direct rows (truncated); vertices_without_normal and rays_traced count these vertices only (the
// warning too). With bounces = 0 these are the range's final rows. Error when the range is not
// in the scene; `rays` as for compute_wavelet_transfer.
WaveletTransfer compute_wavelet_direct_range(const Scene& scene, const EmbreeScene* rays,
                                             const WaveletTransferSettings& settings,
                                             std::size_t first, std::size_t count,
                                             const Context& ctx);

// Consecutive ranges' direct passes, in vertex order, as one: rows and per-vertex data
// concatenated, counts, rays and seconds summed, the means recomputed over the whole subset as
// the whole bake sums them. Error when they differ in parameterisation or size.
WaveletTransfer join_wavelet_ranges(const WaveletTransferSettings& settings,
                                    std::vector<WaveletTransfer> ranges);

// Finishes a whole bake from the direct pass of every vertex of `scene`: adds the settings'
// bounce passes (none for bounces = 0), then warns once about the vertices without a usable
// normal. Adds the rays and seconds it spends. Error when `whole_direct` is not every vertex's
// pass with these settings.
void add_wavelet_bounces(const Scene& scene, const EmbreeScene* rays,
                         const WaveletTransferSettings& settings, WaveletTransfer& whole_direct,
                         const Context& ctx);

// The texel values of one vertex before the transform (dense, faces * size^2 floats), with an
// unoccluded hemisphere (no scene): for tests of the sampling and the horizon rule.
std::vector<float> unoccluded_wavelet_texels(std::uint32_t param, std::uint32_t size,
                                             std::uint32_t samples, const glm::vec3& normal,
                                             std::uint32_t seed);

// Truncation of one dense transformed row: the positions kept (ascending). keep = 0 and
// keep_energy = 0 keep every non-zero. Exposed for tests.
std::vector<std::uint32_t> select_wavelet_coefficients(const std::vector<float>& row,
                                                       std::uint32_t keep, double keep_energy);

// Outgoing radiance per vertex from the float rows: albedo * sum_j T_j L_j per channel, with
// `light_rgba` a light in Haar coefficients (prt_wavelet.h, 4 floats per coefficient), summed
// in double. For measurements and as the self-check's independent product.
std::vector<glm::vec3> shade_wavelet_transfer(const WaveletTransfer& transfer,
                                              const std::vector<float>& light_rgba);

}  // namespace prt::bake
