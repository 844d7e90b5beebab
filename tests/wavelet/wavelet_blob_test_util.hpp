// SPDX-License-Identifier: MIT
// Builds `wavelet` blobs (WVLT section, formats/SPEC.md §7.2) byte by byte from the layout table,
// for the runtime, SIMD, GL and benchmark code, independently of the baker and the runtime: the
// band of a coefficient and every offset are recomputed here from the SPEC's formulas.
//
// Use:
//   prt_test::WvltTransfer t = prt_test::wvlt_random(PRT_WAVELET_PARAM_CUBE, 16, 10, 40, 1);
//   // or wvlt_from_dense(param, size, dense_q_rows, band_scale, vertex_scale)
//   prt_test::Bytes section = prt_test::wvlt_encode(t);
//   prt_test::Bytes blob = prt_test::wvlt_make_blob(section, t.vertices, /*zstd=*/false);
//   double expected = t.transfer(v, c, j);  // q * bs[band(j)] * vs[v][c]
// All names carry a `wvlt` prefix so this header can be included next to sh_blob_test_util.hpp.
#pragma once

#include <prt/prt_wavelet.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "support/blob_test_util.hpp"
#include "support/mesh_blob.hpp"

namespace prt_test {

// One stored non-zero: global coefficient index j (= face*S^2 + y*S + x) and its 8-bit value.
struct WvltPair {
  uint32_t j = 0;
  int8_t q = 0;
};

// One WVLT section's contents, per the layout table of §7.2.
struct WvltTransfer {
  prt_wavelet_param param = PRT_WAVELET_PARAM_CUBE;
  uint32_t size = 16;  // S
  uint32_t vertices = 0;
  uint32_t quantizer = 1, keep = 0, bounces = 0;
  std::vector<float> band_scale;            // [bands()]
  std::vector<float> vertex_scale;          // [vertices][3]
  std::vector<std::vector<WvltPair>> rows;  // [vertices], each sorted by j, q != 0

