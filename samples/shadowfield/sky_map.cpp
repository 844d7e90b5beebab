// SPDX-License-Identifier: MIT
#include "sky_map.hpp"

#include <algorithm>
#include <cmath>

#include "prt/io/image_io.hpp"

namespace prt::shadowfield_app {

// The built-in sky of the scenes (`builtin:sky`, the baker's demo sky): a blue gradient over a
// dim ground and a small bright sun, as a lat-long .hdr so that the framework and the reference
// tool read the same map.
std::string write_builtin_sky(const std::string& path) {
  const int width = 512, height = width / 2;
  const float pi = 3.14159265358979f;
  const glm::vec3 sun = glm::normalize(glm::vec3(-0.55f, 0.7f, 0.75f));
  const float sun_cos_radius = std::cos(glm::radians(2.0f));
  prt::io::LinearImage image;
  image.width = width, image.height = height;
  image.pixels.resize(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float theta = (float(y) + 0.5f) / float(height) * pi;
      const float phi = ((float(x) + 0.5f) / float(width) - 0.5f) * 2.0f * pi;
      const glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                        -std::sin(theta) * std::cos(phi));
      glm::vec3 radiance;
      if (d.y >= 0.0f)
        radiance = glm::mix(glm::vec3(0.25f, 0.45f, 1.0f), glm::vec3(1.0f, 0.95f, 0.9f),
                            std::pow(1.0f - d.y, 3.0f));
      else
        radiance = glm::vec3(0.35f, 0.3f, 0.25f) * (0.6f + 0.4f * (1.0f + d.y));
      if (glm::dot(d, sun) >= sun_cos_radius) radiance = glm::vec3(1500.0f, 1350.0f, 1150.0f);
      image.pixels[std::size_t(y) * width + x] = radiance;
    }
  prt::io::write_image(path, image, 0.0f);
  return path;
}

// `map` turned by `degrees` about +Y, resampled to a lat-long .hdr: the reference tool takes the
// map as it is.
std::string write_turned_map(const prt::io::EnvMap& map, double degrees, const std::string& path) {
  prt::io::EnvMap turned = map;
  turned.set_rotation(prt::io::rotation_about_y(degrees));
  const int width = std::clamp(map.width(), 64, 1024), height = width / 2;
  const float pi = 3.14159265358979f;
  prt::io::LinearImage image;
  image.width = width, image.height = height;
  image.pixels.resize(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float theta = (float(y) + 0.5f) / float(height) * pi;
      const float phi = ((float(x) + 0.5f) / float(width) - 0.5f) * 2.0f * pi;
      const glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                        -std::sin(theta) * std::cos(phi));
      image.pixels[std::size_t(y) * width + x] = turned.radiance(d);
    }
  prt::io::write_image(path, image, 0.0f);
  return path;
}

}  // namespace prt::shadowfield_app
