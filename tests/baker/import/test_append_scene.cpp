// SPDX-License-Identifier: MIT
// append_scene (prt/baker/scene.hpp): a scene assembled from parts keeps every reference between
// the parts' meshes, materials, images, nodes, skins and animations.
#include <gtest/gtest.h>

#include <string>

#include "prt/baker/mesh_generators.hpp"
#include "prt/baker/scene.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

// Two nodes (a parent with a mesh, its child with a skinned mesh), one textured material, a skin
// on both nodes as joints, and one animation channel on the child.
Scene part(const std::string& tag) {
  Scene scene;
  Image image;
  image.name = tag + "-image";
  image.width = image.height = 1;
  image.rgba = {255, 255, 255, 255};
  scene.images.push_back(image);
  Material material;
  material.name = tag + "-material";
  material.base_color_texture = 0;
  scene.materials.push_back(material);
  Node parent, child;
  parent.name = tag + "-parent";
  parent.mesh = 0;
  parent.children = {1};
  child.name = tag + "-child";
  child.parent = 0;
  child.mesh = 1;
  child.skin = 0;
  scene.nodes = {parent, child};
  Skin skin;
  skin.name = tag + "-skin";
  skin.joints = {0, 1};
  skin.inverse_bind = {glm::mat4(1.0f), glm::mat4(1.0f)};
  skin.skeleton = 0;
  scene.skins.push_back(skin);
  Mesh rigid = make_box_mesh(0, glm::vec3(0.0f), 1.0f, 1.0f, 1);
  rigid.node = 0;
  Mesh skinned = make_box_mesh(0, glm::vec3(2.0f), 1.0f, 1.0f, 1);
  skinned.node = 1;
  skinned.skin = 0;
  scene.meshes = {rigid, skinned};
  Animation animation;
  animation.name = tag + "-clip";
  AnimationChannel channel;
  channel.node = 1;
  animation.channels.push_back(channel);
  scene.animations.push_back(animation);
  scene.problems.push_back({1, 1, 0, tag + "-problem"});
  return scene;
}

// The name of what each index of `scene` refers to, so that two scenes can be compared by what
// their references mean rather than by their numbers.
std::string node_name(const Scene& scene, int node) {
  return node < 0 ? "-" : scene.nodes.at(std::size_t(node)).name;
}

TEST(AppendScene, EveryIndexOfTheAppendedPartStillNamesWhatItNamedBefore) {
  Scene scene = part("a");
  append_scene(scene, part("b"));
  ASSERT_EQ(scene.nodes.size(), 4u);
  ASSERT_EQ(scene.meshes.size(), 4u);
  ASSERT_EQ(scene.skins.size(), 2u);
  ASSERT_EQ(scene.animations.size(), 2u);

  const Node& b_parent = scene.nodes[2];
  const Node& b_child = scene.nodes[3];
  EXPECT_EQ(b_parent.name, "b-parent");
  EXPECT_EQ(b_parent.parent, -1);  // a further root
  EXPECT_EQ(node_name(scene, b_parent.children.at(0)), "b-child");
  EXPECT_EQ(node_name(scene, b_child.parent), "b-parent");
  EXPECT_EQ(scene.skins[std::size_t(b_child.skin)].name, "b-skin");
  // glTF mesh indices of the parts do not collide: "a" uses 0 and 1.
  EXPECT_EQ(b_parent.mesh, 2);
  EXPECT_EQ(b_child.mesh, 3);

  const Skin& b_skin = scene.skins[1];
  EXPECT_EQ(node_name(scene, b_skin.joints.at(0)), "b-parent");
  EXPECT_EQ(node_name(scene, b_skin.joints.at(1)), "b-child");
  EXPECT_EQ(node_name(scene, b_skin.skeleton), "b-parent");

  const Mesh& b_skinned = scene.meshes[3];
  EXPECT_EQ(node_name(scene, b_skinned.node), "b-child");
  EXPECT_EQ(scene.skins[std::size_t(b_skinned.skin)].name, "b-skin");
  const Material& b_material = scene.materials[std::size_t(b_skinned.material)];
  EXPECT_EQ(b_material.name, "b-material");
  EXPECT_EQ(scene.images[std::size_t(b_material.base_color_texture)].name, "b-image");

  EXPECT_EQ(node_name(scene, scene.animations[1].channels.at(0).node), "b-child");
  ASSERT_EQ(scene.problems.size(), 2u);
  EXPECT_EQ(node_name(scene, scene.problems[1].node), "b-child");
  EXPECT_EQ(scene.problems[1].mesh, 3);
  EXPECT_EQ(scene.materials[std::size_t(scene.problems[1].material)].name, "b-material");

  // The first part is untouched.
  EXPECT_EQ(node_name(scene, scene.skins[0].joints.at(1)), "a-child");
  EXPECT_EQ(scene.meshes[1].skin, 0);
}

TEST(AppendScene, AnImportedCharacterKeepsItsSkinAndClipsInALevel) {
  const std::string path = prt_test::shared_asset("characters/RiggedSimple/RiggedSimple.gltf");
  if (path.empty()) GTEST_SKIP() << "shared asset characters/RiggedSimple is absent";
  const Context ctx;
  const Scene character = import_scene(path, ctx);
  Scene level;
  level.meshes.push_back(make_plane_mesh("ground", -1, 2.0f, 2.0f, 2, 2));
  append_scene(level, character);

  ASSERT_EQ(level.meshes.size(), character.meshes.size() + 1);
  EXPECT_EQ(level.vertex_count(), character.vertex_count() + 9);
  for (std::size_t m = 1; m < level.meshes.size(); ++m) {
    const Mesh& mesh = level.meshes[m];
    const Mesh& original = character.meshes[m - 1];
    EXPECT_EQ(node_name(level, mesh.node), node_name(character, original.node));
    ASSERT_EQ(mesh.skin, original.skin);  // the level had no skins
  }
  ASSERT_EQ(level.animations.size(), character.animations.size());
  for (std::size_t a = 0; a < level.animations.size(); ++a) {
    for (std::size_t c = 0; c < level.animations[a].channels.size(); ++c) {
      EXPECT_EQ(level.animations[a].channels[c].node, character.animations[a].channels[c].node);
    }
  }
}

}  // namespace
}  // namespace prt::bake
