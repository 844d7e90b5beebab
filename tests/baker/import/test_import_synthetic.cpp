// SPDX-License-Identifier: MIT
// Small glTF and OBJ files written by the tests, with expected values worked out by hand:
// node transforms, every buffer kind, strides and normalised integers, strips and fans,
// generated normals and tangents, skinning at the rest pose, OBJ polygons and objects.
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gltf_builder.hpp"
#include "prt/baker/scene.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using prt_test::shared_asset;
using prt_test::TempDir;

void expect_vec3(const glm::vec3& got, const glm::vec3& want, float tol = 1e-5f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

glm::vec3 geometric_normal(const Mesh& mesh, std::size_t t) {
  const glm::vec3 a = mesh.positions[mesh.indices[3 * t]],
                  b = mesh.positions[mesh.indices[3 * t + 1]],
                  c = mesh.positions[mesh.indices[3 * t + 2]];
  return glm::normalize(glm::cross(b - a, c - a));
}

TEST(ImportGltf, SameSceneFromGlbDataUriAndExternalBuffer) {
  const TempDir dir("gltf_buffers");
  const GltfBuilder b = triangle_builder();
  dir.write("external.bin", b.bin);
  for (const std::string& path :
       {dir.write("a.glb", b.glb()), dir.write("b.gltf", b.gltf_with_data_uri()),
        dir.write("c.gltf", b.gltf_with_external_buffer("external.bin"))}) {
    const Scene scene = import_scene(path, Context{});
    ASSERT_EQ(scene.meshes.size(), 1u) << path;
    const Mesh& mesh = scene.meshes[0];
    ASSERT_EQ(mesh.vertex_count(), 3u);
    expect_vec3(mesh.positions[1], {1, 0, 0});
    expect_vec3(mesh.positions[2], {0, 1, 0});
    expect_vec3(mesh.normals[0], {0, 0, 1});
    EXPECT_FALSE(mesh.normals_generated);
    EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
  }
}

// parent: T(1,0,0) R(90° about Y); child: S(2); the mesh on the child.
// A point p goes to T R S p; R maps (x, y, z) to (z, y, -x).
TEST(ImportGltf, NodeHierarchyPlacesMeshesInWorldSpace) {
  const TempDir dir("gltf_nodes");
  GltfBuilder b = triangle_builder();
  const float s = std::sqrt(0.5f);
  b.doc["nodes"] = nlohmann::json::array(
      {{{"translation", {1, 0, 0}}, {"rotation", {0, s, 0, s}}, {"children", {1}}},
       {{"scale", {2, 2, 2}}, {"mesh", 0}}});
  const Scene scene = import_scene(dir.write("nodes.glb", b.glb()), Context{});
  ASSERT_EQ(scene.nodes.size(), 2u);
  EXPECT_EQ(scene.nodes[1].parent, 0);
  const Mesh& mesh = scene.meshes.at(0);
  EXPECT_EQ(mesh.node, 1);
  expect_vec3(mesh.positions[0], {1, 0, 0});
  expect_vec3(mesh.positions[1], {1, 0, -2});  // (1,0,0) -> (2,0,0) -> (0,0,-2) -> (1,0,-2)
  expect_vec3(mesh.positions[2], {1, 2, 0});
  expect_vec3(mesh.normals[0], {1, 0, 0});  // +Z turned by R
  expect_vec3(mesh.local_positions[1], {1, 0, 0});
}

TEST(ImportGltf, NodeMatrixAndMirroringKeepFrontFaces) {
  const TempDir dir("gltf_matrix");
  GltfBuilder b = triangle_builder();
  // Column-major: scale x by -1 and translate by (0, 0, 5).
  b.doc["nodes"] = nlohmann::json::array(
      {{{"mesh", 0}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1}}}});
  const Scene scene = import_scene(dir.write("mirror.glb", b.glb()), Context{});
  const Mesh& mesh = scene.meshes.at(0);
  expect_vec3(mesh.positions[1], {-1, 0, 5});
  expect_vec3(mesh.normals[0], {0, 0, 1});
  // The winding is flipped back so the triangle still faces its normal.
  EXPECT_GT(glm::dot(geometric_normal(mesh, 0), mesh.normals[0]), 0.99f);
  // The decomposed T, R, S (a mirror has more than one) rebuild the matrix.
  const Node& node = scene.nodes[0];
  const glm::mat4 trs = glm::translate(glm::mat4(1.0f), node.translation) *
                        glm::mat4_cast(node.rotation) * glm::scale(glm::mat4(1.0f), node.scale);
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(trs[c][r], node.local[c][r], 1e-5f);
  }
}

