// SPDX-License-Identifier: MIT
#include "shadowfield/shadowfield_view.hpp"

#include <prt/prt.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "env_image.hpp"

namespace prt::view {
namespace {

struct SceneDeleter {
  void operator()(prt_shadowfield_scene* scene) const { prt_shadowfield_scene_destroy(scene); }
};
using ScenePtr = std::unique_ptr<prt_shadowfield_scene, SceneDeleter>;

struct GlDeleter {
  void operator()(prt_gl_shadowfield* shader) const { prt_gl_shadowfield_destroy(shader); }
};
using GlShadowfieldPtr = std::unique_ptr<prt_gl_shadowfield, GlDeleter>;

// The frame's settings: direct light only (one instance), on `backend`.
prt_shadowfield_settings settings_for(prt_backend backend) {
  prt_shadowfield_settings settings = prt::sized<prt_shadowfield_settings>();
  settings.bounces = 0;
  settings.backend = backend;
  return settings;
}

// The whole frame on GL each time it is asked for vertices (the frame's passes span every
// vertex); instance 0's vertices start the output buffer, one RGB float triple each.
class GlShadowfieldShader : public GlVertexShader {
 public:
  GlShadowfieldShader(GlShadowfieldPtr shader, const std::vector<float>& light, const float* eye)
      : shader_(std::move(shader)), light_(light), eye_(eye) {}
  prt_result shade(std::uint32_t, std::uint32_t) override {
    const prt_shadowfield_settings settings = settings_for(PRT_BACKEND_GL);
    return prt_gl_shadowfield_shade(shader_.get(), light_.data(), eye_, &settings);
  }
  prt_result read(std::uint32_t first, std::uint32_t count, float* rgb) override {
    return prt_gl_shadowfield_read(shader_.get(), 0, first, count, rgb);
  }
  std::uint32_t output_buffer() const override {
    return prt_gl_shadowfield_output_buffer(shader_.get());
  }

 private:
  GlShadowfieldPtr shader_;
  const std::vector<float>& light_;
  const float* eye_;
};

class ShadowfieldView : public ViewTechnique {
 public:
  prt_technique technique() const override { return PRT_TECHNIQUE_SHADOWFIELD; }
  std::uint32_t section_tag() const override { return PRT_SECTION_SFLD; }

  std::uint32_t open(const BlobScene& scene) override {
    prt_result result = prt_shadowfield_get_info(scene.asset(), &info_);
    if (result != PRT_OK)
      scene.fail(std::string("cannot read the SFLD header: ") + prt_result_string(result));
    prt_shadowfield_scene* made = nullptr;
    result = prt_shadowfield_scene_create(scene.context(), 1, &made);
    scene_.reset(made);
    std::uint32_t object = 0, instance = 0;
    if (result == PRT_OK) result = prt_shadowfield_scene_add_object(made, scene.asset(), &object);
    prt_shadowfield_transform identity = prt::sized<prt_shadowfield_transform>();
    identity.rotation[0] = identity.rotation[4] = identity.rotation[8] = 1.0f;
    identity.scale = 1.0f;
    if (result == PRT_OK)
      result = prt_shadowfield_scene_add_instance(made, object, &identity, &instance);
    if (result != PRT_OK)
      scene.fail(std::string("cannot make a shadowfield scene of its object: ") +
                 prt_result_string(result) + ": " + prt_context_last_message(scene.context()));
    return info_.vertex_count;
  }

  void describe(const BlobScene& scene) const override {
    std::printf(
        "%s: %u vertices, %u triangles, shadowfield order %u, %s (%u BRDF term(s)), basis %u, "
        "%u-bit; one instance, direct light with self-shadowing\n",
        scene.path().c_str(), scene.mesh().vertex_count, scene.mesh().triangle_count, info_.order,
        info_.glossy ? "glossy" : "diffuse", info_.terms, info_.basis_size, info_.bits);
  }

  // order^2 RGB coefficients, coefficient-major, turned about world +Y (the instance is in its
  // own frame, so this is the object's light too).
  void prepare_light(const BlobScene&, const LightRequest& request) override {
    const prt::io::EnvMap& map = *request.map;
    light_.assign(3u * info_.order * info_.order, 0.0f);
    std::vector<float> faces;
    const prt_env_image env = environment_image(map, nullptr, &faces);
    check_runtime(prt_sh_project(info_.order, &env, light_.data()), "prt_sh_project");
    float rotation[9];
    prt::io::rotation_about_y_row_major(request.rotate_degrees, rotation);
    check_runtime(prt_sh_rotate(info_.order, rotation, light_.data(), light_.data(), 3),
                  "prt_sh_rotate");
    if (!request.describe) return;
    std::printf(
        "%s: %dx%d %s map, projected to order %u by the runtime (prt_sh_project, %s), rotated "
        "%g deg about +Y\n",
        request.map_path.c_str(), map.width(), map.height(),
        prt::io::env_mapping_name(map.mapping()), info_.order,
        environment_image_layout(map).c_str(), request.rotate_degrees);
  }

  void set_eye(const float eye[3]) override { std::copy(eye, eye + 3, eye_); }

  const char* shade_function() const override { return "prt_shadowfield_shade"; }

  // The whole frame (its passes span every vertex), then the range asked for.
  prt_result shade(const BlobScene&, prt_backend backend, std::uint32_t first, std::uint32_t count,
                   float* rgb) const override {
    if (std::uint64_t(first) + count > info_.vertex_count) return PRT_ERROR_INVALID_ARGUMENT;
    frame_.resize(3u * std::size_t(info_.vertex_count));
    const prt_shadowfield_settings settings = settings_for(backend);
    float* const out[1] = {frame_.data()};
    const prt_result result =
        prt_shadowfield_shade(scene_.get(), light_.data(), eye_, &settings, out);
    if (result != PRT_OK) return result;
    std::copy(frame_.begin() + 3 * std::ptrdiff_t(first),
              frame_.begin() + 3 * (std::ptrdiff_t(first) + count), rgb);
    return PRT_OK;
  }

  std::unique_ptr<GlVertexShader> create_gl(const BlobScene&, prt_gl_loader_fn loader,
                                            void* loader_user, prt_result* result) const override {
    prt_gl_shadowfield* shader = nullptr;
    *result = prt_gl_shadowfield_create(scene_.get(), loader, loader_user, &shader);
    if (*result != PRT_OK) return nullptr;
    return std::make_unique<GlShadowfieldShader>(GlShadowfieldPtr(shader), light_, eye_);
  }

 private:
  prt_shadowfield_info info_ = prt::sized<prt_shadowfield_info>();
  ScenePtr scene_;  // the object and its one instance; a frame changes it
  std::vector<float> light_;
  float eye_[3] = {0.0f, 0.0f, 1.0f};
  mutable std::vector<float> frame_;  // every vertex's RGB of the last frame
};

}  // namespace

std::unique_ptr<ViewTechnique> make_shadowfield_view() {
  return std::make_unique<ShadowfieldView>();
}

}  // namespace prt::view
