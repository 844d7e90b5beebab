// SPDX-License-Identifier: MIT
// The Embree scene: hits land on the right mesh and triangle, degenerate triangles are dropped
// and counted, and the ray-offset policy keeps surfaces from shadowing themselves.
#include <gtest/gtest.h>

#include <limits>

#include "prt/baker/embree_scene.hpp"
#include "prt/baker/sampling.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

using test::make_icosphere;
using test::make_plane;
using test::scene_of;

TEST(EmbreeScene, HitReportsMeshTriangleAndDistance) {
  // Two planes: y = 0 (mesh 0) and y = 1 (mesh 1), 2x2 cells each.
  const Scene scene = scene_of({make_plane(1.0f, 2), make_plane(1.0f, 2, 1.0f)});
  const EmbreeScene rays(scene, Context{});
  EXPECT_EQ(rays.triangle_count(), 16u);
  EXPECT_EQ(rays.dropped_triangles(), 0u);

  RayHit hit;
  const glm::vec3 origin(0.3f, 5.0f, -0.6f), down(0.0f, -1.0f, 0.0f);
  ASSERT_TRUE(rays.intersect(origin, down, &hit));
  EXPECT_EQ(hit.mesh, 1u);
  EXPECT_NEAR(hit.t, 4.0f, 1e-5f);
  // The hit point rebuilt from the reported triangle and barycentrics is the ray's point.
  const Mesh& mesh = scene.meshes[hit.mesh];
  const glm::vec3 p = (1 - hit.u - hit.v) * mesh.positions[mesh.indices[3 * hit.triangle]] +
                      hit.u * mesh.positions[mesh.indices[3 * hit.triangle + 1]] +
                      hit.v * mesh.positions[mesh.indices[3 * hit.triangle + 2]];
  EXPECT_NEAR(glm::distance(p, origin + hit.t * down), 0.0f, 1e-5f);

  ASSERT_TRUE(rays.intersect(glm::vec3(0.3f, 0.5f, -0.6f), down, &hit));
  EXPECT_EQ(hit.mesh, 0u);
  EXPECT_TRUE(rays.occluded(origin, down));
  EXPECT_FALSE(rays.occluded(origin, -down));
  EXPECT_FALSE(rays.occluded(origin, down, 0.0f, 3.9f));                  // stops short of y = 1
  EXPECT_FALSE(rays.intersect(glm::vec3(3.0f, 5.0f, 0.0f), down, &hit));  // beside both planes
}

TEST(EmbreeScene, DegenerateTrianglesAreDroppedAndCounted) {
  Mesh mesh = make_plane(1.0f, 1);  // 4 vertices, 2 good triangles
  const float nan = std::numeric_limits<float>::quiet_NaN();
  mesh.positions.push_back(glm::vec3(nan, 0.0f, 0.0f));                         // 4: NaN
  mesh.positions.push_back(glm::vec3(std::numeric_limits<float>::infinity()));  // 5: Inf
  mesh.positions.push_back(glm::vec3(0.0f, 0.0f, 0.0f));                        // 6, 7, 8:
  mesh.positions.push_back(glm::vec3(0.5f, 0.0f, 0.0f));                        // collinear
  mesh.positions.push_back(glm::vec3(1.0f, 0.0f, 0.0f));
  mesh.normals.resize(mesh.positions.size(), glm::vec3(0, 1, 0));
  mesh.indices.insert(mesh.indices.end(), {
                                              0, 1, 1,   // repeated index
                                              2, 2, 2,   // all the same
                                              0, 4, 1,   // NaN position
                                              5, 0, 1,   // infinite position
                                              6, 7, 8,   // zero area
                                              0, 1, 99,  // index out of range
                                              0, 3, 3,   // repeated index
                                          });
  const Scene scene = scene_of({mesh});
  int warnings = 0;
  Context ctx;
  ctx.log = [&](LogLevel level, const std::string&) { warnings += level == LogLevel::Warning; };
  const EmbreeScene rays(scene, ctx);
  EXPECT_EQ(rays.triangle_count(), 2u);
  EXPECT_EQ(rays.dropped_triangles(), 7u);
  EXPECT_EQ(warnings, 1);
  // The good triangles still work, and the bounds ignore the non-finite vertices.
  EXPECT_TRUE(rays.occluded(glm::vec3(0.1f, 1.0f, 0.2f), glm::vec3(0, -1, 0)));
  EXPECT_EQ(rays.bounds_lo(), glm::vec3(-1.0f, 0.0f, -1.0f));
  EXPECT_EQ(rays.bounds_hi(), glm::vec3(1.0f, 0.0f, 1.0f));
}