// A node matrix T(1,2,3) R(90° about Y) S(2,3,4), written out by hand (column-major): its
// decomposition must give back those factors.
TEST(ImportGltf, NodeMatrixIsDecomposedIntoTrs) {
  const TempDir dir("gltf_decompose");
  GltfBuilder b = triangle_builder();
  // R maps x -> -z and z -> x: columns R*S = (0,0,-2), (0,3,0), (4,0,0).
  b.doc["nodes"] = nlohmann::json::array(
      {{{"mesh", 0}, {"matrix", {0, 0, -2, 0, 0, 3, 0, 0, 4, 0, 0, 0, 1, 2, 3, 1}}}});
  const Scene scene = import_scene(dir.write("decompose.glb", b.glb()), Context{});
  const Node& node = scene.nodes[0];
  expect_vec3(node.translation, {1, 2, 3});
  expect_vec3(node.scale, {2, 3, 4});
  const float s = std::sqrt(0.5f);
  EXPECT_NEAR(std::abs(glm::dot(node.rotation, glm::quat(s, 0, s, 0))), 1.0f, 1e-5f);
  expect_vec3(scene.meshes.at(0).positions[1], {1, 2, 1});  // (1,0,0) -> (2,0,0) -> (0,0,-2) + T
}

TEST(ImportGltf, ReadsInterleavedStridesAndNormalisedIntegers) {
  const TempDir dir("gltf_components");
  GltfBuilder b;
  // Interleaved vertex: position as 3 shorts (KHR_mesh_quantization style, not normalised),
  // 2 bytes padding, texcoord as 2 normalised unsigned bytes, 2 bytes padding: stride 12.
  struct Vertex {
    std::int16_t p[3];
    std::uint16_t pad0;
    std::uint8_t uv[2];
    std::uint16_t pad1;
  };
  static_assert(sizeof(Vertex) == 12);
  const Vertex vertices[3] = {
      {{0, 0, 0}, 0, {0, 255}, 0}, {{300, 0, 0}, 0, {255, 255}, 0}, {{0, -400, 0}, 0, {51, 0}, 0}};
  const int view = b.add_view(vertices, sizeof(vertices), 12);
  const int position = b.add_accessor(view, GltfBuilder::kShort, 3, "VEC3");
  const int uv = b.add_accessor(view, GltfBuilder::kUByte, 3, "VEC2", true, 8);
  // Colours as normalised unsigned shorts, RGB (alpha becomes 1); weights as normalised bytes.
  const int color = b.add_array(std::vector<std::uint16_t>{65535, 0, 0, 0, 65535, 0, 0, 0, 13107},
                                GltfBuilder::kUShort, "VEC3", true);
  b.add_mesh({{"attributes", {{"POSITION", position}, {"TEXCOORD_0", uv}, {"COLOR_0", color}}}});
  b.single_node_scene();
  b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  const Scene scene = import_scene(dir.write("components.glb", b.glb()), Context{});
  const Mesh& mesh = scene.meshes.at(0);
  expect_vec3(mesh.positions[1], {300, 0, 0});
  expect_vec3(mesh.positions[2], {0, -400, 0});
  EXPECT_NEAR(mesh.texcoords0[1].x, 1.0f, 1e-6f);
  EXPECT_NEAR(mesh.texcoords0[2].x, 0.2f, 1e-6f);  // 51 / 255
  EXPECT_NEAR(mesh.colors0[2].b, 0.2f, 1e-6f);     // 13107 / 65535
  EXPECT_EQ(mesh.colors0[0].a, 1.0f);
  // No indices: the vertices in order are the triangle; normals generated from the winding.
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_TRUE(mesh.normals_generated);
  expect_vec3(mesh.normals[0], {0, 0, -1});  // (300,0,0) x (0,-400,0) points to -Z
  // Tangents from UVs: u grows along +X.
  ASSERT_EQ(mesh.tangents.size(), 3u);
  EXPECT_TRUE(mesh.tangents_generated);
  expect_vec3(glm::vec3(mesh.tangents[0]), {1, 0, 0}, 1e-4f);
}

