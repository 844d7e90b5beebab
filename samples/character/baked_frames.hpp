// SPDX-License-Identifier: MIT
// The training frames `prt-bake bake pose --ground-truth PREFIX` writes beside the blob: each
// frame's joint rotations (which make the clips the character sample plays) and its baked
// transfer (the ground truth the learned model is compared with). The blob itself holds only
// the skeleton and the model, so this is where the animation comes from.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace prt::character {

// A float32 little-endian C-order .npy array (format 1.0 or 2.0).
struct NpyArray {
  std::vector<std::size_t> shape;
  std::vector<float> values;
};
// Throws std::runtime_error naming the file on anything else.
NpyArray read_npy(const std::string& path);

struct BakedFrames {
  std::uint32_t frames = 0, vertices = 0, coefficients = 0, joints = 0;
  std::vector<float> transfer;   // [frames][vertices][coefficients], each in its model frame
  std::vector<float> rotations;  // [frames][joints][4], x y z w
  std::vector<std::uint32_t> clip;
  std::vector<float> time;  // seconds into the clip; ascending within a clip

  const float* frame_transfer(std::uint32_t f) const {
    return transfer.data() + std::size_t(f) * vertices * coefficients;
  }
  const float* frame_rotations(std::uint32_t f) const {
    return rotations.data() + std::size_t(f) * joints * 4;
  }
  std::uint32_t clip_count() const { return clip.empty() ? 0 : clip.back() + 1; }
  // The frames of clip c: [first, last].
  void clip_frames(std::uint32_t c, std::uint32_t* first, std::uint32_t* last) const;
};

// Reads PREFIX.transfer.npy, PREFIX.rotations.npy and PREFIX.times.npy; throws
// std::runtime_error naming the file unless their shapes agree with each other and with the
// blob's vertex, coefficient and joint counts.
BakedFrames read_baked_frames(const std::string& prefix, std::uint32_t vertices,
                              std::uint32_t coefficients, std::uint32_t joints);

// The joint rotations of clip c at `time` (clamped to the clip): the two baked frames around it
// slerped per joint, into out (joints x 4). Returns the nearest baked frame.
std::uint32_t clip_pose(const BakedFrames& baked, std::uint32_t c, double time, float* out);

}  // namespace prt::character
