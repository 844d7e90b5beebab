// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s preset scenes (prt/baker/shadowfield/shadowfield_scenes.hpp): the
// floor's size and flatness, the room's vertex count, every object resting on the floor at t = 0
// and never sinking into it along its loop, the moving objects' bounding spheres apart at rest
// and along the loop, the materials the issue asks for, and the presets' errors. The presets
// that read ../shared skip when it is missing; the procedural one never does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

struct Sphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};

std::vector<glm::vec3> all_positions(const Scene& scene) {
  std::vector<glm::vec3> positions;
  for (const Mesh& mesh : scene.meshes) {
    positions.insert(positions.end(), mesh.positions.begin(), mesh.positions.end());
  }
  return positions;
}

// Centre of the bounds and the farthest vertex from it, as the shadowfield bake bounds objects.
Sphere bounding_sphere(const Scene& scene) {
  glm::vec3 lo, hi;
  scene.bounds(lo, hi);
  Sphere s{0.5f * (lo + hi), 0.0f};
  for (const glm::vec3& p : all_positions(scene))
    s.radius = std::max(s.radius, glm::length(p - s.centre));
  return s;
}

Sphere placed(const Sphere& s, const ShadowfieldPlacement& p) {
  return {p.apply(s.centre), s.radius * p.scale};
}

bool is_shell(const ShadowfieldSceneObject& object) {
  return object.name == "floor" || object.name == "wall";
}

const ShadowfieldSceneObject& floor_of(const ShadowfieldSceneDescription& scene) {
  for (const ShadowfieldSceneObject& object : scene.objects) {
    if (object.name == "floor") return object;
  }
  throw Error(scene.name + ": no floor");
}

float lowest_point(const std::vector<glm::vec3>& positions, const ShadowfieldPlacement& p) {
  float lowest = INFINITY;
  for (const glm::vec3& v : positions) lowest = std::min(lowest, p.apply(v).y);
  return lowest;
}

float longest_loop(const ShadowfieldSceneDescription& scene) {
  float longest = 0.0f;
  for (const ShadowfieldInstance& i : scene.instances) longest = std::max(longest, i.path.duration);
  return longest;
}

class Scenes : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    const std::string name = GetParam();
    if (shadowfield_scene_needs_shared(name) && prt_test::shared_asset("meshes").empty())
      GTEST_SKIP() << "no ../shared/assets/meshes";
    scene_ = make_shadowfield_scene(name, PRT_SHARED_DIR);
  }
  ShadowfieldSceneDescription scene_;
};

TEST_P(Scenes, TheFloorHas4096VerticesAndIsFlat) {
  const Scene& floor = floor_of(scene_).mesh;
  EXPECT_EQ(floor.vertex_count(), 4096u);
  for (const Mesh& mesh : floor.meshes) {
    for (const glm::vec3& n : mesh.normals) EXPECT_EQ(n, glm::vec3(0.0f, 1.0f, 0.0f));
    for (const glm::vec3& p : mesh.positions) EXPECT_EQ(p.y, 0.0f);
  }
}

TEST_P(Scenes, EveryObjectIsAValidMesh) {
  ASSERT_FALSE(scene_.objects.empty());
  for (const ShadowfieldSceneObject& object : scene_.objects) {
    ASSERT_FALSE(object.mesh.meshes.empty()) << object.name;
    for (const Mesh& mesh : object.mesh.meshes) {
      ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << object.name;
      EXPECT_EQ(mesh.local_positions, mesh.positions) << object.name;
      ASSERT_GE(mesh.material, 0);
      ASSERT_LT(std::size_t(mesh.material), object.mesh.materials.size());
      for (std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size()) << object.name;
      for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
    }
    if (object.material.model == ShadowfieldBrdfModel::Phong) check_brdf(object.material.phong);
    if (object.material.model == ShadowfieldBrdfModel::Ggx) check_brdf(object.material.ggx);
  }
  for (const ShadowfieldInstance& instance : scene_.instances) {
    ASSERT_LT(instance.object, scene_.objects.size());
    instance.path.check();
  }
}

TEST_P(Scenes, EveryObjectRestsOnTheFloorAtTimeZero) {
  for (const ShadowfieldInstance& instance : scene_.instances) {
    const ShadowfieldSceneObject& object = scene_.objects[instance.object];
    if (object.name == "floor") continue;
    const float lowest = lowest_point(all_positions(object.mesh), instance.path.at(0.0f));
    EXPECT_GE(lowest, 0.0f) << object.name;
    // Objects stand on their origin and turn about +Y only: the gap holds to rounding.
    EXPECT_FLOAT_EQ(lowest, kShadowfieldRestGap) << object.name;
  }
}

TEST_P(Scenes, MovingObjectsNeverSinkIntoTheFloorNorLeaveIt) {
  const float loop = longest_loop(scene_);
  glm::vec3 floor_lo, floor_hi;
  floor_of(scene_).mesh.bounds(floor_lo, floor_hi);
  for (const ShadowfieldInstance& instance : scene_.instances) {
    const ShadowfieldSceneObject& object = scene_.objects[instance.object];
    if (is_shell(object)) continue;
    const std::vector<glm::vec3> positions = all_positions(object.mesh);
    const Sphere sphere = bounding_sphere(object.mesh);
    for (int step = 0; step < 96; ++step) {
      const ShadowfieldPlacement p = instance.path.at(loop * float(step) / 96.0f);
      ASSERT_GE(lowest_point(positions, p), 0.0f) << object.name << " at step " << step;
      const Sphere s = placed(sphere, p);
      EXPECT_LE(std::abs(s.centre.x) + s.radius, floor_hi.x) << object.name;
      EXPECT_LE(std::abs(s.centre.z) + s.radius, floor_hi.z) << object.name;
    }
  }
}

