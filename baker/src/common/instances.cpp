// SPDX-License-Identifier: MIT
#include "prt/baker/instances.hpp"

#include <cmath>
#include <string>

namespace prt::bake {
namespace {

bool is_rotation(const glm::mat3& r) {
  const glm::mat3 gram = glm::transpose(r) * r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const float expected = i == j ? 1.0f : 0.0f;
      if (!(std::abs(gram[i][j] - expected) <= 1e-4f)) return false;
    }
  }
  return std::abs(glm::determinant(r) - 1.0f) <= 1e-4f;
}

void check_instance(const Instance& instance, std::size_t index, std::size_t objects) {
  const std::string name = "instance " + std::to_string(index);
  if (instance.object >= objects) {
    throw Error(name + ": object " + std::to_string(instance.object) + " out of range (" +
                std::to_string(objects) + " objects)");
  }
  if (!is_rotation(instance.rotation)) throw Error(name + ": rotation is not a proper rotation");
  if (!(std::isfinite(instance.scale) && instance.scale > 0.0f)) {
    throw Error(name + ": scale must be finite and positive");
  }
  const glm::vec3& t = instance.translation;
  if (!(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z))) {
    throw Error(name + ": translation must be finite");
  }
}

Mesh placed_mesh(const Mesh& object_mesh, const Instance& instance, int material_offset) {
  Mesh mesh = object_mesh;
  mesh.node = -1;
  mesh.skin = -1;
  mesh.joints0.clear();
  mesh.weights0.clear();
  if (mesh.material >= 0) mesh.material += material_offset;
  mesh.local_positions = object_mesh.positions;
  mesh.local_normals = object_mesh.normals;
  for (glm::vec3& p : mesh.positions) p = instance.place(p);
  for (glm::vec3& n : mesh.normals) n = instance.rotation * n;
  for (glm::vec4& t : mesh.tangents) t = glm::vec4(instance.rotation * glm::vec3(t), t.w);
  return mesh;
}

}  // namespace

PlacedScene place_instances(const std::vector<Scene>& objects,
                            const std::vector<Instance>& instances) {
  for (std::size_t i = 0; i < instances.size(); ++i) {
    check_instance(instances[i], i, objects.size());
  }
  PlacedScene placed;
  placed.scene.source = "instances";
  // Each object's materials and images, once.
  std::vector<int> material_offset(objects.size(), 0);
  for (std::size_t o = 0; o < objects.size(); ++o) {
    material_offset[o] = static_cast<int>(placed.scene.materials.size());
    const int image_offset = static_cast<int>(placed.scene.images.size());
    for (Material material : objects[o].materials) {
      if (material.base_color_texture >= 0) material.base_color_texture += image_offset;
      placed.scene.materials.push_back(std::move(material));
    }
    placed.scene.images.insert(placed.scene.images.end(), objects[o].images.begin(),
                               objects[o].images.end());
  }
  std::size_t vertices = 0;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const Instance& instance = instances[i];
    placed.first_vertex.push_back(vertices);
    placed.first_mesh.push_back(placed.scene.meshes.size());
    for (const Mesh& object_mesh : objects[instance.object].meshes) {
      placed.scene.meshes.push_back(
          placed_mesh(object_mesh, instance, material_offset[instance.object]));
      placed.instance_of_mesh.push_back(i);
      placed.object_of_mesh.push_back(instance.object);
      vertices += object_mesh.vertex_count();
    }
  }
  placed.first_vertex.push_back(vertices);
  placed.first_mesh.push_back(placed.scene.meshes.size());
  return placed;
}

}  // namespace prt::bake
