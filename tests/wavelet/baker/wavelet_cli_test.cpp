// SPDX-License-Identifier: MIT
// `prt-bake bake --technique wavelet` end to end: the blob loads at full validation with the
// settings asked for, the JSON report carries what it promises, and bad or inapplicable options
// fail without writing a blob.
#include <gtest/gtest.h>

#include <prt/prt.hpp>
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>
#include <nlohmann/json.hpp>

#include "support/render_test_scenes.hpp"
#include "prt/baker/demo_scene.hpp"

namespace prt::bake {
namespace {

std::filesystem::path temp_dir() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("prt_wavelet_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

int run_bake(const std::string& arguments) {
  const std::string command = std::string("\"") + PRT_BAKE_EXE + "\" --quiet bake " + arguments;
  return std::system(command.c_str());
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
  ASSERT_EQ(run_bake(scene_file() + " --technique wavelet --cube 16 --keep 50 --quantizer vertex " +
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
  ASSERT_EQ(run_bake(scene_file() + " --technique wavelet --param dual-paraboloid --cube 32 " +
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

TEST(WaveletBakeCommand, BadAndInapplicableOptionsFail) {
  const std::filesystem::path blob = temp_dir() / "bad.prtk";
  const std::string out = " -o \"" + blob.string() + "\" 2>/dev/null";
  for (const std::string& bad :
       {std::string("--technique wavelet --cube 24"), std::string("--technique wavelet --cube 256"),
        std::string("--technique wavelet --cube 8"), std::string("--technique wavelet --order 3"),
        std::string("--technique wavelet --rays 64"), std::string("--technique wavelet --bits 8"),
        std::string("--technique sh --cube 32"), std::string("--technique sh --keep 10"),
        std::string("--technique sh --quantizer band"),
        std::string("--technique wavelet --keep 10 --keep-energy 0.5"),
        std::string("--technique wavelet --keep-energy 1.5"),
        std::string("--technique wavelet --samples 2"),
        std::string("--technique wavelet --bounces 9"),
        std::string("--technique wavelet --quantizer max"),
        std::string("--technique wavelet --param sphere"), std::string("--technique haar")}) {
    std::filesystem::remove(blob);
    EXPECT_NE(run_bake(scene_file() + " " + bad + out), 0) << bad;
    EXPECT_FALSE(std::filesystem::exists(blob)) << bad;
  }
}

}  // namespace
}  // namespace prt::bake
