// SPDX-License-Identifier: MIT
#include "environments.hpp"

#include <algorithm>
#include <cmath>

#include "prt/io/demo_sky.hpp"

namespace prt::sample {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The map (unturned) on a lat-long grid of formats/SPEC.md: texel (x, y) of W x H looks along
// (sin t sin p, cos t, -sin t cos p), p = 2 pi ((x + 0.5)/W - 0.5), t = pi (y + 0.5)/H; rows from
// the top. A lat-long map at its own size gives back its texels.
std::vector<float> latlong_texels(const prt::io::EnvMap& map, int width, int height) {
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    const double theta = kPi * (y + 0.5) / height;
    for (int x = 0; x < width; ++x) {
      const double phi = 2.0 * kPi * ((x + 0.5) / width - 0.5);
      const glm::vec3 dir(std::sin(theta) * std::sin(phi), std::cos(theta),
                          -std::sin(theta) * std::cos(phi));
      const glm::vec3 value = map.radiance(dir);
      float* out = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
      out[0] = value.r, out[1] = value.g, out[2] = value.b;
    }
  }
  return rgb;
}

}  // namespace

void Environments::add(const std::string& path, const std::string& mapping) {
  prt::io::EnvMap map = path == kBuiltinSky
                            ? prt::io::make_demo_sky()
                            : prt::io::load_envmap(path, prt::io::parse_env_mapping(mapping));
  maps_.push_back(std::make_unique<Entry>(Entry{path, std::move(map), GlTexture()}));
  select(maps_.size() - 1);
}

void Environments::select(std::size_t index) {
  if (index >= maps_.size()) return;
  current_ = index;
  ++version_;
}

void Environments::set_rotation_degrees(double degrees) {
  const double wrapped = std::remainder(degrees, 360.0);
  if (wrapped == rotation_) return;
  rotation_ = wrapped;
  ++version_;
}

void Environments::advance(double seconds) {
  if (spin_degrees_per_second != 0.0)
    set_rotation_degrees(rotation_ + spin_degrees_per_second * seconds);
}

GLuint Environments::texture() {
  Entry& entry = *maps_.at(current_);
  if (entry.texture.get()) return entry.texture.get();
  const prt::io::EnvMap& map = entry.map;
  const bool latlong = map.mapping() == prt::io::EnvMapping::LatLong;
  // Other mappings resampled to a lat-long grid about as detailed as the map.
  const int width = std::clamp(latlong ? map.width() : 2 * map.height(), 8, 4096);
  const int height = std::max(width / 2, 4);
  const std::vector<float> texels = latlong_texels(map, width, height);
  entry.texture = make_texture();
  glBindTexture(GL_TEXTURE_2D, entry.texture.get());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width, height, 0, GL_RGB, GL_FLOAT, texels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  return entry.texture.get();
}

void Environments::release_textures() {
  for (const std::unique_ptr<Entry>& entry : maps_) entry->texture.reset();
}

}  // namespace prt::sample
