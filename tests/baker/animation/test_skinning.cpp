// SPDX-License-Identifier: MIT
// Posed scenes: at rest they are the importer's own; through a clip every skinned vertex lands
// where an independent computation puts it (each joint's chain of translations, quaternion
// rotations and scales applied to the point in double, the points blended, instead of products
// of float matrices); normals stay unit and perpendicular under non-uniform scale; weights that
// do not sum to one are normalised; the Draco copies pose like their originals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "prt/baker/animation.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using prt_test::shared_asset;

const char* const kCharacters[] = {
    "characters/SimpleSkin.gltf", "characters/RiggedSimple/RiggedSimple.gltf",
    "characters/RiggedFigure.glb", "characters/CesiumMan.glb", "characters/Fox.glb"};

#define IMPORT_OR_SKIP(var, relative)                                            \
  if (shared_asset(relative).empty()) GTEST_SKIP() << "shared assets not found"; \
  const Scene var = import_scene(shared_asset(relative), Context{})

// p moved by node n's world transform, each node's T, R (a quaternion rotating the vector) and
// S applied in turn from n up to its root, in double.
glm::dvec3 through_chain(const Scene& scene, const ScenePose& pose, int n, glm::dvec3 p) {
  for (; n >= 0; n = scene.nodes[static_cast<std::size_t>(n)].parent) {
    const NodeTRS& trs = pose.local(static_cast<std::size_t>(n));
    const glm::dquat q(trs.rotation.w, trs.rotation.x, trs.rotation.y, trs.rotation.z);
    p = glm::dvec3(trs.translation) + q * (glm::dvec3(trs.scale) * p);
  }
  return p;
}

// Vertex i of a skinned mesh at the pose, blended from each joint's chain.
glm::dvec3 reference_position(const Scene& scene, const ScenePose& pose, const Mesh& mesh,
                              std::size_t i) {
  const Skin& skin = scene.skins[static_cast<std::size_t>(mesh.skin)];
  const glm::vec4 w = mesh.weights0[i];
  const double total = double(w.x) + w.y + w.z + w.w;
  glm::dvec3 sum(0.0);
  for (int k = 0; k < 4; ++k) {
    if (w[k] == 0.0f) continue;
    const std::size_t j = mesh.joints0[i][k];
    const glm::dvec3 bind_local =
        glm::dvec3(glm::dmat4(skin.inverse_bind[j]) * glm::dvec4(mesh.local_positions[i], 1.0));
    sum += (double(w[k]) / total) * through_chain(scene, pose, skin.joints[j], bind_local);
  }
  return sum;
}

double extent(const Mesh& mesh) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return double(glm::length(hi - lo));
}

TEST(ScenePose, AtRestGivesTheImportersMatricesAndMeshes) {
  for (const char* relative : kCharacters) {
    SCOPED_TRACE(relative);
    IMPORT_OR_SKIP(scene, relative);
    const ScenePose rest(scene);
    const std::vector<glm::mat4> world = rest.world_matrices();
    ASSERT_EQ(world.size(), scene.nodes.size());
    for (std::size_t n = 0; n < world.size(); ++n) EXPECT_EQ(world[n], scene.nodes[n].world);
    const Scene posed = posed_scene(scene, rest);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
      EXPECT_EQ(posed.meshes[m].positions, scene.meshes[m].positions);
      EXPECT_EQ(posed.meshes[m].normals, scene.meshes[m].normals);
    }
  }
}

