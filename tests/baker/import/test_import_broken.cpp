// SPDX-License-Identifier: MIT
// Broken input gives an Error whose message names the file and what is wrong. Every broken file
// is written here, in a temp folder: from a small valid file built by the test, or a damaged
// copy of a shared asset.
#include <gtest/gtest.h>

#include "gltf_builder.hpp"
#include "prt/baker/scene.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

using prt_test::read_bytes;
using prt_test::shared_asset;
using prt_test::TempDir;

// Imports path and expects an Error whose message contains the file path and every fragment.
void expect_import_error(const std::string& path, const std::vector<std::string>& fragments) {
  try {
    import_scene(path, Context{});
    ADD_FAILURE() << path << " imported without error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos)
        << "message does not name the file: " << message;
    for (const std::string& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message lacks '" << fragment << "': " << message;
    }
  }
}

TEST(ImportBroken, ValidFilesOfTheFixtureImport) {
  const TempDir dir("broken_valid");
  const GltfBuilder b = triangle_builder();
  EXPECT_EQ(import_scene(dir.write("ok.glb", b.glb()), Context{}).triangle_count(), 1u);
  EXPECT_EQ(import_scene(dir.write("ok.gltf", b.gltf_with_data_uri()), Context{}).triangle_count(),
            1u);
}

TEST(ImportBroken, TruncatedGlb) {
  const TempDir dir("broken_truncated");
  const std::string glb = triangle_builder().glb();
  // Cut inside the binary chunk, inside the JSON chunk, and inside the header.
  for (std::size_t keep : {glb.size() - 5, std::size_t(40), std::size_t(8)}) {
    const std::string path = dir.write("cut" + std::to_string(keep) + ".glb", glb.substr(0, keep));
    expect_import_error(path, {"truncated .glb"});
  }
}

TEST(ImportBroken, TruncatedCopyOfSharedDracoAsset) {
  const std::string source = shared_asset("draco/CesiumMan_Draco.glb");
  if (source.empty()) GTEST_SKIP() << "shared assets not found";
  const TempDir dir("broken_truncated_asset");
  const std::string bytes = read_bytes(source);
  const std::string path = dir.write("CesiumMan_Draco_cut.glb", bytes.substr(0, bytes.size() / 2));
  expect_import_error(path, {"truncated .glb", "header says"});
}

TEST(ImportBroken, CorruptDracoBitstream) {
  const std::string source = shared_asset("draco/Box_Draco.glb");
  if (source.empty()) GTEST_SKIP() << "shared assets not found";
  const TempDir dir("broken_draco");
  std::string bytes = read_bytes(source);
  const std::size_t draco = bytes.find("DRACO");
  ASSERT_NE(draco, std::string::npos);
  for (std::size_t i = draco + 5; i < bytes.size(); ++i) bytes[i] = static_cast<char>(0xA5);
  expect_import_error(dir.write("Box_bad_draco.glb", bytes),
                      {"mesh 0 primitive 0", "Draco bitstream"});
}

TEST(ImportBroken, MissingExternalBuffer) {
  const TempDir dir("broken_missing_buffer");
  const std::string path =
      dir.write("scene.gltf", triangle_builder().gltf_with_external_buffer("scene_data.bin"));
  expect_import_error(path, {"buffer 0", "scene_data.bin", "missing"});
  // With the file present, it imports.
  dir.write("scene_data.bin", triangle_builder().bin);
  EXPECT_EQ(import_scene(path, Context{}).vertex_count(), 3u);
}

TEST(ImportBroken, SharedAssetCopiedWithoutItsBuffer) {
  const std::string source = shared_asset("characters/RiggedSimple/RiggedSimple.gltf");
  if (source.empty()) GTEST_SKIP() << "shared assets not found";
  const TempDir dir("broken_asset_buffer");
  const std::string path = dir.write("RiggedSimple.gltf", read_bytes(source));
  expect_import_error(path, {"buffer 0", "RiggedSimple0.bin", "missing"});
}

TEST(ImportBroken, ShortExternalBuffer) {
  const TempDir dir("broken_short_buffer");
  const GltfBuilder b = triangle_builder();
  const std::string path = dir.write("scene.gltf", b.gltf_with_external_buffer("scene.bin"));
  dir.write("scene.bin", b.bin.substr(0, b.bin.size() - 8));
  expect_import_error(path, {"buffer 0", "scene.bin", "byteLength"});
}

TEST(ImportBroken, AccessorReadsPastItsBufferView) {
  const TempDir dir("broken_accessor_range");
  GltfBuilder b = triangle_builder();
  b.doc["accessors"][0]["count"] = 30;  // POSITION: 30 vec3 in a 36-byte view
  expect_import_error(dir.write("long_accessor.glb", b.glb()),
                      {"accessor 0", "reads past the end of bufferView 0"});
}

