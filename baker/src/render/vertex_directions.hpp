// SPDX-License-Identifier: MIT
// The per-vertex cosine-weighted directions the transfer bakes share (private header): which
// vertices can cast rays at all, and the i-th direction of a vertex's own Sobol stream.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "prt/baker/sampling.hpp"

namespace prt::bake::render {

// A normal the bakes can build a frame from: finite and not (nearly) zero.
inline bool usable_normal(const glm::vec3& n) {
  const float len2 = glm::dot(n, n);
  return std::isfinite(len2) && len2 > 1e-12f;
}

inline bool finite_point(const glm::vec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// The i-th direction of a vertex: cosine-weighted about its unit normal, from a stream keyed by
// (seed, vertex, tag); each bake passes its own tag so two bakes never share sample points.
struct VertexDirections {
  SampleStream stream;
  Frame frame;
  VertexDirections(std::uint32_t seed, std::size_t vertex, const glm::vec3& normal,
                   std::uint64_t tag)
      : stream(hash_key(seed, vertex, tag)), frame(normal) {}
  // In the frame's coordinates (normal +Z), and in the world.
  glm::vec3 local(std::uint32_t i) const { return cosine_hemisphere(stream.get_2d(i, 0)); }
  glm::vec3 operator()(std::uint32_t i) const { return frame.to_world(local(i)); }
};

}  // namespace prt::bake::render
