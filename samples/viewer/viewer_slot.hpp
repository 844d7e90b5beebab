// SPDX-License-Identifier: MIT
// One blob in prt-viewer: the runtime's context and asset (BlobScene), the technique that draws
// it (its own instance from the registry, so two blobs of one technique keep their own light and
// parameters), its mesh on the GPU, and its shading each frame on the sample's backend.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "blob_scene.hpp"
#include "sample_app.hpp"
#include "scene_renderer.hpp"
#include "view_techniques.hpp"

namespace prt::view {

class ViewerSlot {
 public:
  // Loads `path` and picks its technique as `chooser` does (--technique, else the first the blob
  // holds); the technique starts with `chooser`'s instance's live parameter values (the command
  // line's). Needs the GL context current. Throws ViewerError.
  ViewerSlot(const std::string& path, const ViewTechniques& chooser);
  ~ViewerSlot();
  ViewerSlot(const ViewerSlot&) = delete;
  ViewerSlot& operator=(const ViewerSlot&) = delete;

  const std::string& path() const { return scene_->path(); }
  const std::string& technique_name() const { return technique_name_; }
  ViewTechnique& technique() { return *technique_; }
  const prt::sample::GpuMesh& mesh() const { return *mesh_; }
  const BlobMesh& blob_mesh() const { return scene_->mesh(); }

  // Makes the technique's light again on the next shade().
  void invalidate_light() { light_version_ = ~0ull; }

  // Prepares the light if the environment changed, then shades every vertex on the sample's
  // backend (timed by the sample). Returns the GL buffer holding the colours: the runtime's
  // output buffer for gl, the mesh's own buffer (uploaded once) otherwise. With `keep_radiance`
  // the radiance is also kept on the CPU (read back from GL for gl). Throws ViewerError when the
  // runtime refuses; a failing GL backend is reported and the sample falls back to a CPU one.
  GLuint shade(prt::sample::Sample& sample, bool keep_radiance);
  // The last radiance kept by shade(keep_radiance = true): RGB per vertex.
  const std::vector<float>& radiance() const { return radiance_; }

  // Releases the GL objects (while the context is current).
  void release_gl();

 private:
  std::unique_ptr<BlobScene> scene_;
  ViewTechniques techniques_;
  ViewTechnique* technique_ = nullptr;
  std::string technique_name_;
  std::unique_ptr<prt::sample::GpuMesh> mesh_;
  std::unique_ptr<GlVertexShader> gl_shader_;
  bool gl_failed_ = false;
  std::uint64_t light_version_ = ~0ull;
  std::vector<float> radiance_;

  void prepare_light(prt::sample::Sample& sample);
  GLuint shade_gl(prt::sample::Sample& sample, bool keep_radiance);
};

}  // namespace prt::view
