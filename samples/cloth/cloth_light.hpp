// SPDX-License-Identifier: MIT
// The two lights prt-cloth makes from the framework's environment (the current map, turned about
// +Y): the spherical Gaussians the runtime shades with, fitted by prt_cloth_fit_light whenever
// the map, its rotation or the number of lobes changes, and the texels the brute-force reference
// sums over.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <string>
#include <vector>

#include "environments.hpp"

namespace prt::cloth_app {

class FittedLight {
 public:
  // Fits K lobes to the current map at its rotation unless they were fitted for these already;
  // true when the lobes changed. Throws ViewerError when the runtime refuses.
  bool update(prt_context* context, const prt::sample::Environments& envs,
              std::uint32_t lobe_count);
  const prt_cloth_light& light() const { return light_; }
  const prt_cloth_fit_report& report() const { return report_; }
  // "10 lobes, fit error 12.3 % (power 0.4 %)"
  std::string describe() const;

 private:
  std::size_t map_ = ~std::size_t(0);
  std::uint64_t version_ = ~0ull;
  std::uint32_t lobe_count_ = 0;
  prt_env_image image_{};
  std::vector<float> faces_;  // a cross or probe map resampled to cube faces, once per map
  float rotation_[9] = {};
  std::vector<prt_cloth_lobe> lobes_;
  prt_cloth_light light_{};
  prt_cloth_fit_report report_{};
};

// The environment as prt_cloth_reference takes it: the map's texels binned onto a lat-long grid
// of cells (each cell its texels' power at their power-weighted mean direction), except the
// brightest texels (above `bright_factor` times the map's mean radiance, at most `max_bright`
// of them, brightest first), which are kept one by one at full resolution, so that a sun is
// not smeared over a cell. Cells without power are left out.
struct ReferenceSettings {
  int width = 128, height = 64;
  std::uint32_t max_bright = 1024;
  double bright_factor = 20.0;
};

class ReferenceTexels {
 public:
  // Bins the current map (once per map and settings) and turns the texels by the rotation;
  // true when they changed.
  bool update(const prt::sample::Environments& envs, const ReferenceSettings& settings);
  const prt_cloth_env_texels& texels() const { return texels_; }
  std::uint32_t count() const { return texels_.count; }
  // "128x64 cells (8192 lit) + 37 texels at full resolution (41 % of the power)"
  std::string describe() const;

 private:
  std::size_t map_ = ~std::size_t(0);
  std::uint64_t version_ = ~0ull;
  ReferenceSettings settings_{0, 0, 0, 0.0};
  std::vector<float> image_directions_, power_, directions_;  // 3 floats per texel
  std::uint32_t cells_ = 0, bright_ = 0;
  double bright_share_ = 0.0;
  prt_cloth_env_texels texels_{};

  void bin(const prt::io::EnvMap& map, const ReferenceSettings& settings);
};

}  // namespace prt::cloth_app
