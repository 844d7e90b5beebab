// SPDX-License-Identifier: MIT
#include "prt/io/camera.hpp"

#include <algorithm>
#include <cmath>

namespace prt::io {

Camera Camera::look_at(const glm::vec3& eye, const glm::vec3& target, float vertical_fov_degrees,
                       float aspect) {
  Camera camera;
  camera.eye = eye;
  camera.forward = glm::normalize(target - eye);
  glm::vec3 up_hint(0.0f, 1.0f, 0.0f);
  if (std::abs(glm::dot(camera.forward, up_hint)) > 0.999f) up_hint = glm::vec3(0.0f, 0.0f, -1.0f);
  camera.right = glm::normalize(glm::cross(camera.forward, up_hint));
  camera.up = glm::cross(camera.right, camera.forward);
  camera.vertical_fov_degrees = vertical_fov_degrees;
  camera.aspect = aspect;
  return camera;
}

Camera Camera::auto_frame(const glm::vec3& lo, const glm::vec3& hi, float aspect,
                          float vertical_fov_degrees) {
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * glm::length(hi - lo), 1e-6f);
  // The sphere fits the narrower of the two fields of view, with a 5 % margin.
  const float half_v = glm::radians(vertical_fov_degrees) * 0.5f;
  const float half_h = std::atan(std::tan(half_v) * aspect);
  const float distance = 1.05f * radius / std::sin(std::min(half_v, half_h));
  const glm::vec3 from = glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f));
  return look_at(centre + distance * from, centre, vertical_fov_degrees, aspect);
}

Camera Camera::frame_box(const glm::vec3& lo, const glm::vec3& hi, float aspect,
                         float vertical_fov_degrees) {
  const glm::vec3 centre = 0.5f * (lo + hi);
  const glm::vec3 from = glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f));
  // The axes look_at gives, with the eye anywhere on the line through the centre.
  const Camera axes = look_at(centre + from, centre, vertical_fov_degrees, aspect);
  const float tan_v = 0.95f * std::tan(glm::radians(vertical_fov_degrees) * 0.5f);
  const float tan_h = tan_v * aspect;
  // A corner at offset (x, y, z) in camera axes (z towards the scene) is in view from distance
  // d when |x| <= (d + z) tan_h and |y| <= (d + z) tan_v.
  float distance = 1e-6f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                      (corner & 4) ? hi.z : lo.z);
    const glm::vec3 offset = p - centre;
    const float x = glm::dot(offset, axes.right), y = glm::dot(offset, axes.up);
    const float z = glm::dot(offset, axes.forward);
    distance = std::max({distance, std::abs(x) / tan_h - z, std::abs(y) / tan_v - z});
  }
  return look_at(centre + distance * from, centre, vertical_fov_degrees, aspect);
}

glm::vec3 Camera::direction(float sx, float sy) const {
  const float tan_half = std::tan(glm::radians(vertical_fov_degrees) * 0.5f);
  const float x = (2.0f * sx - 1.0f) * tan_half * aspect;
  const float y = (1.0f - 2.0f * sy) * tan_half;
  return glm::normalize(forward + x * right + y * up);
}

}  // namespace prt::io
