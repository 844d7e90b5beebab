// SPDX-License-Identifier: MIT
// prt-bake trade sh end to end on the generated demo scene with tiny settings: the rows the sweep
// design calls for, the reference cache, determinism of everything but the timings, the de-ringing
// axis, and clear errors for bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "support/trade_cli.hpp"

namespace {

namespace fs = std::filesystem;

using prt_test::CommandResult;
using Table = prt_test::CsvTable;

class ShTradeCli : public prt_test::TradeCliTest {
 protected:
  std::string trade_arguments(const std::string& out, int threads) const override {
    return "--threads " + std::to_string(threads) + " trade sh " + quoted(demo_scene_) + " --env " +
           quoted(sky_) + " --out-dir " + quoted(out) + " --cache-dir " + quoted(dir_ / "cache") +
           " --orders 1,3 --rays 16,32 --bounces 0,1 --base-rays 16 --base-order 3"
           " --ref-spp 16 --frames 2 --albedo 0.8,0.8,0.8" +
           extra_arguments_;
  }

  std::string extra_arguments_;
};

TEST_F(ShTradeCli, SweepsCachesAndRepeatsItself) {
  const Table a = run_trade("a", 2, false);
  ASSERT_FALSE(a.empty());

  // Orders {1,3} at 16 rays; rays {16,32} at order 3; bounces {0,1} at order 3, 16 rays: the
  // base setting (3, 16, 0) is in all three sweeps and baked once.
  // Every setting shades better than black (relative RMSE 1), and order 3 is closer to the
  // reference than order 1 by far more than its noise.
  const auto [sweeps, error] = swept(a, [](const std::map<std::string, std::string>& row) {
    return row.at("order") + "/" + row.at("rays") + "/" + row.at("bounces");
  });
  for (const auto& row : a)
    EXPECT_EQ(row.at("transfer"), row.at("bounces") == "0" ? "shadowed" : "interreflected");
  EXPECT_LT(error.at("3/16/0"), error.at("1/16/0"));
  const std::map<std::string, std::string> expected = {{"1/16/0", "order"},
                                                       {"3/16/0", "order+rays+bounces"},
                                                       {"3/32/0", "rays"},
                                                       {"3/16/1", "bounces"}};
  EXPECT_EQ(sweeps, expected);

  // Second run, on one thread: references from the cache, the same numbers but for the timings.
  const Table b = run_trade("b", 1, true);
  ASSERT_FALSE(b.empty());
  expect_same_but_timings(a, b,
                          {"shade_cpu_ms", "shade_simd_ms", "bake_seconds", "rays_per_second"});
}

// --dering adds rows with the light de-ringed; its strength-0 rows are the rows of a run without
// it (every column but the timings), and de-ringing changes the error.
TEST_F(ShTradeCli, DeringAxisAddsRowsAndKeepsTheUnwindowedOnes) {
  const Table plain = run_trade("plain", 2, false);
  ASSERT_FALSE(plain.empty());
  for (const auto& row : plain) EXPECT_EQ(row.at("dering"), "0");
  extra_arguments_ = " --dering 0,1";
  const Table both = run_trade("both", 2, true);
  ASSERT_EQ(both.size(), 2 * plain.size());
  Table unwindowed, windowed;
  for (const auto& row : both) (row.at("dering") == "0" ? unwindowed : windowed).push_back(row);
  expect_same_but_timings(plain, unwindowed,
                          {"shade_cpu_ms", "shade_simd_ms", "bake_seconds", "rays_per_second"});
  ASSERT_EQ(windowed.size(), plain.size());
  for (std::size_t i = 0; i < windowed.size(); ++i) {
    EXPECT_EQ(windowed[i].at("dering"), "1");
    for (const char* column : {"order", "rays", "bounces", "blob_bytes", "ref_noise"})
      EXPECT_EQ(windowed[i].at(column), plain[i].at(column)) << column;
    // Order 1 has nothing to window.
    if (plain[i].at("order") == "1")
      EXPECT_EQ(windowed[i].at("rel_rmse"), plain[i].at("rel_rmse"));
    else
      EXPECT_NE(windowed[i].at("rel_rmse"), plain[i].at("rel_rmse")) << "row " << i + 1;
  }
  const CommandResult bad = run_bake("trade sh " + quoted(demo_scene_) + " --env " + quoted(sky_) +
                                         " --out-dir " + quoted(dir_ / "bad") + " --dering 0,-1",
                                     dir_ / "bad.log");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--dering: '-1'"), std::string::npos) << bad.output;
}

TEST_F(ShTradeCli, BadInputGivesAClearError) {
  const CommandResult missing_map = run_bake(
      "trade sh " + quoted(demo_scene_) + " --env nothere.hdr --out-dir " + quoted(dir_ / "x"),
      dir_ / "x.log");
  EXPECT_NE(missing_map.exit_code, 0);
  EXPECT_NE(missing_map.output.find("nothere.hdr"), std::string::npos) << missing_map.output;
  const CommandResult bad_order =
      run_bake("trade sh " + quoted(demo_scene_) + " --env " + quoted(sky_) + " --out-dir " +
                   quoted(dir_ / "y") + " --orders 2,17",
               dir_ / "y.log");
  EXPECT_NE(bad_order.exit_code, 0);
  EXPECT_NE(bad_order.output.find("--orders: 17"), std::string::npos) << bad_order.output;
  const CommandResult foreign =
      run_bake("trade sh " + quoted(demo_scene_) + " --env " + quoted(sky_) + " --out-dir " +
                   quoted(dir_ / "z") + " --sizes 16",
               dir_ / "z.log");
  EXPECT_NE(foreign.exit_code, 0);
  EXPECT_NE(foreign.output.find("--sizes"), std::string::npos) << foreign.output;
  EXPECT_FALSE(fs::exists(dir_ / "z" / "trade.csv"));
}

// --help lists the sweep's flags and the shared ones with sh's defaults (4096 reference
// samples, 20 frames), not wavelet's flags.
TEST_F(ShTradeCli, HelpListsShSweepFlagsOnly) {
  const CommandResult help = run_bake("trade sh --help", dir_ / "help.log");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  for (const char* flag : {"--orders", "--rays", "--bounces", "--base-rays", "--base-order",
                           "--bits", "--dering", "--env", "--out-dir", "--cache-dir",
                           "1073741824]=4096", "--frames INT=20", "--albedo", "--seed"})
    EXPECT_NE(help.output.find(flag), std::string::npos) << flag << "\n" << help.output;
  for (const char* flag : {"--sizes", "--keeps", "--light-terms", "--sh-orders", "--quantizer"})
    EXPECT_EQ(help.output.find(flag), std::string::npos) << flag << "\n" << help.output;
}

}  // namespace
