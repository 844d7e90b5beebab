// SPDX-License-Identifier: MIT
#include "prt/baker/mesh_generators.hpp"

#include <cmath>

#include "numbers.hpp"

namespace prt::bake {
namespace {

// The shared kPi, rounded once to the float the generators work in.
constexpr float kPiFloat = static_cast<float>(kPi);

void append_triangle(Mesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const auto& p = mesh.positions;
  if (glm::length(glm::cross(p[b] - p[a], p[c] - p[a])) <= 1e-12f) return;
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// A disc of `rings` rings around `centre`, facing `up_sign` * +Y; the angle runs so that the
// triangles wind counter-clockwise seen from the side the normal points to.
Mesh make_disc_mesh(int material, glm::vec3 centre, float radius, int rings, int cols,
                    float up_sign) {
  const glm::vec3 normal(0.0f, up_sign, 0.0f);
  return make_grid_mesh("", material, rings, cols, [&](float u, float v) {
    const float a = up_sign * u * 2 * kPiFloat, r = radius * (1.0f - v);
    return SurfacePoint{centre + glm::vec3(r * std::cos(a), 0.0f, r * std::sin(a)), normal};
  });
}

}  // namespace

Mesh make_grid_mesh(std::string name, int material, int rows, int cols,
                    const ParametricSurface& surface) {
  Mesh mesh;
  mesh.name = std::move(name);
  mesh.material = material;
  for (int r = 0; r <= rows; ++r) {
    for (int c = 0; c <= cols; ++c) {
      auto [p, n] = surface(float(c) / float(cols), float(r) / float(rows));
      mesh.positions.push_back(p);
      mesh.normals.push_back(glm::normalize(n));
    }
  }
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      std::uint32_t i0 = std::uint32_t(r * (cols + 1) + c), i1 = i0 + 1;
      std::uint32_t i2 = i0 + std::uint32_t(cols + 1), i3 = i2 + 1;
      append_triangle(mesh, i0, i2, i1);
      append_triangle(mesh, i1, i2, i3);
    }
  }
  return mesh;
}

Mesh make_plane_mesh(std::string name, int material, float half_x, float half_z, int cells_x,
                     int cells_z) {
  return make_grid_mesh(std::move(name), material, cells_z, cells_x, [&](float u, float v) {
    return SurfacePoint{glm::vec3(-half_x + 2 * half_x * u, 0.0f, -half_z + 2 * half_z * v),
                        glm::vec3(0, 1, 0)};
  });
}

Mesh make_sphere_mesh(int material, glm::vec3 centre, float radius, int rows, int cols) {
  return make_grid_mesh("sphere", material, rows, cols, [&](float u, float v) {
    float theta = v * kPiFloat, phi = -u * 2 * kPiFloat;
    glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    return SurfacePoint{centre + radius * n, n};
  });
}

Mesh make_torus_mesh(int material, glm::vec3 centre, float major, float minor, int rows, int cols) {
  return make_grid_mesh("torus", material, rows, cols, [&](float u, float v) {
    float a = u * 2 * kPiFloat, b = v * 2 * kPiFloat;
    glm::vec3 ring(std::cos(a), 0.0f, std::sin(a));
    glm::vec3 n = std::cos(b) * ring + std::sin(b) * glm::vec3(0, 1, 0);
    return SurfacePoint{centre + major * ring + minor * n, n};
  });
}

Mesh make_box_mesh(int material, glm::vec3 centre, float half, float yaw, int cells) {
  Mesh box;
  box.name = "box";
  box.material = material;
  const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      glm::vec3 n = sign * axes[axis];
      glm::vec3 s = axes[(axis + 1) % 3], t = -sign * axes[(axis + 2) % 3];
      append_mesh(box, make_grid_mesh("", material, cells, cells, [&](float u, float v) {
                    return SurfacePoint{half * (n + (2 * u - 1) * s + (2 * v - 1) * t), n};
                  }));
    }
  }
  const float c = std::cos(yaw), s = std::sin(yaw);
  for (std::size_t i = 0; i < box.positions.size(); ++i) {
    glm::vec3& p = box.positions[i];
    glm::vec3& n = box.normals[i];
    p = centre + glm::vec3(c * p.x + s * p.z, p.y, -s * p.x + c * p.z);
    n = glm::vec3(c * n.x + s * n.z, n.y, -s * n.x + c * n.z);
  }
  return box;
}

Mesh make_cylinder_mesh(int material, glm::vec3 base_centre, float radius, float height, int rows,
                        int cols, int cap_rings) {
  Mesh cylinder = make_grid_mesh("cylinder", material, rows, cols, [&](float u, float v) {
    const float a = u * 2 * kPiFloat;
    const glm::vec3 n(std::cos(a), 0.0f, std::sin(a));
    return SurfacePoint{base_centre + radius * n + glm::vec3(0.0f, v * height, 0.0f), n};
  });
  append_mesh(cylinder, make_disc_mesh(material, base_centre, radius, cap_rings, cols, -1.0f));
  append_mesh(cylinder, make_disc_mesh(material, base_centre + glm::vec3(0.0f, height, 0.0f),
                                       radius, cap_rings, cols, 1.0f));
  return cylinder;
}

void append_mesh(Mesh& mesh, const Mesh& part) {
  const auto base = std::uint32_t(mesh.positions.size());
  for (std::uint32_t i : part.indices) mesh.indices.push_back(base + i);
  mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
  mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
}

}  // namespace prt::bake
