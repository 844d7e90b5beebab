// SPDX-License-Identifier: MIT
// Builds `sh` blobs (SHTR section, formats/SPEC.md) byte by byte from the layout table, for the
// runtime, SIMD and GL tests; expected values are recomputed from the stored q, offset and scale,
// independently of the runtime.
#pragma once

#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "support/blob_test_util.hpp"
#include "support/mesh_blob.hpp"

namespace prt_test {

// One SHTR section's contents, per the layout table.
struct Transfer {
  uint32_t order = 2, vertices = 4, channels = 3, bits = 8, kind = 1, bounces = 0;
  std::vector<float> offset, scale;  // [channels * order^2]
  std::vector<uint32_t> q;           // [vertices][channels * order^2]

  uint32_t coefficients() const { return channels * order * order; }
  double value(uint32_t v, uint32_t j) const {
    return double(offset[j]) + double(scale[j]) * double(q[size_t(v) * coefficients() + j]);
  }
};

// Random but reproducible contents: offsets in [-1, 1], scales in [0, 2/(2^b - 1)], any q.
inline Transfer random_transfer(uint32_t order, uint32_t vertices, uint32_t channels, uint32_t bits,
                                uint32_t seed) {
  Transfer t;
  t.order = order, t.vertices = vertices, t.channels = channels, t.bits = bits;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const uint32_t qmax = (1u << bits) - 1u;
  std::uniform_int_distribution<uint32_t> qdist(0, qmax);
  for (uint32_t j = 0; j < t.coefficients(); ++j) {
    t.offset.push_back(unit(rng));
    t.scale.push_back((unit(rng) + 1.0f) / float(qmax));
  }
  for (size_t i = 0; i < size_t(vertices) * t.coefficients(); ++i) t.q.push_back(qdist(rng));
  return t;
}

inline void put_f32(Bytes& b, size_t off, float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, 4);
  put_u32(b, off, bits);
}

// The section bytes exactly as the layout table says.
inline Bytes encode(const Transfer& t) {
  const size_t params = 32 + 8 * size_t(t.coefficients());
  const size_t payload = params + size_t(t.vertices) * t.coefficients() * (t.bits / 8);
  Bytes b((payload + 3) / 4 * 4, 0);
  const uint32_t header[6] = {t.order, t.vertices, t.channels, t.bits, t.kind, t.bounces};
  for (int i = 0; i < 6; ++i) put_u32(b, 4 * size_t(i), header[i]);
  for (uint32_t j = 0; j < t.coefficients(); ++j) {
    put_f32(b, 32 + 8 * size_t(j), t.offset[j]);
    put_f32(b, 32 + 8 * size_t(j) + 4, t.scale[j]);
  }
  for (size_t i = 0; i < t.q.size(); ++i) {
    if (t.bits == 8)
      b[params + i] = uint8_t(t.q[i]);
    else
      put_u16(b, params + 2 * i, uint16_t(t.q[i]));
  }
  return b;
}

inline constexpr uint32_t kVPOS = PRT_BLOB_TAG_VPOS, kTRIS = PRT_BLOB_TAG_TRIS,
                          kSHTR = PRT_BLOB_TAG_SHTR;

// The mesh blob (support/mesh_blob.hpp) with the given SHTR bytes as section 2.
inline Bytes make_blob(const Bytes& shtr, uint32_t vertex_count, bool zstd = false) {
  return mesh_blob(kSHTR, shtr, vertex_count, zstd);
}

}  // namespace prt_test
