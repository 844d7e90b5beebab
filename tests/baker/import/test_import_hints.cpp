// SPDX-License-Identifier: MIT
// What a glTF file says to `prt-bake scene` (docs/pipeline.md): KHR_materials_sheen, the
// material's extras.prt.cloth, each node's extras.prt hints (wrong types warned about and
// ignored) and which nodes an animation moves. Every file is written by the test itself.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "gltf_builder.hpp"
#include "prt/baker/scene.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using prt_test::TempDir;
using Settings = std::vector<std::pair<std::string, std::string>>;

// A context that keeps every warning.
struct Warnings {
  std::vector<std::string> texts;
  Context ctx;
  Warnings() {
    ctx.log = [this](LogLevel level, const std::string& text) {
      if (level == LogLevel::Warning) texts.push_back(text);
    };
  }
  // How many warnings contain every one of the parts.
  int count(const std::vector<std::string>& parts) const {
    int n = 0;
    for (const std::string& text : texts) {
      bool all = true;
      for (const std::string& part : parts) all = all && text.find(part) != std::string::npos;
      n += all ? 1 : 0;
    }
    return n;
  }
};

std::string joined(const std::vector<std::string>& texts) {
  std::string out;
  for (const std::string& text : texts) out += text + "\n";
  return out;
}

TEST(ImportGltfHints, SheenFactorsAndClothFromMaterialExtras) {
  const TempDir dir("gltf_hints_sheen");
  GltfBuilder b = triangle_builder();
  b.doc["materials"] = nlohmann::json::array(
      {{{"name", "velvet"},
        {"extensions",
         {{"KHR_materials_sheen",
           {{"sheenColorFactor", {0.25, 0.5, 0.75}}, {"sheenRoughnessFactor", 0.375}}}}},
        {"extras", {{"prt", {{"cloth", true}}}}}},
       {{"name", "defaults"}, {"extensions", {{"KHR_materials_sheen", nlohmann::json::object()}}}},
       {{"name", "plain"}, {"extras", {{"prt", {{"cloth", false}}}, {"author", "someone"}}}}});
  // Required, so the file is refused by an importer that does not know the extension.
  b.doc["extensionsUsed"] = {"KHR_materials_sheen"};
  b.doc["extensionsRequired"] = {"KHR_materials_sheen"};
  Warnings warnings;
  const Scene scene = import_scene(dir.write("sheen.gltf", b.gltf_with_data_uri()), warnings.ctx);
  EXPECT_TRUE(warnings.texts.empty()) << joined(warnings.texts);
  ASSERT_EQ(scene.materials.size(), 3u);

  const Material& velvet = scene.materials[0];
  EXPECT_TRUE(velvet.sheen);
  EXPECT_EQ(velvet.sheen_color, glm::vec3(0.25f, 0.5f, 0.75f));
  EXPECT_EQ(velvet.sheen_roughness, 0.375f);
  EXPECT_TRUE(velvet.cloth);

  // The extension with nothing in it: its defaults, black and roughness 0.
  const Material& defaults = scene.materials[1];
  EXPECT_TRUE(defaults.sheen);
  EXPECT_EQ(defaults.sheen_color, glm::vec3(0.0f));
  EXPECT_EQ(defaults.sheen_roughness, 0.0f);
  EXPECT_FALSE(defaults.cloth);

  const Material& plain = scene.materials[2];
  EXPECT_FALSE(plain.sheen);
  EXPECT_FALSE(plain.cloth);
}

