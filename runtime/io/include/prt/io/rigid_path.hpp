// SPDX-License-Identifier: MIT
// Rigid placements on scripted, looping keyframe paths: the one definition the baker's shadowfield
// scenes and the shadowfield app share, so that the app and the reference place instances alike.
#pragma once

#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace prt::io {

// world = scale * rotation * local + translation.
struct RigidPlacement {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z; unit
  float scale = 1.0f;

  glm::vec3 apply(const glm::vec3& local) const { return scale * (rotation * local) + translation; }
  // The runtime's transform (prt_shadowfield_transform): the rotation as a row-major 3x3.
  void to_rows(float rotation_rows[9]) const;
};

struct RigidKeyframe {
  float time = 0.0f;  // seconds, in [0, duration)
  RigidPlacement placement;
};

// Keyframes at ascending times in [0, duration); between two keyframes translation and scale are
// interpolated linearly and rotation by slerp (the shorter arc), and after the last keyframe the
// path runs back to the first, reached again at its time + duration: the path loops with period
// `duration`. One keyframe is a constant placement (duration is then ignored).
struct RigidPath {
  std::vector<RigidKeyframe> keyframes;
  float duration = 0.0f;  // seconds, > the last keyframe's time when there are several

  bool moves() const { return keyframes.size() > 1; }
  // The placement at any finite time (negative too), its rotation unit. Throws Error for a path
  // check() rejects and, when the path moves, for a non-finite time.
  RigidPlacement at(float time) const;
  // Throws Error naming what is wrong: no keyframe, times not ascending or outside
  // [0, duration), a scale <= 0, a zero rotation, a non-finite value.
  void check() const;
};

}  // namespace prt::io
