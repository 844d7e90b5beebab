// SPDX-License-Identifier: MIT
// The viewer's side of the runtime: a context, a blob loaded at full validation and its mesh
// (VPOS/TRIS sections). Which technique draws it is view_techniques.hpp's business. Failures
// throw ViewerError with the runtime's own message.
#pragma once

#include <prt/prt.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace prt::view {

// What the viewer reports and exits 1 on.
class ViewerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Borrowed views into the asset's decoded sections (valid while the BlobScene lives).
struct BlobMesh {
  const float* positions = nullptr;  // x,y,z per vertex
  std::uint32_t vertex_count = 0;
  const std::uint32_t* indices = nullptr;  // i0,i1,i2 per triangle
  std::uint32_t triangle_count = 0;
};

// The mesh of a loaded asset (its VPOS/TRIS sections), borrowed from it. Throws ViewerError
// "<path>: <what>" when a section is missing, is not whole vertices or triangles, or a triangle
// names a vertex past VPOS's.
BlobMesh read_blob_mesh(const prt_asset* asset, const std::string& path);

class BlobScene {
 public:
  // Creates a context (messages recorded, not printed; backend limits from the PRT_BACKEND /
  // PRT_SIMD_ISA environment variables as for any prtkit program) and loads `path` with full
  // validation. Throws ViewerError naming the file and quoting the runtime on failure, or when
  // the blob has no usable mesh.
  explicit BlobScene(const std::string& path);
  ~BlobScene();
  BlobScene(const BlobScene&) = delete;
  BlobScene& operator=(const BlobScene&) = delete;

  prt_context* context() const { return context_; }
  const prt_asset* asset() const { return asset_; }
  const BlobMesh& mesh() const { return mesh_; }
  std::uint32_t vertex_count() const { return mesh_.vertex_count; }
  const std::string& path() const { return path_; }

  // Throws ViewerError unless the technique's section (`section_tag`, a PRT_TAG) shades as many
  // vertices as VPOS holds.
  void check_shaded_vertices(std::uint32_t section_tag, std::uint32_t shaded) const;

  // Throws ViewerError "<path>: <what>".
  [[noreturn]] void fail(const std::string& what) const;

 private:
  std::string path_;
  prt_context* context_ = nullptr;
  prt_asset* asset_ = nullptr;
  BlobMesh mesh_;
};

}  // namespace prt::view
