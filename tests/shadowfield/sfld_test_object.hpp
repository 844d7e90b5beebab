// SPDX-License-Identifier: MIT
// A small synthetic ShadowfieldObject whose every value comes from a formula, and blobs of it:
// the baker's own (build_shadowfield_blob) and one of given SFLD bytes stored raw, for tests
// that change a byte and see the reader reject it.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "prt/baker/shadowfield/shadowfield_blob.hpp"
#include "prt/format/blob_writer.hpp"
#include "prt/format/mesh_layout.h"
#include "prt/format/shadowfield_layout.h"
#include "support/blob_test_util.hpp"

namespace prt_test {

// A wave in [-amplitude, amplitude] different for every index and seed.
inline float sf_wave(std::size_t index, float seed, float amplitude) {
  return amplitude * static_cast<float>(std::sin(0.61803 * double(index) + seed));
}

inline std::vector<float> sf_values(std::size_t count, float seed, float amplitude) {
  std::vector<float> v(count);
  for (std::size_t i = 0; i < count; ++i) v[i] = sf_wave(i, seed, amplitude);
  return v;
}

// An octahedron (6 vertices, 8 triangles), order 3, two BRDF terms on a 4 x 4 grid (or diffuse),
// three basis functions, an OOF on 2 shells of 2 x 2 faces and an SRF on one shell of 1 x 1.
// OOF coefficient 3 is the constant 0.25 (a row of scale 0, stored exactly).
inline prt::bake::ShadowfieldObject sf_test_object(bool glossy = true) {
  prt::bake::ShadowfieldObject o;
  o.order = 3;
  o.material.glossy = glossy;
  if (glossy) {
    o.material.brdf.grid.size = 4;
    o.material.brdf.terms = 2;
    for (std::size_t i = 0; i < 2 * 16; ++i)
      o.material.brdf.outgoing.push_back(0.3 + 0.01 * double(i));
  }
  const std::uint32_t k = o.material.terms();
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 p(0.0f);
      p[axis] = sign;
      o.positions.push_back(p);
      o.normals.push_back(p);
    }
  o.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  for (std::size_t v = 0; v < 6; ++v)
    o.albedo.push_back(glm::vec3(0.1f * float(v), 0.5f, 1.0f - 0.1f * float(v)));
  o.transfer = sf_values(6 * k * 9, 0.3f, 0.8f);
  o.oof_shells = prt_sf_shells{{0.1f, -0.2f, 0.05f}, 1.25f, 0.5f, 4.0f, 2, 2};
  o.oof = sf_values(48 * 9, 1.1f, 0.6f);
  for (std::size_t p = 0; p < 48; ++p) o.oof[p * 9 + 3] = 0.25f;
  o.basis_size = 3;
  o.basis = sf_values(3 * 6, 2.0f, 0.4f);
  o.vertex_weights = {0.5f, 0.25f, 0.75f, 1.0f, 0.125f, 0.375f};
  o.basis_inverse = sf_values(9, 2.7f, 3.0f);
  o.srf_shells = prt_sf_shells{{0.1f, -0.2f, 0.05f}, 1.25f, 1.5f, 1.5f, 1, 1};
  o.srf = sf_values(3 * k * 6 * 9, 3.3f, 0.05f);
  return o;
}

// VPOS, VNRM, TRIS of `o` and `sfld`, each stored raw, SFLD with `element_count`.
inline Bytes sf_raw_blob(const prt::bake::ShadowfieldObject& o, const Bytes& sfld,
                         std::uint64_t element_count = 1) {
  std::vector<float> positions, normals;
  for (const glm::vec3& p : o.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
  for (const glm::vec3& n : o.normals) normals.insert(normals.end(), {n.x, n.y, n.z});
  prt::format::SectionOptions required;
  required.required = true;
  prt::format::BlobWriter w;
  const std::size_t v = o.positions.size();
  w.add_section(PRT_BLOB_TAG_VPOS, positions.data(), 12 * v, v, required);
  w.add_section(PRT_BLOB_TAG_VNRM, normals.data(), 12 * v, v, required);
  w.add_section(PRT_BLOB_TAG_TRIS, o.indices.data(), 4 * o.indices.size(), o.indices.size() / 3,
                required);
  w.add_section(PRT_BLOB_TAG_SFLD, sfld.data(), sfld.size(), element_count, required);
  return w.finish();
}

// The layout of encoded SFLD bytes.
inline prt_blob_sfld_layout sf_layout(const Bytes& sfld) {
  prt_blob_sfld_header h;
  prt_blob_sfld_layout l{};
  prt_blob_sfld_read_header(sfld.data(), &h);
  prt_blob_sfld_layout_of(&h, &l);
  return l;
}

}  // namespace prt_test
