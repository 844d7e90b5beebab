// SPDX-License-Identifier: MIT
// The pinhole camera: auto framing keeps a box in view from the front and above, whatever the
// aspect ratio (checked against the camera's own frame, corner by corner); box framing keeps the
// box in view and fills the frame to its margin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "prt/io/camera.hpp"

namespace prt::io {
namespace {

TEST(Camera, AutoFrameKeepsTheBoundsInViewFromAboveAndFront) {
  const glm::vec3 lo(-3.0f, 1.0f, 2.0f), hi(5.0f, 2.0f, 4.0f);
  for (const float aspect : {0.5f, 1.0f, 16.0f / 9.0f}) {
    const Camera camera = Camera::auto_frame(lo, hi, aspect);
    EXPECT_NEAR(glm::distance(camera.direction(0.5f, 0.5f), camera.forward), 0.0f, 1e-6f);
    EXPECT_GT(camera.eye.z, hi.z);  // in front (+Z) ...
    EXPECT_GT(camera.eye.y, hi.y);  // ... and above
    const float tan_half = std::tan(glm::radians(camera.vertical_fov_degrees) * 0.5f);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 q((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                        (corner & 4) ? hi.z : lo.z);
      const glm::vec3 d = q - camera.eye;
      const float depth = glm::dot(d, camera.forward);
      ASSERT_GT(depth, 0.0f);
      EXPECT_LE(std::abs(glm::dot(d, camera.right) / depth), tan_half * aspect) << corner;
      EXPECT_LE(std::abs(glm::dot(d, camera.up) / depth), tan_half) << corner;
    }
  }
}

// Where corner q lands in the image, as multiples of the half field of view (|.| <= 1 in view).
glm::vec2 image_position(const Camera& camera, const glm::vec3& q) {
  const float tan_half = std::tan(glm::radians(camera.vertical_fov_degrees) * 0.5f);
  const glm::vec3 d = q - camera.eye;
  const float depth = glm::dot(d, camera.forward);
  EXPECT_GT(depth, 0.0f);
  return {glm::dot(d, camera.right) / depth / (tan_half * camera.aspect),
          glm::dot(d, camera.up) / depth / tan_half};
}

TEST(Camera, FrameBoxFillsTheFrameToItsMargin) {
  const glm::vec3 lo(-1.6f, 0.0f, -1.5f), hi(1.7f, 1.2f, 1.3f);  // wide and flat
  for (const float aspect : {0.5f, 1.0f, 16.0f / 9.0f}) {
    const Camera camera = Camera::frame_box(lo, hi, aspect);
    EXPECT_GT(camera.eye.z, hi.z);
    EXPECT_GT(camera.eye.y, hi.y);
    float widest = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 q((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                        (corner & 4) ? hi.z : lo.z);
      const glm::vec2 at = image_position(camera, q);
      EXPECT_LE(std::abs(at.x), 0.95f + 1e-5f) << corner;
      EXPECT_LE(std::abs(at.y), 0.95f + 1e-5f) << corner;
      widest = std::max({widest, std::abs(at.x), std::abs(at.y)});
    }
    // The nearest limiting corner sits on the 5 % margin: the box is as large as it can be.
    EXPECT_NEAR(widest, 0.95f, 1e-4f) << aspect;
    // Closer than the bounding-sphere framing, so the box fills more of the frame.
    const Camera sphere = Camera::auto_frame(lo, hi, aspect);
    EXPECT_LT(glm::distance(camera.eye, 0.5f * (lo + hi)),
              glm::distance(sphere.eye, 0.5f * (lo + hi)));
  }
}

}  // namespace
}  // namespace prt::io
