// SPDX-License-Identifier: MIT
#include "cloth/cloth_view.hpp"

#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "env_image.hpp"

namespace prt::view {
namespace {

// Lobes fitted when the command line does not say (prt_cloth_fit_desc's default).
constexpr std::uint32_t kDefaultLobes = 10;

class ClothView : public ViewTechnique {
 public:
  prt_technique technique() const override { return PRT_TECHNIQUE_CLOTH; }
  std::uint32_t section_tag() const override { return PRT_SECTION_CLTH; }

  std::vector<LiveParameter> live_parameters() override {
    LiveParameter fabric;
    fabric.label = "fabric";
    fabric.option = "--fabric";
    fabric.help = "Index of the blob's fabric to draw the mesh with (default 0)";
    fabric.kind = LiveParameter::Kind::Int;
    fabric.max = info_.fabric_count ? info_.fabric_count - 1.0 : 0.0;
    fabric.get = [this] { return double(fabric_); };
    fabric.set = [this](double value) {
      fabric_ = static_cast<std::uint32_t>(std::clamp(value, 0.0, 63.0));  // CLTH: 64 at most
    };
    LiveParameter lobes;
    lobes.label = "light lobes K";
    lobes.option = "--cloth-lobes";
    lobes.help = "Spherical-Gaussian lobes fitted to the map each time the light changes";
    lobes.kind = LiveParameter::Kind::Int;
    lobes.min = 1.0;
    lobes.max = double(PRT_CLOTH_MAX_LOBES);
    lobes.get = [this] { return double(lobe_count_); };
    lobes.set = [this](double value) {
      lobe_count_ = static_cast<std::uint32_t>(std::clamp(value, 1.0, double(PRT_CLOTH_MAX_LOBES)));
    };
    return {fabric, lobes};
  }

  std::uint32_t open(const BlobScene& scene) override {
    const prt_result result = prt_cloth_get_info(scene.asset(), &info_);
    if (result != PRT_OK)
      scene.fail(std::string("cannot read the CLTH header: ") + prt_result_string(result));
    if (fabric_ >= info_.fabric_count)
      scene.fail("has " + std::to_string(info_.fabric_count) + " fabrics, no fabric " +
                 std::to_string(fabric_));
    normals_ = vertex_vectors(scene, PRT_SECTION_VNRM, "VNRM (normals)");
    warps_ = vertex_vectors(scene, PRT_SECTION_VTAN, "VTAN (warps)");
    views_.assign(3u * scene.vertex_count(), 0.0f);
    return scene.vertex_count();
  }

  void describe(const BlobScene& scene) const override {
    const char* name = "?";
    prt_cloth_get_fabric(scene.asset(), fabric_, &name, nullptr, nullptr, nullptr);
    std::printf(
        "%s: %u vertices, %u triangles, cloth: %u fabrics (drawn as %u, %s), %u tables, "
        "%zu table bytes at %u bits; shaded per vertex\n",
        scene.path().c_str(), scene.mesh().vertex_count, scene.mesh().triangle_count,
        info_.fabric_count, fabric_, name, info_.table_count, info_.table_bytes, info_.bits);
  }

  // The map turned about +Y as an environment image, fitted with lobes by the runtime.
  void prepare_light(const BlobScene& scene, const LightRequest& request) override {
    const prt::io::EnvMap& map = *request.map;
    float rotation[9];
    prt::io::rotation_about_y_row_major(request.rotate_degrees, rotation);
    std::vector<float> faces;
    const prt_env_image env = environment_image(map, rotation, &faces);
    prt_cloth_fit_desc desc = prt::sized<prt_cloth_fit_desc>();
    desc.lobe_count = lobe_count_;
    prt_cloth_fit_report report = prt::sized<prt_cloth_fit_report>();
    lobes_.assign(lobe_count_, prt_cloth_lobe{});
    check_runtime(prt_cloth_fit_light(scene.context(), &env, &desc, lobes_.data(), &report),
                  "prt_cloth_fit_light");
    if (!request.describe) return;
    std::printf(
        "%s: %dx%d %s map, rotated %g deg about +Y, fitted with %u lobes by the runtime "
        "(prt_cloth_fit_light: relative error %.3g, power error %.3g)\n",
        request.map_path.c_str(), map.width(), map.height(),
        prt::io::env_mapping_name(map.mapping()), request.rotate_degrees, report.lobe_count,
        double(report.relative_error), double(report.power_error));
  }

  void set_eye(const float eye[3]) override { std::copy(eye, eye + 3, eye_); }

  const char* shade_function() const override { return "prt_cloth_shade"; }

  prt_result shade(const BlobScene& scene, prt_backend backend, std::uint32_t first,
                   std::uint32_t count, float* rgb) const override {
    if (std::uint64_t(first) + count > scene.vertex_count()) return PRT_ERROR_INVALID_ARGUMENT;
    view_directions(scene, first, count);
    prt_cloth_light light = prt::sized<prt_cloth_light>();
    light.lobe_count = static_cast<std::uint32_t>(lobes_.size());
    light.lobes = lobes_.data();
    prt_cloth_pixels pixels = prt::sized<prt_cloth_pixels>();
    pixels.normals = normals_;
    pixels.warps = warps_;
    pixels.views = views_.data();
    return prt_cloth_shade(scene.asset(), backend, fabric_, nullptr, &light, nullptr, &pixels,
                           first, count, rgb);
  }

  std::unique_ptr<GlVertexShader> create_gl(const BlobScene&, prt_gl_loader_fn, void*,
                                            prt_result* result) const override {
    *result = PRT_ERROR_UNSUPPORTED_BACKEND;
    return nullptr;
  }

 private:
  prt_cloth_info info_ = prt::sized<prt_cloth_info>();
  std::uint32_t fabric_ = 0;
  std::uint32_t lobe_count_ = kDefaultLobes;
  std::vector<prt_cloth_lobe> lobes_;
  const float* normals_ = nullptr;  // the asset's VNRM, 3 floats per vertex
  const float* warps_ = nullptr;    // the asset's VTAN
  float eye_[3] = {0.0f, 0.0f, 1.0f};
  mutable std::vector<float> views_;  // unit vertex-to-eye directions, filled by shade()

  // A per-vertex float x, y, z section of the asset; fails unless there is one per vertex.
  static const float* vertex_vectors(const BlobScene& scene, std::uint32_t tag, const char* what) {
    const void* data = nullptr;
    std::size_t size = 0;
    if (prt_asset_section_data(scene.asset(), tag, &data, &size) != PRT_OK ||
        size != 12u * std::size_t(scene.vertex_count()))
      scene.fail(std::string("has no ") + what + " for each vertex: cloth needs the surface frame");
    return static_cast<const float*>(data);
  }

  // The unit direction from each vertex of the range to the eye (a vertex at the eye gets a zero
  // vector, which the runtime shades to 0).
  void view_directions(const BlobScene& scene, std::uint32_t first, std::uint32_t count) const {
    const float* p = scene.mesh().positions;
    for (std::uint32_t v = first; v < first + count; ++v) {
      const float d[3] = {eye_[0] - p[3 * v], eye_[1] - p[3 * v + 1], eye_[2] - p[3 * v + 2]};
      const float length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int c = 0; c < 3; ++c) views_[3u * v + c] = length > 0.0f ? d[c] / length : 0.0f;
    }
  }
};

}  // namespace

std::unique_ptr<ViewTechnique> make_cloth_view() {
  return std::make_unique<ClothView>();
}

}  // namespace prt::view
