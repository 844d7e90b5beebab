// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s basis comparison (docs/shadowfield/basis.md): how well spherical
// harmonics, Haar wavelets, a Fourier cosine series and the PCA basis (shadowfield_radiance.hpp)
// approximate the radiance of a surface with N terms, and how much that error changes the light
// the surface throws on another object. A study, not part of the bake.
//
// Every family is N functions over the surface's vertices, orthonormal under the vertex-area
// weights W of shadowfield_vertex_weights, so every family's weights of a radiance r are
// A^-1 (B W r) by the same code (basis_weights), A = B W B^T.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/shadowfield/shadowfield_object.hpp"
#include "prt/baker/shadowfield/shadowfield_radiance.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake {

// ---- The bases ----------------------------------------------------------------------------------

enum class SurfaceBasisFamily { SphericalHarmonics, Haar, FourierCosine, Pca };
const char* surface_basis_name(SurfaceBasisFamily family);

// N functions over V vertices: functions[i * V + v].
struct SurfaceBasis {
  std::size_t size = 0, vertices = 0;
  std::vector<double> functions;
  double at(std::size_t i, std::size_t v) const { return functions[i * vertices + v]; }
};

// Candidate function `index` of a family (0, 1, 2, ... in the family's order), written into
// `values` (one per vertex). Returns false when the family has no function of that index.
using CandidateFunction = std::function<bool(std::size_t index, std::vector<double>& values)>;

// Gram-Schmidt (twice, for rounding) in the W inner product over the candidates in order: a
// candidate whose part outside the span of those taken is below 1e-4 of its W-norm adds nothing
// over these vertices (e.g. an SH function that is constant on a flat floor) and is skipped, so
// the result is the first `size` independent ones. A weight that is negative or not finite counts
// as 0 (its vertex then does not constrain the basis). Throws Error when the family runs out
// first or W has no area. The first n functions of a basis of size N > n are the basis of size n.
SurfaceBasis orthonormal_surface_basis(const CandidateFunction& candidate,
                                       const std::vector<float>& weights, std::size_t size);

// SH (prt/prt_sh.h's real basis, by band l then m) of the unit direction from `centre` to each
// vertex (the constant alone where the vertex is at the centre or not finite). Orders 2, 3, 4 give
// 4, 9, 16 functions; 8 is the first 8 of order 3 (bands 0 and 1, and band 2 but its m = +2
// function). On a surface where some of them coincide (a plane through the centre sees only its
// azimuth) the next bands fill in, up to PRT_SH_MAX_ORDER.
SurfaceBasis sh_surface_basis(const std::vector<glm::vec3>& positions, const glm::vec3& centre,
                              const std::vector<float>& weights, std::size_t size);

// The 2-D non-standard Haar basis over the uv square, coarsest first: the box, then level by
// level (level j: 4^j cells of side 2^-j), in each level the horizontal detail of every cell,
// then the vertical, then the diagonal, cells in row-major order. 4 functions are the box and
// level 0; 16 add level 1; 8 add the first 4 of level 1 (the horizontal detail of its 4 cells).
// uv is clamped to [0, 1]; u = 1 belongs to the last cell. Here and in the cosine series a
// non-finite uv coordinate is read as 0.
SurfaceBasis haar_surface_basis(const std::vector<glm::vec2>& uv, const std::vector<float>& weights,
                                std::size_t size);

// cos(pi a u) cos(pi b v), ordered by a + b, then by a.
SurfaceBasis cosine_surface_basis(const std::vector<glm::vec2>& uv,
                                  const std::vector<float>& weights, std::size_t size);

// The first `size` functions of the object's baked PCA basis (object.basis), as stored.
SurfaceBasis pca_surface_basis(const ShadowfieldObject& object, std::size_t size);

// w = A^-1 (B W r), A = B W B^T (solved in double by a full-pivot LU), and the approximation
// B^T w. Weights read as in orthonormal_surface_basis. Throws Error for sizes that do not match
// or a singular A. A non-finite radiance gives non-finite weights (nothing is hidden).
std::vector<double> basis_weights(const SurfaceBasis& basis, const std::vector<float>& weights,
                                  const std::vector<double>& radiance);
std::vector<double> approximated_radiance(const SurfaceBasis& basis,
                                          const std::vector<float>& weights,
                                          const std::vector<double>& radiance);

