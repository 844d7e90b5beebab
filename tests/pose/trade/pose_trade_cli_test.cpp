// SPDX-License-Identifier: MIT
// prt-bake trade pose end to end on the golden hinge (formats/golden/scenes/hinge.gltf) with tiny
// settings: the rows the sweep design calls for (docs/pose/trade.md), each fitted model better
// than black, the basis projection bounding the residual model from below (it is the least-squares
// fit onto the same basis), the mean-pose row sized as one frame, and the same table twice but
// for the timings.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "support/command.hpp"

namespace {

namespace fs = std::filesystem;
using Table = prt_test::CsvTable;

class PoseTradeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("prt_pose_trade_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A constant sky: the trade needs a map; what it holds does not matter to these checks.
    const prt_test::CommandResult demo =
        prt_test::run_command(PRT_BAKE_EXE, "demo-scene " + quoted(dir_), dir_ / "demo.log");
    ASSERT_EQ(demo.exit_code, 0) << demo.output;
  }

  static std::string quoted(const fs::path& path) { return prt_test::shell_quote(path.string()); }

  prt_test::CommandResult trade(const std::string& out, const std::string& extra) const {
    const fs::path hinge = fs::path(PRT_SOURCE_DIR) / "formats/golden/scenes/hinge.gltf";
    return prt_test::run_command(
        PRT_BAKE_EXE,
        "--threads 2 trade pose " + quoted(hinge) + " --env " + quoted(dir_ / "demo_sky.hdr") +
            " --out-dir " + quoted(dir_ / out) + " --order 3 --rays 32 --rate 8 --frames 2" + extra,
        dir_ / (out + ".log"));
  }

  fs::path dir_;
};

double number(const std::map<std::string, std::string>& row, const std::string& column) {
  return std::stod(row.at(column));
}

TEST_F(PoseTradeCli, RowsBoundsAndRepeats) {
  const prt_test::CommandResult a = trade("a", " --split even-odd --basis-dims 1 2");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  for (const char* file : {"trade.csv", "trade.md", "alpha.csv"})
    EXPECT_TRUE(fs::exists(dir_ / "a" / file)) << file;
  const Table rows = prt_test::read_csv(dir_ / "a" / "trade.csv");

  // Per light (the map and the directional light): mean pose, unshadowed only, the visibility
  // oracle, and per q the paper's model, the residual model and its basis projection.
  std::map<std::string, std::set<std::string>> models_by_light;
  std::map<std::string, std::map<std::string, double>> transfer_error;  // model -> q -> error
  for (const auto& row : rows) {
    models_by_light[row.at("map")].insert(row.at("model") + "/" + row.at("q"));
    transfer_error[row.at("model")][row.at("q")] = number(row, "transfer_error");
    const std::string& model = row.at("model");
    if (model == "paper (direct)" || model == "residual" || model == "visibility oracle") {
      EXPECT_LT(number(row, "shaded_rel_rmse"), 1.0) << model << " q " << row.at("q");
    }
    if (model == "mean pose") {
      EXPECT_EQ(number(row, "model_bytes"), 8 * 9 * 4);  // V = 8, n² = 9 floats each
      EXPECT_EQ(row.at("frame_share"), "100.0");
    }
  }
  const std::set<std::string> expected = {
      "mean pose/",       "unshadowed only/",   "visibility oracle/",
      "paper (direct)/1", "paper (direct)/2",   "residual/1",
      "residual/2",       "basis projection/1", "basis projection/2"};
  ASSERT_EQ(models_by_light.size(), 2u);
  for (const auto& [light, models] : models_by_light) EXPECT_EQ(models, expected) << light;
  // The projection is the least-squares fit of each test frame onto the (unquantised) basis;
  // the residual model lies in the span of the 16-bit quantised basis, so it can undercut the
  // projection by no more than the quantisation's share.
  for (const char* q : {"1", "2"}) {
    EXPECT_LE(transfer_error["basis projection"][q],
              transfer_error["residual"][q] * (1.0 + 1e-3) + 1e-9)
        << "q " << q;
  }

  const prt_test::CommandResult b = trade("b", " --split even-odd --basis-dims 1 2");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const Table again = prt_test::read_csv(dir_ / "b" / "trade.csv");
  ASSERT_EQ(again.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (const auto& [column, value] : rows[i]) {
      if (column.find("_ms") != std::string::npos) continue;
      EXPECT_EQ(again[i].at(column), value) << "row " << i << " " << column;
    }
  }
}

TEST_F(PoseTradeCli, ASplitWithoutTestFramesFailsClearly) {
  const prt_test::CommandResult r = trade("c", " --split clips --basis-dims 1");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("leaves no training frames"), std::string::npos) << r.output;
}

}  // namespace
