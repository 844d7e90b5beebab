// SPDX-License-Identifier: MIT
// The content pipeline's object hash (baker/src/pipeline/content_hash.hpp): it changes with what
// places, poses or moves an object, and not with what moves another object.
#include <gtest/gtest.h>

#include <string>

#include "../../../baker/src/pipeline/content_hash.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/scene.hpp"

namespace prt::bake {
namespace {

// Node 0: a root with a box; node 1: its child, a skinned box whose skin's joint is node 2;
// node 3: another root with a box. One clip moves nodes 2 and 3.
Scene rigged_scene() {
  Scene scene;
  scene.nodes.resize(4);
  scene.nodes[0].children = {1};
  scene.nodes[1].parent = 0;
  scene.nodes[1].skin = 0;
  for (int n : {0, 1, 3}) scene.nodes[std::size_t(n)].mesh = n;
  scene.skins.push_back({"skin", {2}, {glm::mat4(1.0f)}, -1});
  for (int n : {0, 1, 3}) {
    Mesh mesh = make_box_mesh(-1, glm::vec3(float(n)), 0.5f, 0.0f, 1);
    mesh.node = n;
    scene.meshes.push_back(mesh);
  }
  Animation clip;
  clip.name = "clip";
  for (int n : {2, 3}) {
    AnimationChannel channel;
    channel.node = n;
    channel.times = {0.0f, 1.0f};
    channel.values = {0, 0, 0, 1, 0, 0};
    clip.channels.push_back(channel);
  }
  scene.animations.push_back(clip);
  return scene;
}

std::string object_hash(const Scene& scene, int node) {
  ContentHash hash;
  hash_object_scene(hash, scene, node);
  return hash.hex();
}

TEST(ObjectHash, ChangesWithTheClipOfItsJointButNotOfAnotherObject) {
  const Scene scene = rigged_scene();
  const std::string skinned = object_hash(scene, 1), other = object_hash(scene, 3);

  Scene joint_moves = scene;
  joint_moves.animations[0].channels[0].values[3] = 2.0f;  // node 2: the skin's joint
  EXPECT_NE(object_hash(joint_moves, 1), skinned);
  EXPECT_EQ(object_hash(joint_moves, 3), other);

  Scene other_moves = scene;
  other_moves.animations[0].channels[1].values[3] = 2.0f;  // node 3
  EXPECT_EQ(object_hash(other_moves, 1), skinned);
  EXPECT_NE(object_hash(other_moves, 3), other);
}

TEST(ObjectHash, ChangesWithItsParentsTransformAndItsSkin) {
  const Scene scene = rigged_scene();
  const std::string skinned = object_hash(scene, 1);

  Scene parent_moved = scene;
  parent_moved.nodes[0].local[3] = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  EXPECT_NE(object_hash(parent_moved, 1), skinned);

  Scene rebound = scene;
  rebound.skins[0].inverse_bind[0][3] = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
  EXPECT_NE(object_hash(rebound, 1), skinned);
  EXPECT_EQ(object_hash(rebound, 3), object_hash(scene, 3));
}

}  // namespace
}  // namespace prt::bake
