// SPDX-License-Identifier: MIT
#include "sky_map.hpp"

#include <algorithm>
#include <cmath>

#include "prt/io/demo_sky.hpp"
#include "prt/io/image_io.hpp"

namespace prt::shadowfield_app {

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

std::string write_builtin_sky(const std::string& path) {
  return write_turned_map(prt::io::make_demo_sky(), 0.0, path);
}

}  // namespace prt::shadowfield_app
