// SPDX-License-Identifier: MIT
// A scene at one instant of an animation clip (glTF 2.0 §3.11 and Appendix C): keyframe
// interpolation, node transforms, joint matrices and linear blend skinning. Shared by every
// technique whose objects move: `pose` bakes each training frame of a skinned character,
// `shadowfield` places rigid objects, the content pipeline tells static nodes from moving ones.
#pragma once

#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "prt/baker/scene.hpp"

namespace prt::bake {

// A node's local transform in the form glTF animates.
struct NodeTRS {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
  glm::vec3 scale{1.0f};

  glm::mat4 matrix() const;  // T * R * S
};

// Channel `channel` at `time` seconds, clamped to its first and last keys: translation and
// scale as (x, y, z, 0), rotation as a unit quaternion (x, y, z, w). Linear rotation keys are
// slerped along the shorter arc; cubic-spline keys use the in/out tangents scaled by the key
// interval, and rotations are normalised afterwards (the spec's Appendix C). Weights channels
// (morph targets) are not sampled: the base shape is what the importer keeps.
glm::vec4 sample_channel(const AnimationChannel& channel, float time);

// Every node's local transform at one instant: the file's own transforms until a clip is applied.
// It refers to `scene`, which must outlive it.
class ScenePose {
 public:
  explicit ScenePose(const Scene& scene);

  // Overrides the TRS parts that `clip`'s channels animate with their values at `time`.
  void apply(const Animation& clip, float time);

  std::size_t node_count() const { return local_.size(); }
  const NodeTRS& local(std::size_t node) const { return local_[node]; }
  void set_local(std::size_t node, const NodeTRS& trs);

  // World matrix of every node, parents first. A node given as a matrix in the file keeps that
  // exact matrix until something of it is animated or set (glTF never animates matrix nodes).
  std::vector<glm::mat4> world_matrices() const;

 private:
  const Scene* scene_;
  std::vector<int> parents_first_;  // node indices, each after its parent
  std::vector<NodeTRS> local_;
  std::vector<unsigned char> from_file_;  // 1 = still the file's local matrix
};

// world(joint_j) * inverse_bind_j for each joint of `skin`.
std::vector<glm::mat4> joint_matrices(const Skin& skin, const std::vector<glm::mat4>& world);

// Each joint's local rotation in the bind pose the inverse bind matrices describe (which need
// not be the file's rest pose): the rotation of IBM_parent * inverse(IBM_joint). A joint whose
// parent is not a joint of `skin` gets its rest rotation: the matrices say where the skin's mesh
// space is relative to each joint, not where that space is in the world, so a root's bind
// rotation is only defined up to that placement. Scale and shear are removed by polar
// decomposition before taking the rotation.
std::vector<glm::quat> bind_local_rotations(const Scene& scene, const Skin& skin);

// The linear-blend skinning matrix of one vertex: sum_k (w_k / sum w) J[joint_k] over the
// non-zero weights naming existing joints; `fallback` when the weights sum to zero or less.
glm::mat4 blend_joints(const glm::u16vec4& joints, const glm::vec4& weights,
                       const std::vector<glm::mat4>& joint_matrices, const glm::mat4& fallback);

// Places `mesh` (its local attributes, as imported into `scene`) at the pose given by every
// node's world matrix: a skinned mesh by blending its skin's joints, any other by its node.
// Positions move; normals go through the inverse transpose and are renormalised (recomputed
// from the placed positions when the file had none); tangents, if any, are derived again from
// the UVs at the placed positions.
void place_mesh(const Scene& scene, const std::vector<glm::mat4>& world, Mesh& mesh);

// A copy of `scene` with every mesh placed at `pose`.
Scene posed_scene(const Scene& scene, const ScenePose& pose);

// The instants a clip is sampled at: 0, 1/rate, 2/rate, ... while within its duration, and
// the duration itself when that falls between two of them (so a clip's last key is always
// included). A clip of zero duration gives the single instant 0.
std::vector<float> clip_times(const Animation& clip, double rate);

}  // namespace prt::bake
