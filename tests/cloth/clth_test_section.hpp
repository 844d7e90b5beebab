// SPDX-License-Identifier: MIT
// A small CLTH section written byte by byte at formats/SPEC.md §7.4's offsets, restated here as
// numbers (not through the baker's encoder or cloth_layout.h's helpers), the blob around it, and
// the offsets the corruption tests edit.
#pragma once

#include <prt/format/blob_writer.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "support/blob_test_util.hpp"

namespace prt_test {

inline void put_f32_at(Bytes& b, size_t off, float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  put_u32(b, off, u);
}

struct ClthThread {
  float eta;
  std::array<float, 3> albedo;
  float kd, gamma_s, gamma_v, coverage;
  uint32_t first, count;
};

struct ClthFabric {
  std::string name;
  ClthThread threads[2];
};

struct ClthTangent {
  float offset;
  uint32_t multiplicity, table, mirror;
};

struct ClthTable {
  uint32_t rank, cone_rank;
};

struct ClthTestSection {
  uint32_t xi_size = 3, levels = 2, view_theta = 3, view_phi = 3, bits = 8;
  float lambda_min = 1.0f, lambda_max = 8.0f;
  std::vector<ClthFabric> fabrics;
  std::vector<ClthTangent> tangents;
  std::vector<ClthTable> tables;

  size_t rows() const { return size_t(levels) * xi_size * xi_size; }
  size_t columns() const { return size_t(view_theta) * view_phi; }
  size_t value_size() const { return bits / 8; }
  static size_t align4(size_t n) { return (n + 3) / 4 * 4; }

  // Where things are: a 64-byte header, fabrics of 160 bytes (a 32-byte name, then two threads of
  // 64), tangents of 16, tables of 16, then each table's T and T_c.
  size_t fabric_at(size_t f) const { return 64 + 160 * f; }
  size_t thread_at(size_t f, size_t j) const { return fabric_at(f) + 32 + 64 * j; }
  size_t tangent_at(size_t g) const { return 64 + 160 * fabrics.size() + 16 * g; }
  size_t table_at(size_t q) const { return tangent_at(tangents.size()) + 16 * q; }
  size_t data_at() const { return table_at(tables.size()); }
  uint32_t rank_of(size_t q, int cone) const { return cone ? tables[q].cone_rank : tables[q].rank; }
  size_t factor_size(uint32_t r) const {
    return 8 * r + align4(columns() * r * value_size()) + align4(rows() * r * value_size());
  }
  size_t factor_at(size_t q, int cone) const {
    size_t at = data_at();
    for (size_t i = 0; i < q; ++i)
      at += factor_size(tables[i].rank) + factor_size(tables[i].cone_rank);
    return cone ? at + factor_size(tables[q].rank) : at;
  }
  size_t v_values_at(size_t q, int cone) const { return factor_at(q, cone) + 8 * rank_of(q, cone); }
  size_t u_values_at(size_t q, int cone) const {
    return v_values_at(q, cone) + align4(columns() * rank_of(q, cone) * value_size());
  }
  size_t size() const {
    return factor_at(tables.size() - 1, 1) + factor_size(tables.back().cone_rank);
  }

  // Stored value k of a value block: spread over the whole range, never -128 / -32768.
  int value(size_t k) const {
    return bits == 8 ? int((k * 37 + 11) % 255) - 127 : int((k * 7919 + 13) % 65535) - 32767;
  }
  static float scale(size_t q, int cone, uint32_t r, bool v) {
    return 0.125f * float(r + 1) + 0.5f * float(q) + (cone ? 0.25f : 0.0f) + (v ? 1.0f : 0.0f);
  }

  Bytes bytes() const {
    Bytes b(size(), 0);
    const uint32_t header[] = {uint32_t(fabrics.size()), uint32_t(tangents.size()),
                               uint32_t(tables.size()), xi_size, levels};
    for (int i = 0; i < 5; ++i) put_u32(b, 4 * i, header[i]);
    put_f32_at(b, 20, lambda_min);
    put_f32_at(b, 24, lambda_max);
    put_u32(b, 28, view_theta);
    put_u32(b, 32, view_phi);
    put_u32(b, 36, bits);
    for (size_t f = 0; f < fabrics.size(); ++f) write_fabric(b, f);
    for (size_t g = 0; g < tangents.size(); ++g) {
      put_f32_at(b, tangent_at(g), tangents[g].offset);
      put_u32(b, tangent_at(g) + 4, tangents[g].multiplicity);
      put_u32(b, tangent_at(g) + 8, tangents[g].table);
      put_u32(b, tangent_at(g) + 12, tangents[g].mirror);
    }
    for (size_t q = 0; q < tables.size(); ++q) {
      put_u32(b, table_at(q), tables[q].rank);
      put_u32(b, table_at(q) + 4, tables[q].cone_rank);
      for (int cone = 0; cone < 2; ++cone) write_factor(b, q, cone);
    }
    return b;
  }

