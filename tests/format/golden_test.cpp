// SPDX-License-Identifier: MIT
// The frozen format-1.0 golden blob decodes to the values its generator was given
// (formats/golden/make_golden.cpp), restated here by hand. Set PRT_GOLDEN_FILE to check another
// file (CTest does so for a freshly generated copy).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "support/blob_test_util.hpp"

namespace {

using namespace prt_test;

std::string golden_file() {
  const char* override_path = std::getenv("PRT_GOLDEN_FILE");
  return override_path ? override_path : golden_path();
}

const float kPositions[9][3] = {{0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f},
                                {0.0f, 0.5f, 0.0f}, {0.5f, 0.5f, 0.0f}, {1.0f, 0.5f, 0.0f},
                                {0.0f, 1.0f, 0.0f}, {0.5f, 1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}};
const uint32_t kTriangles[8][3] = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4},
                                   {3, 4, 7}, {3, 7, 6}, {4, 5, 8}, {4, 8, 7}};
const char kInfo[] = "prtkit golden blob 1.0: 3x3 grid";

class GoldenBlob : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NE(ctx.ctx, nullptr);
    ASSERT_EQ(prt_asset_load_file(ctx.ctx, golden_file().c_str(), PRT_VALIDATE_FULL, &asset),
              PRT_OK)
        << prt_context_last_message(ctx.ctx);
  }
  void TearDown() override { prt_asset_destroy(asset); }

  Context ctx;
  prt_asset* asset = nullptr;
};

TEST_F(GoldenBlob, HeaderFacts) {
  prt_asset_info info = prt::sized<prt_asset_info>();
  ASSERT_EQ(prt_asset_get_info(asset, &info), PRT_OK);
  EXPECT_EQ(info.format_major, 1u);
  EXPECT_EQ(info.format_minor, 0u);
  EXPECT_EQ(info.flags, 0u);
  EXPECT_EQ(info.section_count, 4u);
  EXPECT_EQ(info.total_size, read_file(golden_file()).size());
  EXPECT_EQ(info.total_size % 16, 0u);
  EXPECT_EQ(info.borrowed, 0u);
  uint8_t producer[16] = {'p', 'r', 't', 'k', 'i', 't', '-', 'g', 'o', 'l', 'd', 'e', 'n'};
  EXPECT_EQ(std::memcmp(info.producer, producer, 16), 0);
}

TEST_F(GoldenBlob, SectionTable) {
  struct Expected {
    uint32_t tag, flags;
    prt_codec codec;
    uint64_t raw_size, element_count;
  };
  const Expected expected[4] = {
      {PRT_SECTION_INFO, 0, PRT_CODEC_NONE, sizeof kInfo - 1, sizeof kInfo - 1},
      {PRT_SECTION_VPOS, PRT_SECTION_FLAG_REQUIRED, PRT_CODEC_NONE, 9 * 12, 9},
      {PRT_SECTION_VNRM, 0, PRT_CODEC_ZSTD, 9 * 12, 9},
      {PRT_SECTION_TRIS, PRT_SECTION_FLAG_REQUIRED, PRT_CODEC_NONE, 8 * 12, 8},
  };
  // Canonical layout (SPEC.md §Layout): the table follows the header, sections are packed in table
  // order at 16-byte alignment.
  uint64_t end = 64 + 4 * 48;
  for (uint32_t i = 0; i < 4; ++i) {
    prt_section_info s = prt::sized<prt_section_info>();
    ASSERT_EQ(prt_asset_get_section_info(asset, i, &s), PRT_OK);
    EXPECT_EQ(s.tag, expected[i].tag) << i;
    EXPECT_EQ(s.flags, expected[i].flags) << i;
    EXPECT_EQ(s.codec, expected[i].codec) << i;
    EXPECT_EQ(s.layout_version, 1u) << i;
    EXPECT_EQ(s.known, 1u) << i;
    EXPECT_EQ(s.raw_size, expected[i].raw_size) << i;
    EXPECT_EQ(s.element_count, expected[i].element_count) << i;
    EXPECT_EQ(s.offset, (end + 15) / 16 * 16) << i;
    if (s.codec == PRT_CODEC_NONE) {
      EXPECT_EQ(s.stored_size, s.raw_size) << i;
    } else {
      EXPECT_LT(s.stored_size, s.raw_size) << "zstd must pay";
    }
    end = s.offset + s.stored_size;
  }
  prt_asset_info info = prt::sized<prt_asset_info>();
  ASSERT_EQ(prt_asset_get_info(asset, &info), PRT_OK);
  EXPECT_EQ(info.total_size, (end + 15) / 16 * 16);
}

TEST_F(GoldenBlob, DecodedValues) {
  const void* data;
  size_t size;
  ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_INFO, &data, &size), PRT_OK);
  EXPECT_EQ(std::string(static_cast<const char*>(data), size), kInfo);

  ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_VPOS, &data, &size), PRT_OK);
  ASSERT_EQ(size, sizeof kPositions);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(data) % 16, 0u);
  std::vector<float> positions(27);
  std::memcpy(positions.data(), data, size);
  for (int v = 0; v < 9; ++v)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(positions[3 * v + c], kPositions[v][c]) << v << "," << c;

  ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_VNRM, &data, &size), PRT_OK);
  ASSERT_EQ(size, 9u * 12u);
  std::vector<float> normals(27);
  std::memcpy(normals.data(), data, size);
  for (int v = 0; v < 9; ++v) {
    EXPECT_EQ(normals[3 * v + 0], 0.0f);
    EXPECT_EQ(normals[3 * v + 1], 0.0f);
    EXPECT_EQ(normals[3 * v + 2], 1.0f);
  }

  uint32_t triangles[8][3];
  size_t written = 0;
  ASSERT_EQ(prt_asset_copy_section(asset, PRT_SECTION_TRIS, triangles, sizeof triangles, &written),
            PRT_OK);
  EXPECT_EQ(written, sizeof triangles);
  for (int t = 0; t < 8; ++t)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(triangles[t][c], kTriangles[t][c]) << t << "," << c;
}

// The reader core alone (no runtime) agrees on the structure.
TEST(GoldenBlobReaderCore, StructureAndChecksums) {
  const Bytes blob = read_file(golden_file());
  ASSERT_FALSE(blob.empty());
  prt_blob_header h;
  char msg[256] = "";
  ASSERT_EQ(prt_blob_validate_structure(blob.data(), blob.size(), &h, msg, sizeof msg), PRT_BLOB_OK)
      << msg;
  EXPECT_EQ(h.version_major, 1);
  EXPECT_EQ(h.header_size, 64u);
  EXPECT_EQ(h.table_offset, 64u);
  EXPECT_EQ(h.section_count, 4u);
  EXPECT_EQ(prt_blob_verify_checksums(blob.data(), &h, msg, sizeof msg), PRT_BLOB_OK) << msg;
}

}  // namespace
