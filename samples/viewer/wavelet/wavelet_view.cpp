// SPDX-License-Identifier: MIT
#include "wavelet/wavelet_view.hpp"

#include <prt/prt.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "env_image.hpp"

namespace prt::view {
namespace {

class GlWaveletShader : public GlVertexShader {
 public:
  GlWaveletShader(prt::GlWaveletShaderPtr shader, const std::vector<float>& light)
      : shader_(std::move(shader)), light_(light) {}
  prt_result shade(std::uint32_t first, std::uint32_t count) override {
    return prt_gl_wavelet_shade(shader_.get(), light_.data(), first, count);
  }
  prt_result read(std::uint32_t first, std::uint32_t count, float* rgb) override {
    return prt_gl_wavelet_read(shader_.get(), first, count, rgb);
  }
  std::uint32_t output_buffer() const override {
    return prt_gl_wavelet_output_buffer(shader_.get());
  }

 private:
  prt::GlWaveletShaderPtr shader_;
  const std::vector<float>& light_;
};

class WaveletView : public ViewTechnique {
 public:
  prt_technique technique() const override { return PRT_TECHNIQUE_WAVELET; }
  std::uint32_t section_tag() const override { return PRT_SECTION_WVLT; }

  std::vector<LiveParameter> live_parameters() override {
    LiveParameter m;
    m.label = "light terms M";
    m.option = "--light-coefficients";
    m.help =
        "Light detail coefficients kept per frame by area-weighted selection (default: all); the "
        "faces' scaling coefficients are always kept";
    m.kind = LiveParameter::Kind::Int;
    m.max = detail_coefficients();
    m.get = [this] {
      return info_.coefficient_count ? double(std::min(light_coefficients_, detail_coefficients()))
                                     : double(light_coefficients_);
    };
    m.set = [this](double value) {
      light_coefficients_ = static_cast<std::uint32_t>(std::clamp(value, 0.0, 4294967295.0));
    };
    return {m};
  }

  std::uint32_t open(const BlobScene& scene) override {
    const prt_result result = prt_wavelet_get_info(scene.asset(), &info_);
    if (result != PRT_OK)
      scene.fail(std::string("cannot read the WVLT header: ") + prt_result_string(result));
    return info_.vertex_count;
  }

  void describe(const BlobScene& scene) const override {
    std::printf(
        "%s: %u vertices, %u triangles, wavelet %s %u, %.1f non-zeros per vertex (%.0f bytes), "
        "%s quantiser\n",
        scene.path().c_str(), scene.mesh().vertex_count, scene.mesh().triangle_count,
        info_.param == PRT_WAVELET_PARAM_CUBE ? "cube" : "dual paraboloid", info_.size,
        static_cast<double>(info_.pair_count) / std::max(1u, info_.vertex_count),
        2.0 * info_.pair_count / std::max(1u, info_.vertex_count),
        info_.quantizer == PRT_WAVELET_QUANTIZER_VERTEX ? "per-vertex" : "per face and level");
  }

  void prepare_light(const BlobScene& scene, const LightRequest& request) override {
    const prt::io::EnvMap& map = *request.map;
    const std::uint32_t kept = std::min(light_coefficients_, detail_coefficients());
    build_light(scene, map, request.rotate_degrees, kept);
    if (!request.describe) return;
    std::printf(
        "%s: %dx%d %s map, resampled onto the blob's %u coefficients by the runtime, rotated %g "
        "deg about +Y, %u + %u light coefficients kept (area-weighted)\n",
        request.map_path.c_str(), map.width(), map.height(),
        prt::io::env_mapping_name(map.mapping()), info_.coefficient_count, request.rotate_degrees,
        info_.faces, kept);
  }

  const char* shade_function() const override { return "prt_wavelet_shade"; }

  prt_result shade(const BlobScene& scene, prt_backend backend, std::uint32_t first,
                   std::uint32_t count, float* rgb) const override {
    return prt_wavelet_shade(scene.asset(), backend, light_.data(), zero_blocks_.data(), first,
                             count, rgb);
  }

  std::unique_ptr<GlVertexShader> create_gl(const BlobScene& scene, prt_gl_loader_fn loader,
                                            void* loader_user, prt_result* result) const override {
    auto [shader, created] =
        prt::gl_wavelet_create(scene.context(), scene.asset(), loader, loader_user);
    *result = created;
    if (created != PRT_OK) return nullptr;
    return std::make_unique<GlWaveletShader>(std::move(shader), light_);
  }

 private:
  prt_wavelet_info info_ = prt::sized<prt_wavelet_info>();
  std::uint32_t light_coefficients_ = 0xFFFFFFFFu;  // detail coefficients kept (all)
  std::vector<float> light_;                        // coefficient_count prepared RGBA quadruples
  std::vector<std::uint8_t> zero_blocks_;           // block_count bytes, 1 = all-zero light
  // The map prepared once for the per-frame resampling, and what it was made from.
  prt::WaveletSourcePtr source_;
  const float* source_pixels_ = nullptr;
  int source_width_ = 0, source_height_ = 0;

  std::uint32_t detail_coefficients() const { return info_.coefficient_count - info_.faces; }

  // The source of `map` (the same environment image prt_sh_project takes), prepared on first use
  // and again only when the map changes, so that turning the light re-does the per-frame part.
  const prt_wavelet_source* source_for(const BlobScene& scene, const prt::io::EnvMap& map) {
    if (source_ && source_pixels_ == map.pixels().data() && source_width_ == map.width() &&
        source_height_ == map.height())
      return source_.get();
    std::vector<float> faces;
    const prt_env_image env = environment_image(map, nullptr, &faces);
    prt_wavelet_source_desc desc = prt::sized<prt_wavelet_source_desc>();
    desc.param = info_.param;
    desc.size = info_.size;
    desc.env = &env;
    prt_wavelet_source* source = nullptr;
    source_.reset();
    check_runtime(prt_wavelet_source_create(scene.context(), &desc, &source),
                  "prt_wavelet_source_create");
    source_.reset(source);
    source_pixels_ = map.pixels().data();
    source_width_ = map.width();
    source_height_ = map.height();
    return source;
  }

  // The map resampled onto the asset's parameterisation turned by `degrees` about +Y
  // (prt_wavelet_source_resample), Haar-transformed, `kept` detail coefficients kept by
  // area-weighted selection (plus the scaling ones), and prepared (band scales folded in, the
  // blocks of zero light marked).
  void build_light(const BlobScene& scene, const prt::io::EnvMap& map, double degrees,
                   std::uint32_t kept) {
    float rotation[9];
    prt::io::rotation_about_y_row_major(degrees, rotation);
    const prt_wavelet_source* source = source_for(scene, map);
    light_.assign(4u * info_.coefficient_count, 0.0f);
    check_runtime(prt_wavelet_source_resample(source, rotation, light_.data()),
                  "prt_wavelet_source_resample");
    check_runtime(prt_wavelet_transform_light(info_.param, info_.size, light_.data()),
                  "prt_wavelet_transform_light");
    check_runtime(prt_wavelet_select_light(info_.param, info_.size, kept, light_.data()),
                  "prt_wavelet_select_light");
    zero_blocks_.assign(info_.block_count, 0);
    check_runtime(
        prt_wavelet_prepare_light(scene.asset(), light_.data(), light_.data(), zero_blocks_.data()),
        "prt_wavelet_prepare_light");
  }
};

}  // namespace

std::unique_ptr<ViewTechnique> make_wavelet_view() {
  return std::make_unique<WaveletView>();
}

}  // namespace prt::view
