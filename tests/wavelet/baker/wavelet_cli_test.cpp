// SPDX-License-Identifier: MIT
// `prt-bake bake wavelet` end to end: the blob loads at full validation with the settings asked
// for, the JSON report carries what it promises, bad or foreign options fail without writing a
// blob, --help lists wavelet's flags and no other technique's, the self-check decodes each row
// of a small mesh once, and a mesh of degenerate triangles is named.
#include <gtest/gtest.h>

#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>
#include <prt/prt.hpp>

#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>

#include <unistd.h>
#include <nlohmann/json.hpp>

#include "prt/baker/demo_scene.hpp"
#include "support/bake_help.hpp"
#include "support/command.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

using prt_test::CommandResult;

std::filesystem::path temp_dir() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("prt_wavelet_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

// prt-bake with `arguments`, its output captured.
prt_test::CommandResult run_command(const std::string& arguments) {
  return prt_test::run_command(PRT_BAKE_EXE, arguments, temp_dir() / "command.log");
}

// prt-bake --quiet bake wavelet with `arguments`.
prt_test::CommandResult run_bake(const std::string& arguments) {
  return run_command("--quiet bake wavelet " + arguments);
}

std::string quoted(const std::filesystem::path& path) {
  return prt_test::shell_quote(path.string());
}

// A small scene: a plane and a sphere on it (a few hundred vertices).
std::string scene_file() {
  const std::filesystem::path path = temp_dir() / "scene.glb";
  if (!std::filesystem::exists(path)) {
    Scene scene;
    scene.meshes.push_back(test::make_plane(1.0f, 6));
    scene.meshes.push_back(test::make_icosphere(1, 0.4f, {0.0f, 0.45f, 0.0f}));
    write_glb(scene, path.string());
  }
  return quoted(path);
}

TEST(WaveletBakeCommand, BlobLoadsAndReportParses) {
  const std::filesystem::path blob = temp_dir() / "w.prtk", report = temp_dir() / "w.json";
  const prt_test::CommandResult bake = run_bake(
      scene_file() + " --cube 16 --keep 50 --quantizer vertex --samples 4 --seed 2" +
      " --bounces 1 --albedo 0.5,0.6,0.7 -o " + quoted(blob) + " --report " + quoted(report));
  ASSERT_EQ(bake.exit_code, 0) << bake.output;
  const prt::ContextPtr context = prt::create_context().handle;
  const auto [asset, loaded] =
      prt::load_asset_file(context.get(), blob.string().c_str(), PRT_VALIDATE_FULL);
  ASSERT_EQ(loaded, PRT_OK) << prt_context_last_message(context.get());
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  ASSERT_EQ(prt_wavelet_get_info(asset.get(), &info), PRT_OK);
  EXPECT_EQ(info.param, PRT_WAVELET_PARAM_CUBE);
  EXPECT_EQ(info.size, 16u);
  EXPECT_EQ(info.quantizer, 0u);
  EXPECT_EQ(info.keep, 50u);
  EXPECT_EQ(info.bounces, 1u);
  EXPECT_LE(info.pair_count, 50u * info.vertex_count);

  std::ifstream file(report);
  const nlohmann::json json = nlohmann::json::parse(file);
  EXPECT_EQ(json.at("technique"), "wavelet");
  EXPECT_EQ(json.at("settings").at("size"), 16);
  EXPECT_EQ(json.at("settings").at("param"), "cube");
  EXPECT_EQ(json.at("settings").at("samples_per_texel"), 4);
  EXPECT_EQ(json.at("settings").at("quantizer"), "vertex");
  EXPECT_EQ(json.at("settings").at("bounces"), 1);
  EXPECT_EQ(json.at("scene").at("vertices"), info.vertex_count);
  EXPECT_EQ(json.at("blob").at("bytes"), std::filesystem::file_size(blob));
  EXPECT_EQ(json.at("blob").at("pairs"), info.pair_count);
  EXPECT_LE(json.at("blob").at("nonzeros_per_vertex").get<double>(), 50.0 + 1e-9);
  EXPECT_GT(json.at("bake").at("rays").get<double>(), 0.0);
  EXPECT_GT(json.at("bake").at("rays_per_second").get<double>(), 0.0);
  EXPECT_GE(json.at("quantization").at("max_abs_error").get<double>(),
            json.at("quantization").at("rms_abs_error").get<double>());
  EXPECT_TRUE(json.at("self_check").at("passed").get<bool>());
}

TEST(WaveletBakeCommand, DualParaboloidAndKeepEnergy) {
  const std::filesystem::path blob = temp_dir() / "p.prtk";
  const prt_test::CommandResult bake = run_bake(
      scene_file() + " --param dual-paraboloid --cube 32 --keep-energy 0.9 -o " + quoted(blob));
  ASSERT_EQ(bake.exit_code, 0) << bake.output;
  const prt::ContextPtr context = prt::create_context().handle;
  const auto [asset, loaded] =
      prt::load_asset_file(context.get(), blob.string().c_str(), PRT_VALIDATE_FULL);
  ASSERT_EQ(loaded, PRT_OK) << prt_context_last_message(context.get());
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  ASSERT_EQ(prt_wavelet_get_info(asset.get(), &info), PRT_OK);
  EXPECT_EQ(info.param, PRT_WAVELET_PARAM_DUAL_PARABOLOID);
  EXPECT_EQ(info.faces, 2u);
  EXPECT_EQ(info.quantizer, 1u);  // band, the default
}

TEST(WaveletBakeCommand, BadAndForeignOptionsFail) {
  const std::filesystem::path blob = temp_dir() / "bad.prtk";
  const std::string out = " -o " + quoted(blob);
  for (const std::string& bad :
       {std::string("--cube 24"), std::string("--cube 256"), std::string("--cube 8"),
        std::string("--order 3"), std::string("--rays 64"), std::string("--bits 8"),
        std::string("--transfer shadowed"), std::string("--technique wavelet"),
        std::string("--keep 10 --keep-energy 0.5"), std::string("--keep-energy 1.5"),
        std::string("--samples 2"), std::string("--bounces 9"), std::string("--quantizer max"),
        std::string("--param sphere"), std::string("--albedo red")}) {
    std::filesystem::remove(blob);
    EXPECT_NE(run_bake(scene_file() + " " + bad + out).exit_code, 0) << bad;
    EXPECT_FALSE(std::filesystem::exists(blob)) << bad;
  }
  // A technique the table does not have.
  std::filesystem::remove(blob);
  EXPECT_NE(run_command("--quiet bake haar " + scene_file() + out).exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(blob));
}

TEST(WaveletBakeCommand, HelpListsWaveletFlagsOnly) {
  const CommandResult help = run_command("bake wavelet --help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  const std::set<std::string> own =
      prt_test::expect_help_lists_own_flags_only(help.output, "wavelet");
  EXPECT_TRUE(own.count("--cube") && own.count("--keep") && own.count("--quantizer"));
}

// A quad of two triangles has four vertices: the self-check decodes each row once.
TEST(WaveletBakeCommand, SelfCheckOfAFourVertexMeshDecodesFourRows) {
  const std::filesystem::path obj = temp_dir() / "quad.obj", blob = temp_dir() / "quad.prtk";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 0 1\nv 1 0 1\nvn 0 1 0\n"
                        "f 1//1 3//1 2//1\nf 2//1 3//1 4//1\n";
  const CommandResult r =
      run_command("bake wavelet " + quoted(obj) + " --cube 16 -o " + quoted(blob));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("self-check passed: 4 decoded rows match"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("degenerate"), std::string::npos) << r.output;
}

// Four vertices on a line: both triangles have zero area.
TEST(WaveletBakeCommand, AllDegenerateMeshIsNamed) {
  const std::filesystem::path obj = temp_dir() / "flat.obj", blob = temp_dir() / "flat.prtk";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nvn 0 1 0\n"
                        "f 1//1 2//1 3//1\nf 2//1 3//1 4//1\n";
  const CommandResult r =
      run_command("bake wavelet " + quoted(obj) + " --cube 16 -o " + quoted(blob));
  EXPECT_EQ(r.exit_code, 0) << r.output;  // a warning, not an error: the blob is valid
  EXPECT_NE(r.output.find("warning: " + obj.string() +
                          ": every triangle is degenerate (a repeated or out-of-range index, a "
                          "non-finite position or zero area): nothing casts shadows"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(std::filesystem::exists(blob));
}

}  // namespace
}  // namespace prt::bake