// Bounding spheres apart implies the meshes are apart: at rest (the issue) and, by design, all
// along the loop, sampled.
TEST_P(Scenes, MovingObjectsStayApart) {
  std::vector<std::pair<Sphere, const ShadowfieldInstance*>> moving;
  for (const ShadowfieldInstance& instance : scene_.instances) {
    const ShadowfieldSceneObject& object = scene_.objects[instance.object];
    if (!is_shell(object)) moving.push_back({bounding_sphere(object.mesh), &instance});
  }
  const float loop = longest_loop(scene_);
  float closest_gap = INFINITY;
  for (int step = 0; step < 96; ++step) {
    const float t = loop * float(step) / 96.0f;
    for (std::size_t i = 0; i < moving.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        const Sphere a = placed(moving[i].first, moving[i].second->path.at(t));
        const Sphere b = placed(moving[j].first, moving[j].second->path.at(t));
        const float gap = glm::length(a.centre - b.centre) - a.radius - b.radius;
        closest_gap = std::min(closest_gap, gap);
        if (step == 0) {
          EXPECT_GT(gap, 0.0f) << "at rest: instances " << i << " and " << j;
        }
      }
    }
  }
  if (moving.size() < 2) return;
  EXPECT_GT(closest_gap, 0.0f);
  std::printf("%s: closest bounding spheres along the loop %.3f m apart\n", scene_.name.c_str(),
              closest_gap);
}

INSTANTIATE_TEST_SUITE_P(Presets, Scenes, ::testing::ValuesIn(shadowfield_scene_names()),
                         [](const auto& info) { return info.param; });

ShadowfieldSceneDescription shared_scene(const std::string& name) {
  return make_shadowfield_scene(name, PRT_SHARED_DIR);
}

TEST(Room, HasAbout25kVerticesAndSixMovingObjects) {
  if (prt_test::shared_asset("meshes").empty()) GTEST_SKIP() << "no ../shared/assets/meshes";
  const ShadowfieldSceneDescription room = shared_scene("room");
  const std::size_t vertices = room.instanced_vertex_count();
  std::printf("room: %zu vertices over %zu instances\n", vertices, room.instances.size());
  EXPECT_GE(vertices, 24000u);
  EXPECT_LE(vertices, 26000u);
  int moving = 0, glossy = 0;
  for (const ShadowfieldInstance& instance : room.instances) {
    const ShadowfieldSceneObject& object = room.objects[instance.object];
    if (is_shell(object)) continue;
    ++moving;
    glossy += object.material.model != ShadowfieldBrdfModel::Diffuse;
    EXPECT_GE(instance.path.keyframes.size(), 2u) << object.name;
  }
  EXPECT_EQ(moving, 6);
  EXPECT_GE(glossy, 1);
}

TEST(Teapot, IsGlossyPhong10OnTheFloor) {
  if (prt_test::shared_asset("meshes/teapot.obj").empty()) GTEST_SKIP() << "no teapot.obj";
  const ShadowfieldSceneDescription scene = shared_scene("teapot");
  ASSERT_EQ(scene.objects.size(), 2u);
  const ShadowfieldSceneObject& teapot = scene.objects[1];
  EXPECT_EQ(teapot.mesh.vertex_count(), 3644u);
  EXPECT_EQ(teapot.material.model, ShadowfieldBrdfModel::Phong);
  EXPECT_EQ(teapot.material.phong.exponent, 10.0);
  // The floor is about four times the teapot's size.
  glm::vec3 lo, hi, floor_lo, floor_hi;
  teapot.mesh.bounds(lo, hi);
  scene.objects[0].mesh.bounds(floor_lo, floor_hi);
  const float scale = scene.instances[1].path.at(0.0f).scale;
  EXPECT_NEAR((floor_hi.x - floor_lo.x) / (scale * std::max(hi.x - lo.x, hi.z - lo.z)), 4.0f,
              1e-5f);
}

TEST(Bunny, IsTheFullResolutionBunny) {
  if (prt_test::shared_asset("meshes/stanford-bunny.obj").empty()) GTEST_SKIP() << "no bunny";
  const ShadowfieldSceneDescription scene = shared_scene("bunny");
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[1].mesh.vertex_count(), 35947u);
}

TEST(Presets, ProceduralNeedsNoSharedFolder) {
  EXPECT_FALSE(shadowfield_scene_needs_shared("procedural"));
  const ShadowfieldSceneDescription scene = make_shadowfield_scene("procedural", "/nonexistent");
  EXPECT_EQ(scene.env, kShadowfieldBuiltinSky);
  EXPECT_EQ(scene.objects.size(), 4u);
  bool glossy = false;
  for (const ShadowfieldSceneObject& object : scene.objects)
    glossy |= object.material.model != ShadowfieldBrdfModel::Diffuse;
  EXPECT_TRUE(glossy);
}

TEST(Presets, ErrorsNameTheProblem) {
  try {
    make_shadowfield_scene("teapot", "/nonexistent");
    FAIL() << "no error without the shared folder";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("teapot.obj"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_shadowfield_scene("kitchen", PRT_SHARED_DIR), Error);
}

}  // namespace
}  // namespace prt::bake
