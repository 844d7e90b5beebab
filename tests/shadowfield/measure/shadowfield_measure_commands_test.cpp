// SPDX-License-Identifier: MIT
// prt-bake shadowfield-scene, shadowfield-reference and shadowfield-measure on the procedural
// preset with tiny bake settings: each writes what it says (a scene.json the reader accepts,
// blobs the runtime loads with their objects' vertex counts, an .npy of every instanced vertex,
// a table of one row per bounce count), and a bad input fails without a partial file.
#include <gtest/gtest.h>

#include <prt/prt_shadowfield.h>
#include <prt/prt.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "prt/baker/shadowfield/shadowfield_scenes.hpp"
#include "support/command.hpp"
#include "support/test_files.hpp"

namespace prt::bake {
namespace {

namespace fs = std::filesystem;
using prt_test::shell_quote;

prt_test::CommandResult run_in(const prt_test::TempDir& dir, const std::string& arguments,
                               const std::string& log) {
  return prt_test::run_command(PRT_BAKE_EXE, "--threads 2 " + arguments, dir.file(log));
}

// The procedural scene baked once for the tests that read it.
class ShadowfieldMeasureCommands : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new prt_test::TempDir("shadowfield_measure_commands");
    scene_dir_ = dir_->file("scene");
    bake_ = new prt_test::CommandResult(
        run("shadowfield-scene procedural -o " + shell_quote(scene_dir_) +
                " --bits 8 --order 3 --basis 4 --terms 2 --rays 64 --lights 16 --oof-shells 4 "
                "--oof-face 4 --srf-shells 2 --srf-face 2",
            "bake.log"));
  }
  static void TearDownTestSuite() {
    delete bake_;
    delete dir_;
  }
  static prt_test::CommandResult run(const std::string& arguments, const std::string& log) {
    return run_in(*dir_, arguments, log);
  }
  static std::string json() { return scene_dir_ + "/scene.json"; }

  static prt_test::TempDir* dir_;
  static std::string scene_dir_;
  static prt_test::CommandResult* bake_;
};

prt_test::TempDir* ShadowfieldMeasureCommands::dir_ = nullptr;
std::string ShadowfieldMeasureCommands::scene_dir_;
prt_test::CommandResult* ShadowfieldMeasureCommands::bake_ = nullptr;

bool has_partial_file(const std::string& dir) {
  for (const fs::directory_entry& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".partial") return true;
  return false;
}

TEST_F(ShadowfieldMeasureCommands, TheSceneCommandWritesBlobsAndItsJson) {
  ASSERT_EQ(bake_->exit_code, 0) << bake_->output;
  const ShadowfieldSceneDescription preset = make_shadowfield_scene("procedural", "");
  const ShadowfieldSceneFile file = read_shadowfield_scene_json(json());
  EXPECT_EQ(file.name, "procedural");
  ASSERT_EQ(file.objects.size(), preset.objects.size());
  EXPECT_EQ(file.instances.size(), preset.instances.size());
  EXPECT_FALSE(has_partial_file(scene_dir_));

  auto [context, made] = prt::create_context();
  ASSERT_EQ(made, PRT_OK);
  prt_shadowfield_scene* scene = nullptr;
  ASSERT_EQ(prt_shadowfield_scene_create(context.get(), 8, &scene), PRT_OK);
  std::vector<prt::AssetPtr> assets;
  for (std::size_t o = 0; o < file.objects.size(); ++o) {
    EXPECT_EQ(file.objects[o].name, preset.objects[o].name);
    prt_asset* asset = nullptr;
    const std::string blob = scene_dir_ + "/" + file.objects[o].blob;
    ASSERT_EQ(prt_asset_load_file(context.get(), blob.c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK)
        << blob;
    assets.emplace_back(asset);
    std::uint32_t object = 0, instance = 0;
    ASSERT_EQ(prt_shadowfield_scene_add_object(scene, asset, &object), PRT_OK);
    prt_shadowfield_transform identity{};
    identity.struct_size = sizeof identity;
    identity.rotation[0] = identity.rotation[4] = identity.rotation[8] = 1.0f;
    identity.scale = 1.0f;
    ASSERT_EQ(prt_shadowfield_scene_add_instance(scene, object, &identity, &instance), PRT_OK);
    EXPECT_EQ(prt_shadowfield_instance_vertex_count(scene, instance),
              preset.objects[o].mesh.vertex_count());
  }
  prt_shadowfield_scene_destroy(scene);
}

TEST_F(ShadowfieldMeasureCommands, TheReferenceCommandWritesEveryInstancedVertex) {
  ASSERT_EQ(bake_->exit_code, 0) << bake_->output;
  const std::string npy = dir_->file("reference.npy");
  const prt_test::CommandResult result =
      run("shadowfield-reference " + shell_quote(json()) +
              " --time 5 --env sky --bounces 1 --spp 4 --eye 0,2,4 -o " + shell_quote(npy),
          "reference.log");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const prt_test::NpyArray array = prt_test::read_npy_f32(npy);
  EXPECT_EQ(array.rows, make_shadowfield_scene("procedural", "").instanced_vertex_count());
  EXPECT_EQ(array.columns, 3u);
  double sum = 0.0;
  bool finite = true;
  for (const float value : array.values) {
    finite = finite && std::isfinite(value) && value >= 0.0f;
    sum += value;
  }
  EXPECT_TRUE(finite);
  EXPECT_GT(sum, 0.0);
  EXPECT_FALSE(has_partial_file(dir_->file("")));
}

TEST_F(ShadowfieldMeasureCommands, TheMeasureCommandWritesOneRowPerBounceCount) {
  ASSERT_EQ(bake_->exit_code, 0) << bake_->output;
  const std::string table = dir_->file("measure.md");
  const prt_test::CommandResult result =
      run("shadowfield-measure " + shell_quote(json()) + " --times 0 --bounces 0,2 --spp 4 -o " +
              shell_quote(table),
          "measure.log");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const std::string text = prt_test::read_text(table);
  EXPECT_NE(text.find("| 0 | 0 |"), std::string::npos) << text;
  EXPECT_NE(text.find("| 0 | 2 |"), std::string::npos) << text;
  EXPECT_NE(text.find("| floor NRMSE (bias) %"), std::string::npos) << text;
}

TEST(ShadowfieldMeasureCommandErrors, AMissingSceneFailsWithoutWriting) {
  const prt_test::TempDir dir("shadowfield_measure_missing");
  const std::string npy = dir.file("missing.npy");
  const prt_test::CommandResult result = run_in(
      dir,
      "shadowfield-reference " + shell_quote(dir.file("nothing.json")) + " -o " + shell_quote(npy),
      "missing.log");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_FALSE(fs::exists(npy));
  EXPECT_FALSE(fs::exists(npy + ".partial"));
}

TEST(ShadowfieldMeasureCommandErrors, AnUnknownPresetFails) {
  const prt_test::TempDir dir("shadowfield_measure_unknown");
  const prt_test::CommandResult result = run_in(
      dir, "shadowfield-scene nowhere -o " + shell_quote(dir.file("nowhere")), "unknown.log");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("nowhere"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace prt::bake
