// SPDX-License-Identifier: MIT
// The one estimator of outgoing radiance that vertices and image pixels share (private header).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/sampling.hpp"
#include "prt/baker/scene.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake::render {

struct SurfacePoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};  // unit; the hemisphere integrated over
  // Unit, on the side of `normal`, for points inside a triangle; zero at a vertex, which has no
  // single plane: there the neighbouring triangles themselves stop rays that dive under them.
  glm::vec3 geometric_normal{0.0f};
  glm::vec3 albedo{0.0f};
};

class PathEstimator {
 public:
  // All references must outlive the estimator. vertex_albedo holds one entry per scene vertex.
  PathEstimator(const Scene& scene, const EmbreeScene& rays, const io::EnvMap& env,
                const EnvDistribution& env_distribution,
                const std::vector<glm::vec3>& vertex_albedo, int bounces);

  // One sample of the outgoing radiance at `point`: point `index` of `stream`, using dimension
  // pairs first_pair, first_pair+1, ... (two per path vertex). Adds the rays traced to *rays.
  glm::vec3 sample(const SurfacePoint& point, const SampleStream& stream, std::uint32_t index,
                   std::uint32_t first_pair, std::uint64_t* rays) const;

  // The surface a ray with direction `dir` hit, its normals faced against the ray.
  SurfacePoint surface_at(const RayHit& hit, const glm::vec3& dir) const;
  // Scene vertex `vertex` (Scene order); false if it has no usable (finite, non-zero) normal.
  bool vertex_point(std::size_t vertex, SurfacePoint* point) const;

  std::size_t vertex_count() const { return vertex_mesh_.size(); }

 private:
  const Scene& scene_;
  const EmbreeScene& rays_;
  const io::EnvMap& env_;
  const EnvDistribution& env_distribution_;
  const std::vector<glm::vec3>& vertex_albedo_;
  int bounces_;
  std::vector<std::size_t> first_vertex_;   // per mesh: its first vertex in Scene order
  std::vector<std::uint32_t> vertex_mesh_;  // per scene vertex: its mesh
};

}  // namespace prt::bake::render
