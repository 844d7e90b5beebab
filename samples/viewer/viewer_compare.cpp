// SPDX-License-Identifier: MIT
#include "viewer_compare.hpp"

#include "blob_scene.hpp"
#include "compare.hpp"
#include "prt/io/image_io.hpp"
#include "prt/io/radiance_error.hpp"

namespace prt::view {

CompareMode parse_compare_mode(const std::string& name) {
  if (name == "single") return CompareMode::Single;
  if (name == "side") return CompareMode::Side;
  if (name == "split") return CompareMode::Split;
  if (name == "error") return CompareMode::Error;
  throw ViewerError("unknown compare mode '" + name + "' (single, side, split or error)");
}

const char* compare_mode_name(CompareMode mode) {
  static const char* const kNames[] = {"single", "side", "split", "error"};
  return kNames[static_cast<int>(mode)];
}

ErrorView::ErrorView(const std::string& reference_path, const BlobMesh& mesh)
    : path_(reference_path), reference_(prt::io::read_npy_vec3(reference_path)) {
  if (reference_.size() != mesh.vertex_count)
    throw ViewerError(reference_path + ": " + std::to_string(reference_.size()) +
                      " vertices, the blob has " + std::to_string(mesh.vertex_count));
  mesh_ = std::make_unique<prt::sample::GpuMesh>(mesh.positions, mesh.vertex_count, mesh.indices,
                                                 mesh.triangle_count);
}

ErrorView::~ErrorView() = default;

double ErrorView::update(const std::vector<float>& radiance, float scale) {
  std::vector<glm::vec3> shaded(reference_.size());
  for (std::size_t v = 0; v < shaded.size(); ++v)
    shaded[v] = {radiance[3 * v], radiance[3 * v + 1], radiance[3 * v + 2]};
  const std::vector<float> error = relative_vertex_error(shaded, reference_);
  std::vector<float> colours(3 * error.size());
  for (std::size_t v = 0; v < error.size(); ++v) {
    const glm::vec3 c = heat_colour(error[v], scale);
    colours[3 * v] = c.r, colours[3 * v + 1] = c.g, colours[3 * v + 2] = c.b;
  }
  mesh_->upload_colours(colours.data());
  return prt::io::relative_rmse(shaded, reference_);
}

prt::sample::FrameRect left_half() {
  return {0.0f, 0.0f, 0.5f, 1.0f};
}
prt::sample::FrameRect right_half() {
  return {0.5f, 0.0f, 1.0f, 1.0f};
}
prt::sample::FrameRect left_of(float divider) {
  return {0.0f, 0.0f, divider, 1.0f};
}
prt::sample::FrameRect right_of(float divider) {
  return {divider, 0.0f, 1.0f, 1.0f};
}

}  // namespace prt::view
