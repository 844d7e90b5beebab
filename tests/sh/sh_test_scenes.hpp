// SPDX-License-Identifier: MIT
// Scenes and environments for the sh transfer tests, generated in code so their exact shapes are
// what the expectations are computed from.
#pragma once

#include <prt/prt_sh.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/scene.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake::test {

// A parallelogram corner + s*edge_u + t*edge_v, s,t in [0,1], as an nu x nv grid of cells with
// the constant vertex normal `normal`.
inline Mesh make_grid(const char* name, glm::vec3 corner, glm::vec3 edge_u, glm::vec3 edge_v,
                      int nu, int nv, glm::vec3 normal) {
  Mesh mesh;
  mesh.name = name;
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      mesh.positions.push_back(corner + edge_u * (float(i) / nu) + edge_v * (float(j) / nv));
      mesh.normals.push_back(normal);
    }
  }
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const std::uint32_t a = j * (nu + 1) + i, b = a + 1, c = a + (nu + 1), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, c, b, d, c});
    }
  }
  return mesh;
}

// An open box finely meshed: floor at y = 0 (normal +Y, cells x cells) and four walls of the
// given height with inward normals (cells x wall_cells each) along the sides of [-1,1]^2, no lid.
// Floor and walls stop `gap` short of each other, so that no vertex lies on another face: a vertex
// exactly on another surface (a closed seam) starts its rays on that surface, which makes its
// visibility an artefact of the ray offset rather than of the geometry.
inline std::vector<Mesh> make_fine_open_box(float height, int cells, int wall_cells,
                                            float gap = 0.01f) {
  std::vector<Mesh> meshes;
  const float lo = -1.0f + gap, span = 2.0f - 2.0f * gap;
  meshes.push_back(
      make_grid("floor", {lo, 0, lo}, {span, 0, 0}, {0, 0, span}, cells, cells, {0, 1, 0}));
  const glm::vec3 corners[4] = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  for (int w = 0; w < 4; ++w) {
    const glm::vec3 a = corners[w], b = corners[(w + 1) % 4];
    const glm::vec3 along = glm::normalize(b - a);
    const glm::vec3 inward = -glm::normalize(glm::vec3(a.x + b.x, 0, a.z + b.z));
    meshes.push_back(make_grid("wall", a + gap * along, span * along, {0, height, 0}, cells,
                               wall_cells, inward));
  }
  return meshes;
}

// A hemispherical bowl: the lower half (y <= 0) of the sphere of radius 1 about the origin, seen
// from inside (normals point to the centre), rings x segments cells, rim at y = 0. Concave and
// smooth, with no seam where one face meets another, so its transfer varies smoothly.
inline Mesh make_bowl(int rings, int segments) {
  const float pi = 3.14159265358979f;
  Mesh mesh;
  mesh.name = "bowl";
  for (int r = 0; r < rings; ++r) {  // ring r at polar angle pi/2 + r/rings * pi/2 from +Y
    const float theta = 0.5f * pi + 0.5f * pi * float(r) / rings;
    for (int s = 0; s < segments; ++s) {
      const float phi = 2.0f * pi * float(s) / segments;
      const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      mesh.positions.push_back(p);
      mesh.normals.push_back(-p);
    }
  }
  mesh.positions.emplace_back(0.0f, -1.0f, 0.0f);  // the bottom pole
  mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
  const std::uint32_t pole = static_cast<std::uint32_t>(mesh.positions.size() - 1);
  auto at = [&](int r, int s) { return static_cast<std::uint32_t>(r * segments + s % segments); };
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      mesh.indices.insert(mesh.indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s), at(r, s + 1),
                                               at(r + 1, s + 1), at(r + 1, s)});
    }
  }
  for (int s = 0; s < segments; ++s) {
    mesh.indices.insert(mesh.indices.end(), {at(rings - 1, s), at(rings - 1, s + 1), pole});
  }
  return mesh;
}

// A lat-long environment whose texel centres hold radiance(direction), using the map's own
// direction convention (EnvMap::texel).
inline io::EnvMap make_function_map(int width,
                                    const std::function<glm::vec3(glm::vec3)>& radiance) {
  const int height = width / 2;
  const io::EnvMap layout(width, height,
                          std::vector<float>(static_cast<std::size_t>(width) * height * 3, 0.0f),
                          io::EnvMapping::LatLong, "layout");
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      glm::vec3 dir;
      float omega = 0.0f;
      layout.texel(x, y, &dir, &omega);
      const glm::vec3 value = radiance(dir);
      const std::size_t k = (static_cast<std::size_t>(y) * width + x) * 3;
      rgb[k] = value.r;
      rgb[k + 1] = value.g;
      rgb[k + 2] = value.b;
    }
  }
  return io::EnvMap(width, height, std::move(rgb), io::EnvMapping::LatLong, "function map");
}

// SH projection L_k = integral of f(w) y_k(w) dw of a function given analytically, by midpoint
// quadrature in (cos theta about +Y, phi) - equal-area cells, so the weights are all equal and
// the sum is exact up to O(cell^2) for the smooth integrands used here.
inline std::vector<glm::vec3> project_function(std::uint32_t order,
                                               const std::function<glm::vec3(glm::vec3)>& f,
                                               int rows = 256) {
  const double pi = 3.14159265358979323846;
  const int columns = 2 * rows;
  const double cell = 4.0 * pi / (double(rows) * columns);
  std::vector<glm::dvec3> sum(order * order, glm::dvec3(0.0));
  std::vector<float> y(order * order);
  for (int r = 0; r < rows; ++r) {
    const double cos_t = 1.0 - 2.0 * (r + 0.5) / rows, sin_t = std::sqrt(1.0 - cos_t * cos_t);
    for (int c = 0; c < columns; ++c) {
      const double phi = 2.0 * pi * (c + 0.5) / columns;
      const glm::vec3 dir(float(sin_t * std::cos(phi)), float(cos_t), float(sin_t * std::sin(phi)));
      prt_sh_eval(order, &dir.x, y.data());
      const glm::dvec3 value(f(dir));
      for (std::size_t k = 0; k < y.size(); ++k) sum[k] += value * double(y[k]);
    }
  }
  std::vector<glm::vec3> out;
  for (const glm::dvec3& s : sum) out.emplace_back(s * cell);
  return out;
}

}  // namespace prt::bake::test
