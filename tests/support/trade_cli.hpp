// SPDX-License-Identifier: MIT
// What the `prt-bake trade <technique>` tests share: a folder per test holding the demo scene and
// sky that prt-bake itself writes, prt-bake run with its output kept in that folder, the trade
// table read back with the test's own CSV reader, and the check that two runs agree on every
// column but the timings. A test target that includes this defines PRT_BAKE_EXE.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "support/command.hpp"

namespace prt_test {

class TradeCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: ctest may run the tests of one fixture at the same time.
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::path(::testing::TempDir()) /
           (std::string("prt_trade_cli_") + test->test_suite_name() + "_" + test->name());
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