TEST(ScenePose, SkinnedVerticesFollowEachJointsOwnChain) {
  for (const char* relative : kCharacters) {
    SCOPED_TRACE(relative);
    IMPORT_OR_SKIP(scene, relative);
    ASSERT_FALSE(scene.animations.empty());
    for (const Animation& clip : scene.animations) {
      for (float time : {0.0f, 0.37f * clip.duration, 0.81f * clip.duration, clip.duration}) {
        ScenePose pose(scene);
        pose.apply(clip, time);
        const Scene posed = posed_scene(scene, pose);
        for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
          const Mesh& mesh = scene.meshes[m];
          if (mesh.skin < 0) continue;
          const double tol = 5e-7 * extent(mesh);  // float matrices against the double chain
          for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
            const glm::dvec3 want = reference_position(scene, pose, mesh, i);
            const glm::dvec3 got(posed.meshes[m].positions[i]);
            ASSERT_LE(glm::length(got - want), tol)
                << clip.name << " at " << time << " s, mesh " << m << " vertex " << i;
            ASSERT_NEAR(glm::length(posed.meshes[m].normals[i]), 1.0f, 1e-6f);
          }
        }
      }
    }
  }
}

// SimpleSkin (the glTF tutorial's skin): joint 1 sits at (0, 1, 0) and the clip turns it by
// exactly 90 degrees about +Z between 1.0 and 1.5 s. Vertices bound to joint 0 alone stay;
// vertices bound to joint 1 alone turn about (0, 1, 0): (x, y) -> (1 - y, 1 + x).
TEST(ScenePose, SimpleSkinTurnsItsUpperVerticesAQuarterTurn) {
  IMPORT_OR_SKIP(scene, "characters/SimpleSkin.gltf");
  ScenePose pose(scene);
  pose.apply(scene.animations.at(0), 1.25f);
  const Scene posed = posed_scene(scene, pose);
  const Mesh &rest = scene.meshes.at(0), &moved = posed.meshes.at(0);
  int stayed = 0, turned = 0;
  for (std::size_t i = 0; i < rest.vertex_count(); ++i) {
    const glm::vec3 p = rest.positions[i], q = moved.positions[i];
    const glm::vec4 w = rest.weights0[i];
    int only = -1;  // the one joint of a rigidly bound vertex
    for (int k = 0; k < 4; ++k)
      if (w[k] == 1.0f && w.x + w.y + w.z + w.w == 1.0f) only = rest.joints0[i][k];
    if (only == 0) {
      EXPECT_EQ(q, p) << "vertex " << i;
      ++stayed;
    } else if (only == 1) {
      EXPECT_NEAR(q.x, 1.0f - p.y, 1e-6f) << "vertex " << i;
      EXPECT_NEAR(q.y, 1.0f + p.x, 1e-6f) << "vertex " << i;
      EXPECT_EQ(q.z, p.z) << "vertex " << i;
      ++turned;
    }
  }
  EXPECT_EQ(stayed, 2);
  EXPECT_EQ(turned, 2);
}

// One triangle on a node scaled (3, 1, 0.5) and turned about X: the placed normal must be
// perpendicular to the placed edges, which only the inverse transpose gives.
Scene scaled_triangle() {
  Scene scene;
  Node node;
  node.translation = glm::vec3(1.0f, 2.0f, 3.0f);
  node.rotation = glm::angleAxis(0.7f, glm::vec3(1.0f, 0.0f, 0.0f));
  node.scale = glm::vec3(3.0f, 1.0f, 0.5f);
  node.local = NodeTRS{node.translation, node.rotation, node.scale}.matrix();
  node.world = node.local;
  scene.nodes.push_back(node);
  Mesh mesh;
  mesh.node = 0;
  mesh.local_positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f}};
  const glm::vec3 n = glm::normalize(glm::cross(mesh.local_positions[1] - mesh.local_positions[0],
                                                mesh.local_positions[2] - mesh.local_positions[0]));
  mesh.local_normals = {n, n, n};
  mesh.indices = {0, 1, 2};
  scene.meshes.push_back(mesh);
  return scene;
}

TEST(PlaceMesh, NormalsStayPerpendicularUnderNonUniformScale) {
  const Scene scene = scaled_triangle();
  Scene posed = posed_scene(scene, ScenePose(scene));
  const Mesh& mesh = posed.meshes[0];
  const glm::vec3 e1 = mesh.positions[1] - mesh.positions[0],
                  e2 = mesh.positions[2] - mesh.positions[0];
  for (const glm::vec3& normal : mesh.normals) {
    EXPECT_NEAR(glm::length(normal), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(normal, e1) / glm::length(e1), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(normal, e2) / glm::length(e2), 0.0f, 1e-6f);
    EXPECT_GT(glm::dot(normal, glm::cross(e1, e2)), 0.0f);  // still the front
  }
}

