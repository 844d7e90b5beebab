// SPDX-License-Identifier: MIT
// Training data of technique `pose` (paper 002): a skinned character's SH transfer baked at
// every sampled frame of its animation clips, in each frame's model frame, with the pose
// features the runtime computes from the same joint rotations (formats/SPEC.md §7.3), and the
// skeleton and skin the PSTR section stores.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/sh/sh_transfer.hpp"

namespace prt::bake {

// The skeleton and skin as SPEC §7.3 stores them: joints in the skin's order.
struct PoseSkeleton {
  struct Joint {
    int parent = -1;          // index into joints, -1: its parent node is not a joint
    glm::quat bind_rotation;  // features are relative to it (bind_local_rotations)
    glm::vec3 rest_translation{0.0f}, rest_scale{1.0f};
    glm::mat4 pre{1.0f};           // non-joint nodes up to the parent joint, or world of parent
    glm::mat4 inverse_bind{1.0f};  // affine
  };
  std::vector<Joint> joints;
  std::vector<std::uint32_t> eval_order;  // parents first
  std::uint32_t model_joint = 0;          // a joint with parent -1
  // Per vertex, in Scene order: the mesh's own attributes and up to 4 influences.
  std::vector<glm::vec3> local_positions, local_normals;
  std::vector<glm::u8vec4> skin_joints;
  std::vector<glm::u16vec4> skin_weights;  // w / 65535, summing to 65535 where any
};

// The transfer settings of a pose bake: ShTransferSettings' own with order 6 and albedo 1 (SPEC
// §7.3's transfer is for albedo 1 unless the header says otherwise).
inline ShTransferSettings pose_transfer_defaults() {
  ShTransferSettings s;
  s.order = 6;
  s.albedo = glm::vec3(1.0f);
  return s;
}

struct PoseTrainingSettings {
  std::vector<std::string> clips;  // names to sample; empty: every clip
  double rate = 30.0;              // frames per second of clip time
  // order, kind, rays, bounces, seed; the grey albedo is albedo.r (override_albedo is ignored:
  // every vertex gets it)
  ShTransferSettings transfer = pose_transfer_defaults();
};

struct PoseFrame {
  std::uint32_t clip = 0;            // index into PoseTrainingSet::clip_names
  float time = 0.0f;                 // seconds into the clip
  std::vector<glm::quat> rotations;  // every joint's local rotation at this frame
  std::vector<float> features;       // 3 J: SPEC §7.3's pose vector of `rotations`
};

struct PoseTrainingSet {
  std::uint32_t order = 6;
  float albedo = 1.0f;  // grey albedo the transfer was baked with
  ShTransferKind kind = ShTransferKind::Shadowed;
  int bounces = 0;
  std::size_t vertex_count = 0;
  PoseSkeleton skeleton;
  std::vector<std::string> clip_names;  // the sampled clips, in file order
  std::vector<PoseFrame> frames;        // clip by clip, time ascending
  // frames x vertices x order^2 floats: frame f, vertex v, coefficient c at
  // (f * vertex_count + v) * order^2 + c. Grey, model frame.
  std::vector<float> transfer;
  // frames x vertices x 3: the skinned normals in the model frame (the exact part's input).
  std::vector<float> normals;
  double seconds = 0.0;
  std::uint64_t rays_traced = 0;

  std::size_t coefficient_count() const { return static_cast<std::size_t>(order) * order; }
  std::size_t joint_count() const { return skeleton.joints.size(); }
  const float* frame_transfer(std::size_t frame) const {
    return transfer.data() + frame * vertex_count * coefficient_count();
  }
  const float* frame_normals(std::size_t frame) const {
    return normals.data() + frame * vertex_count * 3;
  }
};

// The skeleton of `scene`'s one skin (Error naming the mesh when a mesh is not skinned by it,
// or when the scene has no skin).
PoseSkeleton pose_skeleton(const Scene& scene);

// SPEC §7.3's features of local rotations (one per joint).
std::vector<float> pose_features(const PoseSkeleton& skeleton,
                                 const std::vector<glm::quat>& rotations);

// SPEC §7.3's skinned normals in the model frame at local rotations `rotations` (joint
// translations and scales at rest): normalize(K3^-T n_local) of each vertex's blended skinning
// matrix, 0 where K3 is singular. What the runtime computes, so that the residual model learns
// against the normals it will be evaluated with (the posed mesh's own normals differ where the
// file has none and they are regenerated from the deformed surface). vertex_count x 3.
std::vector<float> skinned_model_normals(const PoseSkeleton& skeleton,
                                         const std::vector<glm::quat>& rotations);

// A bake in parts (a farm's shards, docs/farm.md): the training set without its transfer, which
// is cheap (no rays), and the transfer of a range of its frames, which is the cost.
// sample_pose_training: the skeleton, the clip names, every sampled frame's pose and skinned
// normals; `transfer` empty, `rays_traced` and `seconds` 0. Errors as bake_pose_training's.
PoseTrainingSet sample_pose_training(const Scene& scene, const PoseTrainingSettings& settings);
struct PoseFramesTransfer {
  std::vector<float> transfer;  // count x vertices x order^2, as PoseTrainingSet::transfer
  std::uint64_t rays_traced = 0;
  double seconds = 0.0;
};
// The transfer of frames [first, first + count) of `sampled` (sample_pose_training's of the same
// scene and settings), bitwise the rows bake_pose_training gives them: a frame's transfer depends
// on its own pose only, never on which frames are baked with it. Progress and cancel as
// bake_pose_training's; Error when the range is beyond the frames.
PoseFramesTransfer bake_pose_frames(const Scene& scene, const PoseTrainingSettings& settings,
                                    const PoseTrainingSet& sampled, std::size_t first,
                                    std::size_t count, const Context& ctx);

// Samples the clips and bakes every frame on ctx.thread_count() threads; progress through ctx
// ("pose training"), Error("cancelled") when the callback returns false, Error for an unknown
// clip name or a scene without animation. Bitwise deterministic for any thread count.
PoseTrainingSet bake_pose_training(const Scene& scene, const PoseTrainingSettings& settings,
                                   const Context& ctx);

}  // namespace prt::bake
