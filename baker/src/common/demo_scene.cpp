// SPDX-License-Identifier: MIT
#include "prt/baker/demo_scene.hpp"

#include <cmath>
#include <utility>


#include "prt/baker/mesh_generators.hpp"

namespace prt::bake {
namespace {

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
  scene.meshes.push_back(make_plane_mesh("ground", 0, 2.0f, 2.0f, 64, 64));
  scene.meshes.push_back(make_sphere_mesh(1, {-0.9f, 0.6f, 0.2f}, 0.6f));
  scene.meshes.push_back(make_torus_mesh(2, {0.9f, 0.2f, 0.5f}, 0.5f, 0.2f));
  scene.meshes.push_back(make_box_mesh(3, {0.3f, 0.4f, -0.9f}, 0.4f, 0.5f));
  for (Mesh& mesh : scene.meshes) {
    mesh.local_positions = mesh.positions;
    mesh.local_normals = mesh.normals;
  }
  return scene;
}

}  // namespace prt::bake
