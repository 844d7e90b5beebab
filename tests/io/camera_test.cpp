// SPDX-License-Identifier: MIT
// The pinhole camera: auto framing keeps a box in view from the front and above, whatever the
// aspect ratio (checked against the camera's own frame, corner by corner).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace prt::io
