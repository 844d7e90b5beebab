// SPDX-License-Identifier: MIT
// The orbit camera every sample shares: it turns about the centre of the scene's bounding box
// (yaw about world +Y, pitch above the horizon) at a distance that frames the box for the view's
// aspect, times a zoom factor. Framing fits the box's corners as seen from the direction the
// camera had when it framed (so orbiting keeps the distance), with a 5 % margin: tighter than a
// bounding sphere for flat scenes. Its first direction is prt_io's Camera::auto_frame's (from
// +Z, about 17 degrees up).
#pragma once

#include <glm/glm.hpp>

#include "prt/io/camera.hpp"

namespace prt::sample {

class OrbitCamera {
 public:
  // Degrees the camera turns per pixel of a drag.
  static constexpr float kDegreesPerPixel = 0.25f;
  // auto_frame's elevation: atan(0.3) in degrees.
  static float default_pitch_degrees();

  // Frames the box [lo, hi] from the current direction: aims at its centre, zoom 1.
  void frame(const glm::vec3& lo, const glm::vec3& hi);

  // Left-drag of (dx, dy) window pixels: right turns the scene right (the camera goes left),
  // down raises the camera.
  void drag(float dx, float dy);
  // Wheel: each step up brings the camera 10 % closer.
  void scroll(float steps);

  void set_yaw_pitch(float yaw_degrees, float pitch_degrees);
  void set_zoom(float zoom) { zoom_ = zoom; }
  float yaw_degrees() const { return yaw_; }
  float pitch_degrees() const { return pitch_; }
  float zoom() const { return zoom_; }

  // The pinhole camera of a view of this aspect (width / height), vertical field of view
  // kFovDegrees, with the near and far planes that hold the bounding sphere.
  prt::io::Camera camera(float aspect) const;
  glm::mat4 view_projection(float aspect) const;

  static constexpr float kFovDegrees = 40.0f;

 private:
  glm::vec3 lo_{-1.0f}, hi_{1.0f}, centre_{0.0f};
  float radius_ = 1.0f;
  float yaw_ = 0.0f, pitch_ = default_pitch_degrees(), zoom_ = 1.0f;
  float frame_yaw_ = 0.0f, frame_pitch_ = default_pitch_degrees();

  float distance(float aspect) const;
};

}  // namespace prt::sample
