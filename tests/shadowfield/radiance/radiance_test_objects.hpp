// SPDX-License-Identifier: MIT
// The radiance tests' objects: a ShadowfieldObject from generated meshes (one mesh, object frame
// = the meshes' frame) and the Embree scene over it, with optional blockers that do not glow.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/shadowfield/shadowfield_brdf.hpp"
#include "prt/baker/shadowfield/shadowfield_object.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake::test {

// The meshes as one (indices shifted).
inline Mesh merged(const std::vector<Mesh>& parts) {
  Mesh mesh;
  mesh.name = "merged";
  for (const Mesh& part : parts) {
    const auto first = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
    mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
    for (std::uint32_t index : part.indices) mesh.indices.push_back(first + index);
  }
  return mesh;
}

inline ShadowfieldObject object_of(const Mesh& mesh, glm::vec3 albedo = glm::vec3(0.8f)) {
  ShadowfieldObject object;
  object.positions = mesh.positions;
  object.normals = mesh.normals;
  object.indices = mesh.indices;
  object.albedo.assign(mesh.positions.size(), albedo);
  return object;
}

inline void set_sphere(ShadowfieldObject& object, glm::vec3 centre, float radius) {
  for (int a = 0; a < 3; ++a) object.oof_shells.centre[a] = centre[a];
  object.oof_shells.radius = radius;
}

// The object's mesh first (mesh 0), then the blockers.
inline std::unique_ptr<EmbreeScene> rays_of(const Mesh& object, std::vector<Mesh> blockers = {}) {
  blockers.insert(blockers.begin(), object);
  return std::make_unique<EmbreeScene>(scene_of(std::move(blockers)), Context{});
}

inline ShadowfieldMaterial phong_material(double exponent, std::uint32_t terms) {
  ShadowfieldMaterial material;
  material.glossy = true;
  material.brdf =
      separate_brdf(brdf_function(PhongBrdf{exponent, 1.0, 0.0}), SeparableBrdfOptions{16, terms});
  return material;
}

}  // namespace prt::bake::test
