// SPDX-License-Identifier: MIT
// What every golden technique blob of formats/golden/1.0 holds besides its technique section,
// restated by hand: the container facts read from a hex dump of each file, and the mesh sections
// from the scene they were baked from (formats/golden/scenes/quad_over_ground.obj unless a test
// passes another scene's Mesh, as golden_pose_test.cpp does for hinge.gltf).
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "support/blob_test_util.hpp"

namespace prt_golden {

using prt_test::Bytes;

// One section-table entry as stored (SPEC §4).
struct Entry {
  uint32_t tag;
  uint32_t flags;
  prt_codec codec;
  uint32_t checksum;
  uint64_t offset, stored_size, raw_size, element_count;
};

// One golden file: its size, header checksum, CRC-32C of all its bytes and section table.
struct File {
  const char* name;  // in formats/golden/1.0
  uint64_t size;
  uint32_t header_checksum;
  uint32_t file_crc32c;
  std::vector<Entry> entries;  // five for a per-vertex bake, six with cloth's VTAN
};

inline std::string path_of(const File& f) {
  return std::string(PRT_GOLDEN_DIR) + "/1.0/" + f.name;
}

// A fully validated asset of one golden file, destroyed at the end of the scope.
class Asset {
 public:
  explicit Asset(const File& f) {
    prt_context_desc desc = prt::sized<prt_context_desc>();
    EXPECT_EQ(prt_context_create(&desc, &ctx_), PRT_OK);
    result_ = prt_asset_load_file(ctx_, path_of(f).c_str(), PRT_VALIDATE_FULL, &asset_);
  }
  ~Asset() {
    prt_asset_destroy(asset_);
    prt_context_destroy(ctx_);
  }
  Asset(const Asset&) = delete;
  Asset& operator=(const Asset&) = delete;

  prt_result result() const { return result_; }
  const char* message() const { return prt_context_last_message(ctx_); }
  const prt_asset* get() const { return asset_; }

  // The decoded bytes of section `tag`.
  Bytes section(uint32_t tag) const {
    const void* data = nullptr;
    size_t size = 0;
    EXPECT_EQ(prt_asset_section_data(asset_, tag, &data, &size), PRT_OK);
    const auto* p = static_cast<const uint8_t*>(data);
    return p ? Bytes(p, p + size) : Bytes();
  }

