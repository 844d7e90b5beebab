// SPDX-License-Identifier: MIT
// Synthetic `shadowfield` objects for the runtime's tests, built from formulas: a square patch of
// vertices, its transfer, material, occlusion and source fields set by the test, viewed as the
// runtime's prt_sf_object (runtime/src/shadowfield/shadowfield_object.h).
#pragma once

#include <prt/prt.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

extern "C" {
#include "shadowfield_object.h"
}

namespace prt::test {

constexpr double kSfPi = 3.14159265358979323846;

// The SH frame's direction (x, y, z) as the world direction prt_sh_eval takes.
inline void world_from_sh(double x, double y, double z, float out[3]) {
  out[0] = float(x);
  out[1] = float(z);
  out[2] = float(-y);
}

// Integral over the sphere of f(w) y_i(w) for every i < order^2: midpoint rule in theta and phi
// on a fine grid (independent of the runtime's Gauss-Legendre rule).
inline std::vector<double> project_dense(uint32_t order,
                                         const std::function<double(const float*)>& f,
                                         int theta_steps = 256) {
  const uint32_t n2 = order * order;
  std::vector<double> out(n2, 0.0);
  std::vector<float> y(n2);
  const int phi_steps = 2 * theta_steps;
  for (int a = 0; a < theta_steps; ++a) {
    const double theta = kSfPi * (a + 0.5) / theta_steps;
    const double weight = std::sin(theta) * (kSfPi / theta_steps) * (2.0 * kSfPi / phi_steps);
    for (int b = 0; b < phi_steps; ++b) {
      const double phi = 2.0 * kSfPi * (b + 0.5) / phi_steps;
      float w[3];
      world_from_sh(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                    std::cos(theta), w);
      prt_sh_eval(order, w, y.data());
      const double value = f(w) * weight;
      for (uint32_t i = 0; i < n2; ++i) out[i] += value * y[i];
    }
  }
  return out;
}

// sum_i c_i y_i(w).
inline double sh_value(uint32_t order, const float* coefficients, const float w[3]) {
  std::vector<float> y(order * order);
  prt_sh_eval(order, w, y.data());
  double sum = 0.0;
  for (uint32_t i = 0; i < order * order; ++i) sum += double(coefficients[i]) * y[i];
  return sum;
}

// A side x side patch of vertices on [-0.5, 0.5]^2 in the plane y = 0, normals +Y, with the
// unshadowed diffuse transfer T_i = A_l y_i(n) / pi (so T . L is the irradiance over pi), one
// term; albedo varies by vertex. Fields are unset (the caller fills them).
struct SyntheticObject {
  uint32_t order = 4, terms = 1, glossy = 0, vertex_count = 0, basis_size = 0, brdf_grid = 0;
  std::vector<float> positions, normals, albedo, transfer, g_table, oof;
  std::vector<float> basis, vertex_weights, basis_inverse, srf;
  prt_sf_shells oof_shells{}, srf_shells{};
  prt_sf_object object{};

  // The runtime's view; valid until the vectors change.
  const prt_sf_object* view() {
    object.order = order;
    object.terms = terms;
    object.glossy = glossy;
    object.vertex_count = vertex_count;
    object.basis_size = basis_size;
    object.brdf_grid = brdf_grid;
    object.positions = positions.data();
    object.normals = normals.data();
    object.albedo = albedo.data();
    object.transfer = transfer.data();
    object.g_table = glossy ? g_table.data() : nullptr;
    object.oof_shells = oof_shells;
    object.oof = oof.data();
    object.basis = basis_size ? basis.data() : nullptr;
    object.vertex_weights = basis_size ? vertex_weights.data() : nullptr;
    object.basis_inverse = basis_size ? basis_inverse.data() : nullptr;
    object.srf_shells = srf_shells;
    object.srf = basis_size ? srf.data() : nullptr;
    return &object;
  }

  uint32_t coefficients() const { return order * order; }

  // The OOF as the same coefficients at every shell point.
  void set_constant_oof(const std::vector<float>& coefficients_at_every_point) {
    const uint64_t points = prt_sf_point_count(&oof_shells);
    oof.clear();
    for (uint64_t p = 0; p < points; ++p)
      oof.insert(oof.end(), coefficients_at_every_point.begin(), coefficients_at_every_point.end());
  }

