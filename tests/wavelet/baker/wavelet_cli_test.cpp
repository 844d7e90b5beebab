// SPDX-License-Identifier: MIT
// `prt-bake bake wavelet` end to end: the blob loads at full validation with the settings asked
// for, the JSON report carries what it promises, bad or foreign options fail without writing a
// blob, --help lists wavelet's flags and no other technique's, the self-check decodes each row
// of a small mesh once, and a mesh of degenerate triangles is named.
#include <gtest/gtest.h>

#include <prt/prt.hpp>
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include <unistd.h>
#include <nlohmann/json.hpp>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/technique.hpp"
#include "support/render_test_scenes.hpp"

namespace prt::bake {
namespace {

std::filesystem::path temp_dir() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("prt_wavelet_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

int run_bake(const std::string& arguments) {
  const std::string command =
      std::string("\"") + PRT_BAKE_EXE + "\" --quiet bake wavelet " + arguments;
  return std::system(command.c_str());
}

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr
};

// prt-bake with `arguments`, its output captured.
CommandResult run_command(const std::string& arguments) {
  const std::filesystem::path log = temp_dir() / "command.log";
  const std::string command =
      std::string("\"") + PRT_BAKE_EXE + "\" " + arguments + " > \"" + log.string() + "\" 2>&1";
  CommandResult r;
  r.status = std::system(command.c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  r.output = text.str();
  return r;
}

std::string quoted(const std::filesystem::path& path) {
  return "\"" + path.string() + "\"";
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
  return "\"" + path.string() + "\"";
}

TEST(WaveletBakeCommand, BlobLoadsAndReportParses) {
  const std::filesystem::path blob = temp_dir() / "w.prtk", report = temp_dir() / "w.json";
  ASSERT_EQ(run_bake(scene_file() + " --cube 16 --keep 50 --quantizer vertex " +
                     "--samples 4 --seed 2 --bounces 1 --albedo 0.5,0.6,0.7 -o \"" + blob.string() +
                     "\" --report \"" + report.string() + "\""),
            0);
  prt_context* context = nullptr;
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_context_create(nullptr, &context), PRT_OK);
  ASSERT_EQ(prt_asset_load_file(context, blob.string().c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK)
      << prt_context_last_message(context);
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  ASSERT_EQ(prt_wavelet_get_info(asset, &info), PRT_OK);
  EXPECT_EQ(info.param, PRT_WAVELET_PARAM_CUBE);
  EXPECT_EQ(info.size, 16u);
  EXPECT_EQ(info.quantizer, 0u);
  EXPECT_EQ(info.keep, 50u);
  EXPECT_EQ(info.bounces, 1u);
  EXPECT_LE(info.pair_count, 50u * info.vertex_count);
  prt_asset_destroy(asset);
  prt_context_destroy(context);

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
  ASSERT_EQ(run_bake(scene_file() + " --param dual-paraboloid --cube 32 " +
                     "--keep-energy 0.9 -o \"" + blob.string() + "\""),
            0);
  prt_context* context = nullptr;
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_context_create(nullptr, &context), PRT_OK);
  ASSERT_EQ(prt_asset_load_file(context, blob.string().c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK);
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  ASSERT_EQ(prt_wavelet_get_info(asset, &info), PRT_OK);
  EXPECT_EQ(info.param, PRT_WAVELET_PARAM_DUAL_PARABOLOID);
  EXPECT_EQ(info.faces, 2u);
  EXPECT_EQ(info.quantizer, 1u);  // band, the default
  prt_asset_destroy(asset);
  prt_context_destroy(context);
}

TEST(WaveletBakeCommand, BadAndForeignOptionsFail) {
  const std::filesystem::path blob = temp_dir() / "bad.prtk";
  const std::string out = " -o \"" + blob.string() + "\" 2>/dev/null";
  for (const std::string& bad :
       {std::string("--cube 24"), std::string("--cube 256"), std::string("--cube 8"),
        std::string("--order 3"), std::string("--rays 64"), std::string("--bits 8"),
        std::string("--transfer shadowed"), std::string("--technique wavelet"),
        std::string("--keep 10 --keep-energy 0.5"), std::string("--keep-energy 1.5"),
        std::string("--samples 2"), std::string("--bounces 9"), std::string("--quantizer max"),
        std::string("--param sphere"), std::string("--albedo red")}) {
    std::filesystem::remove(blob);
    EXPECT_NE(run_bake(scene_file() + " " + bad + out), 0) << bad;
    EXPECT_FALSE(std::filesystem::exists(blob)) << bad;
  }
  // A technique the table does not have.
  std::filesystem::remove(blob);
  EXPECT_NE(run_command("--quiet bake haar " + scene_file() + out).status, 0);
  EXPECT_FALSE(std::filesystem::exists(blob));
}

// Each flag's name as --help prints it: the long name, followed by a space, '=' or a newline.
bool lists_flag(const std::string& help, const std::string& name) {
  const std::string flag = name.substr(name.rfind(',') + 1);
  for (std::size_t at = help.find(flag); at != std::string::npos; at = help.find(flag, at + 1)) {
    const char next = at + flag.size() < help.size() ? help[at + flag.size()] : ' ';
    if (next == ' ' || next == '=' || next == '\n') return true;
  }
  return false;
}

TEST(WaveletBakeCommand, HelpListsWaveletFlagsOnly) {
  const CommandResult help = run_command("bake wavelet --help");
  ASSERT_EQ(help.status, 0) << help.output;
  std::set<std::string> own;
  const std::unique_ptr<TechniqueBake> bake = find_technique("wavelet")->make_bake();
  const OptionList options = bake->options();  // holds pointers into `bake`
  for (const OptionSpec& spec : options.specs()) {
    own.insert(spec.name);
    EXPECT_TRUE(lists_flag(help.output, spec.name)) << spec.name << "\n" << help.output;
  }
  EXPECT_TRUE(own.count("--cube") && own.count("--keep") && own.count("--quantizer"));
  for (const char* shared : {"--albedo", "--seed", "--output", "--report", "SCENE"})
    EXPECT_NE(help.output.find(shared), std::string::npos) << shared;
  std::size_t foreign = 0;
  for (const Technique* other : techniques()) {
    if (std::string(other->name()) == "wavelet") continue;
    const std::unique_ptr<TechniqueBake> other_bake = other->make_bake();
    const OptionList other_options = other_bake->options();
    for (const OptionSpec& spec : other_options.specs()) {
      if (own.count(spec.name)) continue;
      ++foreign;
      EXPECT_FALSE(lists_flag(help.output, spec.name)) << spec.name << "\n" << help.output;
    }
  }
  EXPECT_GT(foreign, 0u);  // sh's --order, --transfer, ...
  EXPECT_FALSE(lists_flag(help.output, "--technique"));
}

// A quad of two triangles has four vertices: the self-check decodes each row once.
TEST(WaveletBakeCommand, SelfCheckOfAFourVertexMeshDecodesFourRows) {
  const std::filesystem::path obj = temp_dir() / "quad.obj", blob = temp_dir() / "quad.prtk";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 0 1\nv 1 0 1\nvn 0 1 0\n"
                        "f 1//1 3//1 2//1\nf 2//1 3//1 4//1\n";
  const CommandResult r =
      run_command("bake wavelet " + quoted(obj) + " --cube 16 -o " + quoted(blob));
  ASSERT_EQ(r.status, 0) << r.output;
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
  EXPECT_EQ(r.status, 0) << r.output;  // a warning, not an error: the blob is valid
  EXPECT_NE(r.output.find("warning: " + obj.string() +
                          ": every triangle is degenerate (a repeated or out-of-range index, a "
                          "non-finite position or zero area): nothing casts shadows"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(std::filesystem::exists(blob));
}

}  // namespace
}  // namespace prt::bake
