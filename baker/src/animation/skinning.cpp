// SPDX-License-Identifier: MIT
// Joint matrices and linear blend skinning (glTF 2.0 §3.7.3): a mesh placed at a pose.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

#include "prt/baker/animation.hpp"

namespace prt::bake {

std::vector<glm::mat4> joint_matrices(const Skin& skin, const std::vector<glm::mat4>& world) {
  std::vector<glm::mat4> joints;
  joints.reserve(skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const std::size_t node = static_cast<std::size_t>(skin.joints[j]);
    if (node >= world.size()) throw Error("skin '" + skin.name + "' names a missing joint node");
    joints.push_back(world[node] * skin.inverse_bind[j]);
  }
  return joints;
}

namespace {

// The rotation of a matrix's linear part: its orthogonal polar factor, found by averaging with
// the inverse transpose until it settles (Higham's iteration; it converges quadratically for
// the well-conditioned transforms of a rig).
glm::quat rotation_of(const glm::mat4& m) {
  glm::dmat3 r(m);
  for (int i = 0; i < 32; ++i) {
    const glm::dmat3 next = 0.5 * (r + glm::transpose(glm::inverse(r)));
    double change = 0.0;
    for (int c = 0; c < 3; ++c) change = std::max(change, glm::length(next[c] - r[c]));
    r = next;
    if (change < 1e-15) break;
  }
  if (glm::determinant(r) < 0.0) r = -r;  // a mirrored joint: keep a proper rotation
  return glm::normalize(glm::quat(glm::quat_cast(r)));
}

}  // namespace

std::vector<glm::quat> bind_local_rotations(const Scene& scene, const Skin& skin) {
  std::vector<int> joint_of_node(scene.nodes.size(), -1);
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    joint_of_node.at(static_cast<std::size_t>(skin.joints[j])) = static_cast<int>(j);
  std::vector<glm::quat> out;
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const Node& node = scene.nodes[static_cast<std::size_t>(skin.joints[j])];
    const int parent = node.parent >= 0 ? joint_of_node[static_cast<std::size_t>(node.parent)] : -1;
    if (parent < 0) {
      out.push_back(node.rotation);
      continue;
    }
    // Both bind transforms map the skin's mesh space, so whatever places that space in the
    // world cancels out of the parent-to-child transform.
    const glm::dmat4 local = glm::dmat4(skin.inverse_bind[static_cast<std::size_t>(parent)]) *
                             glm::inverse(glm::dmat4(skin.inverse_bind[j]));
    out.push_back(rotation_of(glm::mat4(local)));
  }
  return out;
}

glm::mat4 blend_joints(const glm::u16vec4& joints, const glm::vec4& weights,
                       const std::vector<glm::mat4>& joint_matrices, const glm::mat4& fallback) {
  // Files often store weights that do not quite sum to 1 (the spec asks for it, exporters
  // round): dividing by the sum keeps a rigidly bound vertex rigid.
  const float total = weights.x + weights.y + weights.z + weights.w;
  if (!(total > 0.0f)) return fallback;
  glm::mat4 m(0.0f);
  for (int k = 0; k < 4; ++k) {
    const std::size_t joint = joints[k];
    if (weights[k] != 0.0f && joint < joint_matrices.size())
      m += (weights[k] / total) * joint_matrices[joint];
  }
  return m;
}

namespace {

// The transform of each vertex of `mesh` at the pose.
std::vector<glm::mat4> vertex_transforms(const Scene& scene, const std::vector<glm::mat4>& world,
                                         const Mesh& mesh) {
  const glm::mat4 node_world = mesh.node >= 0 && static_cast<std::size_t>(mesh.node) < world.size()
                                   ? world[static_cast<std::size_t>(mesh.node)]
                                   : glm::mat4(1.0f);  // OBJ meshes are imported in world space
  const std::size_t n = mesh.local_positions.size();
  std::vector<glm::mat4> out(n, node_world);
  if (mesh.skin < 0) return out;
  if (static_cast<std::size_t>(mesh.skin) >= scene.skins.size() || mesh.joints0.size() != n ||
      mesh.weights0.size() != n) {
    throw Error("mesh '" + mesh.name + "' is skinned but its skin or joint attributes are missing");
  }
  const std::vector<glm::mat4> joints = joint_matrices(scene.skins[mesh.skin], world);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = blend_joints(mesh.joints0[i], mesh.weights0[i], joints, node_world);
  return out;
}

// Normals through each vertex's inverse transpose, divided by their length (the importer's
// arithmetic). A vertex whose transform collapsed its normal takes the area-weighted normal of the
// placed surface, as the importer does for a zero normal in the file.
void place_normals(const std::vector<glm::mat4>& transform, Mesh& mesh) {
  std::vector<glm::vec3> fallback;
  mesh.normals.resize(transform.size());
  for (std::size_t i = 0; i < transform.size(); ++i) {
    glm::vec3 normal = glm::inverseTranspose(glm::mat3(transform[i])) * mesh.local_normals[i];
    const float len = glm::length(normal);
    if (len > 1e-20f && std::isfinite(len)) {
      normal /= len;
    } else {
      if (fallback.empty()) {  // rare: a copy keeps the normals placed so far
        Mesh surface = mesh;
        generate_normals(surface);
        fallback = surface.normals;
      }
      normal = fallback[i];
    }
    mesh.normals[i] = normal;
  }
}

}  // namespace

void place_mesh(const Scene& scene, const std::vector<glm::mat4>& world, Mesh& mesh) {
  const std::vector<glm::mat4> transform = vertex_transforms(scene, world, mesh);
  const std::size_t n = transform.size();
  mesh.positions.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    mesh.positions[i] = glm::vec3(transform[i] * glm::vec4(mesh.local_positions[i], 1.0f));
  if (mesh.normals_generated || mesh.local_normals.size() != n) {
    generate_normals(mesh);  // the file had none: the placed surface decides
    mesh.normals_generated = true;
  } else {
    place_normals(transform, mesh);
  }
  // World tangents cannot be carried through a pose (the mesh keeps no local ones): they are
  // derived again from the UVs at the placed positions.
  if (!mesh.tangents.empty()) generate_tangents(mesh);
}

Scene posed_scene(const Scene& scene, const ScenePose& pose) {
  Scene posed = scene;
  const std::vector<glm::mat4> world = pose.world_matrices();
  for (Mesh& mesh : posed.meshes) place_mesh(scene, world, mesh);
  return posed;
}

}  // namespace prt::bake
