// SPDX-License-Identifier: MIT
// prt-bake trade shadowfield on a scene preset (the procedural one, generated, under the built-in
// sky) with tiny settings, checked by properties the sweep must have whatever its figures: more
// shells bake more bytes and the runtime holds more; without bounces the surface-radiance basis
// and the source fields are never read, so their sweeps shade exactly as the base does; a second
// run takes its blobs and references from the cache and repeats every figure but the timings;
// and the scene mode's flags are refused where they do not apply.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "support/trade_cli.hpp"

namespace {

using prt_test::CommandResult;
using Table = prt_test::CsvTable;

// The knobs, in the table's order: a row's setting.
const char* const kKnobs[] = {"order",      "terms",    "rays",  "oof_shells", "oof_face",
                              "srf_shells", "srf_face", "basis", "bits",       "bounces"};

std::string setting_of(const std::map<std::string, std::string>& row) {
  std::string key;
  for (const char* knob : kKnobs) key += std::string(key.empty() ? "" : "/") + row.at(knob);
  return key + "@" + row.at("time_s");
}

class ShadowfieldSceneTradeCli : public prt_test::TradeCliTest {
 protected:
  std::string trade_arguments(const std::string& out, int threads) const override {
    return "--threads " + std::to_string(threads) + " trade shadowfield procedural --env sky" +
           " --out-dir " + quoted(out) + " --cache-dir " + quoted(dir_ / "cache") +
           " --times 0,5 --orders 3 --base-order 3 --terms 2 --base-terms 2 --rays 16"
           " --base-rays 16 --bits 16 --lights 8 --oof-shells 1,3 --base-oof-shells 3"
           " --oof-faces 2 --base-oof-face 2 --srf-shells 1,2 --base-srf-shells 2 --srf-faces 2"
           " --base-srf-face 2 --ref-spp 16 --frames 1" +
           extra_arguments_;
  }

  // The rows of `table` whose setting has `knob` at `value` and is in its sweep, by time.
  static std::map<std::string, std::map<std::string, std::string>> rows_at(
      const Table& table, const std::string& knob, const std::string& value) {
    std::map<std::string, std::map<std::string, std::string>> by_time;
    for (const auto& row : table) {
      if (row.at(knob) == value &&
          ("+" + row.at("sweeps") + "+").find("+" + knob + "+") != std::string::npos)
        by_time[row.at("time_s")] = row;
    }
    return by_time;
  }

  std::string extra_arguments_;
};

TEST_F(ShadowfieldSceneTradeCli, ShellsCostBytesAndTheBasisIsUnreadWithoutBounces) {
  extra_arguments_ = " --basis-sizes 2,8 --base-basis 8 --bounces 0,1 --base-bounces 0";
  const Table a = run_trade("a", 2, false);
  ASSERT_FALSE(a.empty());
  // Base 3 OOF shells, 2 SRF shells, N 8, 0 bounces; one knob at a time; 2 times each.
  const auto [sweeps, error] = swept(a, setting_of);
  EXPECT_EQ(sweeps.at("3/2/16/3/2/2/2/8/16/0@0"),
            "order+terms+rays+oof_shells+oof_face+srf_shells+srf_face+basis+bits+bounces");
  EXPECT_EQ(sweeps.at("3/2/16/1/2/2/2/8/16/0@5"), "oof_shells");
  EXPECT_EQ(sweeps.at("3/2/16/3/2/2/2/2/16/0@0"), "basis");
  EXPECT_EQ(sweeps.at("3/2/16/3/2/2/2/8/16/1@5"), "bounces");
  EXPECT_EQ(a.size(), 2u * 5u);  // base, 1 OOF shell, 1 SRF shell, N 2, 1 bounce

  for (const auto& row : a) {
    EXPECT_EQ(row.at("vertices"), "15336");  // the procedural preset's instanced vertices
    EXPECT_GT(std::stod(row.at("scalar_cpu_ms")), 0.0);
  }
  // More shells: more baked bytes, and more the runtime holds.
  for (const char* knob : {"oof_shells", "srf_shells"}) {
    const auto one = rows_at(a, knob, "1"), more = rows_at(a, knob, knob[0] == 'o' ? "3" : "2");
    ASSERT_EQ(one.size(), 2u) << knob;
    ASSERT_EQ(more.size(), 2u) << knob;
    EXPECT_LT(std::stoull(one.at("0").at("blob_bytes")), std::stoull(more.at("0").at("blob_bytes")))
        << knob;
    EXPECT_LT(std::stoull(one.at("0").at("runtime_bytes")),
              std::stoull(more.at("0").at("runtime_bytes")))
        << knob;
  }
  // 0 bounces: what N and the SRF shells change is never read, so the radiance, and the error,
  // are the base's to the last digit; with one bounce the same bake shades something else.
  const auto base = rows_at(a, "bounces", "0");
  for (const auto& [knob, value] :
       std::map<std::string, std::string>{{"basis", "2"}, {"srf_shells", "1"}}) {
    for (const auto& [time, row] : rows_at(a, knob, value))
      EXPECT_EQ(row.at("rel_rmse"), base.at(time).at("rel_rmse")) << knob << " at t = " << time;
  }
  for (const auto& [time, row] : rows_at(a, "bounces", "1"))
    EXPECT_NE(row.at("rel_rmse"), base.at(time).at("rel_rmse")) << "t = " << time;

  // Second run, on one thread: blobs and references from the cache, the same figures.
  const Table b = run_trade("b", 1, true);
  ASSERT_FALSE(b.empty());
  expect_same_but_timings(a, b, {"simd_cpu_ms", "scalar_cpu_ms"});
}

TEST_F(ShadowfieldSceneTradeCli, BadFlagsFailByName) {
  const std::string scene = " --env sky --out-dir " + quoted(dir_ / "bad");
  for (const auto& [arguments, flag] : std::map<std::string, std::string>{
           {"procedural" + scene + " --oof-shells 0", "--oof-shells: 0"},
           {"procedural" + scene + " --bounces 9", "--bounces: 9"},
           {"procedural" + scene + " --times 1,x", "--times: 'x'"},
           {"procedural" + scene + " --brdf lambert", "--brdf"},
           {"procedural" + scene + " --albedo 1,1,1", "--albedo"},
           {quoted(demo_scene_) + " --env " + quoted(sky_) + " --out-dir " + quoted(dir_ / "bad") +
                " --basis-sizes 4",
            "--basis-sizes: only with a scene preset"}}) {
    const CommandResult r = run_bake("trade shadowfield " + arguments, dir_ / "bad.log");
    EXPECT_NE(r.exit_code, 0) << arguments;
    EXPECT_NE(r.output.find(flag), std::string::npos) << arguments << "\n" << r.output;
  }
}

}  // namespace
