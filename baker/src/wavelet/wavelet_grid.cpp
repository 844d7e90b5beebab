// SPDX-License-Identifier: MIT
#include "wavelet_grid.hpp"

#include <prt/prt_wavelet.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "prt/baker/context.hpp"

namespace prt::bake::wavelet {
namespace {

// max over a in [a0, a1] of 2 a A - C a^2 (concave when C > 0: its vertex A / C, clamped).
double max_quadratic(double a0, double a1, double A, double C) {
  auto h = [&](double a) { return 2.0 * a * A - C * a * a; };
  double best = std::max(h(a0), h(a1));
  if (C > 0.0) best = std::max(best, h(std::clamp(A / C, a0, a1)));
  return best;
}

}  // namespace

TexelGrid::TexelGrid(std::uint32_t param, std::uint32_t size)
    : param_(param),
      size_(size),
      faces_(prt_wavelet_face_count(static_cast<prt_wavelet_param>(param))) {
  if (prt_wavelet_coefficient_count(static_cast<prt_wavelet_param>(param), size) == 0) {
    throw Error("wavelet transfer: face size must be a power of two in " +
                std::to_string(PRT_WAVELET_MIN_SIZE) + ".." + std::to_string(PRT_WAVELET_MAX_SIZE) +
                " and the parameterisation cube or dual-paraboloid");
  }
  solid_angle_.resize(count());
  for (std::uint32_t f = 0; f < faces_; ++f) {
    for (std::uint32_t y = 0; y < size; ++y) {
      for (std::uint32_t x = 0; x < size; ++x) {
        solid_angle_[(f * size + y) * size + x] =
            prt_wavelet_texel_solid_angle(static_cast<prt_wavelet_param>(param), size, f, x, y);
      }
    }
  }
  if (param != PRT_WAVELET_PARAM_CUBE) return;
  const std::uint32_t side = size + 1;
  corner_.resize(std::size_t(faces_) * side * side);
  for (std::uint32_t f = 0; f < faces_; ++f) {
    for (std::uint32_t v = 0; v <= size; ++v) {
      for (std::uint32_t u = 0; u <= size; ++u) {
        glm::vec3& d = corner_[(std::size_t(f) * side + v) * side + u];
        if (!prt_wavelet_direction(static_cast<prt_wavelet_param>(param), size, f, float(u),
                                   float(v), &d.x))
          d = glm::vec3(0.0f);
      }
    }
  }
  for (const glm::vec3& d : corner_) {
    corner_x_.push_back(d.x);
    corner_y_.push_back(d.y);
    corner_z_.push_back(d.z);
  }
}

bool TexelGrid::below_horizon(std::uint32_t j, const glm::vec3& n) const {
  if (!(solid_angle_[j] > 0.0)) return true;
  const std::uint32_t face = j / (size_ * size_), x = j % size_, y = (j / size_) % size_;
  if (param_ == PRT_WAVELET_PARAM_CUBE) {
    // On a face, n.w has the sign of a linear function of (s, t): the corners decide.
    const std::uint32_t side = size_ + 1;
    const glm::vec3* c = corner_.data() + std::size_t(face) * side * side;
    for (std::uint32_t dy = 0; dy < 2; ++dy) {
      for (std::uint32_t dx = 0; dx < 2; ++dx) {
        if (glm::dot(n, c[(y + dy) * side + x + dx]) > 0.0f) return false;
      }
    }
    return true;
  }
  // Paraboloid: n.w (1 + r^2) = 2a A + 2b B + C (1 - a^2 - b^2), separable in a and b.
  const double A = n.x, B = face == 0 ? n.z : -n.z, C = face == 0 ? n.y : -n.y;
  const double scale = 2.0 / size_;
  const double a0 = x * scale - 1.0, b0 = y * scale - 1.0;
  const double best = C + max_quadratic(a0, a0 + scale, A, C) + max_quadratic(b0, b0 + scale, B, C);
  return !(best > 0.0);
}

TexelGrid::Horizon::Horizon(const TexelGrid& grid, const glm::vec3& n,
                            std::vector<unsigned char>& above)
    : grid_(grid), n_(n), above_(nullptr) {
  if (grid.param_ != PRT_WAVELET_PARAM_CUBE) return;
  const std::size_t count = grid.corner_.size();
  const float* cx = grid.corner_x_.data();
  const float* cy = grid.corner_y_.data();
  const float* cz = grid.corner_z_.data();
  const float nx = n.x, ny = n.y, nz = n.z;  // locals: the byte stores cannot alias them
  above.resize(count);
  unsigned char* out = above.data();
  // glm::dot's order of additions, so every corner falls on the same side as with it.
  for (std::size_t i = 0; i < count; ++i) out[i] = (nx * cx[i] + ny * cy[i]) + nz * cz[i] > 0.0f;
  above_ = above.data();
}

bool TexelGrid::Horizon::below(std::uint32_t face, std::uint32_t x, std::uint32_t y) const {
  const std::uint32_t size = grid_.size_;
  if (!above_) return grid_.below_horizon((face * size + y) * size + x, n_);
  if (!(grid_.solid_angle_[(face * size + y) * size + x] > 0.0)) return true;
  const std::uint32_t side = size + 1;
  const unsigned char* c = above_ + (std::size_t(face) * side + y) * side + x;
  return !(c[0] | c[1] | c[side] | c[side + 1]);
}

bool TexelGrid::sample(std::uint32_t face, float u, float v, glm::vec3* dir,
                       double* jacobian) const {
  if (!prt_wavelet_direction(static_cast<prt_wavelet_param>(param_), size_, face, u, v, &dir->x))
    return false;
  *jacobian = this->jacobian(u, v);
  return true;
}

void TexelGrid::sample(std::uint32_t face, std::size_t count, const float* u, const float* v,
                       glm::vec3* dir, double* jacobian, unsigned char* on_grid) const {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "directions are packed float triples");
  if (count == 0) return;
  if (count > UINT32_MAX ||
      !prt_wavelet_directions(static_cast<prt_wavelet_param>(param_), size_, face,
                              static_cast<std::uint32_t>(count), u, v, &dir->x, on_grid)) {
    throw Error("wavelet transfer: prt_wavelet_directions rejected a face's samples");
  }
  for (std::size_t i = 0; i < count; ++i)
    if (on_grid[i]) jacobian[i] = this->jacobian(u[i], v[i]);
}

}  // namespace prt::bake::wavelet