TEST(ImportGltf, SparseAccessorOverridesValues) {
  const TempDir dir("gltf_sparse");
  GltfBuilder b = triangle_builder();
  const std::vector<std::uint8_t> which = {2};
  const std::vector<float> value = {0, 5, 0};
  const int index_view = b.add_view(which.data(), which.size());
  const int value_view = b.add_view(value.data(), value.size() * sizeof(float));
  b.doc["accessors"][0]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", index_view}, {"componentType", GltfBuilder::kUByte}}},
      {"values", {{"bufferView", value_view}}}};
  const Scene scene = import_scene(dir.write("sparse.glb", b.glb()), Context{});
  expect_vec3(scene.meshes.at(0).positions[2], {0, 5, 0});
  expect_vec3(scene.meshes.at(0).positions[1], {1, 0, 0});
}

// A unit square as a strip and as a fan: two triangles, both facing +Z.
TEST(ImportGltf, StripsAndFansBecomeTriangleLists) {
  const TempDir dir("gltf_strips");
  for (int mode : {5, 6}) {
    GltfBuilder b;
    const std::vector<float> strip = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const std::vector<float> fan = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const int p = b.add_array(mode == 5 ? strip : fan, GltfBuilder::kFloat, "VEC3");
    b.add_mesh({{"attributes", {{"POSITION", p}}}, {"mode", mode}});
    b.single_node_scene();
    const Scene scene =
        import_scene(dir.write("mode" + std::to_string(mode) + ".glb", b.glb()), Context{});
    const Mesh& mesh = scene.meshes.at(0);
    ASSERT_EQ(mesh.triangle_count(), 2u) << "mode " << mode;
    for (std::size_t t = 0; t < 2; ++t) expect_vec3(geometric_normal(mesh, t), {0, 0, 1});
  }
}

// Two triangles share vertex 0: one of area 1 in the XY plane (normal +Z), one of area 3 in the
// YZ plane (normal +X). Area weighting gives normalize(1*Z + 3*X) at the shared vertex.
TEST(ImportGltf, GeneratedNormalsAreAreaWeighted) {
  const TempDir dir("gltf_normals");
  GltfBuilder b;
  const std::vector<float> positions = {0, 0, 0, 2, 0, 0, 0, 1, 0,  // XY: area 1
                                        0, 3, 0, 0, 0, 2};          // YZ with (0,0,0): area 3
  const int p = b.add_array(positions, GltfBuilder::kFloat, "VEC3");
  const int i =
      b.add_array(std::vector<std::uint16_t>{0, 1, 2, 0, 3, 4}, GltfBuilder::kUShort, "SCALAR");
  b.add_mesh({{"attributes", {{"POSITION", p}}}, {"indices", i}});
  b.single_node_scene();
  const Scene scene = import_scene(dir.write("normals.glb", b.glb()), Context{});
  const Mesh& mesh = scene.meshes.at(0);
  EXPECT_TRUE(mesh.normals_generated);
  expect_vec3(mesh.normals[0], glm::normalize(glm::vec3(3, 0, 1)));
  expect_vec3(mesh.normals[1], {0, 0, 1});
  expect_vec3(mesh.normals[3], {1, 0, 0});
}

