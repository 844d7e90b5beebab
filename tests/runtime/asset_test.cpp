// SPDX-License-Identifier: MIT
// Asset API: loading (copy, borrow, file), queries, validate-only, allocation failures.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "support/blob_test_util.hpp"
#include "support/counting_allocator.hpp"

namespace {

using namespace prt_test;

class Asset : public ::testing::Test {
 protected:
  void SetUp() override { golden = read_file(golden_path()); }
  Context ctx;
  Bytes golden;
};

TEST_F(Asset, CopyingLoadOutlivesTheCallersBytes) {
  prt_asset* asset = nullptr;
  {
    Bytes temporary = golden;
    ASSERT_EQ(prt_asset_load_memory(ctx.ctx, temporary.data(), temporary.size(), PRT_VALIDATE_FULL,
                                    &asset),
              PRT_OK);
    std::memset(temporary.data(), 0xAB, temporary.size());
  }
  prt_asset_info info = prt::sized<prt_asset_info>();
  ASSERT_EQ(prt_asset_get_info(asset, &info), PRT_OK);
  EXPECT_EQ(info.borrowed, 0u);
  const void* data;
  size_t size;
  ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_INFO, &data, &size), PRT_OK);
  EXPECT_EQ(std::string(static_cast<const char*>(data), size), "prtkit golden blob 1.0: 3x3 grid");
  prt_asset_destroy(asset);
}

TEST_F(Asset, BorrowedLoadReadsInPlace) {
  // 16-byte aligned storage for the blob.
  std::vector<uint64_t> storage((golden.size() + 15) / 8 + 2);
  uint8_t* aligned = reinterpret_cast<uint8_t*>(storage.data());
  aligned += (16 - reinterpret_cast<uintptr_t>(aligned) % 16) % 16;
  std::memcpy(aligned, golden.data(), golden.size());
  prt_asset* asset = nullptr;
  ASSERT_EQ(
      prt_asset_load_memory_borrowed(ctx.ctx, aligned, golden.size(), PRT_VALIDATE_FULL, &asset),
      PRT_OK);
  prt_asset_info info = prt::sized<prt_asset_info>();
  ASSERT_EQ(prt_asset_get_info(asset, &info), PRT_OK);
  EXPECT_EQ(info.borrowed, 1u);
  const void* data;
  size_t size;
  prt_section_info s = prt::sized<prt_section_info>();
  uint32_t index;
  ASSERT_EQ(prt_asset_find_section(asset, PRT_SECTION_VPOS, &index), PRT_OK);
  ASSERT_EQ(prt_asset_get_section_info(asset, index, &s), PRT_OK);
  ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_VPOS, &data, &size), PRT_OK);
  EXPECT_EQ(data, aligned + s.offset) << "uncompressed sections are read in place";
  ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_VNRM, &data, &size), PRT_OK);
  EXPECT_TRUE(data < aligned || data >= aligned + golden.size()) << "zstd decodes elsewhere";
  EXPECT_EQ(reinterpret_cast<uintptr_t>(data) % 16, 0u);
  prt_asset_destroy(asset);

  EXPECT_EQ(prt_asset_load_memory_borrowed(ctx.ctx, aligned + 1, golden.size() - 1,
                                           PRT_VALIDATE_QUICK, &asset),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(asset, nullptr);
}

