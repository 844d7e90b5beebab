// SPDX-License-Identifier: MIT
#include "sh/sh_view.hpp"

#include <prt/prt.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "env_image.hpp"

namespace prt::view {
namespace {

const char* transfer_kind(std::uint32_t kind) {
  static const char* const kKinds[] = {"unshadowed", "shadowed", "interreflected"};
  return kind < 3 ? kKinds[kind] : "unknown kind";
}

// order² RGB coefficients, coefficient-major: the map projected by prt_sh_project, then turned
// about world +Y by prt_sh_rotate (light from d comes from R d, R = [[c,0,s],[0,1,0],[-s,0,c]]).
std::vector<float> project_and_rotate(const prt::io::EnvMap& map, std::uint32_t order,
                                      double degrees) {
  std::vector<float> coefficients(3u * order * order), faces;
  const prt_env_image env = environment_image(map, nullptr, &faces);
  check_runtime(prt_sh_project(order, &env, coefficients.data()), "prt_sh_project");
  float rotation[9];
  prt::io::rotation_about_y_row_major(degrees, rotation);
  check_runtime(prt_sh_rotate(order, rotation, coefficients.data(), coefficients.data(), 3),
                "prt_sh_rotate");
  return coefficients;
}

class GlShShader : public GlVertexShader {
 public:
  GlShShader(prt::GlShShaderPtr shader, const std::vector<float>& light)
      : shader_(std::move(shader)), light_(light) {}
  prt_result shade(std::uint32_t first, std::uint32_t count) override {
    return prt_gl_sh_shade(shader_.get(), light_.data(), first, count);
  }
  prt_result read(std::uint32_t first, std::uint32_t count, float* rgb) override {
    return prt_gl_sh_read(shader_.get(), first, count, rgb);
  }
  std::uint32_t output_buffer() const override { return prt_gl_sh_output_buffer(shader_.get()); }

 private:
  prt::GlShShaderPtr shader_;
  const std::vector<float>& light_;
};

class ShView : public ViewTechnique {
 public:
  prt_technique technique() const override { return PRT_TECHNIQUE_SH; }
  std::uint32_t section_tag() const override { return PRT_SECTION_SHTR; }

  std::uint32_t open(const BlobScene& scene) override {
    const prt_result result = prt_sh_get_info(scene.asset(), &info_);
    if (result != PRT_OK)
      scene.fail(std::string("cannot read the SHTR header: ") + prt_result_string(result));
    return info_.vertex_count;
  }

  void describe(const BlobScene& scene) const override {
    std::printf("%s: %u vertices, %u triangles, sh order %u, %s transfer, %u channel(s)\n",
                scene.path().c_str(), scene.mesh().vertex_count, scene.mesh().triangle_count,
                info_.order, transfer_kind(info_.kind), info_.channels);
  }

  std::vector<LiveParameter> live_parameters() override {
    LiveParameter dering;
    dering.label = "de-ringing";
    dering.option = "--dering";
    dering.help =
        "De-ring the SH light (prt_sh_dering_light, Sloan's window): no dark far side under a "
        "bright sun, at the cost of blur";
    dering.kind = LiveParameter::Kind::Bool;
    dering.max = 1.0;
    dering.get = [this] { return dering_ ? 1.0 : 0.0; };
    dering.set = [this](double value) { dering_ = value != 0.0; };
    LiveParameter strength;
    strength.label = "strength";
    strength.option = "--dering-strength";
    strength.help =
        "With --dering: the window's strength (1: the weakest that keeps a point light's "
        "irradiance non-negative; 0: none)";
    strength.kind = LiveParameter::Kind::Float;
    strength.max = 4.0;
    strength.get = [this] { return double(dering_strength_); };
    strength.set = [this](double value) { dering_strength_ = float(std::max(value, 0.0)); };
    return {dering, strength};
  }

  void prepare_light(const BlobScene&, const LightRequest& request) override {
    const prt::io::EnvMap& map = *request.map;
    light_ = project_and_rotate(map, info_.order, request.rotate_degrees);
    if (dering_)
      check_runtime(
          prt_sh_dering_light(info_.order, dering_strength_, light_.data(), light_.data()),
          "prt_sh_dering_light");
    if (!request.describe) return;
    std::printf(
        "%s: %dx%d %s map, projected to order %u by the runtime (prt_sh_project, %s), rotated "
        "%g deg about +Y",
        request.map_path.c_str(), map.width(), map.height(),
        prt::io::env_mapping_name(map.mapping()), info_.order,
        environment_image_layout(map).c_str(), request.rotate_degrees);
    if (dering_) std::printf(", de-ringed at strength %g (prt_sh_dering_light)", dering_strength_);
    std::printf("\n");
  }

  const char* shade_function() const override { return "prt_sh_shade"; }

  prt_result shade(const BlobScene& scene, prt_backend backend, std::uint32_t first,
                   std::uint32_t count, float* rgb) const override {
    return prt_sh_shade(scene.asset(), backend, light_.data(), first, count, rgb);
  }

  std::unique_ptr<GlVertexShader> create_gl(const BlobScene& scene, prt_gl_loader_fn loader,
                                            void* loader_user, prt_result* result) const override {
    auto [shader, created] = prt::gl_sh_create(scene.context(), scene.asset(), loader, loader_user);
    *result = created;
    if (created != PRT_OK) return nullptr;
    return std::make_unique<GlShShader>(std::move(shader), light_);
  }

 private:
  prt_sh_info info_ = prt::sized<prt_sh_info>();
  std::vector<float> light_;  // order² RGB coefficients
  bool dering_ = false;
  float dering_strength_ = PRT_SH_DERING_DEFAULT_STRENGTH;
};

}  // namespace

std::unique_ptr<ViewTechnique> make_sh_view() {
  return std::make_unique<ShView>();
}

}  // namespace prt::view