TEST(ImportBroken, AccessorWithAHugeCount) {
  const TempDir dir("broken_accessor_huge");
  GltfBuilder b = triangle_builder();
  b.doc["accessors"][0]["count"] = 4611686018427387904ULL;  // 2^62: must not wrap or allocate
  expect_import_error(dir.write("huge_accessor.glb", b.glb()),
                      {"accessor 0", "reads past the end"});
}

TEST(ImportBroken, AccessorWithBadBufferView) {
  const TempDir dir("broken_accessor_view");
  GltfBuilder b = triangle_builder();
  b.doc["accessors"][1]["bufferView"] = 42;
  expect_import_error(dir.write("bad_view.glb", b.glb()), {"accessor 1", "bufferView"});
}

TEST(ImportBroken, BufferViewOutsideItsBuffer) {
  const TempDir dir("broken_view_range");
  GltfBuilder b = triangle_builder();
  b.doc["bufferViews"][0]["byteOffset"] = 4000;
  expect_import_error(dir.write("bad_view_range.glb", b.glb()),
                      {"bufferView 0", "outside its buffer"});
}

TEST(ImportBroken, IndexOutOfRange) {
  const TempDir dir("broken_index");
  expect_import_error(dir.write("bad_index.glb", triangle_builder({0, 1, 7}).glb()),
                      {"mesh 0", "index 7", "out of range (3 vertices)"});
  expect_import_error(dir.write("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n"),
                      {"bad_index.obj:4", "index -4", "out of range"});
}

TEST(ImportBroken, EmptyMesh) {
  const TempDir dir("broken_empty");
  expect_import_error(dir.write("empty.glb", triangle_builder({}).glb()),
                      {"mesh 0", "empty (no triangles)"});
  expect_import_error(dir.write("two_indices.glb", triangle_builder({0, 1}).glb()),
                      {"not a multiple of 3"});
  GltfBuilder no_meshes;
  no_meshes.doc["scenes"] = nlohmann::json::array({{{"nodes", nlohmann::json::array()}}});
  expect_import_error(dir.write("no_meshes.gltf", no_meshes.gltf_with_data_uri()),
                      {"no triangle meshes"});
  expect_import_error(dir.write("no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"),
                      {"no faces", "empty"});
}

TEST(ImportBroken, PointPrimitivesAloneAreAnEmptyScene) {
  const TempDir dir("broken_points");
  GltfBuilder b = triangle_builder();
  b.doc["meshes"][0]["primitives"][0]["mode"] = 0;  // POINTS
  std::vector<std::string> warnings;
  Context ctx;
  ctx.log = [&](LogLevel, const std::string& text) { warnings.push_back(text); };
  const std::string path = dir.write("points.glb", b.glb());
  EXPECT_THROW(import_scene(path, ctx), Error);
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].find("points or lines"), std::string::npos);
}

TEST(ImportBroken, UnsupportedRequiredExtension) {
  const TempDir dir("broken_extension");
  GltfBuilder b = triangle_builder();
  b.doc["extensionsUsed"] = {"KHR_materials_pbrSpecularGlossiness"};
  b.doc["extensionsRequired"] = {"KHR_materials_pbrSpecularGlossiness"};
  expect_import_error(dir.write("spec_gloss.glb", b.glb()),
                      {"KHR_materials_pbrSpecularGlossiness", "does not support"});
}

TEST(ImportBroken, NotJsonNotGltf2) {
  const TempDir dir("broken_json");
  expect_import_error(dir.write("garbage.gltf", "{ this is not json"), {"invalid glTF JSON"});
  expect_import_error(dir.write("old.gltf", R"({"asset": {"version": "1.0"}})"),
                      {"not a glTF 2.0 file"});
  expect_import_error(dir.write("bad_magic.glb", std::string("GLTF") + std::string(40, '\0')),
                      {"not a binary glTF"});
}

TEST(ImportBroken, UnknownExtensionAndMissingFile) {
  const TempDir dir("broken_extension_name");
  expect_import_error(dir.write("scene.fbx", "Kaydara"), {"unknown scene file extension 'fbx'"});
  expect_import_error(dir.file("absent.glb"), {"cannot open"});
  expect_import_error(dir.file("absent.obj"), {"cannot open"});
}

TEST(ImportBroken, NodeCycle) {
  const TempDir dir("broken_cycle");
  GltfBuilder b = triangle_builder();
  b.doc["nodes"] = nlohmann::json::array({{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}});
  expect_import_error(dir.write("cycle.glb", b.glb()), {"node"});
}

}  // namespace
}  // namespace prt::bake
