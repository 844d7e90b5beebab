// SPDX-License-Identifier: MIT
// The one estimator of outgoing radiance that vertices and image pixels share (private header).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/reference.hpp"
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
  // Unit, towards the viewer: the direction back along the path (at a vertex: to the eye). Only a
  // glossy surface reads it.
  glm::vec3 outgoing{0.0f, 1.0f, 0.0f};
  std::uint32_t mesh = 0;  // whose BRDF applies
};

class PathEstimator {
 public:
  // All references must outlive the estimator. vertex_albedo holds one entry per scene vertex,
  // mesh_brdf one per scene mesh.
  PathEstimator(const Scene& scene, const EmbreeScene& rays, const io::EnvMap& env,
                const EnvDistribution& env_distribution,
                const std::vector<glm::vec3>& vertex_albedo,
                const std::vector<SurfaceBrdf>& mesh_brdf, int bounces);

  // One sample of the outgoing radiance at `point` towards point.outgoing: point `index` of
  // `stream`, using dimension pairs first_pair, first_pair+1, ... (two per path vertex). Adds the
  // rays traced to *rays.
  glm::vec3 sample(const SurfacePoint& point, const SampleStream& stream, std::uint32_t index,
                   std::uint32_t first_pair, std::uint64_t* rays) const;

  // The surface a ray with direction `dir` hit, its normals faced against the ray, seen along
  // -dir.
  SurfacePoint surface_at(const RayHit& hit, const glm::vec3& dir) const;
  // Scene vertex `vertex` (Scene order), seen along its normal; false if it has no usable
  // (finite, non-zero) normal.
  bool vertex_point(std::size_t vertex, SurfacePoint* point) const;

  std::size_t vertex_count() const { return vertex_mesh_.size(); }

 private:
  // How a path vertex ends its step: the path goes on from `next` (along -next.outgoing), or
  // stops.
  enum class Step { Continue, Stop };
  // One path vertex on a Lambertian surface (two strategies) or a glossy one (three): adds what
  // reaches the viewer to *radiance, scales *throughput and fills *next when the path goes on.
  Step lambert_step(const SurfacePoint& x, const SampleStream& stream, std::uint32_t index,
                    std::uint32_t pair, bool last, glm::vec3* throughput, glm::vec3* radiance,
                    SurfacePoint* next, std::uint64_t* rays) const;
  Step glossy_step(const SurfacePoint& x, const SampleStream& stream, std::uint32_t index,
                   std::uint32_t pair, bool last, glm::vec3* throughput, glm::vec3* radiance,
                   SurfacePoint* next, std::uint64_t* rays) const;

  const Scene& scene_;
  const EmbreeScene& rays_;
  const io::EnvMap& env_;
  const EnvDistribution& env_distribution_;
  const std::vector<glm::vec3>& vertex_albedo_;
  const std::vector<SurfaceBrdf>& mesh_brdf_;
  int bounces_;
  std::vector<std::size_t> first_vertex_;   // per mesh: its first vertex in Scene order
  std::vector<std::uint32_t> vertex_mesh_;  // per scene vertex: its mesh
};

}  // namespace prt::bake::render