// A triangle in z = 0 whose first vertex hangs on a joint scaled to nothing: that vertex's normal
// has no inverse transpose and takes the placed surface's (+Z); the other two, on an untouched
// joint, keep the tilted normal the file gives them.
TEST(PlaceMesh, ACollapsedJointTakesTheSurfaceNormalForItsVerticesOnly) {
  Scene scene;
  scene.nodes.resize(2);
  scene.nodes[1].scale = glm::vec3(0.0f);
  scene.nodes[1].local = NodeTRS{{}, {}, glm::vec3(0.0f)}.matrix();
  Skin skin;
  skin.joints = {0, 1};
  skin.inverse_bind = {glm::mat4(1.0f), glm::mat4(1.0f)};
  scene.skins.push_back(skin);
  Mesh mesh;
  mesh.skin = 0;
  mesh.local_positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  const glm::vec3 tilted(0.6f, 0.0f, 0.8f);
  mesh.local_normals = {tilted, tilted, tilted};
  mesh.joints0 = {{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
  mesh.weights0 = {{1, 0, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
  mesh.indices = {0, 1, 2};
  scene.meshes.push_back(mesh);
  const Scene posed = posed_scene(scene, ScenePose(scene));
  const std::vector<glm::vec3>& normals = posed.meshes[0].normals;
  ASSERT_EQ(normals.size(), 3u);
  EXPECT_NEAR(glm::length(normals[0] - glm::vec3(0.0f, 0.0f, 1.0f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(normals[1] - tilted), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(normals[2] - tilted), 0.0f, 1e-6f);
}

TEST(BlendJoints, NormalisesWeightsAndFallsBackWhenThereAreNone) {
  const std::vector<glm::mat4> joints = {glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0)),
                                         glm::translate(glm::mat4(1.0f), glm::vec3(0, 4, 0))};
  const glm::mat4 fallback = glm::scale(glm::mat4(1.0f), glm::vec3(7.0f));
  const glm::u16vec4 ids(0, 1, 0, 0);
  const glm::vec4 p(0.0f, 0.0f, 0.0f, 1.0f);
  // Weights summing to 0.9 blend as if they summed to 1.
  EXPECT_EQ(blend_joints(ids, {0.45f, 0.45f, 0.0f, 0.0f}, joints, fallback) * p,
            glm::vec4(1.0f, 2.0f, 0.0f, 1.0f));
  EXPECT_EQ(blend_joints(ids, glm::vec4(0.0f), joints, fallback), fallback);
  // A joint index past the skin's joints is skipped, not read.
  const glm::mat4 only_first =
      blend_joints(glm::u16vec4(0, 9, 0, 0), {0.5f, 0.5f, 0.0f, 0.0f}, joints, fallback);
  EXPECT_EQ(only_first * p, glm::vec4(1.0f, 0.0f, 0.0f, 0.5f));
}

TEST(ScenePose, DracoCharactersPoseLikeTheirOriginals) {
  const char* const pairs[][2] = {{"characters/CesiumMan.glb", "draco/CesiumMan_Draco.glb"},
                                  {"characters/Fox.glb", "draco/Fox_Draco.glb"}};
  for (const auto& pair : pairs) {
    SCOPED_TRACE(pair[1]);
    IMPORT_OR_SKIP(plain, pair[0]);
    IMPORT_OR_SKIP(draco, pair[1]);
    ASSERT_EQ(plain.meshes.size(), draco.meshes.size());
    ASSERT_EQ(plain.animations.size(), draco.animations.size());
    const Animation& clip = plain.animations.back();
    ScenePose plain_pose(plain), draco_pose(draco);
    plain_pose.apply(clip, 0.5f * clip.duration);
    draco_pose.apply(draco.animations.back(), 0.5f * clip.duration);
    const Scene a = posed_scene(plain, plain_pose), b = posed_scene(draco, draco_pose);
    for (std::size_t m = 0; m < a.meshes.size(); ++m) {
      // Draco reorders and splits vertices: each is matched to the original vertex nearest at
      // rest (mesh-local), and the two are compared once posed.
      const Mesh &rest_a = plain.meshes[m], &rest_b = draco.meshes[m];
      double worst = 0.0;
      for (std::size_t i = 0; i < rest_b.vertex_count(); ++i) {
        std::size_t nearest = 0;
        float best = 1e30f;
        for (std::size_t k = 0; k < rest_a.vertex_count(); ++k) {
          const float d = glm::length(rest_a.local_positions[k] - rest_b.local_positions[i]);
          if (d < best) best = d, nearest = k;
        }
        worst = std::max(
            worst, double(glm::length(a.meshes[m].positions[nearest] - b.meshes[m].positions[i])));
      }
      // Draco quantises positions (14 bits over the mesh's extent) and weights (12 bits), and
      // split vertices match a twin with the same position; a posed vertex moves by a few steps.
      EXPECT_LE(worst, 2e-4 * extent(a.meshes[m])) << "mesh " << m;
    }
  }
}

// The rotation between two unit quaternions, in radians (q and -q are the same rotation).
double angle_between(const glm::quat& a, const glm::quat& b) {
  const double d = std::min(1.0, std::abs(double(glm::dot(a, b))));
  return 2.0 * std::acos(d);
}

// A two-joint skin whose bind pose (rotations about Y and about an oblique axis, a scaled root)
// differs from the nodes' rest transforms: the child's bind rotation comes from the inverse bind
// matrices alone; the root, whose placement they cannot tell, keeps its rest rotation.
TEST(BindLocalRotations, RecoversTheBindPoseFromTheInverseBindMatrices) {
  Scene scene;
  scene.nodes.resize(2);
  scene.nodes[0].children = {1};
  scene.nodes[1].parent = 0;
  scene.nodes[0].rotation = glm::angleAxis(0.9f, glm::vec3(1, 0, 0));
  const glm::quat root = glm::angleAxis(0.4f, glm::vec3(0, 1, 0));
  const glm::quat child = glm::angleAxis(-1.1f, glm::normalize(glm::vec3(1, 2, 3)));
  const glm::mat4 root_bind = NodeTRS{{0, 1, 0}, root, {2, 2, 2}}.matrix();
  const glm::mat4 child_bind = root_bind * NodeTRS{{0, 0.5f, 0}, child, {1, 1, 1}}.matrix();
  Skin skin;
  skin.joints = {0, 1};
  skin.inverse_bind = {glm::inverse(root_bind), glm::inverse(child_bind)};
  const std::vector<glm::quat> bind = bind_local_rotations(scene, skin);
  ASSERT_EQ(bind.size(), 2u);
  EXPECT_EQ(bind[0], scene.nodes[0].rotation);
  EXPECT_LT(angle_between(bind[1], child), 1e-6);
}

// The sample characters are bound in their rest pose: the rest rotations are the bind ones.
TEST(BindLocalRotations, AreTheRestRotationsOfTheSampleCharacters) {
  for (const char* relative : kCharacters) {
    SCOPED_TRACE(relative);
    IMPORT_OR_SKIP(scene, relative);
    for (const Skin& skin : scene.skins) {
      const std::vector<glm::quat> bind = bind_local_rotations(scene, skin);
      double worst = 0.0;
      for (std::size_t j = 0; j < skin.joints.size(); ++j)
        worst = std::max(worst, angle_between(bind[j], scene.nodes[skin.joints[j]].rotation));
      EXPECT_LT(worst, 1e-3);  // RiggedFigure rests slightly off its bind pose
    }
  }
}

}  // namespace
}  // namespace prt::bake
