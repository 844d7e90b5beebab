// SPDX-License-Identifier: MIT
// Meshes and environments generated in code for the render tests: their exact shapes are what
// the analytic expectations are computed from.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/scene.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake::test {

// Icosphere: a subdivided icosahedron projected onto the sphere; closed and convex, vertex
// normals are the exact sphere normals. level 3: 642 vertices, level 4: 2562.
inline Mesh make_icosphere(int level, float radius = 1.0f, glm::vec3 centre = glm::vec3(0.0f)) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& v : p) v = glm::normalize(v);
  std::vector<std::uint32_t> f = {0, 11, 5, 0, 5,  1,  0,  1,  7,  0,  7, 10, 0, 10, 11,
                                  1, 5,  9, 5, 11, 4,  11, 10, 2,  10, 7, 6,  7, 1,  8,
                                  3, 9,  4, 3, 4,  2,  3,  2,  6,  3,  6, 8,  3, 8,  9,
                                  4, 9,  5, 2, 4,  11, 6,  2,  10, 8,  6, 7,  9, 8,  1};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      p.push_back(glm::normalize(p[a] + p[b]));
      return midpoint[key] = static_cast<std::uint32_t>(p.size() - 1);
    };
    std::vector<std::uint32_t> next;
    for (std::size_t i = 0; i < f.size(); i += 3) {
      const std::uint32_t a = f[i], b = f[i + 1], c = f[i + 2];
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    f = std::move(next);
  }
  Mesh mesh;
  mesh.name = "icosphere";
  for (const auto& v : p) {
    mesh.positions.push_back(centre + radius * v);
    mesh.normals.push_back(v);
  }
  mesh.indices = std::move(f);
  return mesh;
}

// A square grid in the plane y = height, [-half, half]^2 in x and z, normal +Y (counter-clockwise
// seen from above), n x n cells.
inline Mesh make_plane(float half, int n, float height = 0.0f) {
  Mesh mesh;
  mesh.name = "plane";
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      mesh.positions.emplace_back(-half + 2.0f * half * i / n, height, -half + 2.0f * half * j / n);
      mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  }
  return mesh;
}

// An open box: floor [-1,1]^2 at y = 0 with a vertex at its centre (vertex 0, normal +Y), and
// four walls of the given height meeting the floor's edges exactly; no lid.
inline Mesh make_open_box(float height) {
  Mesh mesh;
  mesh.name = "open box";
  auto add = [&](glm::vec3 p, glm::vec3 n) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(n);
    return static_cast<std::uint32_t>(mesh.positions.size() - 1);
  };
  const glm::vec3 up(0, 1, 0);
  const std::uint32_t centre = add({0, 0, 0}, up);
  const std::uint32_t c0 = add({-1, 0, -1}, up), c1 = add({1, 0, -1}, up), c2 = add({1, 0, 1}, up),
                      c3 = add({-1, 0, 1}, up);
  mesh.indices.insert(mesh.indices.end(),
                      {centre, c1, c0, centre, c2, c1, centre, c3, c2, centre, c0, c3});
  const glm::vec3 corners[4] = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  for (int w = 0; w < 4; ++w) {
    const glm::vec3 a = corners[w], b = corners[(w + 1) % 4];
    const glm::vec3 inward = -glm::normalize(glm::vec3(a.x + b.x, 0, a.z + b.z));
    const std::uint32_t i0 = add(a, inward), i1 = add(b, inward),
                        i2 = add(b + glm::vec3(0, height, 0), inward),
                        i3 = add(a + glm::vec3(0, height, 0), inward);
    mesh.indices.insert(mesh.indices.end(), {i0, i1, i2, i0, i2, i3});
  }
  return mesh;
}

inline Scene scene_of(std::vector<Mesh> meshes) {
  Scene scene;
  scene.source = "generated";
  scene.meshes = std::move(meshes);
  return scene;
}

// A lat-long map, black but for a block of `size` x `size` texels of radiance `sun` whose
// top-left texel is (x, y).
inline io::EnvMap make_sun_map(int width, int x, int y, int size, glm::vec3 sun) {
  const int height = width / 2;
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3, 0.0f);
  for (int j = y; j < y + size; ++j) {
    for (int i = x; i < x + size; ++i) {
      const std::size_t k = (static_cast<std::size_t>(j) * width + i) * 3;
      rgb[k] = sun.r;
      rgb[k + 1] = sun.g;
      rgb[k + 2] = sun.b;
    }
  }
  return io::EnvMap(width, height, std::move(rgb), io::EnvMapping::LatLong, "sun map");
}

}  // namespace prt::bake::test