  // A radiance basis of `size` functions B_i(v) = cos(i v) (the first constant), area weights
  // 1 / V and the true A^-1 of that basis (for size <= 2, inverted here in closed form); SRFs
  // srf(i, k, point, coefficient) set by `field`.
  void set_basis(
      uint32_t size,
      const std::function<float(uint32_t i, uint32_t k, uint64_t p, uint32_t c)>& field) {
    basis_size = size;
    basis.assign(size_t(size) * vertex_count, 0.0f);
    vertex_weights.assign(vertex_count, 1.0f / float(vertex_count));
    for (uint32_t i = 0; i < size; ++i)
      for (uint32_t v = 0; v < vertex_count; ++v)
        basis[i * vertex_count + v] = std::cos(float(i * v));
    std::vector<double> a(size_t(size) * size, 0.0);
    for (uint32_t i = 0; i < size; ++i)
      for (uint32_t j = 0; j < size; ++j)
        for (uint32_t v = 0; v < vertex_count; ++v)
          a[i * size + j] +=
              double(basis[i * vertex_count + v]) * vertex_weights[v] * basis[j * vertex_count + v];
    basis_inverse.assign(size_t(size) * size, 0.0f);
    if (size == 1) {
      basis_inverse[0] = float(1.0 / a[0]);
    } else {
      const double det = a[0] * a[3] - a[1] * a[2];
      basis_inverse = {float(a[3] / det), float(-a[1] / det), float(-a[2] / det),
                       float(a[0] / det)};
    }
    const uint64_t points = prt_sf_point_count(&srf_shells);
    srf.assign(size_t(size) * terms * points * coefficients(), 0.0f);
    for (uint32_t i = 0; i < size; ++i)
      for (uint32_t k = 0; k < terms; ++k)
        for (uint64_t p = 0; p < points; ++p)
          for (uint32_t c = 0; c < coefficients(); ++c)
            srf[((size_t(i) * terms + k) * points + p) * coefficients() + c] = field(i, k, p, c);
  }
};

inline prt_sf_shells default_shells(float radius) {
  prt_sf_shells grid{};
  grid.radius = radius;
  grid.inner = 0.2f;
  grid.outer = 8.0f;
  grid.shells = 4;
  grid.face_size = 2;
  return grid;
}

inline SyntheticObject make_patch(uint32_t order, uint32_t side) {
  SyntheticObject o;
  o.order = order;
  o.vertex_count = side * side;
  const uint32_t n2 = order * order;
  const float up[3] = {0.0f, 1.0f, 0.0f};
  std::vector<float> y(n2);
  prt_sh_eval(order, up, y.data());
  for (uint32_t j = 0; j < side; ++j)
    for (uint32_t i = 0; i < side; ++i) {
      const float x = side > 1 ? -0.5f + float(i) / float(side - 1) : 0.0f;
      const float z = side > 1 ? -0.5f + float(j) / float(side - 1) : 0.0f;
      o.positions.insert(o.positions.end(), {x, 0.0f, z});
      o.normals.insert(o.normals.end(), {0.0f, 1.0f, 0.0f});
      const float v = float(j * side + i);
      o.albedo.insert(o.albedo.end(), {0.5f + 0.3f * std::sin(v), 0.6f, 0.4f + 0.2f * std::cos(v)});
      for (uint32_t c = 0; c < n2; ++c) {
        const uint32_t l = uint32_t(std::sqrt(float(c)) + 1e-4f);
        o.transfer.push_back(float(prt_sh_cosine_band_factor(l) * y[c] / kSfPi));
      }
    }
  o.oof_shells = default_shells(0.75f);
  o.srf_shells = default_shells(0.75f);
  std::vector<float> open(n2, 0.0f);
  open[0] = float(std::sqrt(4.0 * kSfPi));
  o.set_constant_oof(open);
  return o;
}

// Row-major rotation by `angle` about the unit axis.
inline void axis_rotation(const float axis[3], float angle, float out[9]) {
  const float c = std::cos(angle), s = std::sin(angle), t = 1.0f - c;
  const float x = axis[0], y = axis[1], z = axis[2];
  const float m[9] = {t * x * x + c,     t * x * y - s * z, t * x * z + s * y,
                      t * x * y + s * z, t * y * y + c,     t * y * z - s * x,
                      t * x * z - s * y, t * y * z + s * x, t * z * z + c};
  for (int e = 0; e < 9; ++e) out[e] = m[e];
}

inline prt_shadowfield_transform make_transform(const float rotation[9], float tx, float ty,
                                                float tz, float scale = 1.0f) {
  prt_shadowfield_transform t{};
  t.struct_size = sizeof t;
  for (int e = 0; e < 9; ++e) t.rotation[e] = rotation[e];
  t.translation[0] = tx;
  t.translation[1] = ty;
  t.translation[2] = tz;
  t.scale = scale;
  return t;
}

inline const float* identity_rotation() {
  static const float kIdentity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  return kIdentity;
}

}  // namespace prt::test
