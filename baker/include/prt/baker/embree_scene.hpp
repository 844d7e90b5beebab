// SPDX-License-Identifier: MIT
// The ray-tracing view of a Scene: every triangle of every mesh in world space in one Embree 3
// BVH, one geometry per mesh.
//
// Degenerate triangles (an index out of range, a repeated index, a non-finite position, or zero
// area) are left out of the BVH and counted; they can never be hit.
//
// Ray-offset policy (docs/reference-renderer.md): a ray leaving a surface starts at the surface
// point moved by ray_epsilon() along the normal on the side it leaves from, with tnear = 0.
// ray_epsilon() is relative to the scene's size: 1e-5 x (largest |coordinate| + bounding radius),
// far above float rounding of positions (~6e-8 x that) and far below any feature of a mesh a
// renderer would use.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"

namespace prt::bake {

struct RayHit {
  float t = 0.0f;
  // Index into Scene::meshes; meshes.size() + k for Scene::occluders[k].
  std::uint32_t mesh = 0;
  std::uint32_t triangle = 0;  // triangle index within that mesh (indices[3*triangle ...])
  float u = 0.0f, v = 0.0f;    // barycentrics: p = (1-u-v) p0 + u p1 + v p2
};

class EmbreeScene {
 public:
  // Builds the BVH. The Scene is copied into Embree's buffers; it need not outlive this object.
  // Throws Error if Embree fails (e.g. out of memory).
  EmbreeScene(const Scene& scene, const Context& ctx);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Thread-safe queries. dir need not be unit length; t is in units of |dir|.
  bool occluded(const glm::vec3& origin, const glm::vec3& dir, float tnear = 0.0f,
                float tfar = INFINITY) const;
  bool intersect(const glm::vec3& origin, const glm::vec3& dir, RayHit* hit, float tnear = 0.0f,
                 float tfar = INFINITY) const;

  // Triangles in the BVH and triangles dropped as degenerate.
  std::size_t triangle_count() const { return triangle_count_; }
  std::size_t dropped_triangles() const { return dropped_triangles_; }
  // World-space bounds of the triangles in the BVH, and the offset of the ray-offset policy.
  const glm::vec3& bounds_lo() const { return lo_; }
  const glm::vec3& bounds_hi() const { return hi_; }
  float ray_epsilon() const { return epsilon_; }
  // Where a ray leaving point p on the side of unit normal n starts.
  glm::vec3 offset_origin(const glm::vec3& p, const glm::vec3& n) const { return p + epsilon_ * n; }

 private:
  friend class RayBatch;  // casts packets into the same BVH (ray_batch.hpp)
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t triangle_count_ = 0, dropped_triangles_ = 0;
  glm::vec3 lo_{0.0f}, hi_{0.0f};
  float epsilon_ = 0.0f;
};

// Whether a triangle would be dropped by EmbreeScene (see above).
bool is_degenerate_triangle(const Mesh& mesh, std::size_t triangle);

}  // namespace prt::bake
