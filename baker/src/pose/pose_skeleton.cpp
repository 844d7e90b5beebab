// SPDX-License-Identifier: MIT
// The skeleton and skin of technique `pose` as formats/SPEC.md §7.3 stores them, and the pose
// features of joint rotations.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "prt/baker/animation.hpp"
#include "prt/baker/pose/pose_training.hpp"

namespace prt::bake {
namespace {

constexpr std::size_t kMaxJoints = 256;  // joint indices are stored as u8

std::string scene_name(const Scene& scene) {
  return scene.source.empty() ? std::string("scene") : scene.source;
}

// The one skin every mesh is skinned by.
const Skin& the_skin(const Scene& scene) {
  const std::string file = scene_name(scene);
  if (scene.skins.empty()) throw Error(file + ": pose needs a skinned character; it has no skin");
  if (scene.skins.size() > 1) {
    throw Error(file + ": pose bakes one skin; the file has " + std::to_string(scene.skins.size()));
  }
  for (const Mesh& mesh : scene.meshes) {
    if (mesh.skin != 0) {
      throw Error(file + ": mesh '" + mesh.name +
                  "' is not skinned by the skin; pose needs every mesh skinned by one skin");
    }
  }
  if (scene.meshes.empty()) throw Error(file + ": pose needs a mesh; the file has none");
  return scene.skins[0];
}

// w / 65535 summing to exactly 65535 where any weight is positive: the weights normalised as
// blend_joints does (divided by their sum), rounded down, and the missing units given to the
// largest remainders (ties: the lower slot). Zero weights stay zero.
glm::u16vec4 quantise_weights(const glm::vec4& weights) {
  const float total = weights.x + weights.y + weights.z + weights.w;
  glm::u16vec4 out(0);
  if (!(total > 0.0f)) return out;
  std::array<double, 4> remainder{};
  long sum = 0;
  for (int k = 0; k < 4; ++k) {
    const std::size_t slot = static_cast<std::size_t>(k);
    const double share = std::min(65535.0, static_cast<double>(weights[k] / total) * 65535.0);
    const double down = std::floor(share);
    out[k] = static_cast<std::uint16_t>(down);
    sum += static_cast<long>(down);
    remainder[slot] = weights[k] > 0.0f ? share - down : -INFINITY;  // never given a unit
  }
  // Float rounding of the shares leaves at most a few units to move either way.
  for (; sum < 65535; ++sum) {
    const std::size_t best = static_cast<std::size_t>(
        std::max_element(remainder.begin(), remainder.end()) - remainder.begin());
    out[static_cast<int>(best)] = static_cast<std::uint16_t>(out[static_cast<int>(best)] + 1);
    remainder[best] -= 1.0;
  }
  for (; sum > 65535; --sum) {
    std::size_t worst = 4;
    for (std::size_t k = 0; k < 4; ++k) {
      if (out[static_cast<int>(k)] > 0 && (worst == 4 || remainder[k] < remainder[worst]))
        worst = k;
    }
    out[static_cast<int>(worst)] = static_cast<std::uint16_t>(out[static_cast<int>(worst)] - 1);
    remainder[worst] += 1.0;
  }
  return out;
}

}  // namespace

PoseSkeleton pose_skeleton(const Scene& scene) {
  const std::string file = scene_name(scene);
  const Skin& skin = the_skin(scene);
  const std::size_t joint_count = skin.joints.size();
  if (joint_count == 0) throw Error(file + ": skin '" + skin.name + "' has no joints");
  if (joint_count > kMaxJoints) {
    throw Error(file + ": skin '" + skin.name + "' has " + std::to_string(joint_count) +
                " joints; pose stores at most " + std::to_string(kMaxJoints));
  }
  std::vector<int> joint_of_node(scene.nodes.size(), -1);
  for (std::size_t j = 0; j < joint_count; ++j) {
    const int node = skin.joints[j];
    if (node < 0 || static_cast<std::size_t>(node) >= scene.nodes.size()) {
      throw Error(file + ": skin '" + skin.name + "' names a missing joint node");
    }
    if (joint_of_node[static_cast<std::size_t>(node)] >= 0) {
      throw Error(file + ": skin '" + skin.name + "' names node " + std::to_string(node) +
                  " twice");
    }
    joint_of_node[static_cast<std::size_t>(node)] = static_cast<int>(j);
  }

  PoseSkeleton out;
  const std::vector<glm::quat> bind = bind_local_rotations(scene, skin);
  out.joints.resize(joint_count);
  for (std::size_t j = 0; j < joint_count; ++j) {
    PoseSkeleton::Joint& joint = out.joints[j];
    const Node& node = scene.nodes[static_cast<std::size_t>(skin.joints[j])];
    joint.bind_rotation = bind[j];
    joint.rest_translation = node.translation;
    joint.rest_scale = node.scale;
    joint.inverse_bind = skin.inverse_bind[j];
    // Up the tree to the nearest joint, multiplying the non-joint nodes on the way.
    glm::mat4 pre(1.0f);
    int ancestor = node.parent;
    while (ancestor >= 0 && joint_of_node[static_cast<std::size_t>(ancestor)] < 0) {
      pre = scene.nodes[static_cast<std::size_t>(ancestor)].local * pre;
      ancestor = scene.nodes[static_cast<std::size_t>(ancestor)].parent;
    }
    if (ancestor >= 0) {
      joint.parent = joint_of_node[static_cast<std::size_t>(ancestor)];
      joint.pre = pre;
    } else {
      joint.parent = -1;
      joint.pre = node.parent >= 0 ? scene.nodes[static_cast<std::size_t>(node.parent)].world
                                   : glm::mat4(1.0f);
    }
  }

  // Parents first: by depth in the joint tree, ties in skin order.
  std::vector<std::size_t> depth(joint_count, 0);
  for (std::size_t j = 0; j < joint_count; ++j) {
    for (int p = out.joints[j].parent; p >= 0; p = out.joints[static_cast<std::size_t>(p)].parent)
      ++depth[j];
  }
  for (std::size_t j = 0; j < joint_count; ++j)
    out.eval_order.push_back(static_cast<std::uint32_t>(j));
  std::stable_sort(out.eval_order.begin(), out.eval_order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return depth[a] < depth[b]; });

