// SPDX-License-Identifier: MIT
// prt-bake trade cloth end to end on the golden quad (one frame: normal +Y, warp +X) under the
// demo sky with tiny settings: a row for every knob the sweep design calls for
// (docs/cloth/trade.md), every setting of the method better than black, detail that helps where
// it must (more lobes, more rank), the reference's own error below the method's, the table bytes
// ordered by rank and bits, a row for each of paper 003's printed rules and one for all of them,
// each changing the shading, and a second run that reads its references from the cache and
// writes the same table but for the timings.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <iterator>
#include <map>
#include <string>

#include "support/command.hpp"

namespace {

namespace fs = std::filesystem;
using Row = std::map<std::string, std::string>;

class ClothTradeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("prt_cloth_trade_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const prt_test::CommandResult demo =
        prt_test::run_command(PRT_BAKE_EXE, "demo-scene " + quoted(dir_), dir_ / "demo.log");
    ASSERT_EQ(demo.exit_code, 0) << demo.output;
  }

  static std::string quoted(const fs::path& path) { return prt_test::shell_quote(path.string()); }

  prt_test::CommandResult trade(const std::string& out) const {
    const fs::path quad = fs::path(PRT_SOURCE_DIR) / "formats/golden/scenes/quad_over_ground.obj";
    return prt_test::run_command(
        PRT_BAKE_EXE,
        "--threads 2 trade cloth " + quoted(quad) + " --env " + quoted(dir_ / "demo_sky.hdr") +
            " --out-dir " + quoted(dir_ / out) + " --cache-dir " + quoted(dir_ / "cache") +
            " --fabric linen_plain --lobes 8,1 --energy 1e-4,1e-2 --xi-size 8 --levels 4"
            " --view-nodes 6,4 --panels 2,1 --phi-nodes 3,1 --turns 1 --frames 1",
        dir_ / (out + ".log"));
  }

  fs::path dir_;
};

double number(const Row& row, const std::string& column) {
  return std::stod(row.at(column));
}

// The rows of one sweep, in table order.
std::vector<Row> of(const prt_test::CsvTable& rows, const std::string& sweep) {
  std::vector<Row> out;
  for (const Row& r : rows)
    if (("+" + r.at("sweeps") + "+").find("+" + sweep + "+") != std::string::npos) out.push_back(r);
  return out;
}

TEST_F(ClothTradeCli, RowsBoundsAndTheCache) {
  const prt_test::CommandResult a = trade("a");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("cloth trade: reference of linen_plain"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "a" / "trade.md"));
  const prt_test::CsvTable rows = prt_test::read_csv(dir_ / "a" / "trade.csv");
  for (const Row& r : rows) ASSERT_EQ(r.count("#fields"), 0u) << r.at("setting");

  // The defaults, then: the energy 1e-2 and every rank, 8 bits, one grid, K 1, the per-frame
  // fit, 1 panel, 1 phi node, T alone, no culling, the paper's printed rules (Eq. 13 in three
  // steps) and the paper as printed, and the two reference rows.
  const std::map<std::string, std::size_t> expected = {
      {"defaults", 1},    {"energy", 3},     {"bits", 2},   {"grid", 2},
      {"lobes", 2},       {"fast_light", 1}, {"panels", 2}, {"phi_nodes", 2},
      {"no_cone", 1},     {"no_culling", 1}, {"paper", 9},  {"reference_merged", 1},
      {"reference_sg", 1}};
  for (const auto& [sweep, count] : expected) EXPECT_EQ(of(rows, sweep).size(), count) << sweep;
  ASSERT_EQ(rows.size(), 22u);

  const Row defaults = of(rows, "defaults").front();
  const double error = number(defaults, "nrmse");
  for (const Row& r : rows) {
    if (r.at("sweeps").rfind("reference", 0) == 0) continue;
    EXPECT_GT(number(r, "nrmse"), 0.0) << r.at("setting");
    if (r.at("sweeps") == "paper") continue;  // the paper's Fresnel expansion is worse than black
    EXPECT_LT(number(r, "nrmse"), 1.0) << r.at("setting");  // better than black
  }
  // Detail helps: one lobe cannot hold the sky the way eight do; a rank that leaves out 1 %
  // of each table's energy costs more than one that leaves out 0.01 %.
  EXPECT_GT(number(of(rows, "lobes").back(), "nrmse"), error);
  const std::vector<Row> energy = of(rows, "energy");
  const Row &coarse = energy[2], &full = energy[1];
  EXPECT_EQ(full.at("energy"), "0");
  EXPECT_EQ(full.at("truncation_cost"), "");
  EXPECT_GT(number(coarse, "truncation_cost"), number(defaults, "truncation_cost"));
  EXPECT_LE(number(coarse, "table_mb"), number(defaults, "table_mb"));
  EXPECT_LE(number(defaults, "table_mb"), number(full, "table_mb"));
  EXPECT_LT(number(of(rows, "bits").back(), "table_mb"), number(defaults, "table_mb"));
  // Each of the paper's rules, and all of them, changes the shading.
  const std::vector<Row> paper = of(rows, "paper");
  const char* paper_settings[] = {"paper: T over the full sphere",
                                  "paper: phi over the fibre's front",
                                  "paper: 6 straight theta segments",
                                  "paper: Schlick's Fresnel (Eq. 13 corrected)",
                                  "paper: Schlick with cos phi_d as printed",
                                  "paper: Schlick's sum cut at the cube as printed",
                                  "paper: Eq. 13's Fresnel as printed",
                                  "paper: g_u as printed",
                                  "the paper as printed"};
  ASSERT_EQ(paper.size(), std::size(paper_settings));
  for (std::size_t i = 0; i < paper.size(); ++i) {
    EXPECT_EQ(paper[i].at("setting"), paper_settings[i]);
    EXPECT_NE(paper[i].at("nrmse"), defaults.at("nrmse")) << paper[i].at("setting");
  }
  // The reference's discretisation error is well below the method's.
  EXPECT_LT(number(of(rows, "reference_merged").front(), "nrmse"), error / 4);

  const prt_test::CommandResult b = trade("b");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_EQ(b.output.find("cloth trade: reference of"), std::string::npos) << b.output;
  const prt_test::CsvTable again = prt_test::read_csv(dir_ / "b" / "trade.csv");
  ASSERT_EQ(again.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (const auto& [column, value] : rows[i]) {
      if (column == "cpu_us" || column == "simd_us") continue;
      EXPECT_EQ(value, again[i].at(column)) << "row " << i + 1 << ", " << column;
    }
  }
}

TEST_F(ClothTradeCli, RejectsSettingsItCannotSweep) {
  const fs::path quad = fs::path(PRT_SOURCE_DIR) / "formats/golden/scenes/quad_over_ground.obj";
  const std::string base = "trade cloth " + quoted(quad) + " --env " +
                           quoted(dir_ / "demo_sky.hdr") + " --out-dir " + quoted(dir_ / "x");
  for (const char* bad : {" --energy 2", " --energy x", " --panels 0", " --phi-nodes 9",
                          " --lobes 0", " --fabric denim"}) {
    const prt_test::CommandResult r =
        prt_test::run_command(PRT_BAKE_EXE, base + bad, dir_ / "bad.log");
    EXPECT_NE(r.exit_code, 0) << bad;
  }
}

}  // namespace
