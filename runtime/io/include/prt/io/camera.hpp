// SPDX-License-Identifier: MIT
// A pinhole camera for the reference renderer's images.
#pragma once

#include <glm/glm.hpp>

namespace prt::io {

struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 1.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit, towards the scene
  glm::vec3 right{1.0f, 0.0f, 0.0f};     // unit
  glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit
  float vertical_fov_degrees = 40.0f;
  float aspect = 4.0f / 3.0f;  // width / height

  // Looks from `eye` at `target` with world +Y as the up hint.
  static Camera look_at(const glm::vec3& eye, const glm::vec3& target, float vertical_fov_degrees,
                        float aspect);
  // Frames the bounding sphere of [lo, hi] so it fills the view: looking from +Z and a little
  // above (elevation ~17 degrees), at the sphere's centre.
  static Camera auto_frame(const glm::vec3& lo, const glm::vec3& hi, float aspect,
                           float vertical_fov_degrees = 40.0f);
  // Frames the box [lo, hi] itself, from the direction auto_frame looks: at the box's centre,
  // as close as keeps all eight corners inside the view with a 5 % margin. A wide, flat box
  // fills the frame, where its bounding sphere leaves it small.
  static Camera frame_box(const glm::vec3& lo, const glm::vec3& hi, float aspect,
                          float vertical_fov_degrees = 40.0f);

  // Unit direction of the ray through image point (sx, sy), both in [0,1], (0,0) = top left.
  glm::vec3 direction(float sx, float sy) const;
};

}  // namespace prt::io
