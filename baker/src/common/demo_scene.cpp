// SPDX-License-Identifier: MIT
#include "prt/baker/demo_scene.hpp"

#include <cmath>
#include <utility>

#include <glm/gtc/constants.hpp>

namespace prt::bake {
namespace {

constexpr float kPi = glm::pi<float>();

// Skips the zero-area triangles a grid makes where a row collapses to a point (sphere poles).
void append_triangle(Mesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const auto& p = mesh.positions;
  if (glm::length(glm::cross(p[b] - p[a], p[c] - p[a])) <= 1e-12f) return;
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// Appends a (rows+1) x (cols+1) vertex grid; position_normal(u, v) gives a point and its normal.
template <class Surface>
Mesh make_grid_mesh(std::string name, int material, int rows, int cols, Surface position_normal) {
  Mesh mesh;
  mesh.name = std::move(name);
  mesh.material = material;
  for (int r = 0; r <= rows; ++r) {
    for (int c = 0; c <= cols; ++c) {
      auto [p, n] = position_normal(float(c) / float(cols), float(r) / float(rows));
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

Mesh make_ground(int material) {
  const float half = 2.0f;
  return make_grid_mesh("ground", material, 64, 64, [&](float u, float v) {
    return std::pair{glm::vec3(-half + 2 * half * u, 0.0f, -half + 2 * half * v),
                     glm::vec3(0, 1, 0)};
  });
}

// Seam vertices are duplicated, so the sphere is closed geometrically but not topologically.
Mesh make_sphere(int material, glm::vec3 centre, float radius) {
  return make_grid_mesh("sphere", material, 48, 96, [&](float u, float v) {
    float theta = v * kPi, phi = -u * 2 * kPi;
    glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    return std::pair{centre + radius * n, n};
  });
}

Mesh make_torus(int material, glm::vec3 centre, float major, float minor) {
  return make_grid_mesh("torus", material, 48, 96, [&](float u, float v) {
    float a = u * 2 * kPi, b = v * 2 * kPi;
    glm::vec3 ring(std::cos(a), 0.0f, std::sin(a));
    glm::vec3 n = std::cos(b) * ring + std::sin(b) * glm::vec3(0, 1, 0);
    return std::pair{centre + major * ring + minor * n, n};
  });
}

// Six subdivided faces with their own vertices (sharp edges keep flat normals).
Mesh make_box(int material, glm::vec3 centre, float half, float yaw) {
  Mesh box;
  box.name = "box";
  box.material = material;
  const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      glm::vec3 n = sign * axes[axis];
      glm::vec3 s = axes[(axis + 1) % 3], t = -sign * axes[(axis + 2) % 3];
      Mesh face = make_grid_mesh("", material, 16, 16, [&](float u, float v) {
        return std::pair{half * (n + (2 * u - 1) * s + (2 * v - 1) * t), n};
      });
      auto base = std::uint32_t(box.positions.size());
      for (std::uint32_t i : face.indices) box.indices.push_back(base + i);
      box.positions.insert(box.positions.end(), face.positions.begin(), face.positions.end());
      box.normals.insert(box.normals.end(), face.normals.begin(), face.normals.end());
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

Material diffuse(std::string name, glm::vec3 colour) {
  Material m;
  m.name = std::move(name);
  m.base_color = glm::vec4(colour, 1.0f);
  return m;
}

}  // namespace

Scene make_demo_scene() {
  Scene scene;
  scene.source = "prtkit demo scene";
  scene.materials = {
      diffuse("ground", {0.55f, 0.55f, 0.52f}), diffuse("clay", {0.80f, 0.32f, 0.18f}),
      diffuse("glaze", {0.20f, 0.35f, 0.75f}), diffuse("plaster", {0.85f, 0.85f, 0.80f})};
  scene.meshes.push_back(make_ground(0));
  scene.meshes.push_back(make_sphere(1, {-0.9f, 0.6f, 0.2f}, 0.6f));
  scene.meshes.push_back(make_torus(2, {0.9f, 0.2f, 0.5f}, 0.5f, 0.2f));
  scene.meshes.push_back(make_box(3, {0.3f, 0.4f, -0.9f}, 0.4f, 0.5f));
  for (Mesh& mesh : scene.meshes) {
    mesh.local_positions = mesh.positions;
    mesh.local_normals = mesh.normals;
  }
  return scene;
}

io::EnvMap make_demo_sky(int width) {
  const int height = width / 2;
  // Sun behind the camera's left shoulder, 35 degrees up, so shadows fall toward the back right.
  const glm::vec3 sun_dir = glm::normalize(glm::vec3(-0.55f, 0.7f, 0.75f));
  const float sun_cos_radius = std::cos(glm::radians(2.0f));
  std::vector<float> rgb(std::size_t(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // Inverse of the lat-long convention in formats/SPEC.md.
      float theta = (float(y) + 0.5f) / float(height) * kPi;
      float phi = ((float(x) + 0.5f) / float(width) - 0.5f) * 2 * kPi;
      glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                  -std::sin(theta) * std::cos(phi));
      glm::vec3 radiance;
      if (d.y >= 0) {
        float t = std::pow(1.0f - d.y, 3.0f);
        radiance = glm::mix(glm::vec3(0.25f, 0.45f, 1.0f), glm::vec3(1.0f, 0.95f, 0.9f), t);
      } else {
        radiance = glm::vec3(0.35f, 0.3f, 0.25f) * (0.6f + 0.4f * (1.0f + d.y));
      }
      if (glm::dot(d, sun_dir) >= sun_cos_radius) radiance = glm::vec3(1500.0f, 1350.0f, 1150.0f);
      float* px = &rgb[(std::size_t(y) * width + x) * 3];
      px[0] = radiance.r, px[1] = radiance.g, px[2] = radiance.b;
    }
  }
  return io::EnvMap(width, height, std::move(rgb), io::EnvMapping::LatLong, "prtkit demo sky");
}

}  // namespace prt::bake
