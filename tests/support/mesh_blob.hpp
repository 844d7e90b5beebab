// SPDX-License-Identifier: MIT
// The mesh every technique's byte-built section is tested on: a blob whose sections 0 and 1 are
// `vertex_count` positions and one triangle, and whose section 2 is the technique's, written by
// the format's own writer, and the asset loaded from an exact-size heap copy of it.
#pragma once

#include <prt/format/blob_writer.hpp>

#include <cstdint>
#include <vector>

#include "support/blob_test_util.hpp"

namespace prt_test {

// Positions, one triangle and `section` under `tag` with `vertex_count` elements. The triangle's
// indices are clamped to the last vertex, so 1 and 2 vertices work too; `zstd` asks the writer to
// compress the technique's section (kept raw where that is not smaller).
inline Bytes mesh_blob(uint32_t tag, const Bytes& section, uint32_t vertex_count,
                       bool zstd = false) {
  prt::format::BlobWriter w;
  std::vector<float> positions(size_t(vertex_count) * 3);
  for (size_t i = 0; i < positions.size(); ++i) positions[i] = float(i % 7) * 0.25f;
  const uint32_t last = vertex_count > 0 ? vertex_count - 1 : 2u;
  const uint32_t tri[3] = {0, last < 1 ? last : 1u, last < 2 ? last : 2u};
  prt::format::SectionOptions required;
  required.required = true;
  w.add_section(PRT_BLOB_TAG_VPOS, positions.data(), positions.size() * 4, vertex_count, required);
  w.add_section(PRT_BLOB_TAG_TRIS, tri, sizeof tri, 1, required);
  prt::format::SectionOptions technique = required;
  if (zstd) technique.compression = prt::format::Compression::kZstd;
  w.add_section(tag, section.data(), section.size(), vertex_count, technique);
  return w.finish();
}

// The given mesh (x,y,z per vertex; three indices per triangle) and `section` under `tag`, one
// element per vertex.
inline Bytes mesh_blob(const std::vector<float>& positions, const std::vector<uint32_t>& triangles,
                       uint32_t tag, const Bytes& section) {
  prt::format::BlobWriter w;
  const uint32_t vertex_count = uint32_t(positions.size() / 3);
  prt::format::SectionOptions required;
  required.required = true;
  w.add_section(PRT_BLOB_TAG_VPOS, positions.data(), positions.size() * 4, vertex_count, required);
  w.add_section(PRT_BLOB_TAG_TRIS, triangles.data(), triangles.size() * 4,
                uint32_t(triangles.size() / 3), required);
  w.add_section(tag, section.data(), section.size(), vertex_count, required);
  return w.finish();
}

// A blob of one triangle and nothing else (no technique's section).
inline Bytes mesh_only_blob() {
  prt::format::BlobWriter w;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint32_t tri[3] = {0, 1, 2};
  prt::format::SectionOptions required;
  required.required = true;
  w.add_section(PRT_BLOB_TAG_VPOS, positions, sizeof positions, 3, required);
  w.add_section(PRT_BLOB_TAG_TRIS, tri, sizeof tri, 1, required);
  return w.finish();
}

// An asset loaded from an exact-size heap copy that it borrows (ASan sees any over-read).
struct LoadedAsset {
  std::unique_ptr<uint8_t[]> bytes;
  prt_asset* asset = nullptr;
  prt_result result;
  LoadedAsset(prt_context* ctx, const Bytes& blob, prt_validation level = PRT_VALIDATE_FULL)
      : bytes(exact_copy(blob)),
        result(prt_asset_load_memory_borrowed(ctx, bytes.get(), blob.size(), level, &asset)) {}
  ~LoadedAsset() { prt_asset_destroy(asset); }
  LoadedAsset(const LoadedAsset&) = delete;
  LoadedAsset& operator=(const LoadedAsset&) = delete;
};

}  // namespace prt_test