 private:
  void write_fabric(Bytes& b, size_t f) const {
    std::memcpy(b.data() + fabric_at(f), fabrics[f].name.data(), fabrics[f].name.size());
    for (size_t j = 0; j < 2; ++j) {
      const ClthThread& t = fabrics[f].threads[j];
      const size_t at = thread_at(f, j);
      const float floats[] = {t.eta, t.albedo[0], t.albedo[1], t.albedo[2],
                              t.kd,  t.gamma_s,   t.gamma_v,   t.coverage};
      for (int i = 0; i < 8; ++i) put_f32_at(b, at + 4 * i, floats[i]);
      put_u32(b, at + 32, t.first);
      put_u32(b, at + 36, t.count);
    }
  }
  void write_values(Bytes& b, size_t at, size_t count, size_t seed) const {
    for (size_t k = 0; k < count; ++k) {
      const int q = value(seed + k);
      if (bits == 8)
        b[at + k] = uint8_t(int8_t(q));
      else
        put_u16(b, at + 2 * k, uint16_t(int16_t(q)));
    }
  }
  void write_factor(Bytes& b, size_t q, int cone) const {
    const uint32_t r = rank_of(q, cone);
    for (uint32_t i = 0; i < r; ++i) {
      put_f32_at(b, factor_at(q, cone) + 4 * i, scale(q, cone, i, false));
      put_f32_at(b, factor_at(q, cone) + 4 * (r + i), scale(q, cone, i, true));
    }
    write_values(b, v_values_at(q, cone), columns() * r, 100 * q + 50 * cone);
    write_values(b, u_values_at(q, cone), rows() * r, 100 * q + 50 * cone + 7);
  }
};

// Two fabrics over three tangent records and two tables on N_xi 3, L 2, N_theta 3, N_phi 3: 18
// rows and 9 columns, so that 8-bit U blocks of odd rank and every V block of odd rank are padded.
// Fabric 0 "linen_plain": thread 1 has record 0 (offset 0, 3 copies, table 0), thread 2 records 1
// and 2 (+-0.3, table 1, the second mirrored). Fabric 1, a 32-byte name: both threads share record
// 0; coverages sum to exactly 1.
inline ClthTestSection small_clth(uint32_t bits = 8) {
  ClthTestSection s;
  s.bits = bits;
  s.fabrics = {
      {"linen_plain",
       {{1.46f, {0.2f, 0.8f, 0.3f}, 0.3f, 0.2094395f, 0.418879f, 0.33f, 0, 1},
        {1.46f, {0.3f, 0.3f, 0.3f}, 0.3f, 0.2f, 0.4f, 0.33f, 1, 2}}},
      {"abcdefghijklmnopqrstuvwxyz012345",
       {{1.345f, {1.0f, 0.95f, 0.05f}, 0.1f, 0.05f, 0.1f, 0.75f, 0, 1},
        {4.0f, {0.0f, 0.5f, 1.0f}, 1.0f, 3.14159274f, 3.14159274f, 0.25f, 0, 1}}},
  };
  s.tangents = {{0.0f, 3, 0, 0}, {0.3f, 1, 1, 0}, {-0.3f, 1, 1, 1}};
  s.tables = {{2, 1}, {1, 3}};
  return s;
}

// A blob of the CLTH section alone (required), `element_count` elements (the fabric count unless
// a test says otherwise); `zstd` asks the writer to compress it.
inline Bytes clth_blob(const Bytes& section, uint64_t element_count, bool zstd = false) {
  prt::format::BlobWriter w;
  prt::format::SectionOptions options;
  options.required = true;
  if (zstd) options.compression = prt::format::Compression::kZstd;
  w.add_section(PRT_BLOB_TAG('C', 'L', 'T', 'H'), section.data(), section.size(), element_count,
                options);
  return w.finish();
}

}  // namespace prt_test
