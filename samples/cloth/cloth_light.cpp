// SPDX-License-Identifier: MIT
#include "cloth_light.hpp"

#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "blob_scene.hpp"
#include "env_image.hpp"

namespace prt::cloth_app {
namespace {

constexpr double kPi = 3.14159265358979323846;

double luminance(const glm::vec3& rgb) {
  return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

}  // namespace

bool FittedLight::update(prt_context* context, const prt::sample::Environments& envs,
                         std::uint32_t lobe_count) {
  if (version_ == envs.light_version() && lobe_count_ == lobe_count && map_ == envs.current_index())
    return false;
  if (map_ != envs.current_index()) {
    image_ = prt::view::environment_image(envs.current(), nullptr, &faces_);
    map_ = envs.current_index();
  }
  prt::io::rotation_about_y_row_major(envs.rotation_degrees(), rotation_);
  prt_env_image turned = image_;
  turned.rotation = rotation_;
  prt_cloth_fit_desc desc = prt::sized<prt_cloth_fit_desc>();
  desc.lobe_count = lobe_count;
  lobes_.assign(lobe_count, prt_cloth_lobe{});
  report_ = prt::sized<prt_cloth_fit_report>();
  const prt_result fitted = prt_cloth_fit_light(context, &turned, &desc, lobes_.data(), &report_);
  if (fitted != PRT_OK)
    throw prt::view::ViewerError(std::string("prt_cloth_fit_light failed: ") +
                                 prt_context_last_message(context));
  light_ = prt::sized<prt_cloth_light>();
  light_.lobe_count = lobe_count;
  light_.lobes = lobes_.data();
  version_ = envs.light_version();
  lobe_count_ = lobe_count;
  return true;
}

std::string FittedLight::describe() const {
  char text[128];
  std::snprintf(text, sizeof text, "%u lobes, fit error %.1f %% (power %.1f %%)",
                report_.lobe_count, 100.0 * report_.relative_error, 100.0 * report_.power_error);
  return text;
}

void ReferenceTexels::bin(const prt::io::EnvMap& map, const ReferenceSettings& s) {
  struct Texel {
    glm::vec3 direction, power;
    double luminance;
  };
  // Every texel of the map with its power (radiance x solid angle), and the map's mean radiance.
  std::vector<Texel> texels;
  double total = 0.0, solid_angle = 0.0;
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < map.width(); ++x) {
      glm::vec3 direction;
      float omega = 0.0f;
      if (!map.texel(x, y, &direction, &omega)) continue;
      const glm::vec3 radiance = map.texel_value(x, y);
      texels.push_back({glm::normalize(direction), radiance * omega, luminance(radiance)});
      total += luminance(radiance) * omega;
      solid_angle += omega;
    }
  const double mean = solid_angle > 0.0 ? total / solid_angle : 0.0;
  // The brightest texels above the threshold, at most max_bright of them, stay as they are.
  std::vector<std::size_t> bright;
  for (std::size_t i = 0; i < texels.size(); ++i)
    if (texels[i].luminance > s.bright_factor * mean && texels[i].luminance > 0.0)
      bright.push_back(i);
  std::sort(bright.begin(), bright.end(), [&](std::size_t a, std::size_t b) {
    return texels[a].luminance > texels[b].luminance ||
           (texels[a].luminance == texels[b].luminance && a < b);
  });
  if (bright.size() > s.max_bright) bright.resize(s.max_bright);
  std::vector<char> kept(texels.size(), 0);
  for (std::size_t i : bright) kept[i] = 1;
  // The others summed into cells of the lat-long grid (formats/SPEC.md's directions).
  const std::size_t cells = std::size_t(s.width) * s.height;
  std::vector<glm::dvec3> power(cells, glm::dvec3(0.0)), direction(cells, glm::dvec3(0.0));
  for (std::size_t i = 0; i < texels.size(); ++i) {
    if (kept[i]) continue;
    const glm::vec3 d = texels[i].direction;
    const double u = std::atan2(double(d.x), double(-d.z)) / (2.0 * kPi) + 0.5;
    const double v = std::acos(std::clamp(double(d.y), -1.0, 1.0)) / kPi;
    const int cx = std::clamp(int(u * s.width), 0, s.width - 1);
    const int cy = std::clamp(int(v * s.height), 0, s.height - 1);
    const std::size_t c = std::size_t(cy) * s.width + cx;
    power[c] += glm::dvec3(texels[i].power);
    direction[c] += glm::dvec3(d) * luminance(texels[i].power);
  }
  image_directions_.clear(), power_.clear();
  double bright_power = 0.0;
  auto add = [this](const glm::dvec3& d, const glm::dvec3& p) {
    const glm::dvec3 unit = glm::normalize(d);
    image_directions_.insert(image_directions_.end(),
                             {float(unit.x), float(unit.y), float(unit.z)});
    power_.insert(power_.end(), {float(p.x), float(p.y), float(p.z)});
  };
  cells_ = 0;
  for (std::size_t c = 0; c < cells; ++c)
    if (luminance(glm::vec3(power[c])) > 0.0 && glm::length(direction[c]) > 0.0) {
      add(direction[c], power[c]);
      ++cells_;
    }
  for (std::size_t i : bright) {
    add(glm::dvec3(texels[i].direction), glm::dvec3(texels[i].power));
    bright_power += luminance(texels[i].power);
  }
  bright_ = std::uint32_t(bright.size());
  bright_share_ = total > 0.0 ? bright_power / total : 0.0;
}

bool ReferenceTexels::update(const prt::sample::Environments& envs,
                             const ReferenceSettings& settings) {
  const bool same_settings = settings.width == settings_.width &&
                             settings.height == settings_.height &&
                             settings.max_bright == settings_.max_bright &&
                             settings.bright_factor == settings_.bright_factor;
  if (version_ == envs.light_version() && map_ == envs.current_index() && same_settings)
    return false;
  if (map_ != envs.current_index() || !same_settings) {
    bin(envs.current(), settings);
    map_ = envs.current_index();
    settings_ = settings;
  }
  // Turned as the light is: the light seen along d in the image comes from R d.
  const glm::mat3 rotation = prt::io::rotation_about_y(envs.rotation_degrees());
  directions_.resize(image_directions_.size());
  for (std::size_t i = 0; i < image_directions_.size(); i += 3) {
    const glm::vec3 d =
        glm::normalize(rotation * glm::vec3(image_directions_[i], image_directions_[i + 1],
                                            image_directions_[i + 2]));
    directions_[i] = d.x, directions_[i + 1] = d.y, directions_[i + 2] = d.z;
  }
  texels_ = prt::sized<prt_cloth_env_texels>();
  texels_.count = std::uint32_t(power_.size() / 3);
  texels_.directions = directions_.data();
  texels_.power = power_.data();
  version_ = envs.light_version();
  return true;
}

std::string ReferenceTexels::describe() const {
  char text[160];
  std::snprintf(text, sizeof text,
                "%dx%d cells (%u lit) + %u texels at full resolution (%.0f %% of the power)",
                settings_.width, settings_.height, cells_, bright_, 100.0 * bright_share_);
  return text;
}

}  // namespace prt::cloth_app
