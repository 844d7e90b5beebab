// SPDX-License-Identifier: MIT
// Helpers for the wavelet bake tests: the exact clamped-cosine integral over a cube texel
// (Lambert's polygon formula, independent of the bake's sampling), runtime handles, and the
// runtime's light pipeline.
#pragma once

#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/scene.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake::test {

constexpr double kPi = 3.14159265358979323846;

// The unnormalised direction at face coordinates (s, t) in [-1, 1]^2 (formats/SPEC.md §14, typed
// from the table there, not from the runtime).
inline glm::dvec3 cube_point(std::uint32_t face, double s, double t) {
  switch (face) {
    case 0:
      return {1, -t, -s};
    case 1:
      return {-1, -t, s};
    case 2:
      return {s, 1, t};
    case 3:
      return {s, -1, -t};
    case 4:
      return {s, -t, 1};
    default:
      return {-s, -t, -1};
  }
}

// Integral of max(0, n.w) over the spherical polygon whose vertices (not necessarily unit) are
// `poly` (edges great arcs): clipped to n.p >= 0, then Lambert's formula
// 1/2 sum_i angle(v_i, v_i+1) * (n . unit(v_i x v_i+1)), whose sign follows the winding.
inline double clamped_cosine_integral(std::vector<glm::dvec3> poly, const glm::dvec3& n) {
  std::vector<glm::dvec3> clipped;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec3 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double da = glm::dot(n, a), db = glm::dot(n, b);
    if (da >= 0) clipped.push_back(a);
    if ((da >= 0) != (db >= 0)) clipped.push_back(a + (b - a) * (da / (da - db)));
  }
  if (clipped.size() < 3) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < clipped.size(); ++i) {
    const glm::dvec3 a = glm::normalize(clipped[i]);
    const glm::dvec3 b = glm::normalize(clipped[(i + 1) % clipped.size()]);
    const glm::dvec3 c = glm::cross(a, b);
    const double len = glm::length(c);
    if (len < 1e-300) continue;
    sum += std::atan2(len, glm::dot(a, b)) * glm::dot(n, c / len);
  }
  return std::abs(0.5 * sum);
}

// Integral of max(0, n.w) over the directions in which a closed convex mesh is seen from the
// point p outside it: the faces turned towards p tile exactly that solid angle (a ray from p
// enters a convex body once, through such a face), each a spherical triangle seen from p.
inline double convex_mesh_clamped_cosine_integral(const Mesh& mesh, const glm::dvec3& p,
                                                  const glm::dvec3& n) {
  glm::dvec3 inside(0.0);
  for (const glm::vec3& v : mesh.positions) inside += glm::dvec3(v) / double(mesh.positions.size());
  double sum = 0.0;
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[i]]), b(mesh.positions[mesh.indices[i + 1]]),
        c(mesh.positions[mesh.indices[i + 2]]);
    glm::dvec3 outward = glm::cross(b - a, c - a);
    if (glm::dot(outward, a - inside) < 0.0) outward = -outward;
    if (glm::dot(outward, p - a) > 0.0) sum += clamped_cosine_integral({a - p, b - p, c - p}, n);
  }
  return sum;
}

// The corners of cube texel (face, x, y) of an S x S face, in order around it.
inline std::vector<glm::dvec3> cube_texel(std::uint32_t size, std::uint32_t face, std::uint32_t x,
                                          std::uint32_t y) {
  auto st = [&](double u) { return 2.0 * u / size - 1.0; };
  return {cube_point(face, st(x), st(y)), cube_point(face, st(x + 1), st(y)),
          cube_point(face, st(x + 1), st(y + 1)), cube_point(face, st(x), st(y + 1))};
}

struct RuntimeAsset {
  prt_context* context = nullptr;
  prt_asset* asset = nullptr;
  RuntimeAsset() { EXPECT_EQ(prt_context_create(nullptr, &context), PRT_OK); }
  ~RuntimeAsset() {
    prt_asset_destroy(asset);
    prt_context_destroy(context);
  }
  prt_result load(const std::vector<std::uint8_t>& blob) {
    return prt_asset_load_memory(context, blob.data(), blob.size(), PRT_VALIDATE_FULL, &asset);
  }
  const char* message() const { return prt_context_last_message(context); }
};

// The runtime's per-frame light of a lat-long map: resample -> transform -> select(m).
inline std::vector<float> runtime_light(const io::EnvMap& map, prt_wavelet_param param,
                                        std::uint32_t size, std::uint32_t m = 0xFFFFFFFFu) {
  std::vector<float> light(std::size_t(prt_wavelet_coefficient_count(param, size)) * 4);
  const prt_env_image env = prt::latlong_env(map.width(), map.height(), map.pixels().data());
  EXPECT_EQ(prt_wavelet_resample(param, size, &env, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_transform_light(param, size, light.data()), PRT_OK);
  EXPECT_EQ(prt_wavelet_select_light(param, size, m, light.data()), PRT_OK);
  return light;
}

// prepare + shade every vertex through the runtime (scalar reference).
inline std::vector<glm::vec3> runtime_shade(const RuntimeAsset& a, std::vector<float> light) {
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  EXPECT_EQ(prt_wavelet_get_info(a.asset, &info), PRT_OK);
  EXPECT_EQ(prt_wavelet_prepare_light(a.asset, light.data(), light.data(), nullptr), PRT_OK);
  std::vector<glm::vec3> out(info.vertex_count);
  EXPECT_EQ(prt_wavelet_shade(a.asset, PRT_BACKEND_CPU, light.data(), nullptr, 0, info.vertex_count,
                              &out[0].x),
            PRT_OK);
  return out;
}

}  // namespace prt::bake::test