  uint32_t faces() const { return param == 0 ? 6u : 2u; }
  uint32_t log2_size() const {
    uint32_t l = 0;
    while ((1u << l) < size) ++l;
    return l;
  }
  uint32_t bands_per_face() const { return log2_size() + 1; }
  uint32_t bands() const { return faces() * bands_per_face(); }
  uint32_t coefficients() const { return faces() * size * size; }
  uint32_t blocks() const { return coefficients() / PRT_BLOB_WVLT_BLOCK; }
  uint32_t pair_count() const {
    uint64_t n = 0;
    for (const auto& row : rows) n += row.size();
    return uint32_t(n);
  }
  // §7.2: band = face * (log2 S + 1) + (level + 1), level = floor(log2 max(x, y)), -1 at (0, 0).
  uint32_t band(uint32_t j) const {
    const uint32_t s2 = size * size, f = j / s2, y = (j % s2) / size, x = j % size;
    const uint32_t m = std::max(x, y);
    int level = -1;  // floor(log2 m), -1 for m = 0
    for (uint32_t rest = m; rest != 0; rest >>= 1) ++level;
    return f * bands_per_face() + uint32_t(level + 1);
  }
  // Dequantised transfer t[v][c][j] = q * bs[band(j)] * vs[v][c] in double; 0 where not stored.
  double transfer(uint32_t v, uint32_t c, uint32_t j) const {
    for (const WvltPair& p : rows[v])
      if (p.j == j)
        return double(p.q) * double(band_scale[band(j)]) * double(vertex_scale[3 * size_t(v) + c]);
    return 0.0;
  }
};

// Byte offsets of the parts of a WVLT section with these header values (§7.2's table).
struct WvltOffsets {
  size_t band_scale, vertex_scale, row_start, counts, pairs, payload_end, raw_size;
};

inline WvltOffsets wvlt_offsets(const WvltTransfer& t, uint64_t pair_count) {
  WvltOffsets o{};
  o.band_scale = 32;
  o.vertex_scale = o.band_scale + 4 * size_t(t.bands());
  o.row_start = o.vertex_scale + 12 * size_t(t.vertices);
  o.counts = o.row_start + 4 * (size_t(t.vertices) + 1);
  o.pairs = o.counts + 2 * size_t(t.vertices) * t.blocks();
  o.payload_end = o.pairs + 2 * size_t(pair_count);
  o.raw_size = (o.payload_end + 3) / 4 * 4;
  return o;
}
inline WvltOffsets wvlt_offsets(const WvltTransfer& t) {
  return wvlt_offsets(t, t.pair_count());
}

// A transfer from dense quantised rows dense_q[v][j] (coefficients() each; 0 = not stored).
inline WvltTransfer wvlt_from_dense(prt_wavelet_param param, uint32_t size,
                                    const std::vector<std::vector<int8_t>>& dense_q,
                                    std::vector<float> band_scale,
                                    std::vector<float> vertex_scale) {
  WvltTransfer t;
  t.param = param, t.size = size, t.vertices = uint32_t(dense_q.size());
  t.band_scale = std::move(band_scale);
  t.vertex_scale = std::move(vertex_scale);
  if (t.band_scale.size() != t.bands() || t.vertex_scale.size() != 3 * size_t(t.vertices))
    throw std::invalid_argument("wvlt_from_dense: scale array sizes do not match");
  uint32_t keep = 0;
  for (const auto& dense : dense_q) {
    if (dense.size() != t.coefficients()) throw std::invalid_argument("wvlt_from_dense: row size");
    std::vector<WvltPair> row;
    for (uint32_t j = 0; j < dense.size(); ++j)
      if (dense[j] != 0) row.push_back({j, dense[j]});
    keep = std::max(keep, uint32_t(row.size()));
    t.rows.push_back(std::move(row));
  }
  t.keep = keep;
  return t;
}

// Random but reproducible contents: `nonzeros` distinct coefficients per row (fewer if the row is
// shorter), values in -127..127 without 0, band scales in (0, 1], vertex scales in [0, 2).
inline WvltTransfer wvlt_random(prt_wavelet_param param, uint32_t size, uint32_t vertices,
                                uint32_t nonzeros, uint32_t seed) {
  WvltTransfer t;
  t.param = param, t.size = size, t.vertices = vertices;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> value(1, 127);
  for (uint32_t b = 0; b < t.bands(); ++b) t.band_scale.push_back(1.0f - unit(rng) * 0.99f);
  for (size_t i = 0; i < 3 * size_t(vertices); ++i) t.vertex_scale.push_back(2.0f * unit(rng));
  const uint32_t n = std::min(nonzeros, t.coefficients());
  std::vector<uint32_t> all(t.coefficients());
  std::iota(all.begin(), all.end(), 0u);
  for (uint32_t v = 0; v < vertices; ++v) {
    // A partial Fisher-Yates shuffle picks n distinct indices.
    for (uint32_t i = 0; i < n; ++i) {
      std::uniform_int_distribution<uint32_t> pick(i, t.coefficients() - 1);
      std::swap(all[i], all[pick(rng)]);
    }
    std::vector<WvltPair> row;
    for (uint32_t i = 0; i < n; ++i) {
      const int magnitude = value(rng);
      row.push_back({all[i], int8_t(unit(rng) < 0.5f ? -magnitude : magnitude)});
    }
    std::sort(row.begin(), row.end(),
              [](const WvltPair& a, const WvltPair& b) { return a.j < b.j; });
    t.rows.push_back(std::move(row));
  }
  t.keep = n;
  return t;
}

inline void wvlt_put_f32(Bytes& b, size_t off, float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, 4);
  prt_le_store_u32(b.data() + off, bits);
}

