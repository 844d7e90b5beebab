// SPDX-License-Identifier: MIT
// Technique `pose`'s parts that prt-bake's steps call (private to baker/src/pose/).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/pose/pose_model.hpp"
#include "prt/baker/pose/pose_training.hpp"
#include "prt/baker/technique.hpp"

namespace prt::bake {

// The stored model measured on its own training frames: Σ|Δt|²/Σ|t|² over every frame, vertex
// and coefficient, and the worst frame's.
struct PoseFit {
  double transfer_error = 0.0;
  double worst_frame_error = 0.0;
};
PoseFit measure_pose_fit(const PoseTrainingSet& training, const PoseModel& model);

// The baker's self-check: the blob loaded through the runtime at full validation, its header
// against the model, and the runtime's transfer from each training frame's joint rotations
// (features and skinned normals computed by the runtime) against predict_pose_transfer's.
struct PoseBlobCheck {
  bool passed = false;
  std::string message;
  std::size_t frames_checked = 0;
  double max_abs_error = 0.0;     // max |runtime - baker| over the checked frames
  double max_budget_ratio = 0.0;  // max_abs_error / allowed, <= 1 when passed
};
PoseBlobCheck check_pose_blob(const std::vector<std::uint8_t>& blob,
                              const PoseTrainingSet& training, const PoseModel& model);

void write_pose_bake_report(const std::string& path, const BakeInput& input, const BakeFacts& facts,
                            const PoseTrainingSet& training, const PoseModel& model,
                            const PoseFit& fit, const PoseBlobCheck& check);

std::unique_ptr<TechniqueTrade> make_pose_trade();

// Shards of a pose bake (pose_shards.cpp, docs/farm.md): the unit is the training frame.
// The settings of a bake as its options and the shared flags resolve them; `training.clips`
// names the clips it samples (the default chosen: those that move the skin).
struct PoseBakeSettings {
  PoseTrainingSettings training;
  PoseModelSettings model;
  std::uint32_t subdivide_to = 0;
};
// The payload of frames [first, first + count) of `scene` (the baked one, subdivided when
// --subdivide-to asks): a header of the settings, the scene and the range, then their transfer.
std::vector<std::uint8_t> bake_pose_shard(const Scene& scene, const PoseBakeSettings& settings,
                                          std::size_t first, std::size_t count, const Context& ctx);
// The training set bake_pose_training gives (bitwise but for `seconds`, the parts' summed) from
// every part's payload in frame order; Error naming the part and what differs when one is not of
// this bake, or is damaged.
PoseTrainingSet merge_pose_shards(const Scene& scene, const PoseBakeSettings& settings,
                                  const std::vector<std::vector<std::uint8_t>>& parts,
                                  const Context& ctx);

// prt-bake scene (pose_scene.cpp): whether a node suits pose (skinned, moved by a clip), the
// settings ladder, and the measurement on frames of the clips against the posed character's
// reference.
ObjectFit pose_scene_fit(const Scene& scene, int node);
// The names of the clips that move a joint of the scene's one skin (a channel on a joint or a node
// above one), in file order; empty when the scene has no skin or several.
std::vector<std::string> pose_clips_moving_skin(const Scene& scene);
std::vector<Rung> pose_scene_ladder(int bounces);
std::unique_ptr<ObjectMeasure> make_pose_scene_measure(const ObjectMeasureInput& input);

}  // namespace prt::bake
