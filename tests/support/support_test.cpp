// SPDX-License-Identifier: MIT
// The test helpers themselves, on files written here byte by byte: a helper that misread a table
// or an array would let the tests that use it pass on wrong output.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "support/command.hpp"
#include "support/test_files.hpp"

namespace {

TEST(Support, RunCommandCapturesBothStreamsAndTheExitCode) {
  prt_test::TempDir dir("support_run");
  const prt_test::CommandResult r = prt_test::run_command(
      "/bin/sh", "-c " + prt_test::shell_quote("echo out; echo 'it''s err' >&2; exit 3"),
      dir.file("log.txt"));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.output, "out\nits err\n");
  const prt_test::CommandResult env = prt_test::run_command(
      "/bin/sh", "-c " + prt_test::shell_quote("echo \"$PRT_X\""), dir.file("env.txt"), "PRT_X=a");
  EXPECT_EQ(env.exit_code, 0);
  EXPECT_EQ(env.output, "a\n");
}

TEST(Support, ReadCsvMapsFieldsToColumnsAndFlagsShortRows) {
  prt_test::TempDir dir("support_csv");
  const prt_test::CsvTable rows =
      prt_test::read_csv(dir.write("t.csv", "a,b,c\n1,2,3\n4,,6\n7,8\n"));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].at("a"), "1");
  EXPECT_EQ(rows[0].at("c"), "3");
  EXPECT_EQ(rows[1].at("b"), "");
  EXPECT_EQ(rows[1].count("#fields"), 0u);
  EXPECT_EQ(rows[2].at("#fields"), "2");
}

// A .npy 1.0 file: magic, version, header length, header, then little-endian float32 data.
std::string npy(const std::string& shape, const float* values, std::size_t count) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
  header += std::string(64 - (10 + header.size() + 1) % 64, ' ') + "\n";
  std::string bytes = std::string("\x93NUMPY\x01\x00", 8);
  bytes += static_cast<char>(header.size() & 0xFF);
  bytes += static_cast<char>(header.size() >> 8);
  bytes += header;
  bytes.append(reinterpret_cast<const char*>(values), 4 * count);
  return bytes;
}

TEST(Support, ReadNpyReadsShapeAndValuesAndRejectsOtherFiles) {
  prt_test::TempDir dir("support_npy");
  const float v[6] = {1.0f, -2.5f, 3.0f, 0.25f, 5.0f, 6.0f};
  const prt_test::NpyArray a = prt_test::read_npy_f32(dir.write("a.npy", npy("(2, 3)", v, 6)));
  ASSERT_EQ(a.rows, 2u);
  EXPECT_EQ(a.columns, 3u);
  ASSERT_EQ(a.values.size(), 6u);
  EXPECT_EQ(a.values[1], -2.5f);
  EXPECT_EQ(a.values[3], 0.25f);
  const prt_test::NpyArray b = prt_test::read_npy_f32(dir.write("b.npy", npy("(6,)", v, 6)));
  EXPECT_EQ(b.rows, 6u);
  EXPECT_EQ(b.columns, 1u);
  EXPECT_EQ(prt_test::read_npy_f32(dir.write("c.npy", npy("(2, 3)", v, 5))).rows, 0u);
  EXPECT_EQ(prt_test::read_npy_f32(dir.write("d.npy", "not an array")).rows, 0u);
}

}  // namespace
