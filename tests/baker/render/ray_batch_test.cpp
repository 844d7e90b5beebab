// SPDX-License-Identifier: MIT
// The ray batch: every mode gives each direction the bit EmbreeScene::occluded (rtcOccluded1)
// gives it, on the demo scene and on a sphere above a plane whose occlusion cone is known, and
// the hit EmbreeScene::intersect gives it; directions on or below the horizon are never cast.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "../../../baker/src/render/embree_scene_impl.hpp"
#include "prt/baker/demo_scene.hpp"
#include "prt/baker/ray_batch.hpp"
#include "prt/baker/sampling.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

using test::make_icosphere;
using test::make_plane;
using test::scene_of;

constexpr RayBatchMode kModes[] = {RayBatchMode::Packet16, RayBatchMode::Single,
                                   RayBatchMode::Stream};

// Directions spread over the whole sphere (about half below any horizon), not unit length.
std::vector<glm::vec3> sphere_directions(std::uint32_t count, std::uint32_t key) {
  const SampleStream stream(key);
  std::vector<glm::vec3> out;
  for (std::uint32_t i = 0; i < count; ++i) {
    const glm::vec2 u = stream.get_2d(i, 0);
    const float z = 1.0f - 2.0f * u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 6.2831853f * u.y;
    out.emplace_back((1.0f + float(i % 3)) * glm::vec3(r * std::cos(phi), z, r * std::sin(phi)));
  }
  return out;
}

// What the batch must return: 0 on or below the horizon, else EmbreeScene::occluded's answer.
std::vector<unsigned char> reference(const EmbreeScene& rays, const glm::vec3& origin,
                                     const glm::vec3& n, const std::vector<glm::vec3>& dirs,
                                     float tnear, float tfar, std::size_t* cast) {
  std::vector<unsigned char> out(dirs.size(), 0);
  *cast = 0;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    if (!(glm::dot(n, dirs[i]) > 0.0f)) continue;
    ++*cast;
    out[i] = rays.occluded(origin, dirs[i], tnear, tfar) ? 0 : 1;
  }
  return out;
}

void expect_modes_agree(const EmbreeScene& rays, const glm::vec3& origin, const glm::vec3& n,
                        const std::vector<glm::vec3>& dirs, float tnear = 0.0f,
                        float tfar = INFINITY) {
  std::size_t expected_cast = 0;
  const std::vector<unsigned char> expected =
      reference(rays, origin, n, dirs, tnear, tfar, &expected_cast);
  for (RayBatchMode mode : kModes) {
    RayBatch batch(rays, mode);
    std::vector<unsigned char> visible(dirs.size(), 7);
    EXPECT_EQ(batch.cast(origin, n, dirs.data(), dirs.size(), visible.data(), tnear, tfar),
              expected_cast)
        << ray_batch_mode_name(mode);
    EXPECT_EQ(visible, expected) << ray_batch_mode_name(mode);
  }
}

TEST(RayBatch, ModesAgreeWithSingleRaysOnTheDemoScene) {
  const Scene scene = make_demo_scene();
  const EmbreeScene rays(scene, Context{});
  const std::vector<glm::vec3> dirs = sphere_directions(333, 11);  // not a multiple of 16
  std::size_t vertices = 0, occluded_some = 0;
  for (const Mesh& mesh : scene.meshes) {
    for (std::size_t v = 0; v < mesh.vertex_count(); v += 97) {
      const glm::vec3 n = glm::normalize(mesh.normals[v]);
      const glm::vec3 origin = rays.offset_origin(mesh.positions[v], n);
      expect_modes_agree(rays, origin, n, dirs);
      std::size_t cast = 0;
      const std::vector<unsigned char> bits = reference(rays, origin, n, dirs, 0, INFINITY, &cast);
      std::size_t open = 0;
      for (unsigned char b : bits) open += b;
      occluded_some += open < cast ? 1 : 0;
      ++vertices;
    }
  }
  EXPECT_GT(vertices, 100u);
  EXPECT_GT(occluded_some, vertices / 10);  // the scene shadows itself: the test sees both bits
}

