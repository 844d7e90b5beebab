// SPDX-License-Identifier: MIT
// What the `prt-bake trade <technique>` tests share: a folder per test holding the demo scene and
// sky that prt-bake itself writes, prt-bake run with its output kept in that folder, the trade
// table read back with the test's own CSV reader, and the check that two runs agree on every
// column but the timings. A test target that includes this defines PRT_BAKE_EXE.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "support/command.hpp"

namespace prt_test {

class TradeCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: ctest may run the tests of one fixture at the same time,
    // and other builds of the tree may run the same test.
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::path(::testing::TempDir()) /
           (std::string("prt_trade_cli_") + test->test_suite_name() + "_" + test->name() + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    const CommandResult demo = run_bake("demo-scene " + quoted(dir_), dir_ / "demo.log");
    ASSERT_EQ(demo.exit_code, 0) << demo.output;
    demo_scene_ = (dir_ / "demo_scene.glb").string();
    sky_ = (dir_ / "demo_sky.hdr").string();
  }

  static CommandResult run_bake(const std::string& arguments, const std::filesystem::path& log) {
    return run_command(PRT_BAKE_EXE, arguments, log);
  }

  static std::string quoted(const std::filesystem::path& path) {
    return shell_quote(path.string());
  }

  // The sweep's arguments: `out` as its output folder, on `threads` threads.
  virtual std::string trade_arguments(const std::string& out, int threads) const = 0;

  // Runs the sweep into dir_/name on `threads` threads and reads its table back. It must succeed
  // and write trade.csv and trade.md (no rows when it fails); `cached`: its references come from
  // the cache of an earlier run (nothing rendered), otherwise they are rendered.
  CsvTable run_trade(const std::string& name, int threads, bool cached) const {
    const CommandResult r =
        run_bake(trade_arguments((dir_ / name).string(), threads), dir_ / (name + ".log"));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    if (r.exit_code != 0) return {};
    if (cached) {
      EXPECT_EQ(r.output.find("rendering"), std::string::npos) << r.output;
      EXPECT_NE(r.output.find("from the cache"), std::string::npos) << r.output;
    } else {
      EXPECT_NE(r.output.find("rendering"), std::string::npos) << r.output;
    }
    EXPECT_TRUE(std::filesystem::exists(dir_ / name / "trade.md"));
    return read_table(dir_ / name / "trade.csv");
  }

  // Each row's `sweeps` and relative RMSE by the row's key; every setting must have an error
  // above 0 and shade better than black (relative RMSE 1).
  struct Swept {
    std::map<std::string, std::string> sweeps;
    std::map<std::string, double> error;
  };
  template <typename Key>
  static Swept swept(const CsvTable& table, Key&& key) {
    Swept s;
    for (const auto& row : table) {
      const std::string k = key(row);
      s.sweeps[k] = row.at("sweeps");
      s.error[k] = std::stod(row.at("rel_rmse"));
      EXPECT_TRUE(s.error[k] > 0.0 && s.error[k] < 1.0) << k << ": " << s.error[k];
    }
    return s;
  }

  // The table, each row checked to have a field for every column.
  static CsvTable read_table(const std::filesystem::path& path) {
    const CsvTable rows = read_csv(path);
    for (std::size_t i = 0; i < rows.size(); ++i)
      EXPECT_EQ(rows[i].count("#fields"), 0u) << path << " row " << i + 1 << " is short or long";
    return rows;
  }

  // Two runs' tables hold the same rows with the same values, but for the `timings` columns.
  static void expect_same_but_timings(const CsvTable& a, const CsvTable& b,
                                      const std::set<std::string>& timings) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      for (const auto& [column, value] : a[i]) {
        if (!timings.count(column)) {
          EXPECT_EQ(value, b[i].at(column)) << "row " << i + 1 << ", " << column;
        }
      }
    }
  }

  std::filesystem::path dir_;
  std::string demo_scene_, sky_;
};

}  // namespace prt_test