  // The skin's `skeleton` when it is a root joint, else the first root joint.
  const int named =
      skin.skeleton >= 0 && static_cast<std::size_t>(skin.skeleton) < scene.nodes.size()
          ? joint_of_node[static_cast<std::size_t>(skin.skeleton)]
          : -1;
  if (named >= 0 && out.joints[static_cast<std::size_t>(named)].parent < 0) {
    out.model_joint = static_cast<std::uint32_t>(named);
  } else {
    for (std::size_t j = 0; j < joint_count; ++j) {
      if (out.joints[j].parent < 0) {
        out.model_joint = static_cast<std::uint32_t>(j);
        break;
      }
    }
  }

  for (const Mesh& mesh : scene.meshes) {
    const std::size_t n = mesh.vertex_count();
    if (mesh.local_positions.size() != n || mesh.local_normals.size() != n ||
        mesh.joints0.size() != n || mesh.weights0.size() != n) {
      throw Error(file + ": mesh '" + mesh.name +
                  "' lacks local positions, normals or skin weights");
    }
    for (std::size_t v = 0; v < n; ++v) {
      const glm::vec4 w = mesh.weights0[v];
      glm::u8vec4 joints(0);
      for (int k = 0; k < 4; ++k) {
        if (!(w[k] >= 0.0f) || !std::isfinite(w[k])) {
          throw Error(file + ": mesh '" + mesh.name + "' vertex " + std::to_string(v) +
                      " has a negative or non-finite skin weight");
        }
        if (w[k] == 0.0f) continue;  // its joint is never read: stored as 0
        if (mesh.joints0[v][k] >= joint_count) {
          throw Error(file + ": mesh '" + mesh.name + "' vertex " + std::to_string(v) +
                      " names joint " + std::to_string(mesh.joints0[v][k]) + " of a skin of " +
                      std::to_string(joint_count));
        }
        joints[k] = static_cast<std::uint8_t>(mesh.joints0[v][k]);
      }
      out.local_positions.push_back(mesh.local_positions[v]);
      out.local_normals.push_back(mesh.local_normals[v]);
      out.skin_joints.push_back(joints);
      out.skin_weights.push_back(quantise_weights(w));
    }
  }
  return out;
}

