// SPDX-License-Identifier: MIT
#include "orbit_camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace prt::sample {

float OrbitCamera::default_pitch_degrees() {
  return glm::degrees(std::atan(0.3f));
}

namespace {

// The unit vector from the target towards the camera.
glm::vec3 from_direction(float yaw_degrees, float pitch_degrees) {
  const float yaw = glm::radians(yaw_degrees), pitch = glm::radians(pitch_degrees);
  return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
}

}  // namespace

void OrbitCamera::frame(const glm::vec3& lo, const glm::vec3& hi) {
  lo_ = lo, hi_ = hi;
  centre_ = 0.5f * (lo + hi);
  radius_ = std::max(0.5f * glm::length(hi - lo), 1e-6f);
  zoom_ = 1.0f;
  frame_yaw_ = yaw_, frame_pitch_ = pitch_;
}

void OrbitCamera::drag(float dx, float dy) {
  set_yaw_pitch(yaw_ - kDegreesPerPixel * dx, pitch_ + kDegreesPerPixel * dy);
}

void OrbitCamera::scroll(float steps) {
  zoom_ = std::clamp(zoom_ * std::pow(0.9f, steps), 0.05f, 20.0f);
}

void OrbitCamera::set_yaw_pitch(float yaw_degrees, float pitch_degrees) {
  yaw_ = std::remainder(yaw_degrees, 360.0f);
  pitch_ = std::clamp(pitch_degrees, -89.0f, 89.0f);
}

// The distance at which every corner of the box, seen from the framing direction, lies inside
// the view shrunk by the 5 % margin: a corner at (x, y) across and z towards the camera from the
// centre needs d - z >= |x| / tan(half_h) and |y| / tan(half_v).
float OrbitCamera::distance(float aspect) const {
  const float tan_v = std::tan(glm::radians(kFovDegrees) * 0.5f) / 1.05f;
  const float tan_h = tan_v * aspect;
  const prt::io::Camera c = prt::io::Camera::look_at(
      centre_ + from_direction(frame_yaw_, frame_pitch_), centre_, kFovDegrees, aspect);
  float d = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? hi_.x : lo_.x, (corner & 2) ? hi_.y : lo_.y,
                      (corner & 4) ? hi_.z : lo_.z);
    const glm::vec3 q = p - centre_;
    const float towards = -glm::dot(q, c.forward);
    d = std::max({d, std::abs(glm::dot(q, c.right)) / tan_h + towards,
                  std::abs(glm::dot(q, c.up)) / tan_v + towards});
  }
  return zoom_ * std::max(d, 1e-3f * radius_);
}

prt::io::Camera OrbitCamera::camera(float aspect) const {
  return prt::io::Camera::look_at(centre_ + distance(aspect) * from_direction(yaw_, pitch_),
                                  centre_, kFovDegrees, aspect);
}

glm::mat4 OrbitCamera::view_projection(float aspect) const {
  const prt::io::Camera c = camera(aspect);
  const float d = distance(aspect);
  const float near_plane = std::max(d - 1.1f * radius_, 1e-3f * d);
  const float far_plane = d + 1.1f * radius_;
  const glm::mat4 projection =
      glm::perspective(glm::radians(kFovDegrees), aspect, near_plane, far_plane);
  return projection * glm::lookAt(c.eye, c.eye + c.forward, c.up);
}

}  // namespace prt::sample