// Nearest hits: every mode reports exactly EmbreeScene::intersect's hit (rtcIntersect1), bit for
// bit in t and the barycentrics, since the bounce passes interpolate with them; below the horizon
// nothing is cast and the hit is left alone.
TEST(RayBatch, IntersectGivesEmbreeScenesHitsBitForBit) {
  const Scene scene = make_demo_scene();
  const EmbreeScene rays(scene, Context{});
  const std::vector<glm::vec3> dirs = sphere_directions(333, 12);
  std::size_t hits_seen = 0, misses_seen = 0;
  for (const Mesh& mesh : scene.meshes) {
    for (std::size_t v = 0; v < mesh.vertex_count(); v += 131) {
      const glm::vec3 n = glm::normalize(mesh.normals[v]);
      const glm::vec3 origin = rays.offset_origin(mesh.positions[v], n);
      for (RayBatchMode mode : kModes) {
        RayBatch batch(rays, mode);
        RayHit untouched;
        untouched.t = -7.0f;
        std::vector<RayHit> hits(dirs.size(), untouched);
        std::vector<unsigned char> found(dirs.size(), 7);
        std::size_t cast = 0;
        reference(rays, origin, n, dirs, 0.0f, INFINITY, &cast);
        ASSERT_EQ(batch.intersect(origin, n, dirs.data(), dirs.size(), hits.data(), found.data()),
                  cast);
        for (std::size_t i = 0; i < dirs.size(); ++i) {
          RayHit want;
          const bool above = glm::dot(n, dirs[i]) > 0.0f;
          const bool hit = above && rays.intersect(origin, dirs[i], &want);
          ASSERT_EQ(found[i], hit ? 1 : 0) << ray_batch_mode_name(mode) << " direction " << i;
          if (!hit) {
            EXPECT_EQ(hits[i].t, -7.0f);
            ++misses_seen;
            continue;
          }
          ++hits_seen;
          EXPECT_EQ(hits[i].mesh, want.mesh);
          EXPECT_EQ(hits[i].triangle, want.triangle);
          EXPECT_EQ(hits[i].t, want.t);
          EXPECT_EQ(hits[i].u, want.u);
          EXPECT_EQ(hits[i].v, want.v);
        }
      }
    }
  }
  EXPECT_GT(hits_seen, 1000u);
  EXPECT_GT(misses_seen, 1000u);
}

TEST(RayBatch, SphereAbovePlaneOccludesItsCone) {
  // A unit sphere centred 3 above the origin: seen from the origin, it covers the directions
  // within asin(1/3) of +Y. The icosphere lies inside the sphere, so only a margin is checked.
  const float height = 3.0f, radius = 1.0f;
  const Scene scene =
      scene_of({make_plane(10.0f, 4), make_icosphere(4, radius, glm::vec3(0.0f, height, 0.0f))});
  const EmbreeScene rays(scene, Context{});
  const glm::vec3 n(0.0f, 1.0f, 0.0f), origin = rays.offset_origin(glm::vec3(0.0f), n);
  const std::vector<glm::vec3> dirs = sphere_directions(4000, 5);
  const float cone = std::asin(radius / height);
  for (RayBatchMode mode : kModes) {
    RayBatch batch(rays, mode);
    std::vector<unsigned char> visible(dirs.size(), 7);
    batch.cast(origin, n, dirs.data(), dirs.size(), visible.data());
    std::size_t inside = 0, outside = 0;
    for (std::size_t i = 0; i < dirs.size(); ++i) {
      const glm::vec3 d = glm::normalize(dirs[i]);
      const float angle = std::acos(std::min(1.0f, d.y));
      if (!(glm::dot(n, dirs[i]) > 0.0f)) {
        EXPECT_EQ(visible[i], 0) << "below the horizon, " << ray_batch_mode_name(mode);
      } else if (angle < 0.9f * cone) {
        EXPECT_EQ(visible[i], 0) << "inside the cone, " << ray_batch_mode_name(mode);
        ++inside;
      } else if (angle > 1.1f * cone) {
        EXPECT_EQ(visible[i], 1) << "outside the cone, " << ray_batch_mode_name(mode);
        ++outside;
      }
    }
    EXPECT_GT(inside, 50u);
    EXPECT_GT(outside, 1000u);
  }
  expect_modes_agree(rays, origin, n, dirs);
}