TEST(ImportGltfHints, SheenTexturesAreIgnoredWithOneWarningPerMaterial) {
  const TempDir dir("gltf_hints_sheen_textures");
  GltfBuilder b = triangle_builder();
  b.doc["materials"] = nlohmann::json::array(
      {{{"name", "both"},
        {"extensions",
         {{"KHR_materials_sheen",
           {{"sheenColorFactor", {1, 1, 1}},
            {"sheenColorTexture", {{"index", 0}}},
            {"sheenRoughnessTexture", {{"index", 0}}}}}}}},
       {{"name", "factors only"},
        {"extensions", {{"KHR_materials_sheen", {{"sheenRoughnessFactor", 1}}}}}}});
  b.doc["extensionsUsed"] = {"KHR_materials_sheen"};
  Warnings warnings;
  const std::string path = dir.write("textures.glb", b.glb());
  const Scene scene = import_scene(path, warnings.ctx);
  ASSERT_EQ(warnings.texts.size(), 1u) << joined(warnings.texts);
  EXPECT_EQ(warnings.count({path, "material 0 'both'", "sheenColorTexture", "sheenRoughnessTexture",
                            "ignored"}),
            1)
      << warnings.texts[0];
  // The factors are still read, integers included.
  EXPECT_EQ(scene.materials.at(0).sheen_color, glm::vec3(1.0f));
  EXPECT_EQ(scene.materials.at(1).sheen_roughness, 1.0f);
}

TEST(ImportGltfHints, NodeHintsFromExtras) {
  const TempDir dir("gltf_hints_nodes");
  GltfBuilder b = triangle_builder();
  b.doc["nodes"] = nlohmann::json::array(
      {{{"name", "statue"},
        {"mesh", 0},
        {"extras",
         {{"prt",
           {{"dynamic", true},
            {"technique", "wavelet"},
            {"skip", true},
            {"settings",
             {{"order", 4},
              {"bounce_weight", 0.5},
              {"rays_per_vertex", 256.0},
              {"mode", "fast"},
              {"visibility", false}}}}}}}},
       {{"name", "bare"}, {"mesh", 0}},
       {{"name", "other tool"}, {"mesh", 0}, {"extras", {{"exporter", {{"layer", 3}}}}}}});
  b.doc["scenes"][0]["nodes"] = {0, 1, 2};
  Warnings warnings;
  const Scene scene = import_scene(dir.write("hints.glb", b.glb()), warnings.ctx);
  EXPECT_TRUE(warnings.texts.empty()) << joined(warnings.texts);
  ASSERT_EQ(scene.nodes.size(), 3u);

  const Node::Hints& statue = scene.nodes[0].hints;
  EXPECT_TRUE(statue.dynamic);
  EXPECT_EQ(statue.technique, "wavelet");
  EXPECT_TRUE(statue.skip);
  // Keys in tinygltf's order (alphabetical), '_' as '-'; numbers as their shortest text (256.0
  // is written "256"), booleans as true/false.
  EXPECT_EQ(statue.settings, (Settings{{"--bounce-weight", "0.5"},
                                       {"--mode", "fast"},
                                       {"--order", "4"},
                                       {"--rays-per-vertex", "256"},
                                       {"--visibility", "false"}}));

  // No extras, and extras without "prt": nothing set, nothing said.
  for (int n : {1, 2}) {
    const Node::Hints& hints = scene.nodes[n].hints;
    EXPECT_FALSE(hints.dynamic) << n;
    EXPECT_TRUE(hints.technique.empty()) << n;
    EXPECT_TRUE(hints.settings.empty()) << n;
    EXPECT_FALSE(hints.skip) << n;
  }
}

