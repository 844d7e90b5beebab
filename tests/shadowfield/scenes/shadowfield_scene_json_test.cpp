// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s scene file (docs/shadowfield/scenes.md): a preset written and read
// back is the same scene, value for value, and broken files are refused with the file's name.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

std::vector<std::string> blob_names(const ShadowfieldSceneDescription& scene) {
  std::vector<std::string> names;
  for (const ShadowfieldSceneObject& object : scene.objects) names.push_back(object.name + ".prtk");
  return names;
}

void expect_same_path(const ShadowfieldPath& a, const ShadowfieldPath& b) {
  ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
  EXPECT_EQ(a.duration, b.duration);
  for (std::size_t k = 0; k < a.keyframes.size(); ++k) {
    const ShadowfieldKeyframe &x = a.keyframes[k], &y = b.keyframes[k];
    EXPECT_EQ(x.time, y.time);
    EXPECT_EQ(x.placement.translation, y.placement.translation);
    EXPECT_EQ(x.placement.rotation, y.placement.rotation);
    EXPECT_EQ(x.placement.scale, y.placement.scale);
  }
}

TEST(SceneJson, RoundTripsAPreset) {
  const prt_test::TempDir dir("shadowfield_scene_json");
  const ShadowfieldSceneDescription scene = make_shadowfield_scene("procedural", "");
  const std::vector<std::string> blobs = blob_names(scene);
  write_shadowfield_scene_json(scene, blobs, dir.file("scene.json"));
  const ShadowfieldSceneFile file = read_shadowfield_scene_json(dir.file("scene.json"));
  EXPECT_EQ(file.name, scene.name);
  EXPECT_EQ(file.env, scene.env);
  EXPECT_EQ(file.camera.eye, scene.camera.eye);
  EXPECT_EQ(file.camera.target, scene.camera.target);
  ASSERT_EQ(file.objects.size(), scene.objects.size());
  for (std::size_t i = 0; i < blobs.size(); ++i) {
    EXPECT_EQ(file.objects[i].name, scene.objects[i].name);
    EXPECT_EQ(file.objects[i].blob, blobs[i]);
  }
  ASSERT_EQ(file.instances.size(), scene.instances.size());
  for (std::size_t i = 0; i < file.instances.size(); ++i) {
    EXPECT_EQ(file.instances[i].object, scene.instances[i].object);
    expect_same_path(file.instances[i].path, scene.instances[i].path);
  }
  // Numbers in their shortest form: the sphere's scale 0.4f, not 0.4000000059604645.
  EXPECT_NE(prt_test::read_bytes(dir.file("scene.json")).find("\"scale\": 0.4\n"),
            std::string::npos);
}

TEST(SceneJson, RoundTripsAnEmptyScene) {
  const prt_test::TempDir dir("shadowfield_scene_json_empty");
  ShadowfieldSceneDescription empty;
  write_shadowfield_scene_json(empty, {}, dir.file("empty.json"));
  const ShadowfieldSceneFile file = read_shadowfield_scene_json(dir.file("empty.json"));
  EXPECT_TRUE(file.objects.empty());
  EXPECT_TRUE(file.instances.empty());
  EXPECT_EQ(file.env, kShadowfieldBuiltinSky);
}

TEST(SceneJson, WriterRefusesMismatchedBlobNames) {
  const prt_test::TempDir dir("shadowfield_scene_json_names");
  const ShadowfieldSceneDescription scene = make_shadowfield_scene("procedural", "");
  EXPECT_THROW(write_shadowfield_scene_json(scene, {"one.prtk"}, dir.file("s.json")), Error);
}

TEST(SceneJson, BrokenFilesAreRefusedWithTheirName) {
  const prt_test::TempDir dir("shadowfield_scene_json_broken");
  const std::string valid =
      R"({"format": "prtkit shadowfield scene", "version": 1, "name": "x", "env": "builtin:sky",
          "camera": {"eye": [0, 1, 4], "target": [0, 0, 0]},
          "objects": [{"name": "floor", "blob": "floor.prtk"}],
          "instances": [{"object": OBJECT, "duration": 0, "keyframes": [KEYFRAME]}]})";
  const std::string keyframe =
      R"({"time": 0, "translation": [0, 0, 0], "rotation": [0, 0, 0, 1], "scale": SCALE})";
  auto make = [&](const std::string& object, const std::string& scale) {
    std::string text = valid, k = keyframe;
    k.replace(k.find("SCALE"), 5, scale);
    text.replace(text.find("OBJECT"), 6, object);
    text.replace(text.find("KEYFRAME"), 8, k);
    return text;
  };
  EXPECT_NO_THROW(read_shadowfield_scene_json(dir.write("ok.json", make("0", "1"))));
  const std::vector<std::pair<std::string, std::string>> broken = {
      {"object.json", make("1", "1")},
      {"scale.json", make("0", "0")},
      {"truncated.json", make("0", "1").substr(0, 80)},
      {"format.json", R"({"format": "something else", "version": 1})"},
  };
  for (const auto& [name, text] : broken) {
    try {
      read_shadowfield_scene_json(dir.write(name, text));
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_shadowfield_scene_json(dir.file("missing.json")), Error);
}

}  // namespace
}  // namespace prt::bake
