// SPDX-License-Identifier: MIT
// The keep-going import (ImportOptions::keep_going): a broken primitive, node or base colour
// texture is recorded in Scene::problems, with the node(s) it concerns and the reason the
// throwing import gives, and the rest of the file imports as it would without the broken part.
// Every file is written by the test itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "gltf_builder.hpp"
#include "prt/baker/scene.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using nlohmann::json;
using prt_test::TempDir;

// An import that keeps every warning.
struct Import {
  Scene scene;
  std::vector<std::string> warnings;

  Import(const std::string& path, bool keep_going) {
    Context ctx;
    ctx.log = [this](LogLevel level, const std::string& text) {
      if (level == LogLevel::Warning) warnings.push_back(text);
    };
    ImportOptions options;
    options.keep_going = keep_going;
    scene = import_scene(path, ctx, options);
  }
  // How many warnings contain every one of the parts.
  int warned(const std::vector<std::string>& parts) const {
    int n = 0;
    for (const std::string& text : warnings) {
      bool all = true;
      for (const std::string& part : parts) all = all && text.find(part) != std::string::npos;
      n += all ? 1 : 0;
    }
    return n;
  }
};

// The message of the Error the default import throws; "" when it does not throw.
std::string import_error(const std::string& path) {
  try {
    import_scene(path, Context{});
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::vector<float> triangle_at(float x) {
  return {x, 0, 0, x + 1, 0, 0, x, 1, 0};
}

// Appends a mesh of one triangle primitive (POSITION, NORMAL +Z, indices); returns its index.
int add_triangle_mesh(GltfBuilder& b, const std::string& name, const std::vector<float>& positions,
                      const std::vector<std::uint16_t>& indices = {0, 1, 2}) {
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  const int p = b.add_array(positions, GltfBuilder::kFloat, "VEC3");
  const int n = b.add_array(normals, GltfBuilder::kFloat, "VEC3");
  const int i = b.add_array(indices, GltfBuilder::kUShort, "SCALAR");
  b.add_mesh({{"attributes", {{"POSITION", p}, {"NORMAL", n}}}, {"indices", i}});
  b.doc["meshes"].back()["name"] = name;
  return static_cast<int>(b.doc["meshes"].size()) - 1;
}

// Nodes 0 'good', 1 'lost' and 2 'also_good', the roots of the scene, each placing its own mesh
// of the same name (accessors 0-2, 3-5 and 6-8). Mesh 1 gets the positions and indices given.
GltfBuilder three_nodes(const std::vector<float>& lost_positions = triangle_at(2),
                        const std::vector<std::uint16_t>& lost_indices = {0, 1, 2}) {
  GltfBuilder b;
  add_triangle_mesh(b, "good", triangle_at(0));
  add_triangle_mesh(b, "lost", lost_positions, lost_indices);
  add_triangle_mesh(b, "also_good", triangle_at(4));
  b.doc["nodes"] = json::array({{{"name", "good"}, {"mesh", 0}},
                                {{"name", "lost"}, {"mesh", 1}},
                                {{"name", "also_good"}, {"mesh", 2}}});
  b.doc["scenes"] = json::array({{{"nodes", {0, 1, 2}}}});
  b.doc["scene"] = 0;
  return b;
}

// The same file without node 1 in the scene (node 1 and what is under it are not imported).
GltfBuilder without_node_1(GltfBuilder b) {
  b.doc["scenes"][0]["nodes"] = {0, 2};
  return b;
}

// The healthy meshes of a keep-going import are those of the file without the broken node.
void expect_same_meshes(const Scene& kept, const Scene& reference) {
  ASSERT_EQ(kept.meshes.size(), reference.meshes.size());
  for (std::size_t i = 0; i < kept.meshes.size(); ++i) {
    const Mesh& a = kept.meshes[i];
    const Mesh& b = reference.meshes[i];
    EXPECT_EQ(a.name, b.name) << i;
    EXPECT_EQ(a.node, b.node) << i;
    EXPECT_EQ(a.material, b.material) << i;
    EXPECT_TRUE(a.positions == b.positions) << i;
    EXPECT_TRUE(a.normals == b.normals) << i;
    EXPECT_TRUE(a.indices == b.indices) << i;
  }
}

std::vector<int> mesh_nodes(const Scene& scene) {
  std::vector<int> nodes;
  for (const Mesh& mesh : scene.meshes) nodes.push_back(mesh.node);
  return nodes;
}

TEST(ImportKeepGoing, DefaultOptionsAreTheThrowingImport) {
  const TempDir dir("keep_going_default");
  std::vector<float> nan_positions = triangle_at(2);
  nan_positions[4] = std::nanf("");
  const std::string path = dir.write("nan.glb", three_nodes(nan_positions).glb());
  EXPECT_THROW(import_scene(path, Context{}, ImportOptions{}), Error);
  EXPECT_THROW(import_scene(path, Context{}), Error);
  // A healthy file: no problems, either way.
  const std::string healthy = dir.write("healthy.glb", three_nodes().glb());
  EXPECT_EQ(Import(healthy, false).scene.meshes.size(), 3u);
  const Import kept(healthy, true);
  EXPECT_EQ(kept.scene.meshes.size(), 3u);
  EXPECT_TRUE(kept.scene.problems.empty());
  EXPECT_TRUE(kept.warnings.empty());
}

TEST(ImportKeepGoing, NonFinitePositionDropsThePrimitiveOfItsNode) {
  const TempDir dir("keep_going_nan_position");
  std::vector<float> nan_positions = triangle_at(2);
  nan_positions[4] = std::nanf("");
  const GltfBuilder b = three_nodes(nan_positions);
  const std::string path = dir.write("nan.glb", b.glb());
  const std::string reason = "mesh 1 'lost' primitive 0 has a non-finite vertex position";
  EXPECT_EQ(import_error(path), path + ": " + reason);

  const Import kept(path, true);
  EXPECT_EQ(mesh_nodes(kept.scene), (std::vector<int>{0, 2}));
  ASSERT_EQ(kept.scene.problems.size(), 1u);
  const ImportProblem& problem = kept.scene.problems[0];
  EXPECT_EQ(problem.node, 1);
  EXPECT_EQ(problem.mesh, 1);
  EXPECT_EQ(problem.material, -1);
  EXPECT_EQ(problem.reason, reason);
  EXPECT_EQ(kept.warned({path, "node 1 'lost'", reason}), 1) << kept.warnings.size();

  const Scene reference = import_scene(dir.write("without.glb", without_node_1(b).glb()), {});
  expect_same_meshes(kept.scene, reference);
}

TEST(ImportKeepGoing, EveryNodeThatInstancesABrokenMeshHasTheProblem) {
  const TempDir dir("keep_going_instances");
  std::vector<float> nan_positions = triangle_at(2);
  nan_positions[0] = std::nanf("");
  GltfBuilder b = three_nodes(nan_positions);
  b.doc["nodes"].push_back({{"name", "lost_again"}, {"mesh", 1}, {"translation", {0, 0, 3}}});
  b.doc["scenes"][0]["nodes"].push_back(3);
  const Import kept(dir.write("twice.gltf", b.gltf_with_data_uri()), true);
  EXPECT_EQ(mesh_nodes(kept.scene), (std::vector<int>{0, 2}));
  ASSERT_EQ(kept.scene.problems.size(), 2u);
  EXPECT_EQ(kept.scene.problems[0].node, 1);
  EXPECT_EQ(kept.scene.problems[1].node, 3);
  for (const ImportProblem& problem : kept.scene.problems) {
    EXPECT_EQ(problem.mesh, 1);
    EXPECT_EQ(problem.reason, "mesh 1 'lost' primitive 0 has a non-finite vertex position");
  }
}

TEST(ImportKeepGoing, IndexOutOfRange) {
  const TempDir dir("keep_going_index");
  const GltfBuilder b = three_nodes(triangle_at(2), {0, 1, 7});
  const std::string path = dir.write("bad_index.glb", b.glb());
  const std::string reason =
      "mesh 1 'lost' primitive 0: index 7 at position 2 is out of range (3 vertices)";
  EXPECT_EQ(import_error(path), path + ": " + reason);

  const Import kept(path, true);
  EXPECT_EQ(mesh_nodes(kept.scene), (std::vector<int>{0, 2}));
  ASSERT_EQ(kept.scene.problems.size(), 1u);
  EXPECT_EQ(kept.scene.problems[0].node, 1);
  EXPECT_EQ(kept.scene.problems[0].mesh, 1);
  EXPECT_EQ(kept.scene.problems[0].reason, reason);
  expect_same_meshes(kept.scene,
                     import_scene(dir.write("without.glb", without_node_1(b).glb()), {}));
}

TEST(ImportKeepGoing, NonFiniteTransformDropsTheNodeAndWhatIsUnderIt) {
  const TempDir dir("keep_going_transform");
  // 1e39 does not fit a float: the translation becomes infinite. Node 3 'child' (under node 1)
  // places mesh 0, which node 0 places too; node 4 'spun' has a rotation that normalises to NaN.
  GltfBuilder b = three_nodes();
  b.doc["nodes"][1]["translation"] = {1e39, 0, 0};
  b.doc["nodes"][1]["children"] = {3};
  b.doc["nodes"].push_back({{"name", "child"}, {"mesh", 0}, {"translation", {0, 2, 0}}});
  b.doc["nodes"].push_back({{"name", "spun"}, {"mesh", 2}, {"rotation", {1e39, 1e39, 0, 1}}});
  b.doc["scenes"][0]["nodes"].push_back(4);
  const std::string path = dir.write("inf.glb", b.glb());
  EXPECT_NE(import_error(path).find("non-finite vertex position"), std::string::npos);

  const Import kept(path, true);
  EXPECT_EQ(mesh_nodes(kept.scene), (std::vector<int>{0, 2}));
  ASSERT_EQ(kept.scene.problems.size(), 3u);
  const ImportProblem& broken = kept.scene.problems[0];
  EXPECT_EQ(broken.node, 1);
  EXPECT_EQ(broken.mesh, -1);
  EXPECT_EQ(broken.material, -1);
  EXPECT_EQ(broken.reason.rfind("node 1 'lost' has a non-finite transform", 0), 0u)
      << broken.reason;
  EXPECT_EQ(kept.scene.problems[1].node, 3);
  EXPECT_EQ(kept.scene.problems[1].reason,
            "node 3 'child' inherits a non-finite transform from node 1 'lost'");
  EXPECT_EQ(kept.scene.problems[2].node, 4);
  EXPECT_EQ(kept.scene.problems[2].reason.rfind("node 4 'spun' has a non-finite transform", 0), 0u);
  EXPECT_EQ(kept.warned({path, "node 3 'child' inherits", "not imported"}), 1);

  expect_same_meshes(kept.scene,
                     import_scene(dir.write("without.glb", without_node_1(b).glb()), {}));
}

TEST(ImportKeepGoing, NonFiniteMatrix) {
  const TempDir dir("keep_going_matrix");
  GltfBuilder b = three_nodes();
  b.doc["nodes"][1]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1e39, 0, 1};
  const Import kept(dir.write("matrix.glb", b.glb()), true);
  EXPECT_EQ(mesh_nodes(kept.scene), (std::vector<int>{0, 2}));
  ASSERT_EQ(kept.scene.problems.size(), 1u);
  EXPECT_EQ(kept.scene.problems[0].node, 1);
  EXPECT_NE(kept.scene.problems[0].reason.find("non-finite transform"), std::string::npos);
}

// three_nodes() with material 0 'paint' (factor 0.5, 0.25, 1) on mesh 0, whose base colour
// texture is image 0, and node 3 'copy' placing mesh 0 again.
GltfBuilder textured(const json& image) {
  GltfBuilder b = three_nodes();
  const std::vector<float> uvs = {0, 0, 1, 0, 0, 1};
  b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
      b.add_array(uvs, GltfBuilder::kFloat, "VEC2");
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["materials"] = json::array(
      {{{"name", "paint"},
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  b.doc["images"] = json::array({image});
  b.doc["nodes"].push_back({{"name", "copy"}, {"mesh", 0}, {"translation", {0, 0, 3}}});
  b.doc["scenes"][0]["nodes"].push_back(3);
  return b;
}

TEST(ImportKeepGoing, TextureThatDoesNotDecode) {
  const TempDir dir("keep_going_texture");
  GltfBuilder b = textured(json::object());
  const std::string garbage = "these bytes are not a PNG image at all";
  b.doc["images"][0] = {{"name", "garbage"},
                        {"bufferView", b.add_view(garbage.data(), garbage.size())},
                        {"mimeType", "image/png"}};
  const std::string path = dir.write("garbage_texture.glb", b.glb());
  EXPECT_NE(import_error(path).find("STB cannot decode"), std::string::npos);

  const Import kept(path, true);
  EXPECT_EQ(kept.scene.meshes.size(), 4u);  // nodes 0, 3 (mesh 0), 1 and 2
  ASSERT_EQ(kept.scene.materials.size(), 1u);
  const Material& paint = kept.scene.materials[0];
  EXPECT_EQ(paint.base_color_texture, -1);
  EXPECT_EQ(paint.base_color, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
  for (const Mesh& mesh : kept.scene.meshes) {
    if (mesh.material != 0) continue;
    EXPECT_EQ(kept.scene.vertex_albedo(mesh, 0), glm::vec3(0.5f, 0.25f, 1.0f));
  }
  // One problem per node whose meshes use the material.
  ASSERT_EQ(kept.scene.problems.size(), 2u);
  EXPECT_EQ(kept.scene.problems[0].node, 0);
  EXPECT_EQ(kept.scene.problems[1].node, 3);
  for (const ImportProblem& problem : kept.scene.problems) {
    EXPECT_EQ(problem.material, 0);
    EXPECT_EQ(problem.mesh, -1);
    EXPECT_EQ(problem.reason.rfind("material 0 'paint' base colour texture 0: image 0 'garbage' "
                                   "does not decode (",
                                   0),
              0u)
        << problem.reason;
    EXPECT_NE(problem.reason.find("STB cannot decode"), std::string::npos) << problem.reason;
  }
  EXPECT_EQ(kept.warned({path, "node 0 'good'", "image 0 'garbage' does not decode"}), 1);
  EXPECT_EQ(kept.warned({path, "node 3 'copy'", "image 0 'garbage' does not decode"}), 1);
}

TEST(ImportKeepGoing, TextureWhoseFileIsMissing) {
  const TempDir dir("keep_going_texture_file");
  const GltfBuilder b = textured({{"uri", "missing.png"}});
  const std::string path = dir.write("missing_texture.gltf", b.gltf_with_data_uri());
  // Without keep-going: imported, the material refers to the empty image (as before).
  const Scene scene = import_scene(path, Context{});
  EXPECT_EQ(scene.materials[0].base_color_texture, 0);
  EXPECT_TRUE(scene.problems.empty());

  const Import kept(path, true);
  EXPECT_EQ(kept.scene.meshes.size(), 4u);
  EXPECT_EQ(kept.scene.materials[0].base_color_texture, -1);
  ASSERT_EQ(kept.scene.problems.size(), 2u);
  EXPECT_EQ(kept.scene.problems[0].reason,
            "material 0 'paint' base colour texture 0: image 0 'missing.png' did not load (its "
            "file is missing or empty, or its pixel format is not supported)");
}

TEST(ImportKeepGoing, TextureOfAMaterialNoNodeUses) {
  const TempDir dir("keep_going_texture_unused");
  GltfBuilder b = textured({{"uri", "missing.png"}});
  b.doc["meshes"][0]["primitives"][0].erase("material");
  const Import kept(dir.write("unused.gltf", b.gltf_with_data_uri()), true);
  ASSERT_EQ(kept.scene.problems.size(), 1u);
  EXPECT_EQ(kept.scene.problems[0].node, -1);
  EXPECT_EQ(kept.scene.problems[0].material, 0);
}

TEST(ImportKeepGoing, AccessorWithBadBufferView) {
  const TempDir dir("keep_going_accessor");
  GltfBuilder b = three_nodes();
  b.doc["accessors"][4]["bufferView"] = 42;  // mesh 1's NORMAL
  // And an accessor nothing uses, also broken: a warning with keep-going.
  b.doc["accessors"].push_back(
      {{"bufferView", 42}, {"componentType", GltfBuilder::kFloat}, {"count", 3}, {"type", "VEC3"}});
  const std::string path = dir.write("bad_view.glb", b.glb());
  EXPECT_NE(import_error(path).find("bufferView"), std::string::npos);

  const Import kept(path, true);
  EXPECT_EQ(mesh_nodes(kept.scene), (std::vector<int>{0, 2}));
  ASSERT_EQ(kept.scene.problems.size(), 1u);
  EXPECT_EQ(kept.scene.problems[0].node, 1);
  EXPECT_EQ(kept.scene.problems[0].mesh, 1);
  EXPECT_EQ(kept.scene.problems[0].reason.rfind("mesh 1 'lost' primitive 0: accessor 4", 0), 0u)
      << kept.scene.problems[0].reason;
  EXPECT_NE(kept.scene.problems[0].reason.find("bad bufferView (42)"), std::string::npos);
  EXPECT_EQ(kept.warned({"accessor 9", "nothing uses it"}), 1);
}

// Mesh 1 'lost' becomes a Draco primitive whose bitstream is garbage.
GltfBuilder with_garbage_draco() {
  GltfBuilder b = three_nodes();
  const std::string garbage(64, '\x5A');
  const int view = b.add_view(garbage.data(), garbage.size());
  b.doc["accessors"].push_back(
      {{"componentType", GltfBuilder::kUShort}, {"count", 3}, {"type", "SCALAR"}});
  b.doc["accessors"].push_back(
      {{"componentType", GltfBuilder::kFloat}, {"count", 3}, {"type", "VEC3"}});
  b.doc["meshes"][1]["primitives"][0] = {
      {"attributes", {{"POSITION", 10}}},
      {"indices", 9},
      {"extensions",
       {{"KHR_draco_mesh_compression",
         {{"bufferView", view}, {"attributes", {{"POSITION", 0}}}}}}}};
  b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  return b;
}

TEST(ImportKeepGoing, DracoDataThatDoesNotDecode) {
  const TempDir dir("keep_going_draco");
  const GltfBuilder b = with_garbage_draco();
  const std::string reason =
      "mesh 1 primitive 0: the KHR_draco_mesh_compression data does not decode (corrupt or "
      "truncated Draco bitstream)";
  for (const std::string& path :
       {dir.write("draco.glb", b.glb()), dir.write("draco.gltf", b.gltf_with_data_uri())}) {
    EXPECT_EQ(import_error(path), path + ": " + reason);
    const Import kept(path, true);
    EXPECT_EQ(mesh_nodes(kept.scene), (std::vector<int>{0, 2})) << path;
    ASSERT_EQ(kept.scene.problems.size(), 1u) << path;
    EXPECT_EQ(kept.scene.problems[0].node, 1);
    EXPECT_EQ(kept.scene.problems[0].mesh, 1);
    EXPECT_EQ(kept.scene.problems[0].reason, reason);
    EXPECT_EQ(kept.warned({"nothing uses it"}), 0);  // its accessors belong to the dropped part
    // The reference leaves the Draco mesh out: the throwing import refuses it, placed or not.
    expect_same_meshes(
        kept.scene,
        import_scene(dir.write("without.glb", without_node_1(three_nodes()).glb()), {}));
  }
}

TEST(ImportKeepGoing, BrokenMeshThatNoNodePlaces) {
  const TempDir dir("keep_going_unplaced");
  const GltfBuilder b = without_node_1(with_garbage_draco());
  const Import kept(dir.write("unplaced.glb", b.glb()), true);
  EXPECT_EQ(mesh_nodes(kept.scene), (std::vector<int>{0, 2}));
  ASSERT_EQ(kept.scene.problems.size(), 1u);
  EXPECT_EQ(kept.scene.problems[0].node, -1);
  EXPECT_EQ(kept.scene.problems[0].mesh, 1);
}

TEST(ImportKeepGoing, EveryMeshBrokenGivesAnEmptySceneWithItsProblems) {
  const TempDir dir("keep_going_all_broken");
  const std::string path = dir.write("bad_index.glb", triangle_builder({0, 1, 7}).glb());
  const Import kept(path, true);
  EXPECT_TRUE(kept.scene.meshes.empty());
  ASSERT_EQ(kept.scene.problems.size(), 1u);
  EXPECT_EQ(kept.scene.problems[0].node, 0);
  // A file with no meshes at all is still refused.
  GltfBuilder no_meshes;
  no_meshes.doc["scenes"] = json::array({{{"nodes", json::array()}}});
  EXPECT_THROW(Import(dir.write("no_meshes.gltf", no_meshes.gltf_with_data_uri()), true), Error);
}

TEST(ImportKeepGoing, FileLevelProblemsStillThrow) {
  const TempDir dir("keep_going_file_level");
  EXPECT_THROW(Import(dir.write("garbage.gltf", "{ this is not json"), true), Error);
  EXPECT_THROW(
      Import(dir.write("missing_bin.gltf", three_nodes().gltf_with_external_buffer("missing.bin")),
             true),
      Error);
  GltfBuilder cycle = three_nodes();
  cycle.doc["nodes"][0]["children"] = {1};
  cycle.doc["nodes"][1]["children"] = {0};
  EXPECT_THROW(Import(dir.write("cycle.glb", cycle.glb()), true), Error);
  const std::string glb = three_nodes().glb();
  EXPECT_THROW(Import(dir.write("cut.glb", glb.substr(0, glb.size() - 5)), true), Error);
}

}  // namespace
}  // namespace prt::bake
