// SPDX-License-Identifier: MIT
#include "viewer_slot.hpp"

#include <prt/prt.hpp>

namespace prt::view {

ViewerSlot::ViewerSlot(const std::string& path, const ViewTechniques& chooser)
    : scene_(std::make_unique<BlobScene>(path)) {
  ViewTechnique& chosen = chooser.choose(*scene_);
  technique_ = techniques_.find(chosen.technique());
  copy_live_parameters(chosen, *technique_);
  prt_technique_info info = prt::sized<prt_technique_info>();
  technique_name_ =
      prt_technique_get_info(technique_->technique(), &info) == PRT_OK ? info.name : "?";
  scene_->check_shaded_vertices(technique_->section_tag(), technique_->open(*scene_));
  technique_->describe(*scene_);
  const BlobMesh& mesh = scene_->mesh();
  mesh_ = std::make_unique<prt::sample::GpuMesh>(mesh.positions, mesh.vertex_count, mesh.indices,
                                                 mesh.triangle_count);
  radiance_.assign(3u * mesh.vertex_count, 0.0f);
}

ViewerSlot::~ViewerSlot() = default;

void ViewerSlot::release_gl() {
  gl_shader_.reset();
  mesh_.reset();
}

void ViewerSlot::prepare_light(prt::sample::Sample& sample) {
  prt::sample::Environments& envs = sample.environments();
  if (light_version_ == envs.light_version()) return;
  LightRequest request{&envs.current(), envs.current_path(), envs.rotation_degrees()};
  // Print how the light is made once, not on every turn of the light.
  request.describe = light_version_ == ~0ull;
  technique_->prepare_light(*scene_, request);
  light_version_ = envs.light_version();
}

GLuint ViewerSlot::shade(prt::sample::Sample& sample, bool keep_radiance) {
  prepare_light(sample);
  // Before either backend: a view-dependent technique's GL shader reads the eye too.
  const glm::vec3 eye = sample.camera().camera(1.0f).eye;  // the aspect does not move the eye
  technique_->set_eye(&eye.x);
  if (sample.backend() == prt::sample::Backend::Gl) {
    const GLuint buffer = shade_gl(sample, keep_radiance);
    if (buffer) return buffer;
  }
  const std::uint32_t vertices = scene_->vertex_count();
  const prt_backend backend = prt::sample::runtime_backend(sample.backend());
  const prt_result result = sample.time_shading(
      [&] { return technique_->shade(*scene_, backend, 0, vertices, radiance_.data()); });
  if (result != PRT_OK)
    throw ViewerError(path() + ": " + technique_->shade_function() + " failed on backend " +
                      prt_backend_name(backend) + ": " + prt_result_string(result));
  mesh_->upload_colours(radiance_.data());
  return mesh_->own_colours();
}

// The runtime's GL shader writes its output buffer, which the mesh draws from directly; 0 (and
// the sample falls back to a CPU backend) when the shader cannot be made or run.
GLuint ViewerSlot::shade_gl(prt::sample::Sample& sample, bool keep_radiance) {
  if (!gl_shader_ && !gl_failed_) {
    prt_result created = PRT_OK;
    gl_shader_ =
        technique_->create_gl(*scene_, sample.gl_loader(), sample.gl_loader_user(), &created);
    if (!gl_shader_) {
      gl_failed_ = true;
      const char* message = prt_context_last_message(scene_->context());
      sample.fall_back_to_cpu(path() +
                              ": the gl backend is not usable: " + prt_result_string(created) +
                              (message && *message ? std::string(": ") + message : ""));
      return 0;
    }
  }
  if (!gl_shader_) return 0;
  const std::uint32_t vertices = scene_->vertex_count();
  const prt_result result = sample.time_shading([&] { return gl_shader_->shade(0, vertices); });
  if (result != PRT_OK) {
    sample.fall_back_to_cpu(path() + ": GL shading failed: " + prt_result_string(result));
    return 0;
  }
  if (keep_radiance) gl_shader_->read(0, vertices, radiance_.data());
  return gl_shader_->output_buffer();
}

}  // namespace prt::view
