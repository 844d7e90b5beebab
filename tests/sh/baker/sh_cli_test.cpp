// SPDX-License-Identifier: MIT
// `prt-bake bake sh` end to end: the blob loads at full validation with the settings asked for,
// the JSON report carries what it promises, bad or foreign options fail without writing a blob,
// --help lists sh's flags and no other technique's, and a mesh of degenerate triangles is named.
#include <gtest/gtest.h>

#include <prt/prt_sh_asset.h>
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

namespace prt::bake {
namespace {

using prt_test::CommandResult;

namespace fs = std::filesystem;

// One folder per test and process, so parallel runs (ctest -j, two build trees) never share files.
fs::path temp_dir() {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("prt_sh_cli_test_" + std::to_string(::getpid()) + "_" + test->name());
  fs::create_directories(dir);
  return dir;
}

// prt-bake with `arguments`, its output captured.
prt_test::CommandResult run_bake(const std::string& arguments) {
  return prt_test::run_command(PRT_BAKE_EXE, arguments, temp_dir() / "command.log");
}

std::string quoted(const fs::path& path) {
  return prt_test::shell_quote(path.string());
}

fs::path demo_scene_file() {
  const fs::path path = temp_dir() / "demo.glb";
  if (!fs::exists(path)) write_glb(make_demo_scene(), path.string());
  return path;
}

TEST(ShBakeCommand, DemoSceneBlobLoadsAndReportParses) {
  const fs::path blob = temp_dir() / "demo_sh.prtk", report = temp_dir() / "demo_sh.json";
  const CommandResult bake =
      run_bake("--quiet bake sh " + quoted(demo_scene_file()) + " --order 3 --rays 16 --bits 8 " +
               "--transfer interreflected --bounces 1 --seed 3 -o " + quoted(blob) + " --report " +
               quoted(report));
  ASSERT_EQ(bake.exit_code, 0) << bake.output;
  const prt::ContextPtr context = prt::create_context().handle;
  const auto [asset, loaded] =
      prt::load_asset_file(context.get(), blob.string().c_str(), PRT_VALIDATE_FULL);
  ASSERT_EQ(loaded, PRT_OK) << prt_context_last_message(context.get());
  prt_sh_info info = prt::sized<prt_sh_info>();
  ASSERT_EQ(prt_sh_get_info(asset.get(), &info), PRT_OK);
  EXPECT_EQ(info.order, 3u);
  EXPECT_EQ(info.bits, 8u);
  EXPECT_EQ(info.channels, 3u);
  EXPECT_EQ(info.kind, 2u);
  EXPECT_EQ(info.bounces, 1u);

  std::ifstream file(report);
  const nlohmann::json json = nlohmann::json::parse(file);
  EXPECT_EQ(json.at("technique"), "sh");
  EXPECT_EQ(json.at("settings").at("order"), 3);
  EXPECT_EQ(json.at("settings").at("transfer"), "interreflected");
  EXPECT_EQ(json.at("settings").at("rays"), 16);
  EXPECT_EQ(json.at("scene").at("vertices"), info.vertex_count);
  EXPECT_EQ(json.at("blob").at("bytes"), fs::file_size(blob));
  // At least one shadow ray per direction per vertex; a bounce pass adds closest-hit rays.
  EXPECT_GE(json.at("bake").at("rays").get<double>(), 16.0 * info.vertex_count);
  EXPECT_GT(json.at("bake").at("seconds").get<double>(), 0.0);
  EXPECT_GT(json.at("bake").at("rays_per_second").get<double>(), 0.0);
  EXPECT_EQ(json.at("quantization").at("bits"), 8);
  EXPECT_GE(json.at("quantization").at("max_abs_error").get<double>(),
            json.at("quantization").at("rms_abs_error").get<double>());
  EXPECT_TRUE(json.at("self_check").at("passed").get<bool>());
  fs::remove_all(temp_dir());
}

TEST(ShBakeCommand, BadAndForeignOptionsFail) {
  const std::string scene = quoted(demo_scene_file());
  const fs::path blob = temp_dir() / "bad.prtk";
  for (const std::string& bad :
       {std::string("--order 0"), std::string("--order 17"), std::string("--bits 12"),
        std::string("--transfer glossy"), std::string("--rays 0"), std::string("--bounces 65"),
        std::string("--albedo 0.5,0.5"), std::string("--technique sh"), std::string("--cube 16"),
        std::string("--keep 10"), std::string("--quantizer band")}) {
    fs::remove(blob);
    const CommandResult r =
        run_bake("--quiet bake sh " + scene + " --rays 4 " + bad + " -o " + quoted(blob));
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_FALSE(fs::exists(blob)) << bad;
  }
  const CommandResult missing =
      run_bake("--quiet bake sh " + quoted(temp_dir() / "missing.glb") + " -o " + quoted(blob));
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("missing.glb"), std::string::npos) << missing.output;
  EXPECT_NE(run_bake("--quiet bake sh " + scene).exit_code, 0);  // no -o
  fs::remove_all(temp_dir());
}

TEST(ShBakeCommand, HelpListsShFlagsOnly) {
  const CommandResult help = run_bake("bake sh --help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  const std::set<std::string> own = prt_test::expect_help_lists_own_flags_only(help.output, "sh");
  EXPECT_TRUE(own.count("--order") && own.count("--transfer") && own.count("--bits"));
}

// Four vertices on a line with normals: both triangles have zero area. Unshadowed sh builds no
// ray-tracing scene, so only the bake's own check can say so.
TEST(ShBakeCommand, AllDegenerateMeshIsNamed) {
  const fs::path obj = temp_dir() / "flat.obj", blob = temp_dir() / "flat.prtk";
  std::ofstream(obj) << "o flat\nv 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nvn 0 1 0\n"
                        "f 1//1 2//1 3//1\nf 2//1 3//1 4//1\n";
  for (const char* transfer : {"unshadowed", "shadowed"}) {
    const CommandResult r = run_bake("bake sh " + quoted(obj) + " --transfer " + transfer +
                                     " --rays 16 -o " + quoted(blob));
    EXPECT_EQ(r.exit_code, 0) << r.output;  // a warning, not an error: the blob is valid
    EXPECT_NE(r.output.find("warning: " + obj.string() +
                            ": every triangle is degenerate (a repeated or out-of-range index, "
                            "a non-finite position or zero area): nothing casts shadows"),
              std::string::npos)
        << transfer << "\n"
        << r.output;
    EXPECT_TRUE(fs::exists(blob));
  }
  // One good mesh beside the flat one: the flat one is named, the scene is not.
  std::ofstream(obj, std::ios::app) << "o good\nv 0 0 1\nv 1 0 1\nv 0 1 1\nvn 0 0 1\n"
                                       "f 5//2 6//2 7//2\n";
  const CommandResult mixed = run_bake("bake sh " + quoted(obj) + " --rays 16 -o " + quoted(blob));
  EXPECT_EQ(mixed.exit_code, 0) << mixed.output;
  EXPECT_NE(mixed.output.find("every triangle of mesh 0 ('flat') is degenerate"), std::string::npos)
      << mixed.output;
  EXPECT_EQ(mixed.output.find("every triangle is degenerate"), std::string::npos) << mixed.output;
  fs::remove_all(temp_dir());
}

}  // namespace
}  // namespace prt::bake
