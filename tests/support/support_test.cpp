// SPDX-License-Identifier: MIT
// The test helpers themselves, on files written here byte by byte: a helper that misread a table
// or an array would let the tests that use it pass on wrong output.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "support/blob_test_util.hpp"
#include "support/command.hpp"
#include "support/counting_allocator.hpp"
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

TEST(Support, CountingAllocatorCountsFailsAndChecksSizes) {
  prt_test::CountingAllocator counter;
  counter.fail_at = 1;
  void* a = prt_test::CountingAllocator::alloc(&counter, 24, 8);
  EXPECT_EQ(prt_test::CountingAllocator::alloc(&counter, 8, 8), nullptr);
  void* b = prt_test::CountingAllocator::alloc(&counter, 8, 16);
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(counter.live, 2);
  EXPECT_EQ(counter.total, 3);
  prt_test::CountingAllocator::release(&counter, a, 24);
  EXPECT_FALSE(counter.size_mismatch);
  prt_test::CountingAllocator::release(&counter, b, 4);
  EXPECT_TRUE(counter.size_mismatch);
  EXPECT_EQ(counter.live, 0);
}

// Loads the golden blob and reports success whatever the load returned: a failing allocation
// that is swallowed.
prt_result swallowing_load(prt_context* context) {
  static const prt_test::Bytes golden = prt_test::read_file(prt_test::golden_path());
  prt_asset* asset = nullptr;
  prt_asset_load_memory(context, golden.data(), golden.size(), PRT_VALIDATE_FULL, &asset);
  prt_asset_destroy(asset);
  return PRT_OK;
}

TEST(Support, AllocationFailureSweepCatchesASwallowedFailure) {
  ::testing::TestPartResultArray failures;
  {
    const ::testing::ScopedFakeTestPartResultReporter intercept(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
    prt_test::expect_every_allocation_failure_reported(swallowing_load, "swallowing load");
  }
  ASSERT_GT(failures.size(), 0);
  EXPECT_NE(std::string(failures.GetTestPartResult(0).message())
                .find("swallowing load, allocation 1 failing"),
            std::string::npos)
      << failures.GetTestPartResult(0).message();
}

}  // namespace