std::vector<float> pose_features(const PoseSkeleton& skeleton,
                                 const std::vector<glm::quat>& rotations) {
  const std::size_t joint_count = skeleton.joints.size();
  if (rotations.size() != joint_count) {
    throw Error("pose features: " + std::to_string(rotations.size()) + " rotations for " +
                std::to_string(joint_count) + " joints");
  }
  std::vector<float> out(3 * joint_count, 0.0f);
  for (std::size_t j = 0; j < joint_count; ++j) {
    if (j == skeleton.model_joint) continue;  // it moves the model frame, not the model
    const glm::quat& b0 = skeleton.joints[j].bind_rotation;
    const glm::dquat b = glm::normalize(glm::dquat(b0.w, b0.x, b0.y, b0.z));
    const glm::dquat q =
        glm::normalize(glm::dquat(rotations[j].w, rotations[j].x, rotations[j].y, rotations[j].z));
    glm::dquat r = glm::conjugate(b) * q;  // Hamilton product
    if (r.w < 0.0) r = -r;
    const glm::dvec3 axis(r.x, r.y, r.z);
    const double s = glm::length(axis);
    const glm::dvec3 a = s > 0.0 ? (2.0 * std::atan2(s, r.w) / s) * axis : 2.0 * axis;
    for (int c = 0; c < 3; ++c) out[3 * j + static_cast<std::size_t>(c)] = static_cast<float>(a[c]);
  }
  return out;
}

namespace {

// T(t) R(q) S(s) in double.
glm::dmat4 joint_local(const PoseSkeleton::Joint& joint, const glm::quat& q0) {
  const glm::dquat q = glm::normalize(glm::dquat(q0.w, q0.x, q0.y, q0.z));
  glm::dmat4 m(glm::mat3_cast(q));
  for (int c = 0; c < 3; ++c) m[c] *= double(joint.rest_scale[c]);
  m[3] = glm::dvec4(glm::dvec3(joint.rest_translation), 1.0);
  return m;
}

// K_j = M^-1 G_j IBM_j of every joint (SPEC §7.3).
std::vector<glm::dmat4> skinning_matrices(const PoseSkeleton& s,
                                          const std::vector<glm::quat>& rotations) {
  if (rotations.size() != s.joints.size()) throw Error("pose: one rotation per joint needed");
  std::vector<glm::dmat4> g(s.joints.size(), glm::dmat4(1.0));
  for (std::uint32_t j : s.eval_order) {
    const PoseSkeleton::Joint& joint = s.joints[j];
    const glm::dmat4 local = glm::dmat4(joint.pre) * joint_local(joint, rotations[j]);
    g[j] = joint.parent >= 0 ? g[static_cast<std::size_t>(joint.parent)] * local : local;
  }
  const glm::dmat4& gm = g[s.model_joint];
  const glm::dvec3 x = glm::normalize(glm::dvec3(gm[0]));
  const glm::dvec3 y = glm::normalize(glm::dvec3(gm[1]) - glm::dot(glm::dvec3(gm[1]), x) * x);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(x, 0.0);
  m[1] = glm::dvec4(y, 0.0);
  m[2] = glm::dvec4(glm::cross(x, y), 0.0);
  m[3] = gm[3];
  const glm::dmat4 model_inverse = glm::inverse(m);
  std::vector<glm::dmat4> k(s.joints.size());
  for (std::size_t j = 0; j < k.size(); ++j)
    k[j] = model_inverse * g[j] * glm::dmat4(s.joints[j].inverse_bind);
  return k;
}

}  // namespace

std::vector<float> skinned_model_normals(const PoseSkeleton& s,
                                         const std::vector<glm::quat>& rotations) {
  const std::vector<glm::dmat4> k = skinning_matrices(s, rotations);
  std::vector<float> out(3 * s.local_normals.size(), 0.0f);
  for (std::size_t v = 0; v < s.local_normals.size(); ++v) {
    double total = 0.0;
    for (int i = 0; i < 4; ++i) total += s.skin_weights[v][i] / 65535.0;
    glm::dmat3 blend(1.0);
    if (total > 0.0) {
      blend = glm::dmat3(0.0);
      for (int i = 0; i < 4; ++i) {
        const double w = s.skin_weights[v][i] / 65535.0;
        if (w > 0.0) blend += (w / total) * glm::dmat3(k[s.skin_joints[v][i]]);
      }
    }
    const double det = glm::determinant(blend);
    if (det == 0.0 || !std::isfinite(det)) continue;
    const glm::dvec3 n = glm::transpose(glm::inverse(blend)) * glm::dvec3(s.local_normals[v]);
    const double len = glm::length(n);
    if (!(len > 0.0) || !std::isfinite(len)) continue;
    for (int c = 0; c < 3; ++c) out[3 * v + std::size_t(c)] = float(n[c] / len);
  }
  return out;
}

}  // namespace prt::bake