// Skinned at rest: a joint node translated by (0, 2, 0) whose inverse bind matrix undoes
// (0, 1, 0) moves the bind-pose mesh up by 1; the mesh node's own transform is ignored.
TEST(ImportGltf, SkinnedMeshesArePlacedByTheirJointsAtRest) {
  const TempDir dir("gltf_skin");
  GltfBuilder b = triangle_builder();
  const int joints = b.add_array(std::vector<std::uint8_t>(12, 0), GltfBuilder::kUByte, "VEC4");
  const int weights = b.add_array(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0},
                                  GltfBuilder::kFloat, "VEC4");
  const std::vector<float> inverse_bind = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  const int ibm = b.add_array(inverse_bind, GltfBuilder::kFloat, "MAT4");
  b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = joints;
  b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = weights;
  b.doc["nodes"] = nlohmann::json::array(
      {{{"mesh", 0}, {"skin", 0}, {"translation", {100, 0, 0}}}, {{"translation", {0, 2, 0}}}});
  b.doc["scenes"][0]["nodes"] = {0, 1};
  b.doc["skins"] = nlohmann::json::array({{{"joints", {1}}, {"inverseBindMatrices", ibm}}});
  // A two-key rotation animation of the joint.
  const int times = b.add_array(std::vector<float>{0, 2}, GltfBuilder::kFloat, "SCALAR");
  const int rotations =
      b.add_array(std::vector<float>{0, 0, 0, 1, 0, 0, 1, 0}, GltfBuilder::kFloat, "VEC4");
  b.doc["animations"] = nlohmann::json::array(
      {{{"name", "turn"},
        {"samplers", {{{"input", times}, {"output", rotations}, {"interpolation", "STEP"}}}},
        {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}}}}}});
  const Scene scene = import_scene(dir.write("skin.glb", b.glb()), Context{});
  const Mesh& mesh = scene.meshes.at(0);
  EXPECT_EQ(mesh.skin, 0);
  expect_vec3(mesh.positions[0], {0, 1, 0});
  expect_vec3(mesh.positions[1], {1, 1, 0});
  expect_vec3(mesh.local_positions[1], {1, 0, 0});
  EXPECT_EQ(mesh.joints0[2], glm::u16vec4(0));
  ASSERT_EQ(scene.animations.size(), 1u);
  const AnimationChannel& channel = scene.animations[0].channels.at(0);
  EXPECT_EQ(channel.node, 1);
  EXPECT_EQ(channel.interpolation, AnimationChannel::Interpolation::Step);
  EXPECT_EQ(channel.values, (std::vector<float>{0, 0, 0, 1, 0, 0, 1, 0}));
  EXPECT_FLOAT_EQ(scene.animations[0].duration, 2.0f);
}

TEST(ImportGltf, BaseColourFactorTextureAndVertexColour) {
  const TempDir dir("gltf_material");
  GltfBuilder b = triangle_builder();
  // A 2x1 sRGB image: left texel 188 (sRGB) = 0.5029 linear, right texel 255.
  const unsigned char pixels[2 * 4] = {188, 188, 188, 255, 255, 255, 255, 255};
  ASSERT_NE(stbi_write_png(dir.file("albedo.png").c_str(), 2, 1, 4, pixels, 8), 0);
  const int uv = b.add_array(std::vector<float>{0.25f, 0.5f, 0.75f, 0.5f, 0.25f, 0.5f},
                             GltfBuilder::kFloat, "VEC2");
  b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["images"] = nlohmann::json::array({{{"uri", "albedo.png"}}});
  b.doc["textures"] = nlohmann::json::array({{{"source", 0}}});
  b.doc["materials"] = nlohmann::json::array(
      {{{"name", "m"},
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {0.5, 1.0, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}}});
  const std::string path = dir.write("material.gltf", b.gltf_with_data_uri());
  const Scene scene = import_scene(path, Context{});
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].width, 2);
  const Mesh& mesh = scene.meshes.at(0);
  const float srgb188 = std::pow((188.0f / 255.0f + 0.055f) / 1.055f, 2.4f);
  expect_vec3(scene.vertex_albedo(mesh, 0), {0.5f * srgb188, srgb188, srgb188}, 1e-4f);
  expect_vec3(scene.vertex_albedo(mesh, 1), {0.5f, 1.0f, 1.0f}, 1e-4f);
}

// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv, with the extension's
// reference GLSL R = mat3(cos, sin, 0, -sin, cos, 0, 0, 0, 1) (columns).
TEST(ImportGltf, TextureTransformFollowsTheExtension) {
  const TempDir dir("gltf_texture_transform");
  GltfBuilder b = triangle_builder();
  const unsigned char pixel[4] = {255, 255, 255, 255};
  ASSERT_NE(stbi_write_png(dir.file("white.png").c_str(), 1, 1, 4, pixel, 4), 0);
  b.doc["images"] = nlohmann::json::array({{{"uri", "white.png"}}});
  b.doc["textures"] = nlohmann::json::array({{{"source", 0}}});
  const double half_pi = 1.5707963267948966;
  b.doc["materials"] = nlohmann::json::array(
      {{{"pbrMetallicRoughness",
         {{"baseColorTexture",
           {{"index", 0},
            {"extensions",
             {{"KHR_texture_transform",
               {{"offset", {0.5, 0.25}}, {"rotation", half_pi}, {"scale", {2, 3}}}}}}}}}}}});
  b.doc["extensionsUsed"] = {"KHR_texture_transform"};
  const Scene scene = import_scene(dir.write("transform.gltf", b.gltf_with_data_uri()), Context{});
  const glm::mat3& m = scene.materials.at(0).base_color_uv_transform;
  // (1, 0) -> S -> (2, 0) -> R(90°) -> (0, 2) -> T -> (0.5, 2.25)
  const glm::vec3 uv = m * glm::vec3(1, 0, 1);
  EXPECT_NEAR(uv.x, 0.5f, 1e-5f);
  EXPECT_NEAR(uv.y, 2.25f, 1e-5f);
  // (0, 1) -> (0, 3) -> (-3, 0) -> (-2.5, 0.25)
  const glm::vec3 uv2 = m * glm::vec3(0, 1, 1);
  EXPECT_NEAR(uv2.x, -2.5f, 1e-5f);
  EXPECT_NEAR(uv2.y, 0.25f, 1e-5f);
}

TEST(ImportGltf, GeneratedTangentsAgreeWithTheFilesMikkTSpaceTangents) {
  const std::string path = shared_asset("meshes/SheenCloth/SheenCloth.gltf");
  if (path.empty()) GTEST_SKIP() << "shared assets not found";
  Scene scene = import_scene(path, Context{});
  Mesh& mesh = scene.meshes.at(0);
  const std::vector<glm::vec4> from_file = mesh.tangents;
  generate_tangents(mesh);
  ASSERT_EQ(mesh.tangents.size(), from_file.size());
  std::size_t agree = 0, same_handedness = 0;
  for (std::size_t i = 0; i < from_file.size(); ++i) {
    agree += glm::dot(glm::vec3(mesh.tangents[i]), glm::vec3(from_file[i])) > 0.9f ? 1 : 0;
    same_handedness += mesh.tangents[i].w == from_file[i].w ? 1 : 0;
  }
  // Every vertex of this cloth agrees; a thousandth is left for the seams and degenerate
  // corners where MikkTSpace's choices may legitimately differ from the area-weighted sum.
  EXPECT_GE(agree, from_file.size() * 999 / 1000);
  EXPECT_GE(same_handedness, from_file.size() * 999 / 1000);
}