TEST(RayBatch, HorizonIsCulledExactly) {
  // Nothing in the scene can block these rays, so visible = 1 exactly when n.d > 0; directions
  // with n.d = 0 exactly, slightly negative, NaN, and zero are never cast.
  const Scene scene = scene_of({make_plane(1.0f, 1, -5.0f)});
  const EmbreeScene rays(scene, Context{});
  const glm::vec3 n(0.0f, 0.0f, 1.0f), origin(0.0f, 0.0f, 0.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN(), tiny = 1e-30f;
  const std::vector<glm::vec3> dirs = {{1, 0, 0},   {0, 1, 0},    {1, 1, tiny}, {1, 1, -tiny},
                                       {0, 0, 1},   {0, 0, -1},   {0, 0, 0},    {nan, 0, 1},
                                       {0, 0, nan}, {0.3f, 0, 1}, {5, 5, -0.0f}};
  const std::vector<unsigned char> expected = {0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0};
  for (RayBatchMode mode : kModes) {
    RayBatch batch(rays, mode);
    std::vector<unsigned char> visible(dirs.size(), 7);
    EXPECT_EQ(batch.cast(origin, n, dirs.data(), dirs.size(), visible.data()), 3u)
        << ray_batch_mode_name(mode);
    EXPECT_EQ(visible, expected) << ray_batch_mode_name(mode);
  }
}

TEST(RayBatch, EmptyBatchesCastNothing) {
  const Scene scene = scene_of({make_plane(1.0f, 1)});
  const EmbreeScene rays(scene, Context{});
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  for (RayBatchMode mode : kModes) {
    RayBatch batch(rays, mode);
    EXPECT_EQ(batch.cast(glm::vec3(0.0f, 1.0f, 0.0f), n, nullptr, 0, nullptr), 0u);
    const std::vector<glm::vec3> below = {{0, -1, 0}, {1, 0, 0}};
    std::vector<unsigned char> visible(below.size(), 7);
    EXPECT_EQ(
        batch.cast(glm::vec3(0.0f, 1.0f, 0.0f), n, below.data(), below.size(), visible.data()), 0u);
    EXPECT_EQ(visible, std::vector<unsigned char>(2, 0));
    // A batch is reusable after an empty cast.
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    unsigned char bit = 7;
    EXPECT_EQ(batch.cast(glm::vec3(0.0f, -1.0f, 0.0f), n, &up, 1, &bit), 1u);
    EXPECT_EQ(bit, 0);  // the plane at y = 0 is in the way
  }
}

TEST(RayBatch, TnearAndTfarBoundTheSegment) {
  // A plane 2 above the origin: the ray up hits it at t = 2 (|d| = 1) or t = 1 (|d| = 2).
  const Scene scene = scene_of({make_plane(4.0f, 2, 2.0f)});
  const EmbreeScene rays(scene, Context{});
  const glm::vec3 n(0.0f, 1.0f, 0.0f), origin(0.1f, 0.0f, 0.2f);
  const std::vector<glm::vec3> dirs = {{0, 1, 0}, {0, 2, 0}, {0.1f, 1, 0}, {0, -1, 0}};
  struct Case {
    float tnear, tfar;
    std::vector<unsigned char> expected;
  };
  const Case cases[] = {
      {0.0f, INFINITY, {0, 0, 0, 0}},  // all blocked (the last is below the horizon)
      {0.0f, 1.5f, {1, 0, 1, 0}},      // only |d| = 2 reaches the plane
      {0.0f, 0.5f, {1, 1, 1, 0}},      // short of it for every length
      {2.5f, INFINITY, {1, 1, 1, 0}},  // starts beyond it
      {1.5f, INFINITY, {0, 1, 0, 0}},  // starts between the two hits
      {3.0f, 1.0f, {1, 1, 1, 0}},      // empty segment
  };
  for (const Case& c : cases) {
    for (RayBatchMode mode : kModes) {
      RayBatch batch(rays, mode);
      std::vector<unsigned char> visible(dirs.size(), 7);
      EXPECT_EQ(batch.cast(origin, n, dirs.data(), dirs.size(), visible.data(), c.tnear, c.tfar),
                3u);
      EXPECT_EQ(visible, c.expected)
          << ray_batch_mode_name(mode) << " tnear " << c.tnear << " tfar " << c.tfar;
    }
    expect_modes_agree(rays, origin, n, dirs, c.tnear, c.tfar);
  }
}

// The one ray set-up EmbreeScene and every batch mode share: the inputs copied field by field,
// no time, id or flags, every mask bit set.
TEST(RayBatch, SharedRaySetUpCopiesInputsAndSetsFullMask) {
  const RTCRay ray = make_embree_ray({1.0f, -2.0f, 3.5f}, {-0.25f, 0.5f, 2.0f}, 0.125f, 7.0f);
  EXPECT_EQ(ray.org_x, 1.0f);
  EXPECT_EQ(ray.org_y, -2.0f);
  EXPECT_EQ(ray.org_z, 3.5f);
  EXPECT_EQ(ray.dir_x, -0.25f);
  EXPECT_EQ(ray.dir_y, 0.5f);
  EXPECT_EQ(ray.dir_z, 2.0f);
  EXPECT_EQ(ray.tnear, 0.125f);
  EXPECT_EQ(ray.tfar, 7.0f);
  EXPECT_EQ(ray.time, 0.0f);
  EXPECT_EQ(ray.mask, 0xFFFFFFFFu);
  EXPECT_EQ(ray.id, 0u);
  EXPECT_EQ(ray.flags, 0u);
  EXPECT_EQ(make_embree_ray({}, {}, 0.0f, INFINITY).tfar, INFINITY);
}

}  // namespace
}  // namespace prt::bake
