// SPDX-License-Identifier: MIT
// The error figure every technique's accuracy is stated in: relative RMSE of per-vertex radiance
// against the reference renderer, sqrt(mean |x - ref|^2) / sqrt(mean |ref|^2) over all vertices
// and the three channels. It is the definition the reference renderer uses for its own noise
// estimate (VertexRadiance::relative_rmse), so the two can be compared directly. Vertices the
// reference leaves at 0 (no usable normal) add nothing to the reference's sum; an estimate that
// also gives them 0 adds nothing to the difference either.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/io/error.hpp"

namespace prt::io {

// Throws Error when the sizes differ or the reference is all zero.
inline double relative_rmse(const std::vector<glm::vec3>& estimate,
                            const std::vector<glm::vec3>& reference) {
  if (estimate.size() != reference.size()) {
    throw Error("relative RMSE: " + std::to_string(estimate.size()) + " values against " +
                std::to_string(reference.size()) + " reference values");
  }
  double difference_sq = 0.0, reference_sq = 0.0;
  for (std::size_t v = 0; v < reference.size(); ++v) {
    const glm::dvec3 d = glm::dvec3(estimate[v]) - glm::dvec3(reference[v]);
    difference_sq += glm::dot(d, d);
    reference_sq += glm::dot(glm::dvec3(reference[v]), glm::dvec3(reference[v]));
  }
  if (!(reference_sq > 0.0)) throw Error("relative RMSE: the reference is zero everywhere");
  return std::sqrt(difference_sq / reference_sq);
}

}  // namespace prt::io
