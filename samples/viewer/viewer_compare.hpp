// SPDX-License-Identifier: MIT
// prt-viewer's ways of showing blobs: one; two side by side; two in a split screen (one camera,
// a divider between them); one beside its error against a reference .npy (prt-bake reference
// --vertex-out) as a heat map, with the relative RMSE.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "blob_scene.hpp"
#include "scene_renderer.hpp"

namespace prt::view {

enum class CompareMode { Single, Side, Split, Error };
// "single" | "side" | "split" | "error"; throws ViewerError otherwise.
CompareMode parse_compare_mode(const std::string& name);
const char* compare_mode_name(CompareMode mode);

// The heat map of a blob's per-vertex error against a reference: the colours of compare.hpp
// (heat_colour of relative_vertex_error), on a mesh of its own.
class ErrorView {
 public:
  // Reads the reference (float32 [V, 3] .npy); throws ViewerError unless it has `vertices` rows.
  ErrorView(const std::string& reference_path, const BlobMesh& mesh);
  ~ErrorView();

  // Colours the mesh by the error of `radiance` (RGB per vertex) at `scale` (white), and returns
  // the relative RMSE (prt::io::relative_rmse).
  double update(const std::vector<float>& radiance, float scale);
  const prt::sample::GpuMesh& mesh() const { return *mesh_; }
  const std::string& reference_path() const { return path_; }
  void release_gl() { mesh_.reset(); }

 private:
  std::string path_;
  std::vector<glm::vec3> reference_;
  std::unique_ptr<prt::sample::GpuMesh> mesh_;
};

// The frame's two halves as a side-by-side layout places them, and a split screen's clip
// rectangles for a divider at `divider` (a fraction of the width).
prt::sample::FrameRect left_half();
prt::sample::FrameRect right_half();
prt::sample::FrameRect left_of(float divider);
prt::sample::FrameRect right_of(float divider);

}  // namespace prt::view
