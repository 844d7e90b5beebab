// SPDX-License-Identifier: MIT
#include "pose/pose_view.hpp"

#include <prt/prt.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "env_image.hpp"

namespace prt::view {
namespace {

class PoseView : public ViewTechnique {
 public:
  prt_technique technique() const override { return PRT_TECHNIQUE_POSE; }
  std::uint32_t section_tag() const override { return PRT_SECTION_PSTR; }

  std::uint32_t open(const BlobScene& scene) override {
    prt_result result = prt_pose_get_info(scene.asset(), &info_);
    if (result != PRT_OK)
      scene.fail(std::string("cannot read the PSTR header: ") + prt_result_string(result));
    rotations_.resize(4u * info_.joint_count);
    result = prt_pose_bind_pose(scene.asset(), rotations_.data(), nullptr, nullptr);
    if (result != PRT_OK)
      scene.fail(std::string("cannot read the bind pose: ") + prt_result_string(result));
    return info_.vertex_count;
  }

  void describe(const BlobScene& scene) const override {
    std::printf(
        "%s: %u vertices, %u triangles, %u joints, pose order %u, %s model PCA(%u, %u), "
        "%zu model bytes; shown at the bind pose\n",
        scene.path().c_str(), scene.mesh().vertex_count, scene.mesh().triangle_count,
        info_.joint_count, info_.order,
        info_.model == PRT_POSE_MODEL_DIRECT ? "direct" : "residual", info_.pose_dims,
        info_.basis_dims, info_.model_bytes);
  }

  // The light the API documents: the map projected to SH in the world frame and turned about
  // +Y with prt_sh_rotate, as sh does; prt_pose_shade turns it into the model frame itself.
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
        "%s: %dx%d %s map, projected to order %u by the runtime (prt_sh_project, %s), "
        "rotated %g deg about +Y (prt_sh_rotate)\n",
        request.map_path.c_str(), map.width(), map.height(),
        prt::io::env_mapping_name(map.mapping()), info_.order,
        environment_image_layout(map).c_str(), request.rotate_degrees);
  }

  const char* shade_function() const override { return "prt_pose_shade"; }

  prt_result shade(const BlobScene& scene, prt_backend backend, std::uint32_t first,
                   std::uint32_t count, float* rgb) const override {
    prt_pose_input pose = prt::sized<prt_pose_input>();
    pose.joint_rotations = rotations_.data();
    prt_pose_light light = prt::sized<prt_pose_light>();
    light.light_rgb = light_.data();
    return prt_pose_shade(scene.asset(), backend, &pose, &light, first, count, rgb);
  }

  std::unique_ptr<GlVertexShader> create_gl(const BlobScene&, prt_gl_loader_fn, void*,
                                            prt_result* result) const override {
    *result = PRT_ERROR_UNSUPPORTED_BACKEND;
    return nullptr;
  }

 private:
  prt_pose_info info_ = prt::sized<prt_pose_info>();
  std::vector<float> rotations_;  // the bind pose, J x 4
  std::vector<float> light_;      // order² RGB coefficients, world frame
};

}  // namespace

std::unique_ptr<ViewTechnique> make_pose_view() {
  return std::make_unique<PoseView>();
}

}  // namespace prt::view
