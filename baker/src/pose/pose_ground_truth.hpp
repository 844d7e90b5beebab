// SPDX-License-Identifier: MIT
// `prt-bake bake pose --ground-truth PREFIX`: the baked training frames beside the blob, for a
// viewer that compares the learned model with the transfer it was fitted to (samples/character).
#pragma once

#include <string>

#include "prt/baker/pose/pose_training.hpp"

namespace prt::bake {

// Writes float32 little-endian C-order .npy files (format 1.0):
//   PREFIX.transfer.npy  [frames][V][n²]  each frame's baked grey transfer in its model frame
//   PREFIX.rotations.npy [frames][J][4]   the joint rotations (x y z w) the frame was posed by
//   PREFIX.times.npy     [frames][2]      the frame's clip index and its time in seconds
// Throws Error naming the file when one cannot be written.
void write_pose_ground_truth(const std::string& prefix, const PoseTrainingSet& training);

}  // namespace prt::bake