// The section bytes exactly as §7.2's table says (rows must be sorted by j, as the layout needs).
inline Bytes wvlt_encode(const WvltTransfer& t) {
  const WvltOffsets o = wvlt_offsets(t);
  Bytes b(o.raw_size, 0);
  const uint32_t header[8] = {uint32_t(t.param), t.size,         t.vertices, t.quantizer, t.keep,
                              t.bounces,         t.pair_count(), 0u};
  for (int i = 0; i < 8; ++i) prt_le_store_u32(b.data() + 4 * size_t(i), header[i]);
  for (uint32_t k = 0; k < t.bands(); ++k)
    wvlt_put_f32(b, o.band_scale + 4 * size_t(k), t.band_scale[k]);
  for (size_t i = 0; i < 3 * size_t(t.vertices); ++i)
    wvlt_put_f32(b, o.vertex_scale + 4 * i, t.vertex_scale[i]);
  uint32_t start = 0;
  size_t pair_at = o.pairs;
  for (uint32_t v = 0; v < t.vertices; ++v) {
    prt_le_store_u32(b.data() + o.row_start + 4 * size_t(v), start);
    for (const WvltPair& p : t.rows[v]) {
      const size_t count_at = o.counts + 2 * (size_t(v) * t.blocks() + p.j / PRT_BLOB_WVLT_BLOCK);
      prt_le_store_u16(b.data() + count_at, uint16_t(prt_le_load_u16(b.data() + count_at) + 1));
      b[pair_at++] = uint8_t(p.j % PRT_BLOB_WVLT_BLOCK);
      b[pair_at++] = uint8_t(p.q);
    }
    start += uint32_t(t.rows[v].size());
  }
  prt_le_store_u32(b.data() + o.row_start + 4 * size_t(t.vertices), start);
  return b;
}

inline constexpr uint32_t kWvltVPOS = PRT_BLOB_TAG_VPOS, kWvltTRIS = PRT_BLOB_TAG_TRIS,
                          kWvltWVLT = PRT_BLOB_TAG_WVLT;

// The mesh blob (support/mesh_blob.hpp) with the given WVLT bytes as section 2.
inline Bytes wvlt_make_blob(const Bytes& wvlt, uint32_t vertex_count, bool zstd = false) {
  return mesh_blob(kWvltWVLT, wvlt, vertex_count, zstd);
}

// Byte offset of the (uncompressed) WVLT section inside a blob from wvlt_make_blob.
inline size_t wvlt_section_offset(const Bytes& blob) {
  return size_t(get_u64(blob, entry(2) + PRT_BLOB_SEC_OFF_OFFSET));
}

// A random light of coefficient_count RGBA quadruples, channels in [-1, 1], 4th float 0.
inline std::vector<float> wvlt_random_light(uint32_t coefficient_count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<float> light(4 * size_t(coefficient_count));
  for (size_t i = 0; i < light.size(); ++i) light[i] = (i % 4 == 3) ? 0.0f : unit(rng);
  return light;
}

// Reference shading in double from the transfer and an UNPREPARED light (RGBA per j):
// radiance[v][c] = sum_j q bs[band(j)] vs[v][c] L[j][c]. Also returns sum |terms| in magnitude.
inline void wvlt_reference_shade(const WvltTransfer& t, const std::vector<float>& light_rgba,
                                 uint32_t v, double rgb[3], double magnitude[3]) {
  for (uint32_t c = 0; c < 3; ++c) {
    double sum = 0, mag = 0;
    for (const WvltPair& p : t.rows[v]) {
      const double term = double(p.q) * double(t.band_scale[t.band(p.j)]) *
                          double(t.vertex_scale[3 * size_t(v) + c]) *
                          double(light_rgba[4 * size_t(p.j) + c]);
      sum += term;
      mag += term < 0 ? -term : term;
    }
    rgb[c] = sum;
    magnitude[c] = mag;
  }
}

}  // namespace prt_test