TEST_F(Asset, Queries) {
  prt_asset* asset = nullptr;
  ASSERT_EQ(
      prt_asset_load_memory(ctx.ctx, golden.data(), golden.size(), PRT_VALIDATE_QUICK, &asset),
      PRT_OK);
  uint32_t index = 99;
  EXPECT_EQ(prt_asset_find_section(asset, PRT_SECTION_TRIS, &index), PRT_OK);
  EXPECT_EQ(index, 3u);
  EXPECT_EQ(prt_asset_find_section(asset, PRT_TAG('N', 'O', 'N', 'E'), &index),
            PRT_ERROR_NOT_FOUND);
  prt_section_info s = prt::sized<prt_section_info>();
  EXPECT_EQ(prt_asset_get_section_info(asset, 4, &s), PRT_ERROR_NOT_FOUND);
  const void* data;
  size_t size;
  EXPECT_EQ(prt_asset_section_data(asset, PRT_TAG('N', 'O', 'N', 'E'), &data, &size),
            PRT_ERROR_NOT_FOUND);
  // Size query, then a too-small buffer, then the right one.
  size = 0;
  EXPECT_EQ(prt_asset_copy_section(asset, PRT_SECTION_TRIS, nullptr, 0, &size),
            PRT_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(size, 96u);
  std::vector<uint8_t> small(95, 0xEE), exact(96);
  EXPECT_EQ(prt_asset_copy_section(asset, PRT_SECTION_TRIS, small.data(), small.size(), &size),
            PRT_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(small, std::vector<uint8_t>(95, 0xEE)) << "untouched on failure";
  EXPECT_EQ(prt_asset_copy_section(asset, PRT_SECTION_TRIS, exact.data(), exact.size(), nullptr),
            PRT_OK);
  // NULL arguments.
  EXPECT_EQ(prt_asset_get_info(nullptr, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_asset_section_count(nullptr), 0u);
  EXPECT_EQ(prt_asset_find_section(asset, PRT_SECTION_TRIS, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_asset_copy_section(asset, PRT_SECTION_TRIS, nullptr, 5, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  prt_asset_destroy(asset);
  prt_asset_destroy(nullptr);
}

TEST_F(Asset, LoadArguments) {
  prt_asset* asset = nullptr;
  EXPECT_EQ(
      prt_asset_load_memory(nullptr, golden.data(), golden.size(), PRT_VALIDATE_QUICK, &asset),
      PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(
      prt_asset_load_memory(ctx.ctx, golden.data(), golden.size(), PRT_VALIDATE_QUICK, nullptr),
      PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_asset_load_file(ctx.ctx, nullptr, PRT_VALIDATE_QUICK, &asset),
            PRT_ERROR_INVALID_ARGUMENT);
}

TEST_F(Asset, FileErrors) {
  prt_asset* asset = nullptr;
  EXPECT_EQ(prt_asset_load_file(ctx.ctx, "/nonexistent/blob.prtk", PRT_VALIDATE_FULL, &asset),
            PRT_ERROR_IO);
  EXPECT_NE(std::string(prt_context_last_message(ctx.ctx)).find("/nonexistent/blob.prtk"),
            std::string::npos)
      << "the message names the file";
  EXPECT_EQ(prt_asset_load_file(ctx.ctx, PRT_GOLDEN_DIR, PRT_VALIDATE_FULL, &asset), PRT_ERROR_IO)
      << "a directory";
  // A file that is not a blob names the file and the problem.
  EXPECT_EQ(prt_asset_load_file(ctx.ctx, PRT_GOLDEN_DIR "/README.md", PRT_VALIDATE_FULL, &asset),
            PRT_ERROR_BAD_MAGIC);
  EXPECT_NE(std::string(prt_context_last_message(ctx.ctx)).find("README.md"), std::string::npos);
  EXPECT_EQ(asset, nullptr);
}

TEST_F(Asset, ValidateOnlyReportsAMessage) {
  char msg[256];
  EXPECT_EQ(
      prt_asset_validate(ctx.ctx, golden.data(), golden.size(), PRT_VALIDATE_FULL, msg, sizeof msg),
      PRT_OK);
  EXPECT_NE(std::string(msg).find("4 sections"), std::string::npos) << msg;
  Bytes bad = golden;
  bad[PRT_BLOB_OFF_VERSION_MAJOR] = 9;
  EXPECT_EQ(
      prt_asset_validate(ctx.ctx, bad.data(), bad.size(), PRT_VALIDATE_QUICK, msg, sizeof msg),
      PRT_ERROR_UNSUPPORTED_VERSION);
  EXPECT_NE(std::string(msg).find("9.0"), std::string::npos) << msg;
  EXPECT_EQ(prt_context_last_result(ctx.ctx), PRT_ERROR_UNSUPPORTED_VERSION);
  // A tiny message buffer is cut, never overrun.
  char tiny[8];
  std::memset(tiny, 'x', sizeof tiny);
  prt_asset_validate(ctx.ctx, bad.data(), bad.size(), PRT_VALIDATE_QUICK, tiny, 5);
  EXPECT_EQ(tiny[4], '\0');
  EXPECT_EQ(tiny[5], 'x');
}

// Queries on one asset from several threads at once (the header promises they are safe): all
// threads see the same bytes. Run under the sanitizer builds too.
TEST_F(Asset, ConcurrentQueries) {
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_asset_load_memory(ctx.ctx, golden.data(), golden.size(), PRT_VALIDATE_FULL, &asset),
            PRT_OK);
  std::vector<unsigned> sums(4, 0);
  std::vector<std::thread> threads;
  for (size_t t = 0; t < sums.size(); ++t)
    threads.emplace_back([asset, &sums, t] {
      for (int round = 0; round < 200; ++round)
        for (uint32_t i = 0; i < prt_asset_section_count(asset); ++i) {
          prt_section_info info = prt::sized<prt_section_info>();
          const void* data;
          size_t size;
          if (prt_asset_get_section_info(asset, i, &info) != PRT_OK) return;
          if (prt_asset_section_data(asset, info.tag, &data, &size) != PRT_OK) return;
          for (size_t k = 0; k < size; ++k) sums[t] += static_cast<const uint8_t*>(data)[k];
        }
    });
  for (auto& thread : threads) thread.join();
  EXPECT_NE(sums[0], 0u);
  for (unsigned sum : sums) EXPECT_EQ(sum, sums[0]);
  prt_asset_destroy(asset);
}

// Every allocation failing in turn gives OUT_OF_MEMORY and leaks nothing.
TEST_F(Asset, EveryAllocationFailureIsReported) {
  expect_every_allocation_failure_reported(
      [&](prt_context* c) {
        prt_asset* asset = nullptr;
        const prt_result r =
            prt_asset_load_memory(c, golden.data(), golden.size(), PRT_VALIDATE_FULL, &asset);
        prt_asset_destroy(asset);
        return r;
      },
      "copying load at full validation");
  expect_every_allocation_failure_reported(
      [&](prt_context* c) {
        prt_asset* asset = nullptr;
        const prt_result r =
            prt_asset_load_file(c, golden_path().c_str(), PRT_VALIDATE_QUICK, &asset);
        prt_asset_destroy(asset);
        return r;
      },
      "file load at quick validation");
  expect_every_allocation_failure_reported(
      [&](prt_context* c) {
        return prt_asset_validate(c, golden.data(), golden.size(), PRT_VALIDATE_FULL, nullptr, 0);
      },
      "full validation");
}

}  // namespace
