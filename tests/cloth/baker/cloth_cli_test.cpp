// SPDX-License-Identifier: MIT
// `prt-bake bake cloth` end to end on the golden quad (formats/golden/scenes/quad_over_ground.obj,
// both quads facing +Y) with a small grid: the blob loads at full validation with the fabrics and
// grid asked for and the quad's frame (normal +Y, warp +X, the axis least aligned with it), the
// same bytes for 1 and 2 threads, the report carries every table's rank and the self-check, and
// an unknown fabric fails naming the presets, without a blob.
#include <gtest/gtest.h>

#include <prt/prt.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>
#include <nlohmann/json.hpp>

#include "support/command.hpp"

namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("prt_cloth_cli_test_" + std::to_string(::getpid()) + "_" + test->name());
  fs::create_directories(dir);
  return dir;
}

prt_test::CommandResult run_bake(const std::string& arguments) {
  return prt_test::run_command(PRT_BAKE_EXE, arguments, temp_dir() / "command.log");
}

std::string quad() {
  return prt_test::shell_quote(std::string(PRT_SOURCE_DIR) +
                               "/formats/golden/scenes/quad_over_ground.obj");
}

const char* kSmallGrid = " --xi-size 6 --levels 3 --view-theta 3 --view-phi 4";

std::vector<char> bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

prt_test::CommandResult bake(const fs::path& blob, const std::string& extra) {
  return run_bake("--quiet bake cloth " + quad() + kSmallGrid + extra + " -o " +
                  prt_test::shell_quote(blob.string()));
}

TEST(ClothBakeCommand, QuadBlobHoldsTheFabricsGridAndFrames) {
  const fs::path blob = temp_dir() / "quad.prtk", report = temp_dir() / "quad.json";
  const prt_test::CommandResult r =
      bake(blob, " --fabric linen_plain,velvet --bits 8 --threads 2 --report " +
                     prt_test::shell_quote(report.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  prt_context* raw = nullptr;
  ASSERT_EQ(prt_context_create(nullptr, &raw), PRT_OK);
  const prt::ContextPtr context(raw);
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_asset_load_file(raw, blob.string().c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK);
  const prt::AssetPtr owned(asset);
  prt_cloth_info info = prt::sized<prt_cloth_info>();
  ASSERT_EQ(prt_cloth_get_info(asset, &info), PRT_OK);
  EXPECT_EQ(info.fabric_count, 2u);
  EXPECT_EQ(info.xi_size, 6u);
  EXPECT_EQ(info.lambda_levels, 3u);
  EXPECT_EQ(info.view_theta, 3u);
  EXPECT_EQ(info.view_phi, 4u);
  EXPECT_EQ(info.bits, 8u);
  const char* name = nullptr;
  ASSERT_EQ(prt_cloth_get_fabric(asset, 1, &name, nullptr, nullptr, nullptr), PRT_OK);
  EXPECT_STREQ(name, "velvet");
  // Linen's two threads share one table. Velvet's threads have different multisets
  // ({-90, -50} and {-90, -55, 55, 90}): two tables for the first's two offsets, two for the
  // second, which is its own mirror image (-90 reads 90's table mirrored, -55 reads 55's).
  EXPECT_EQ(info.table_count, 5u);

  const nlohmann::json json = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(json.at("technique"), "cloth");
  EXPECT_TRUE(json.at("self_check").at("passed").get<bool>());
  EXPECT_EQ(json.at("tables").size(), 5u);
  for (const auto& t : json.at("tables")) {
    EXPECT_GE(t.at("rank").get<int>(), 1);
    EXPECT_LE(t.at("rank").get<int>(), 12);  // at most the 3 x 4 view columns
  }
  EXPECT_EQ(json.at("fabrics").at(0).at("tables"), nlohmann::json::array({0}));
  EXPECT_EQ(json.at("factor").at("bits"), 8);
}

TEST(ClothBakeCommand, SameBytesForOneAndTwoThreads) {
  const fs::path one = temp_dir() / "one.prtk", two = temp_dir() / "two.prtk";
  ASSERT_EQ(bake(one, " --fabric polyester_satin_charmeuse --threads 1").exit_code, 0);
  ASSERT_EQ(bake(two, " --fabric polyester_satin_charmeuse --threads 2").exit_code, 0);
  const std::vector<char> a = bytes_of(one), b = bytes_of(two);
  EXPECT_FALSE(a.empty());
  EXPECT_TRUE(a == b);
}

TEST(ClothBakeCommand, FixedRankIsEveryTablesRank) {
  const fs::path blob = temp_dir() / "rank.prtk", report = temp_dir() / "rank.json";
  ASSERT_EQ(
      bake(blob, " --fabric silk_shot --rank 2 --report " + prt_test::shell_quote(report.string()))
          .exit_code,
      0);
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(report));
  for (const auto& t : json.at("tables")) {
    EXPECT_EQ(t.at("rank"), 2);
    EXPECT_EQ(t.at("cone_rank"), 2);
  }
}

TEST(ClothBakeCommand, UnknownFabricFailsNamingThePresets) {
  const fs::path blob = temp_dir() / "none.prtk";
  const prt_test::CommandResult r = bake(blob, " --fabric denim");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("linen_plain"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(blob));
}

}  // namespace

// formats/golden/README.md's command for the cloth golden still makes its bytes: a baker change
// that moves them must re-freeze the golden (and restate its test) or say so in the README.
TEST(ClothBakeCommand, GoldenCommandMakesTheGoldenBytes) {
  // From the repository root, as the README says: the blob's info names the scene as given.
  const fs::path blob = temp_dir() / "cloth_quad.prtk";
  const prt_test::CommandResult r = prt_test::run_command(
      PRT_BAKE_EXE,
      "--quiet --threads 2 bake cloth formats/golden/scenes/quad_over_ground.obj"
      " --fabric linen_plain,velvet --xi-size 5 --levels 3 --view-theta 3 --view-phi 4 --bits 8"
      " --energy 1e-3 -o " +
          prt_test::shell_quote(blob.string()),
      temp_dir() / "command.log", "cd " + prt_test::shell_quote(PRT_SOURCE_DIR) + " &&");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<char> golden =
      bytes_of(fs::path(PRT_SOURCE_DIR) / "formats/golden/1.0/cloth_quad.prtk");
  ASSERT_FALSE(golden.empty());
  EXPECT_TRUE(bytes_of(blob) == golden);
}
