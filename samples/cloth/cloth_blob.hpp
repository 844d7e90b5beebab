// SPDX-License-Identifier: MIT
// prt-cloth's content: a cloth blob loaded by the runtime (its fabrics: names, default live
// parameters, weaves) and the mesh to draw it on, the blob's own (VPOS, VNRM, VTAN, TRIS) when it
// has one. Failures throw prt::view::ViewerError naming the file.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <string>
#include <vector>

namespace prt::cloth_app {

// A mesh with a surface frame per vertex: the normal and the warp (thread 1's direction).
struct FramedMesh {
  std::vector<float> positions, normals, warps;  // 3 floats per vertex
  std::vector<std::uint32_t> indices;            // 3 per triangle
  std::uint32_t vertex_count() const { return std::uint32_t(positions.size() / 3); }
  std::uint32_t triangle_count() const { return std::uint32_t(indices.size() / 3); }
};

struct Fabric {
  std::string name;
  prt_cloth_params defaults{};
  prt_cloth_weave weave{};
  std::size_t table_bytes = 0;
};

class ClothBlob {
 public:
  // Creates a context (backend limits from PRT_BACKEND / PRT_SIMD_ISA, as for any prtkit tool)
  // and loads `path` with full validation. Throws ViewerError when it does not load or holds no
  // CLTH section (saying what it holds instead).
  explicit ClothBlob(const std::string& path);
  ~ClothBlob();
  ClothBlob(const ClothBlob&) = delete;
  ClothBlob& operator=(const ClothBlob&) = delete;

  prt_context* context() const { return context_; }
  const prt_asset* asset() const { return asset_; }
  const std::string& path() const { return path_; }
  const prt_cloth_info& info() const { return info_; }
  const std::vector<Fabric>& fabrics() const { return fabrics_; }
  // The fabric called `name`, or -1.
  int find(const std::string& name) const;
  // "a, b, c": the fabrics' names.
  std::string fabric_names() const;

  // Whether the blob has a mesh (VPOS and TRIS); why it cannot be drawn as cloth ("" when it
  // can: it needs the warp per vertex, VTAN); the mesh itself, its normals computed from the
  // triangles when VNRM is absent (throws ViewerError with mesh_problem() when it cannot).
  bool has_mesh() const { return has_mesh_; }
  std::string mesh_problem() const;
  FramedMesh mesh() const;

 private:
  std::string path_;
  prt_context* context_ = nullptr;
  prt_asset* asset_ = nullptr;
  prt_cloth_info info_{};
  std::vector<Fabric> fabrics_;
  bool has_mesh_ = false;

  void read_fabrics();
  [[noreturn]] void fail(const std::string& what) const;
};

}  // namespace prt::cloth_app
