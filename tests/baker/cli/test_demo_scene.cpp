// SPDX-License-Identifier: MIT
// The built-in demo scene and sky: well formed, and they survive the trip through their files.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "prt/baker/demo_scene.hpp"

namespace prt::bake {
namespace {

TEST(DemoScene, MeshesAreWellFormed) {
  Scene scene = make_demo_scene();
  ASSERT_EQ(scene.meshes.size(), 4u);
  for (const Mesh& mesh : scene.meshes) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << mesh.name;
    ASSERT_EQ(mesh.indices.size() % 3, 0u);
    for (std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size());
    for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
    // Triangles wind counter-clockwise seen from outside: the face normal agrees with the
    // vertex normals (glTF's convention).
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      const glm::vec3& a = mesh.positions[mesh.indices[t]];
      glm::vec3 face = glm::cross(mesh.positions[mesh.indices[t + 1]] - a,
                                  mesh.positions[mesh.indices[t + 2]] - a);
      if (glm::length(face) < 1e-6f) continue;  // zero-area triangles at the sphere poles
      glm::vec3 n = mesh.normals[mesh.indices[t]] + mesh.normals[mesh.indices[t + 1]] +
                    mesh.normals[mesh.indices[t + 2]];
      ASSERT_GT(glm::dot(face, n), 0.0f) << mesh.name << " triangle " << t / 3;
    }
  }
  // Everything stands on the ground (y >= 0) and the ground is at y = 0.
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  EXPECT_NEAR(lo.y, 0.0f, 1e-5f);
  EXPECT_GT(hi.y, 0.5f);
}

TEST(DemoScene, SunHoldsMostOfTheSkyPower) {
  io::EnvMap sky = make_demo_sky(256);
  double total = 0.0, sun = 0.0, solid_angle = 0.0;
  for (int y = 0; y < sky.height(); ++y) {
    for (int x = 0; x < sky.width(); ++x) {
      glm::vec3 dir;
      float omega = 0.0f;
      ASSERT_TRUE(sky.texel(x, y, &dir, &omega));
      solid_angle += omega;
      glm::vec3 value = sky.texel_value(x, y);
      double power = (value.r + value.g + value.b) / 3.0 * omega;
      total += power;
      if (value.r > 100.0f) sun += power;
    }
  }
  // The lat-long covers the sphere; its texel solid angles are exact (SPEC §12), so but for
  // float rounding.
  EXPECT_NEAR(solid_angle, 4.0 * M_PI, 1e-6 * 4.0 * M_PI);
  EXPECT_GT(sun / total, 0.3);
  EXPECT_LT(sun / total, 0.9);
}

TEST(DemoScene, RoundTripsThroughGlbAndHdr) {
  const auto dir = std::filesystem::path(testing::TempDir()) / "prt_demo_scene";
  std::filesystem::create_directories(dir);
  Scene scene = make_demo_scene();
  write_glb(scene, (dir / "scene.glb").string());
  Scene loaded = import_scene((dir / "scene.glb").string(), Context{});
  ASSERT_EQ(loaded.meshes.size(), scene.meshes.size());
  ASSERT_EQ(loaded.vertex_count(), scene.vertex_count());
  ASSERT_EQ(loaded.triangle_count(), scene.triangle_count());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh &a = scene.meshes[m], &b = loaded.meshes[m];
    ASSERT_EQ(a.indices, b.indices);
    for (std::size_t v = 0; v < a.positions.size(); ++v)
      ASSERT_EQ(a.positions[v], b.positions[v]);  // float32 stored exactly
    EXPECT_EQ(loaded.vertex_albedo(b, 0), glm::vec3(scene.materials[a.material].base_color));
  }

  io::EnvMap sky = make_demo_sky(128);
  write_envmap_hdr(sky, (dir / "sky.hdr").string());
  io::EnvMap read = io::load_envmap((dir / "sky.hdr").string(), io::EnvMapping::Auto);
  ASSERT_EQ(read.mapping(), io::EnvMapping::LatLong);
  ASSERT_EQ(read.width(), sky.width());
  ASSERT_EQ(read.height(), sky.height());
  // RGBE keeps 8 mantissa bits of the largest channel: relative error below 2^-7.
  for (std::size_t i = 0; i < sky.pixels().size(); i += 3) {
    float largest = std::max({sky.pixels()[i], sky.pixels()[i + 1], sky.pixels()[i + 2]});
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(read.pixels()[i + c], sky.pixels()[i + c], largest / 128.0f) << i / 3;
  }
}

}  // namespace
}  // namespace prt::bake
