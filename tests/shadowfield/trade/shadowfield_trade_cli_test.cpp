// SPDX-License-Identifier: MIT
// prt-bake trade shadowfield end to end on the generated demo scene (baked as one object) with
// tiny settings: every row shades better than black, a higher order and more BRDF terms come
// closer to the reference, the references come from the cache on a second run with the same
// numbers but for the timings, and bad sweeps fail by name.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "support/trade_cli.hpp"

namespace {

using prt_test::CommandResult;
using Table = prt_test::CsvTable;

class ShadowfieldTradeCli : public prt_test::TradeCliTest {
 protected:
  std::string trade_arguments(const std::string& out, int threads) const override {
    return "--threads " + std::to_string(threads) + " trade shadowfield " + quoted(demo_scene_) +
           " --env " + quoted(sky_) + " --out-dir " + quoted(out) + " --cache-dir " +
           quoted(dir_ / "cache") +
           " --orders 2,4 --rays 16 --bits 16 --base-rays 16 --base-order 4 --rotations 2"
           " --ref-spp 16 --frames 2 --albedo 0.8,0.8,0.8" +
           extra_arguments_;
  }

  std::string extra_arguments_;
};

std::string key_of(const std::map<std::string, std::string>& row) {
  return row.at("order") + "/" + row.at("terms") + "/" + row.at("bits") + "/" +
         row.at("rotation_deg");
}

TEST_F(ShadowfieldTradeCli, DiffuseSweepImprovesWithOrderAndRepeatsItself) {
  const Table a = run_trade("a", 2, false);
  ASSERT_FALSE(a.empty());
  // Orders {2, 4} at 16 rays and 16 bits, each at turns 0 and 180: the base setting (order 4)
  // is in every sweep and baked once; a diffuse object has no terms sweep.
  const auto [sweeps, error] = swept(a, key_of);
  const std::map<std::string, std::string> expected = {{"2/1/16/0", "order"},
                                                       {"2/1/16/180", "order"},
                                                       {"4/1/16/0", "order+rays+bits"},
                                                       {"4/1/16/180", "order+rays+bits"}};
  EXPECT_EQ(sweeps, expected);
  for (const char* turn : {"0", "180"})
    EXPECT_LT(error.at(std::string("4/1/16/") + turn), error.at(std::string("2/1/16/") + turn));
  for (const auto& row : a) {
    EXPECT_GT(std::stoul(row.at("vertices_compared")), 0u);
    EXPECT_LE(std::stoul(row.at("vertices_compared")), std::stoul(row.at("vertices")));
    EXPECT_LT(std::abs(std::stod(row.at("bias"))), std::stod(row.at("rel_rmse")) + 1e-9);
  }

  // Second run, on one thread: references from the cache, the same numbers but the timings.
  const Table b = run_trade("b", 1, true);
  ASSERT_FALSE(b.empty());
  expect_same_but_timings(a, b, {"shade_cpu_ms", "bake_seconds"});
}

TEST_F(ShadowfieldTradeCli, GlossySweepImprovesWithTerms) {
  extra_arguments_ =
      " --brdf phong:10,0.5,0.3 --terms 1,4 --base-terms 4 --orders 4 --brdf-grid 16";
  const Table a = run_trade("glossy", 2, false);
  ASSERT_FALSE(a.empty());
  const auto [sweeps, error] = swept(a, key_of);
  EXPECT_EQ(sweeps.at("4/1/16/0"), "terms");
  for (const char* turn : {"0", "180"})
    EXPECT_LT(error.at(std::string("4/4/16/") + turn), error.at(std::string("4/1/16/") + turn));
}

TEST_F(ShadowfieldTradeCli, BadSweepsFailByName) {
  for (const auto& [option, flag] :
       std::map<std::string, std::string>{{" --orders 2,7", "--orders: 7"},
                                          {" --terms 0", "--terms: 0"},
                                          {" --bits 12", "--bits: 12"},
                                          {" --brdf wood", "--brdf"}}) {
    const CommandResult r =
        run_bake("trade shadowfield " + quoted(demo_scene_) + " --env " + quoted(sky_) +
                     " --out-dir " + quoted(dir_ / "bad") + option,
                 dir_ / "bad.log");
    EXPECT_NE(r.exit_code, 0) << option;
    EXPECT_NE(r.output.find(flag), std::string::npos) << option << "\n" << r.output;
  }
}

// --help lists the sweep's flags and the shared ones with this trade's defaults.
TEST_F(ShadowfieldTradeCli, HelpListsTheSweepFlags) {
  const CommandResult help = run_bake("trade shadowfield --help", dir_ / "help.log");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  for (const char* flag :
       {"--brdf", "--orders", "--terms", "--rays", "--bits", "--base-order", "--base-terms",
        "--base-rays", "--base-bits", "--rotations", "--brdf-grid", "--env", "--out-dir",
        "--cache-dir", "1073741824]=1024", "--frames INT=10", "--albedo", "--seed"})
    EXPECT_NE(help.output.find(flag), std::string::npos) << flag << "\n" << help.output;
  EXPECT_EQ(help.output.find("--dering"), std::string::npos) << help.output;
}

}  // namespace