// ---- OBJ ---------------------------------------------------------------------------------------

TEST(ImportObj, PolygonsNegativeIndicesAndNormals) {
  const TempDir dir("obj_polygons");
  const std::string path = dir.write("quad.obj",
                                     "# a unit square as one quad, then a pentagon, relative\n"
                                     "mtllib quad.mtl\n"
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "vn 0 0 1\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                     "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
                                     "v 0 0 1\nv 1 0 1\nv 2 1 1\nv 1 2 1\nv 0 1 1\n"
                                     "f -5//1 -4//1 -3//1 -2//1 -1//1\n");
  std::vector<std::string> notes;
  Context ctx;
  ctx.log = [&](LogLevel, const std::string& text) { notes.push_back(text); };
  const Scene scene = import_scene(path, ctx);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& mesh = scene.meshes[0];
  EXPECT_EQ(mesh.vertex_count(), 9u);
  EXPECT_EQ(mesh.triangle_count(), 2u + 3u);  // fans: n - 2 triangles
  EXPECT_FALSE(mesh.normals_generated);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    expect_vec3(geometric_normal(mesh, t), {0, 0, 1});
  }
  // The quad's texcoords are flipped into glTF's convention (v down): vt (0,0) -> (0,1).
  expect_vec3(glm::vec3(mesh.texcoords0[0], 0), {0, 1, 0});
  bool material_note = false;
  for (const std::string& n : notes) material_note |= n.find("mtllib") != std::string::npos;
  EXPECT_TRUE(material_note);
}

TEST(ImportObj, OneMeshPerObjectKeepingFileOrder) {
  const TempDir dir("obj_objects");
  const std::string path = dir.write("two.obj",
                                     "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                                     "o second\ng part\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 9 9 9\n"
                                     "f 4 5 6\nf 4 6 1\n");
  const Scene scene = import_scene(path, Context{});
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].name, "first");
  EXPECT_EQ(scene.meshes[1].name, "second");
  EXPECT_EQ(scene.meshes[0].vertex_count(), 3u);
  // The second object's own four positions in file order (the unused one too), then the
  // position it borrows from the first object.
  const Mesh& second = scene.meshes[1];
  ASSERT_EQ(second.vertex_count(), 5u);
  expect_vec3(second.positions[0], {5, 0, 0});
  expect_vec3(second.positions[3], {9, 9, 9});
  expect_vec3(second.positions[4], {0, 0, 0});
  EXPECT_EQ(second.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 4}));
  EXPECT_TRUE(second.normals_generated);
  expect_vec3(second.normals[0], {0, 0, 1});
}

TEST(ImportObj, VertexColoursBecomeColor0) {
  const TempDir dir("obj_colours");
  const std::string path =
      dir.write("colours.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 0.5\nf 1 2 3\n");
  const Scene scene = import_scene(path, Context{});
  const Mesh& mesh = scene.meshes.at(0);
  ASSERT_EQ(mesh.colors0.size(), 3u);
  EXPECT_EQ(mesh.colors0[1], glm::vec4(0, 1, 0, 1));
  expect_vec3(scene.vertex_albedo(mesh, 2), {0, 0, 0.5f});  // no material: white x colour
}

TEST(ImportObj, SeamVerticesAreSplitByTexcoord) {
  const TempDir dir("obj_seams");
  const std::string path = dir.write("seam.obj",
                                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\n"
                                     "f 1/1 2/2 3/3\nf 2/4 4/2 3/3\n");
  const Mesh mesh = import_scene(path, Context{}).meshes.at(0);
  EXPECT_EQ(mesh.vertex_count(), 5u);  // vertex 2 is used with two different texcoords
  EXPECT_EQ(mesh.indices[3], 4u);
  expect_vec3(mesh.positions[4], {1, 0, 0});
}

}  // namespace
}  // namespace prt::bake
