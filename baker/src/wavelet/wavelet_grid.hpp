// SPDX-License-Identifier: MIT
// The texels of a `wavelet` parameterisation as the transfer bake needs them (private header):
// solid angles, the exact "entirely below the horizon" test, jittered sample directions and the
// Jacobian that weights them. Directions and solid angles come from the runtime (prt_wavelet.h),
// so bake and runtime cannot disagree on the texel layout.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <prt/prt_wavelet.h>
#include <glm/glm.hpp>

namespace prt::bake::wavelet {

class TexelGrid {
 public:
  // Throws Error for a bad param or size.
  TexelGrid(std::uint32_t param, std::uint32_t size);

  std::uint32_t param() const { return param_; }
  std::uint32_t size() const { return size_; }
  std::uint32_t faces() const { return faces_; }
  std::uint32_t count() const { return faces_ * size_ * size_; }
  double solid_angle(std::uint32_t j) const { return solid_angle_[j]; }

  // True when max(0, n.w) = 0 everywhere on texel j (or the texel carries no direction).
  bool below_horizon(std::uint32_t j, const glm::vec3& n) const;

  // below_horizon for every texel of one normal, texel (face, x, y) at a time: on the cube each
  // corner's side of the horizon is found once for the four texels that share it.
  class Horizon {
   public:
    // `above` is the caller's buffer, reused from normal to normal.
    Horizon(const TexelGrid& grid, const glm::vec3& n, std::vector<unsigned char>& above);
    bool below(std::uint32_t face, std::uint32_t x, std::uint32_t y) const;

   private:
    const TexelGrid& grid_;
    glm::vec3 n_;
    const unsigned char* above_;  // cube: per corner, n.corner > 0
  };

  // The direction at continuous face coordinates (u, v) and its Jacobian relative to the texel
  // (d omega / du dv up to a per-face constant). False when (u, v) has no direction.
  bool sample(std::uint32_t face, float u, float v, glm::vec3* dir, double* jacobian) const;

  // sample at count points of one face: on_grid[i] is sample's return value for point i.
  void sample(std::uint32_t face, std::size_t count, const float* u, const float* v, glm::vec3* dir,
              double* jacobian, unsigned char* on_grid) const;

 private:
  // The Jacobian at (u, v), which has a direction. Inline: called once per texel sample.
  double jacobian(float u, float v) const {
    const double a = 2.0 * u / size_ - 1.0, b = 2.0 * v / size_ - 1.0, r2 = a * a + b * b;
    // Cube: d omega = ds dt / (1 + s^2 + t^2)^(3/2); paraboloid: 4 da db / (1 + r^2)^2.
    const double q = 1.0 + r2;
    return param_ == PRT_WAVELET_PARAM_CUBE ? 1.0 / (q * std::sqrt(q)) : 1.0 / (q * q);
  }

  std::uint32_t param_, size_, faces_;
  std::vector<double> solid_angle_;
  std::vector<glm::vec3> corner_;  // cube: (size+1)^2 corner directions per face
  // The same corners by component, so that Horizon's dot products over all of them vectorise.
  std::vector<float> corner_x_, corner_y_, corner_z_;
};

}  // namespace prt::bake::wavelet
