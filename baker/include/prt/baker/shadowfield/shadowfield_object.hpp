// SPDX-License-Identifier: MIT
// What technique `shadowfield` bakes for one rigid object, alone, in its own frame
// (docs/shadowfield/design.md): the parts the field bakes fill in (shadowfield_fields.hpp,
// shadowfield_radiance.hpp) and the blob writer quantises (shadowfield_blob.hpp).
//
// Frames and SH: the object's own frame (the mesh-local positions), with the SH conventions of
// prt/prt_sh.h applied to object-frame directions. Per-vertex arrays are in the order of the
// object's vertices. Fields are point-major: value (point, coefficient) at point * n^2 +
// coefficient, points numbered as prt/format/shadowfield_shells.h numbers them.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/shadowfield/shadowfield_brdf.hpp"
#include "prt/format/shadowfield_shells.h"

namespace prt::bake {

// The surface's reflectance: albedo(v) * sum_k g_k(wo) h_k(w), with (g, h) the separable BRDF
// (K terms) in each vertex's tangent frame (sampling.hpp's Frame of the vertex normal). A
// diffuse surface is the one-term case g = 1, h = 1/pi, stored without a g table.
struct ShadowfieldMaterial {
  bool glossy = false;
  SeparableBrdf brdf;  // glossy only; brdf.terms = K
  std::uint32_t terms() const { return glossy ? brdf.terms : 1u; }
};

struct ShadowfieldObject {
  std::uint32_t order = 4;  // SH order n of the OOF, the transfer and the SRFs (2..6)
  ShadowfieldMaterial material;

  // The object's mesh, object frame.
  std::vector<glm::vec3> positions, normals;
  std::vector<std::uint32_t> indices;  // 3 per triangle
  std::vector<glm::vec3> albedo;       // linear RGB per vertex, in [0, 1]

  // Self-shadowed transfer, one scalar vector per BRDF term: transfer[(v * K + k) * n^2 + i] =
  // integral of V_self(w) h_k(w_local) max(0, n.w) y_i(w) dw (albedo not included).
  std::vector<float> transfer;

  // Object occlusion field: SH of the visibility the object casts, at every point of
  // `oof_shells` (1 where a ray from the point escapes the object, 0 where it hits it).
  prt_sf_shells oof_shells{};
  std::vector<float> oof;  // point_count * n^2

  // Surface-radiance basis: basis[i * V + v], N functions over the vertices, and the inverse
  // of its normal matrix A = B W B^T (W the vertices' area weights, `vertex_weights`), so
  // weights of a radiance r are A^-1 (B W r).
  std::uint32_t basis_size = 0;  // N
  std::vector<float> basis;
  std::vector<float> vertex_weights;  // V
  std::vector<float> basis_inverse;   // N x N, row-major

  // Source radiance fields: for basis function i and BRDF term k, the SH of the radiance
  // reaching each point of `srf_shells` from the object when its surface glows with
  // g_k(wo) B_i(x): srf[((i * K + k) * point_count + point) * n^2 + coefficient].
  prt_sf_shells srf_shells{};
  std::vector<float> srf;
};

}  // namespace prt::bake
