// SPDX-License-Identifier: MIT
// Comparing shaded per-vertex radiance with a reference (`prt-bake reference --vertex-out`):
// reading the .npy and the error heat map. The error figure itself is the project's one
// definition, prt::io::relative_rmse (prt/io/radiance_error.hpp).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace prt::view {

// Per-vertex error for the heat map: |x - ref| (Euclidean over RGB) divided by the mean of
// |ref| over all vertices, so 0.1 means "10 % of a typical vertex's radiance".
std::vector<float> relative_vertex_error(const std::vector<glm::vec3>& x,
                                         const std::vector<glm::vec3>& ref);

// The heat map's colour ramp (black, blue, magenta, orange, yellow, white: monotonic in
// lightness) at e / scale, clamped to [0, 1]; sRGB-encoded values in [0,1].
glm::vec3 heat_colour(float error, float scale);

}  // namespace prt::view