TEST(EmbreeScene, EmptySceneHitsNothing) {
  const EmbreeScene rays(Scene{}, Context{});
  RayHit hit;
  EXPECT_EQ(rays.triangle_count(), 0u);
  EXPECT_FALSE(rays.occluded(glm::vec3(0.0f), glm::vec3(0, 1, 0)));
  EXPECT_FALSE(rays.intersect(glm::vec3(0.0f), glm::vec3(0, 1, 0), &hit));
}

// Fraction of `count` cosine-distributed rays about n, offset by the policy, that are blocked.
double blocked_fraction(const EmbreeScene& rays, const glm::vec3& p, const glm::vec3& n,
                        std::uint32_t key, int count) {
  const SampleStream stream(key);
  const Frame frame(n);
  const glm::vec3 origin = rays.offset_origin(p, n);
  int blocked = 0;
  for (int i = 0; i < count; ++i) {
    blocked += rays.occluded(origin, frame.to_world(cosine_hemisphere(stream.get_2d(i, 0))));
  }
  return static_cast<double>(blocked) / count;
}

TEST(EmbreeScene, ClosedSphereDoesNotShadowItselfFromItsVertices) {
  // Far from the origin and small, so float rounding of positions is as large as it gets.
  const Scene scene = scene_of({make_icosphere(5, 0.05f, glm::vec3(30.0f, -12.0f, 7.0f))});
  const EmbreeScene rays(scene, Context{});
  const Mesh& mesh = scene.meshes[0];
  std::size_t blocked_vertices = 0;
  double blocked_sum = 0.0;
  for (std::size_t v = 0; v < mesh.vertex_count(); v += 7) {
    const double f = blocked_fraction(rays, mesh.positions[v], mesh.normals[v], v, 64);
    blocked_sum += f;
    blocked_vertices += f > 0.0;
  }
  EXPECT_EQ(blocked_vertices, 0u) << "mean blocked fraction " << blocked_sum;
}

TEST(EmbreeScene, PlaneHasNoSelfHitsFromVerticesOrInteriorPoints) {
  const Scene scene = scene_of({make_plane(100.0f, 50, 3.0f)});
  const EmbreeScene rays(scene, Context{});
  const Mesh& mesh = scene.meshes[0];
  for (std::size_t v = 0; v < mesh.vertex_count(); v += 3) {
    ASSERT_EQ(blocked_fraction(rays, mesh.positions[v], mesh.normals[v], v, 32), 0.0) << v;
  }
  // Points where rays from above land on the plane, then rays leaving them, both sides.
  const SampleStream stream(7);
  for (std::uint32_t i = 0; i < 2000; ++i) {
    const glm::vec2 u = stream.get_2d(i, 0);
    const glm::vec3 above(180.0f * u.x - 90.0f, 50.0f, 180.0f * u.y - 90.0f);
    RayHit hit;
    ASSERT_TRUE(rays.intersect(above, glm::vec3(0.1f, -1.0f, 0.05f), &hit));
    const glm::vec3 p = above + hit.t * glm::vec3(0.1f, -1.0f, 0.05f);
    for (const float side : {1.0f, -1.0f}) {
      const glm::vec3 n(0.0f, side, 0.0f);
      ASSERT_EQ(blocked_fraction(rays, p, n, i, 8), 0.0) << "point " << i << " side " << side;
    }
  }
}

}  // namespace
}  // namespace prt::bake
