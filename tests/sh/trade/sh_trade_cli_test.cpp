// SPDX-License-Identifier: MIT
// prt-bake trade sh end to end on the generated demo scene with tiny settings: the rows the sweep
// design calls for, the reference cache, determinism of everything but the timings, and clear
// errors for bad input.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr
};

CommandResult run_bake(const std::string& arguments, const fs::path& log) {
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

using Table = std::vector<std::map<std::string, std::string>>;

Table read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> header;
  Table rows;
  auto split = [](const std::string& text) {
    std::vector<std::string> fields;
    std::stringstream s(text);
    std::string field;
    while (std::getline(s, field, ',')) fields.push_back(field);
    return fields;
  };
  if (std::getline(in, line)) header = split(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> fields = split(line);
    EXPECT_EQ(fields.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < fields.size() && i < header.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

class ShTradeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: ctest may run the tests of this fixture at the same time.
    dir_ = fs::path(::testing::TempDir()) /
           (std::string("prt_sh_trade_cli_") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const CommandResult demo = run_bake("demo-scene \"" + dir_.string() + "\"", dir_ / "demo.log");
    ASSERT_EQ(demo.status, 0) << demo.output;
    scene_ = (dir_ / "demo_scene.glb").string();
    sky_ = (dir_ / "demo_sky.hdr").string();
  }
  std::string trade_arguments(const std::string& out, int threads) const {
    return "--threads " + std::to_string(threads) + " trade sh \"" + scene_ + "\" --env \"" + sky_ +
           "\" --out-dir \"" + out + "\" --cache-dir \"" + (dir_ / "cache").string() +
           "\" --orders 1,3 --rays 16,32 --bounces 0,1 --base-rays 16 --base-order 3"
           " --ref-spp 16 --frames 2 --albedo 0.8,0.8,0.8";
  }
  fs::path dir_;
  std::string scene_, sky_;
};

TEST_F(ShTradeCli, SweepsCachesAndRepeatsItself) {
  const CommandResult first = run_bake(trade_arguments((dir_ / "a").string(), 2), dir_ / "a.log");
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_NE(first.output.find("rendering"), std::string::npos) << first.output;
  const Table a = read_csv(dir_ / "a" / "trade.csv");
  EXPECT_TRUE(fs::exists(dir_ / "a" / "trade.md"));

  // Orders {1,3} at 16 rays; rays {16,32} at order 3; bounces {0,1} at order 3, 16 rays: the
  // base setting (3, 16, 0) is in all three sweeps and baked once.
  // Every setting shades better than black (relative RMSE 1), and order 3 is closer to the
  // reference than order 1 by far more than its noise.
  std::map<std::string, std::string> sweeps;
  std::map<std::string, double> error;
  for (const auto& row : a) {
    const std::string setting = row.at("order") + "/" + row.at("rays") + "/" + row.at("bounces");
    sweeps[setting] = row.at("sweeps");
    error[setting] = std::stod(row.at("rel_rmse"));
    EXPECT_TRUE(error[setting] > 0.0 && error[setting] < 1.0) << setting << ": " << error[setting];
    EXPECT_EQ(row.at("transfer"), row.at("bounces") == "0" ? "shadowed" : "interreflected");
  }
  EXPECT_LT(error["3/16/0"], error["1/16/0"]);
  const std::map<std::string, std::string> expected = {{"1/16/0", "order"},
                                                       {"3/16/0", "order+rays+bounces"},
                                                       {"3/32/0", "rays"},
                                                       {"3/16/1", "bounces"}};
  EXPECT_EQ(sweeps, expected);

  // Second run, on one thread: references from the cache, the same numbers but for the timings.
  const CommandResult second = run_bake(trade_arguments((dir_ / "b").string(), 1), dir_ / "b.log");
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(second.output.find("rendering"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("from the cache"), std::string::npos) << second.output;
  const Table b = read_csv(dir_ / "b" / "trade.csv");
  ASSERT_EQ(a.size(), b.size());
  const std::set<std::string> timings = {"shade_cpu_ms", "shade_simd_ms", "bake_seconds",
                                         "rays_per_second"};
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (const auto& [column, value] : a[i]) {
      if (!timings.count(column)) {
        EXPECT_EQ(value, b[i].at(column)) << column;
      }
    }
  }
}

TEST_F(ShTradeCli, BadInputGivesAClearError) {
  const CommandResult missing_map = run_bake(
      "trade sh \"" + scene_ + "\" --env nothere.hdr --out-dir \"" + (dir_ / "x").string() + "\"",
      dir_ / "x.log");
  EXPECT_NE(missing_map.status, 0);
  EXPECT_NE(missing_map.output.find("nothere.hdr"), std::string::npos) << missing_map.output;
  const CommandResult bad_order =
      run_bake("trade sh \"" + scene_ + "\" --env \"" + sky_ + "\" --out-dir \"" +
                   (dir_ / "y").string() + "\" --orders 2,17",
               dir_ / "y.log");
  EXPECT_NE(bad_order.status, 0);
  EXPECT_NE(bad_order.output.find("--orders: 17"), std::string::npos) << bad_order.output;
  const CommandResult foreign =
      run_bake("trade sh \"" + scene_ + "\" --env \"" + sky_ + "\" --out-dir \"" +
                   (dir_ / "z").string() + "\" --sizes 16",
               dir_ / "z.log");
  EXPECT_NE(foreign.status, 0);
  EXPECT_NE(foreign.output.find("--sizes"), std::string::npos) << foreign.output;
  EXPECT_FALSE(fs::exists(dir_ / "z" / "trade.csv"));
}

// --help lists the sweep's flags and the shared ones with sh's defaults (4096 reference
// samples, 20 frames), not wavelet's flags.
TEST_F(ShTradeCli, HelpListsShSweepFlagsOnly) {
  const CommandResult help = run_bake("trade sh --help", dir_ / "help.log");
  ASSERT_EQ(help.status, 0) << help.output;
  for (const char* flag :
       {"--orders", "--rays", "--bounces", "--base-rays", "--base-order", "--bits", "--env",
        "--out-dir", "--cache-dir", "1073741824]=4096", "--frames INT=20", "--albedo", "--seed"})
    EXPECT_NE(help.output.find(flag), std::string::npos) << flag << "\n" << help.output;
  for (const char* flag : {"--sizes", "--keeps", "--light-terms", "--sh-orders", "--quantizer"})
    EXPECT_EQ(help.output.find(flag), std::string::npos) << flag << "\n" << help.output;
}

}  // namespace
