// SPDX-License-Identifier: MIT
#include "blob_scene.hpp"

namespace prt::view {

BlobScene::BlobScene(const std::string& path) : path_(path) {
  // A tool: PRT_BACKEND / PRT_SIMD_ISA may lower the backends, as --backend cannot.
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  if (prt_context_create(&desc, &context_) != PRT_OK) {
    throw ViewerError("cannot create a prtkit context");
  }
  if (prt_asset_load_file(context_, path.c_str(), PRT_VALIDATE_FULL, &asset_) != PRT_OK) {
    const std::string message = prt_context_last_message(context_);
    prt_context_destroy(context_);
    throw ViewerError(path + ": " + message);
  }
  try {
    mesh_ = read_blob_mesh(asset_, path_);
  } catch (...) {
    prt_asset_destroy(asset_);
    prt_context_destroy(context_);
    throw;
  }
}

BlobScene::~BlobScene() {
  prt_asset_destroy(asset_);
  prt_context_destroy(context_);
}

void BlobScene::fail(const std::string& what) const {
  throw ViewerError(path_ + ": " + what);
}

BlobMesh read_blob_mesh(const prt_asset* asset, const std::string& path) {
  const auto fail = [&path](const std::string& what) { throw ViewerError(path + ": " + what); };
  const void* positions = nullptr;
  const void* indices = nullptr;
  std::size_t position_bytes = 0, index_bytes = 0;
  if (prt_asset_section_data(asset, PRT_SECTION_VPOS, &positions, &position_bytes) != PRT_OK) {
    fail("no VPOS section (vertex positions)");
  }
  if (prt_asset_section_data(asset, PRT_SECTION_TRIS, &indices, &index_bytes) != PRT_OK) {
    fail("no TRIS section (triangles)");
  }
  if (position_bytes % (3 * sizeof(float)) != 0 || index_bytes % (3 * sizeof(std::uint32_t)) != 0) {
    fail("VPOS/TRIS sizes are not whole vertices/triangles");
  }
  BlobMesh mesh;
  mesh.positions = static_cast<const float*>(positions);
  mesh.vertex_count = static_cast<std::uint32_t>(position_bytes / (3 * sizeof(float)));
  mesh.indices = static_cast<const std::uint32_t*>(indices);
  mesh.triangle_count = static_cast<std::uint32_t>(index_bytes / (3 * sizeof(std::uint32_t)));
  // Full validation checks index ranges already; the rasteriser relies on it, so say so here.
  for (std::size_t i = 0; i < 3u * mesh.triangle_count; ++i) {
    if (mesh.indices[i] >= mesh.vertex_count) fail("TRIS index out of range");
  }
  return mesh;
}

void BlobScene::check_shaded_vertices(std::uint32_t section_tag, std::uint32_t shaded) const {
  if (mesh_.vertex_count == shaded) return;
  std::string tag;
  for (int i = 0; i < 4; ++i) tag += static_cast<char>((section_tag >> (8 * i)) & 0xFFu);
  fail("VPOS has " + std::to_string(mesh_.vertex_count) + " vertices but " + tag + " " +
       std::to_string(shaded));
}

}  // namespace prt::view
