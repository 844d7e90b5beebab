// SPDX-License-Identifier: MIT
// prt-bake scene as a pipeline runs it: the summary line, and the exit code --strict gives a run
// with a broken object.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/mesh_generators.hpp"
#include "support/command.hpp"
#include "support/test_files.hpp"

namespace {

namespace fs = std::filesystem;
using prt_test::shell_quote;

std::string write_scene(const prt_test::TempDir& dir) {
  prt::bake::Scene scene;
  prt::bake::Material grey;
  grey.name = "grey";
  scene.materials = {grey};
  scene.meshes.push_back(prt::bake::make_plane_mesh("ground", 0, 1.0f, 1.0f, 6, 6));
  scene.meshes.push_back(prt::bake::make_box_mesh(0, {0.0f, 0.2f, 0.0f}, 0.2f, 0.3f, 2));
  const std::string path = dir.file("two.glb");
  prt::bake::write_glb(scene, path);
  return path;
}

std::string scene_args(const std::string& scene, const std::string& out) {
  return "--threads 2 scene " + shell_quote(scene) + " -o " + shell_quote(out) +
         " --error-budget 10 --bounces 0 --ref-spp 128 --probe-vertices 32";
}

TEST(PrtBakeScene, PrintsWhatItDidAndExitsZero) {
  prt_test::TempDir dir("scene_cli_ok");
  const auto r = prt_test::run_command(
      PRT_BAKE_EXE, scene_args(write_scene(dir), dir.file("out")) + " --strict", dir.file("log"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir.file("out/ground.prtk")));
  EXPECT_TRUE(fs::exists(dir.file("out/box.prtk")));
  EXPECT_TRUE(fs::exists(dir.file("out/scene.json")));
  EXPECT_TRUE(fs::exists(dir.file("out/report.json")));
}

TEST(PrtBakeScene, ABrokenObjectFailsTheRunOnlyWhenStrict) {
  prt_test::TempDir dir("scene_cli_broken");
  const std::string args =
      scene_args(write_scene(dir), dir.file("out")) + " --object box=no-such-technique";
  const auto lenient = prt_test::run_command(PRT_BAKE_EXE, args, dir.file("lenient.log"));
  EXPECT_EQ(lenient.exit_code, 0) << lenient.output;
  EXPECT_NE(lenient.output.find("box: no technique is named 'no-such-technique'"),
            std::string::npos)
      << lenient.output;
  EXPECT_NE(lenient.output.find("1 broken"), std::string::npos) << lenient.output;
  EXPECT_TRUE(fs::exists(dir.file("out/ground.prtk")));
  EXPECT_FALSE(fs::exists(dir.file("out/box.prtk")));

  const auto strict =
      prt_test::run_command(PRT_BAKE_EXE, args + " --strict", dir.file("strict.log"));
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
}

TEST(PrtBakeScene, ABadBudgetIsRefusedByName) {
  prt_test::TempDir dir("scene_cli_budget");
  const auto r = prt_test::run_command(
      PRT_BAKE_EXE, "scene " + shell_quote(write_scene(dir)) + " -o out --error-budget 0",
      dir.file("log"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--error-budget"), std::string::npos) << r.output;
}

}  // namespace