 private:
  prt_context* ctx_ = nullptr;
  prt_asset* asset_ = nullptr;
  prt_result result_ = PRT_ERROR_INVALID_OPERATION;
};

inline float f32_at(const Bytes& b, size_t offset) {
  const uint32_t bits = prt_test::get_u32(b, offset);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

inline float f32_of_bits(uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// Header (SPEC §3) and section table (SPEC §4) as the runtime reports them, the raw header bytes,
// and the CRC-32C of the whole file.
inline void expect_container(const File& f) {
  SCOPED_TRACE(f.name);
  const Bytes bytes = prt_test::read_file(path_of(f));
  ASSERT_EQ(bytes.size(), f.size);
  EXPECT_EQ(prt_crc32c(0, bytes.data(), bytes.size()), f.file_crc32c);
  const uint8_t head[16] = {'P', 'R', 'T', 'K', 1, 0, 0, 0, 64, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(std::memcmp(bytes.data(), head, sizeof head), 0);
  EXPECT_EQ(prt_test::get_u64(bytes, 16), f.size);            // total_size
  EXPECT_EQ(prt_test::get_u64(bytes, 24), 64u);               // table_offset
  EXPECT_EQ(prt_test::get_u32(bytes, 32), f.entries.size());  // section_count
  EXPECT_EQ(prt_test::get_u32(bytes, 36), f.header_checksum);
  EXPECT_EQ(prt_test::get_u64(bytes, 56), 0u);  // reserved

  Asset a(f);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  prt_asset_info info = prt::sized<prt_asset_info>();
  ASSERT_EQ(prt_asset_get_info(a.get(), &info), PRT_OK);
  EXPECT_EQ(info.format_major, 1u);
  EXPECT_EQ(info.format_minor, 0u);
  EXPECT_EQ(info.flags, 0u);
  EXPECT_EQ(info.section_count, f.entries.size());
  EXPECT_EQ(info.total_size, f.size);
  const uint8_t producer[16] = {'p', 'r', 't', 'k', 'i', 't', ' ', '0', '.', '1', '.', '0'};
  EXPECT_EQ(std::memcmp(info.producer, producer, sizeof producer), 0);
  for (uint32_t i = 0; i < f.entries.size(); ++i) {
    SCOPED_TRACE(i);
    const Entry& e = f.entries[i];
    prt_section_info s = prt::sized<prt_section_info>();
    ASSERT_EQ(prt_asset_get_section_info(a.get(), i, &s), PRT_OK);
    EXPECT_EQ(s.tag, e.tag);
    EXPECT_EQ(s.flags, e.flags);
    EXPECT_EQ(s.codec, e.codec);
    EXPECT_EQ(s.layout_version, 1u);
    EXPECT_EQ(s.known, 1u);
    EXPECT_EQ(s.checksum, e.checksum);
    EXPECT_EQ(s.offset, e.offset);
    EXPECT_EQ(s.stored_size, e.stored_size);
    EXPECT_EQ(s.raw_size, e.raw_size);
    EXPECT_EQ(s.element_count, e.element_count);
  }
}

// A scene's mesh as the bake stores it: positions and normals per vertex, three indices per
// triangle, in the scene's order.
struct Mesh {
  size_t vertex_count;
  const float (*positions)[3];
  const float (*normals)[3];
  size_t triangle_count;
  const uint32_t* indices;
};

// INFO, VPOS, VNRM and TRIS hold exactly `mesh` and the text the bake wrote.
inline void expect_mesh(const Asset& a, const std::string& info, const Mesh& mesh) {
  const Bytes text = a.section(PRT_SECTION_INFO);
  EXPECT_EQ(std::string(text.begin(), text.end()), info);
  const Bytes vpos = a.section(PRT_SECTION_VPOS);
  ASSERT_EQ(vpos.size(), 12 * mesh.vertex_count);
  const Bytes vnrm = a.section(PRT_SECTION_VNRM);
  ASSERT_EQ(vnrm.size(), 12 * mesh.vertex_count);
  for (size_t v = 0; v < mesh.vertex_count; ++v)
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(f32_at(vpos, 12 * v + 4 * c), mesh.positions[v][c]) << v << "," << c;
      EXPECT_EQ(f32_at(vnrm, 12 * v + 4 * c), mesh.normals[v][c]) << v << "," << c;
    }
  const Bytes tris = a.section(PRT_SECTION_TRIS);
  ASSERT_EQ(tris.size(), 12 * mesh.triangle_count);
  for (size_t k = 0; k < 3 * mesh.triangle_count; ++k)
    EXPECT_EQ(prt_test::get_u32(tris, 4 * k), mesh.indices[k]) << k;
}

// The quad scene: the scene file's eight vertices in file order, its one normal, its two quads
// as triangle fans.
inline void expect_mesh(const Asset& a, const std::string& info) {
  static const float positions[8][3] = {{-1, 0, 1},
                                        {1, 0, 1},
                                        {1, 0, -1},
                                        {-1, 0, -1},
                                        {-1.25f, 0.4f, 1.25f},
                                        {0.25f, 0.4f, 1.25f},
                                        {0.25f, 0.4f, -0.25f},
                                        {-1.25f, 0.4f, -0.25f}};
  static const float normals[8][3] = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0},
                                      {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  static const uint32_t triangles[12] = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  expect_mesh(a, info, Mesh{8, positions, normals, 4, triangles});
}

// The zstd file and its uncompressed twin decode to the same bytes, section by section, and the
// twin stores exactly those bytes.
inline void expect_same_sections(const File& zstd, const File& raw) {
  Asset a(zstd), b(raw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  ASSERT_EQ(b.result(), PRT_OK) << b.message();
  const Bytes raw_file = prt_test::read_file(path_of(raw));
  for (const Entry& e : raw.entries) {
    SCOPED_TRACE(e.tag);
    const Bytes decoded = a.section(e.tag);
    EXPECT_EQ(decoded, b.section(e.tag));
    ASSERT_EQ(e.codec, PRT_CODEC_NONE);
    ASSERT_LE(e.offset + e.stored_size, raw_file.size());
    EXPECT_EQ(decoded,
              Bytes(raw_file.begin() + e.offset, raw_file.begin() + e.offset + e.stored_size));
  }
}

}  // namespace prt_golden