// ---- The light a source throws on a receiver ----------------------------------------------------

// E = G r: the irradiance at each receiver vertex from a source glowing with per-vertex radiance
// r, as a sparse matrix. Per receiver vertex, `directions` cosine-weighted directions about its
// normal (the Owen-scrambled Sobol stream of hash(seed, vertex)); a ray that first hits the front
// of mesh 0 (the source: the same vertices and triangles as `source`) reads r there with the
// hit's barycentrics, each ray weighing pi / directions. A hit on another mesh, on the source's
// back or a miss adds nothing. The same rays serve every radiance, so an exact and an
// approximated radiance are compared without noise between them.
struct SourceIrradiance {
  std::size_t receivers = 0, sources = 0;
  std::vector<std::size_t> row_start;  // receivers + 1 (compressed rows)
  std::vector<std::uint32_t> column;   // source vertex
  std::vector<double> value;
  std::uint64_t rays_traced = 0;
  std::vector<double> apply(const std::vector<double>& radiance) const;
};
SourceIrradiance source_irradiance(const ShadowfieldObject& source, const EmbreeScene& scene,
                                   const std::vector<glm::vec3>& receiver_positions,
                                   const std::vector<glm::vec3>& receiver_normals,
                                   std::uint32_t directions, std::uint32_t seed,
                                   const Context& ctx);

// ---- The comparison -----------------------------------------------------------------------------

// A surface whose radiance is approximated (its mesh's TEXCOORD_0 is the uv of Haar and cosine)
// and the receiver it lights, both in one frame, the receiver also blocking the surface's light.
struct BasisStudyScene {
  std::string name;
  Mesh surface, receiver;
};

// A square floor in the plane y = height, centred on (centre.x, centre.y) in x-z, `side` x
// `side` vertices (normals +Y), TEXCOORD_0 = its x-z position scaled to [0, 1]^2.
Mesh make_study_floor(glm::vec2 centre, float half_size, float height, int side);

struct BasisStudySettings {
  std::vector<std::uint32_t> sizes{4, 8, 16};
  ShadowfieldBasisSettings pca;  // its size is raised to the largest of `sizes`
  // Test point lights (other than the PCA's): per distance (x r about c), a Fibonacci lattice of
  // `test_lights` points; the intensity (distance r)^2 as in the training.
  std::uint32_t test_lights = 32;
  std::vector<double> test_light_distances{1.5, 3.0};
  // Sky light: direct with visibility (ReferenceRenderer, bounces 0) with the sky turned about
  // +Y by each of `sky_turns` even steps; `sky_spp` samples per vertex.
  std::uint32_t sky_turns = 4;
  std::uint32_t sky_spp = 256;
  float albedo = 0.8f;                      // grey, on the surface and the receiver
  std::uint32_t receiver_directions = 256;  // rays per receiver vertex for the image error
  std::uint32_t seed = 0;                   // of the sky's samples and the receiver's rays
};

// Errors are pooled over the lightings of a kind: radiance error
// sqrt(sum ||r - B^T w||_W^2 / sum ||r||_W^2) over the surface's vertices, image error the same
// of G r against G B^T w over the receiver's vertices, in the receiver's area weights.
struct BasisStudyRow {
  std::string surface, basis, lighting;  // lighting: "point", "sky" or "all"
  std::uint32_t terms = 0;
  double radiance_error = 0.0, image_error = 0.0;
};

struct BasisStudyReport {
  std::vector<BasisStudyRow> rows;
  std::size_t surface_vertices = 0, receiver_vertices = 0;
  std::size_t point_lightings = 0, sky_lightings = 0;  // radiances with any light
  double sky_noise = 0.0;        // ReferenceRenderer's relative RMSE estimate, largest of the turns
  double pca_energy_kept = 0.0;  // of the training samples by the largest size
  double seconds = 0.0;
};

// Bakes the surface's PCA basis (the receiver blocking), builds the other families, lights the
// surface with the test lights and the sky, and measures every family at every size. Throws
// Error when the surface has no TEXCOORD_0, a size is 0 or a family cannot reach a size.
BasisStudyReport compare_surface_bases(const BasisStudyScene& scene, const io::EnvMap& sky,
                                       const BasisStudySettings& settings, const Context& ctx);

}  // namespace prt::bake
