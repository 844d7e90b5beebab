// SPDX-License-Identifier: MIT
// `prt-bake bake shadowfield` end to end on the golden quad scene with tiny settings: the same
// bytes on one and two threads, a report that states what it promises and a passed self-check,
// bad options refused with a message naming the flag and no blob written, and --help listing
// the technique's flags and no other technique's.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/bake_help.hpp"
#include "support/command.hpp"

namespace {

namespace fs = std::filesystem;
using prt_test::CommandResult;

// One folder per test and process, so parallel runs never share files.
fs::path temp_dir() {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("prt_sf_bake_cli_" + std::to_string(::getpid()) + "_" + test->name());
  fs::create_directories(dir);
  return dir;
}

CommandResult run_bake(const std::string& arguments) {
  return prt_test::run_command(PRT_BAKE_EXE, arguments, temp_dir() / "command.log");
}

std::string quoted(const fs::path& path) {
  return prt_test::shell_quote(path.string());
}

// Every stage, glossy, on grids small enough for a fraction of a second.
const std::string kTinyBake =
    " --brdf phong:10,0.6,0.3 --terms 2 --brdf-grid 8 --order 3 --shells 2 --face-size 2"
    " --srf-shells 2 --srf-face-size 2 --basis 2 --lights 8 --field-rays 64 --transfer-rays 64"
    " --srf-rays 64";

CommandResult bake_quad(int threads, const fs::path& blob, const std::string& extra) {
  return run_bake("--threads " + std::to_string(threads) + " bake shadowfield " +
                  quoted(PRT_QUAD_SCENE) + kTinyBake + extra + " -o " + quoted(blob));
}

std::vector<char> bytes_of(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(file), {});
}

TEST(ShadowfieldBakeCommand, SameBytesOnOneAndTwoThreadsAndAReport) {
  const fs::path one = temp_dir() / "one.prtk", two = temp_dir() / "two.prtk";
  const fs::path report = temp_dir() / "two.json";
  const CommandResult a = bake_quad(1, one, " --bits 8");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const CommandResult b = bake_quad(2, two, " --bits 8 --report " + quoted(report));
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_NE(b.output.find("self-check passed"), std::string::npos) << b.output;
  const std::vector<char> bytes = bytes_of(one);
  EXPECT_FALSE(bytes.empty());
  EXPECT_EQ(bytes, bytes_of(two));

  const nlohmann::json json = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(json["technique"], "shadowfield");
  EXPECT_EQ(json["settings"]["order"], 3);
  // K = 2 would cut Phong's pair of order-1 terms: the pair is completed.
  EXPECT_EQ(json["settings"]["terms"], 3);
  EXPECT_EQ(json["settings"]["terms_requested"], 2);
  EXPECT_EQ(json["settings"]["bits"], 8);
  EXPECT_EQ(json["settings"]["oof"]["shells"], 2);
  EXPECT_EQ(json["blob"]["bytes"], bytes.size());
  EXPECT_TRUE(json["self_check"]["passed"].get<bool>());
  EXPECT_LE(json["self_check"]["max_budget_ratio"].get<double>(), 1.0);
  for (const char* block : {"transfer", "oof", "basis", "srf"}) {
    const nlohmann::json& q = json["quantization"][block];
    // Half an 8-bit step of the block's range at most (a row's range is within twice max |t|).
    EXPECT_LE(q["max_abs_error"].get<double>(), q["max_abs_value"].get<double>() / 255.0 * 1.0001)
        << block;
  }
  for (const char* stage : {"seconds_fields", "seconds_transfer", "seconds_basis", "seconds_srf"})
    EXPECT_GE(json["bake"][stage].get<double>(), 0.0) << stage;
  const double energy = json["bake"]["basis_energy_kept"].get<double>();
  EXPECT_TRUE(energy > 0.0 && energy <= 1.0) << energy;
}

TEST(ShadowfieldBakeCommand, BadOptionsAreRefusedByName) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" --bits 12", "--bits"},
      {" --order 7", "--order"},
      {" --brdf wood", "--brdf"},
      {" --brdf phong:-1", "--brdf"},
      {" --inner 0", "--inner"},
      {" --inner nan", "--inner"},
      {" --outer 0.1", "--outer"},
      {" --terms 0", "--terms"},
      {" --srf-shells 200", "--srf-shells"}};
  for (const auto& [option, flag] : cases) {
    const fs::path blob = temp_dir() / "bad.prtk";
    // kTinyBake sets --order and --brdf; CLI11 takes the last value given.
    const CommandResult r = run_bake("bake shadowfield " + quoted(PRT_QUAD_SCENE) +
                                     " --field-rays 16 --transfer-rays 16 --srf-rays 16" + option +
                                     " -o " + quoted(blob));
    EXPECT_NE(r.exit_code, 0) << option;
    EXPECT_NE(r.output.find(flag), std::string::npos) << option << "\n" << r.output;
    EXPECT_FALSE(fs::exists(blob)) << option;
  }
}

// A mesh without faces, one of zero area and a NaN albedo: refused by name, no blob.
TEST(ShadowfieldBakeCommand, DegenerateInputIsRefused) {
  const fs::path empty = temp_dir() / "empty.obj", flat = temp_dir() / "flat.obj";
  std::ofstream(empty) << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  std::ofstream(flat) << "v 0 0 0\nv 1 0 0\nv 2 0 0\nvn 0 1 0\nf 1//1 2//1 3//1\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {quoted(empty), "no faces"},
      {quoted(flat) + " --basis 1", "no surface area"},
      {quoted(PRT_QUAD_SCENE) + " --albedo nan,0,0", "--albedo"}};
  for (const auto& [arguments, message] : cases) {
    const fs::path blob = temp_dir() / "bad.prtk";
    const CommandResult r =
        run_bake("bake shadowfield " + arguments +
                 " --field-rays 16 --transfer-rays 16 --srf-rays 16 -o " + quoted(blob));
    EXPECT_NE(r.exit_code, 0) << arguments;
    EXPECT_NE(r.output.find(message), std::string::npos) << arguments << "\n" << r.output;
    EXPECT_FALSE(fs::exists(blob)) << arguments;
  }
}

TEST(ShadowfieldBakeCommand, HelpListsShadowfieldFlagsOnly) {
  const CommandResult help = run_bake("bake shadowfield --help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  const std::set<std::string> own =
      prt_test::expect_help_lists_own_flags_only(help.output, "shadowfield");
  for (const char* flag : {"--brdf", "--order", "--terms", "--brdf-grid", "--shells", "--face-size",
                           "--srf-shells", "--srf-face-size", "--inner", "--outer", "--basis",
                           "--lights", "--field-rays", "--transfer-rays", "--srf-rays", "--bits"})
    EXPECT_TRUE(own.count(flag)) << flag;
}

}  // namespace
