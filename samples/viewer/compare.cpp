// SPDX-License-Identifier: MIT
#include "compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "blob_scene.hpp"

namespace prt::view {

std::vector<float> relative_vertex_error(const std::vector<glm::vec3>& x,
                                         const std::vector<glm::vec3>& ref) {
  double mean = 0.0;
  for (const glm::vec3& r : ref) mean += glm::length(glm::dvec3(r));
  mean = ref.empty() ? 0.0 : mean / static_cast<double>(ref.size());
  std::vector<float> error(std::min(x.size(), ref.size()));
  for (std::size_t v = 0; v < error.size(); ++v) {
    const double e = glm::length(glm::dvec3(x[v]) - glm::dvec3(ref[v]));
    error[v] = static_cast<float>(mean > 0.0 ? e / mean : (e > 0.0 ? INFINITY : 0.0));
  }
  return error;
}

glm::vec3 heat_colour(float error, float scale) {
  static const glm::vec3 kRamp[] = {{0.0f, 0.0f, 0.0f}, {0.15f, 0.1f, 0.6f}, {0.7f, 0.15f, 0.6f},
                                    {1.0f, 0.5f, 0.1f}, {1.0f, 0.9f, 0.2f},  {1.0f, 1.0f, 1.0f}};
  constexpr int kSteps = static_cast<int>(sizeof kRamp / sizeof kRamp[0]) - 1;
  float t = scale > 0.0f ? error / scale : 1.0f;
  if (!(t >= 0.0f)) t = 0.0f;  // NaN
  t = std::min(t, 1.0f) * kSteps;
  const int i = std::min(static_cast<int>(t), kSteps - 1);
  return glm::mix(kRamp[i], kRamp[i + 1], t - static_cast<float>(i));
}

}  // namespace prt::view