TEST(ImportGltfHints, WrongTypesAndUnknownKeysWarnAndAreIgnored) {
  const TempDir dir("gltf_hints_wrong");
  GltfBuilder b = triangle_builder();
  b.doc["nodes"] = nlohmann::json::array(
      {{{"name", "root"}, {"mesh", 0}, {"children", {1}}, {"extras", {{"prt", true}}}},
       {{"name", "cape"},
        {"extras",
         {{"prt",
           {{"dynamic", "yes"},
            {"technique", "sh"},
            {"skip", 1},
            {"settings", {{"order", {3, 4}}, {"rays", 64}}},
            {"colour", "red"}}}}}}});
  b.doc["materials"] =
      nlohmann::json::array({{{"name", "wool"}, {"extras", {{"prt", {{"cloth", "yes"}}}}}}});
  Warnings warnings;
  const std::string path = dir.write("wrong.glb", b.glb());
  const Scene scene = import_scene(path, warnings.ctx);
  ASSERT_EQ(scene.nodes.size(), 2u);

  // The well-typed keys are kept, the others left at their defaults.
  const Node::Hints& cape = scene.nodes[1].hints;
  EXPECT_FALSE(cape.dynamic);
  EXPECT_EQ(cape.technique, "sh");
  EXPECT_FALSE(cape.skip);
  EXPECT_EQ(cape.settings, (Settings{{"--rays", "64"}}));
  EXPECT_FALSE(scene.materials.at(0).cloth);

  // One warning per bad key, naming the file, the node (index and name) and the key.
  const std::string all = joined(warnings.texts);
  EXPECT_EQ(warnings.texts.size(), 6u) << all;
  EXPECT_EQ(warnings.count({path + ": node 1 'cape': extras.prt.dynamic should be true or false; "
                                   "ignored"}),
            1)
      << all;
  EXPECT_EQ(warnings.count({path, "node 1 'cape'", "extras.prt.skip", "ignored"}), 1) << all;
  EXPECT_EQ(warnings.count({path, "node 1 'cape'", "extras.prt.settings.order", "ignored"}), 1)
      << all;
  EXPECT_EQ(warnings.count({path, "node 1 'cape'", "'colour'", "unknown", "ignored"}), 1) << all;
  EXPECT_EQ(warnings.count({path, "node 0 'root'", "extras.prt", "object", "ignored"}), 1) << all;
  EXPECT_EQ(warnings.count({path, "material 0 'wool'", "extras.prt.cloth", "ignored"}), 1) << all;
}

// rig (0) -> arm (1) -> hand (3), rig -> leg (2); face (4) a root of its own. A rotation channel
// on the arm moves the arm and the hand, not the rig above nor the leg beside; a weights channel
// on the face only morphs it in place.
TEST(ImportGltfHints, AnimatedMarksTargetedNodesAndTheirDescendants) {
  const TempDir dir("gltf_hints_animated");
  GltfBuilder b = triangle_builder();
  b.doc["nodes"] = nlohmann::json::array({{{"name", "rig"}, {"children", {1, 2}}},
                                          {{"name", "arm"}, {"children", {3}}},
                                          {{"name", "leg"}, {"mesh", 0}},
                                          {{"name", "hand"}, {"mesh", 0}},
                                          {{"name", "face"}, {"mesh", 0}}});
  b.doc["scenes"][0]["nodes"] = {0, 4};
  const int times = b.add_array(std::vector<float>{0, 1}, GltfBuilder::kFloat, "SCALAR");
  const int rotations =
      b.add_array(std::vector<float>{0, 0, 0, 1, 0, 0, 1, 0}, GltfBuilder::kFloat, "VEC4");
  const int weights = b.add_array(std::vector<float>{0, 1}, GltfBuilder::kFloat, "SCALAR");
  // One animation per channel, each with a sampler of its own.
  const auto animation = [&](int output, int node, const char* path) {
    nlohmann::json sampler = {{"input", times}, {"output", output}};
    nlohmann::json target = {{"node", node}, {"path", path}};
    nlohmann::json channel = {{"sampler", 0}, {"target", target}};
    return nlohmann::json{{"samplers", nlohmann::json::array({sampler})},
                          {"channels", nlohmann::json::array({channel})}};
  };
  b.doc["animations"] = nlohmann::json::array(
      {animation(rotations, 1, "rotation"), animation(weights, 4, "weights")});
  const Scene scene = import_scene(dir.write("animated.glb", b.glb()), Context{});
  ASSERT_EQ(scene.nodes.size(), 5u);
  ASSERT_EQ(scene.animations.size(), 2u);
  EXPECT_FALSE(scene.nodes[0].animated) << "rig";
  EXPECT_TRUE(scene.nodes[1].animated) << "arm";
  EXPECT_FALSE(scene.nodes[2].animated) << "leg";
  EXPECT_TRUE(scene.nodes[3].animated) << "hand";
  EXPECT_FALSE(scene.nodes[4].animated) << "face";
}

}  // namespace
}  // namespace prt::bake
