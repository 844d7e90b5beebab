// SPDX-License-Identifier: MIT
#include "prt/io/demo_sky.hpp"

#include <cmath>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

namespace prt::io {
namespace {

constexpr float kPi = glm::pi<float>();

}  // namespace

EnvMap make_demo_sky(int width) {
  const int height = width / 2;
  // Sun behind the camera's left shoulder, 35 degrees up, so shadows fall toward the back right.
  const glm::vec3 sun_dir = glm::normalize(glm::vec3(-0.55f, 0.7f, 0.75f));
  const float sun_cos_radius = std::cos(glm::radians(2.0f));
  std::vector<float> rgb(std::size_t(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // Inverse of the lat-long convention in formats/SPEC.md.
      float theta = (float(y) + 0.5f) / float(height) * kPi;
      float phi = ((float(x) + 0.5f) / float(width) - 0.5f) * 2 * kPi;
      glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                  -std::sin(theta) * std::cos(phi));
      glm::vec3 radiance;
      if (d.y >= 0) {
        float t = std::pow(1.0f - d.y, 3.0f);
        radiance = glm::mix(glm::vec3(0.25f, 0.45f, 1.0f), glm::vec3(1.0f, 0.95f, 0.9f), t);
      } else {
        radiance = glm::vec3(0.35f, 0.3f, 0.25f) * (0.6f + 0.4f * (1.0f + d.y));
      }
      if (glm::dot(d, sun_dir) >= sun_cos_radius) radiance = glm::vec3(1500.0f, 1350.0f, 1150.0f);
      float* px = &rgb[(std::size_t(y) * width + x) * 3];
      px[0] = radiance.r, px[1] = radiance.g, px[2] = radiance.b;
    }
  }
  return EnvMap(width, height, std::move(rgb), EnvMapping::LatLong, "prtkit demo sky");
}

}  // namespace prt::io
