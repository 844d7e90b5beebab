// SPDX-License-Identifier: MIT
// Rigid instances: objects (meshes in their own frame) placed any number of times, each with a
// rotation, a translation and a uniform scale, flattened into one world-space Scene that the
// reference renderer (or any bake stage) reads. world = s R local + t, as technique `shadowfield`
// places its instances (docs/shadowfield/design.md).
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"

namespace prt::bake {

struct Instance {
  std::size_t object = 0;    // index into the objects
  glm::mat3 rotation{1.0f};  // proper rotation (orthonormal, determinant +1)
  glm::vec3 translation{0.0f};
  float scale = 1.0f;  // uniform, > 0

  // The rotation of a unit quaternion (w, x, y, z).
  static glm::mat3 rotation_of(const glm::quat& q) { return glm::mat3_cast(glm::normalize(q)); }
  glm::vec3 place(const glm::vec3& local) const { return scale * (rotation * local) + translation; }
};

struct PlacedScene {
  // One mesh per (instance, object mesh), instances in order, each instance's meshes in its
  // object's order; positions s R x + t, normals R n, tangents R t (w kept), local_positions and
  // local_normals the object's. Materials and images of every object are appended once, object
  // by object, and each mesh's indices into them shifted accordingly. Nodes, skins and animations
  // are not carried over (mesh.node and mesh.skin are -1).
  Scene scene;
  // first_vertex[i]: the world vertex (Scene order) of instance i's object vertex 0; the
  // object's vertices follow in their own order (meshes concatenated), so object vertex v of
  // instance i is world vertex first_vertex[i] + v. One more entry at the end: the total.
  std::vector<std::size_t> first_vertex;
  // first_mesh[i]: the world mesh of instance i's first object mesh (same layout), plus the total.
  std::vector<std::size_t> first_mesh;
  // instance_of_mesh[m], object_of_mesh[m]: the instance world mesh m belongs to, and its object.
  std::vector<std::size_t> instance_of_mesh;
  std::vector<std::size_t> object_of_mesh;

  std::size_t world_vertex(std::size_t instance, std::size_t object_vertex) const {
    return first_vertex[instance] + object_vertex;
  }
  // A per-object value (e.g. a BRDF) for every world mesh, e.g. ReferenceSettings::mesh_brdfs.
  template <typename T>
  std::vector<T> mesh_values(const std::vector<T>& per_object) const {
    std::vector<T> values;
    values.reserve(object_of_mesh.size());
    for (const std::size_t object : object_of_mesh) values.push_back(per_object.at(object));
    return values;
  }
  // The slice of a per-vertex array (Scene order) that belongs to `instance`, in its object's
  // vertex order.
  template <typename T>
  std::vector<T> instance_values(const std::vector<T>& per_world_vertex,
                                 std::size_t instance) const {
    return std::vector<T>(per_world_vertex.begin() + first_vertex[instance],
                          per_world_vertex.begin() + first_vertex[instance + 1]);
  }
};

// Places the instances. Throws Error for an object index out of range, a rotation that is not a
// proper rotation (to 1e-4), or a scale that is not finite and positive; a translation that is
// not finite is an error too.
PlacedScene place_instances(const std::vector<Scene>& objects,
                            const std::vector<Instance>& instances);

}  // namespace prt::bake
