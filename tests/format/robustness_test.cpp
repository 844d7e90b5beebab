// SPDX-License-Identifier: MIT
// Bad blobs never crash and each gives its specific error code (formats/SPEC.md §Validation).
// Every case runs on a fresh heap allocation of exactly the blob's size, so AddressSanitizer
// reports any read past the end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <prt/format/blob_writer.hpp>

#include "support/blob_test_util.hpp"

namespace {

using namespace prt_test;

// Golden section indices.
constexpr uint32_t kInfo = 0, kVpos = 1, kVnrm = 2, kTris = 3;

class BadBlob : public ::testing::Test {
 protected:
  void SetUp() override {
    golden = read_file(golden_path());
    ASSERT_EQ(golden.size(), get_u64(golden, PRT_BLOB_OFF_TOTAL_SIZE));
    ASSERT_EQ(validate(ctx.ctx, golden, PRT_VALIDATE_FULL), PRT_OK);
  }

  // Quick and full validation, and loading at both levels, give the expected codes.
  void expect(const Bytes& b, prt_result quick, prt_result full, const char* what) {
    SCOPED_TRACE(what);
    EXPECT_EQ(validate(ctx.ctx, b, PRT_VALIDATE_QUICK), quick) << prt_context_last_message(ctx.ctx);
    EXPECT_EQ(validate(ctx.ctx, b, PRT_VALIDATE_FULL), full) << prt_context_last_message(ctx.ctx);
    EXPECT_EQ(load(ctx.ctx, b, PRT_VALIDATE_QUICK), quick) << prt_context_last_message(ctx.ctx);
    EXPECT_EQ(load(ctx.ctx, b, PRT_VALIDATE_FULL), full) << prt_context_last_message(ctx.ctx);
  }

  Context ctx;
  Bytes golden;
};

TEST_F(BadBlob, EveryTruncatedPrefixIsTruncated) {
  for (size_t n = 0; n < golden.size(); ++n) {
    const Bytes prefix(golden.begin(), golden.begin() + n);
    ASSERT_EQ(validate(ctx.ctx, prefix, PRT_VALIDATE_QUICK), PRT_ERROR_TRUNCATED) << n;
    ASSERT_EQ(validate(ctx.ctx, prefix, PRT_VALIDATE_FULL), PRT_ERROR_TRUNCATED) << n;
    ASSERT_EQ(load(ctx.ctx, prefix, PRT_VALIDATE_FULL), PRT_ERROR_TRUNCATED) << n;
  }
}

TEST_F(BadBlob, ExtraTrailingByte) {
  Bytes b = golden;
  b.push_back(0);
  expect(b, PRT_ERROR_SIZE_MISMATCH, PRT_ERROR_SIZE_MISMATCH, "one extra byte");
  // Extra zero bytes declared in total_size are still not the canonical end.
  b.resize(golden.size() + 16, 0);
  put_u64(b, PRT_BLOB_OFF_TOTAL_SIZE, b.size());
  fix_header_checksum(b);
  expect(b, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT, "16 declared bytes after the last section");
}

TEST_F(BadBlob, HeaderFields) {
  struct Case {
    const char* what;
    size_t offset;
    int width;  // bytes: 1, 2, 4, 8
    uint64_t value;
    prt_result quick, full;
  };
  const uint64_t kMax = std::numeric_limits<uint64_t>::max();
  const uint64_t size = golden.size();
  const Case cases[] = {
      {"magic", PRT_BLOB_OFF_MAGIC, 1, 'X', PRT_ERROR_BAD_MAGIC, PRT_ERROR_BAD_MAGIC},
      {"magic last byte", PRT_BLOB_OFF_MAGIC + 3, 1, 'k', PRT_ERROR_BAD_MAGIC, PRT_ERROR_BAD_MAGIC},
      {"major 2", PRT_BLOB_OFF_VERSION_MAJOR, 2, 2, PRT_ERROR_UNSUPPORTED_VERSION,
       PRT_ERROR_UNSUPPORTED_VERSION},
      {"major 0", PRT_BLOB_OFF_VERSION_MAJOR, 2, 0, PRT_ERROR_UNSUPPORTED_VERSION,
       PRT_ERROR_UNSUPPORTED_VERSION},
      {"minor 1", PRT_BLOB_OFF_VERSION_MINOR, 2, 1, PRT_OK, PRT_ERROR_CHECKSUM_MISMATCH},
      {"header size 65", PRT_BLOB_OFF_HEADER_SIZE, 4, 65, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"header size 48", PRT_BLOB_OFF_HEADER_SIZE, 4, 48, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"header size 80", PRT_BLOB_OFF_HEADER_SIZE, 4, 80, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"header size huge", PRT_BLOB_OFF_HEADER_SIZE, 4, 0xFFFFFFF0u, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"critical flag", PRT_BLOB_OFF_FLAGS, 4, 1, PRT_ERROR_UNSUPPORTED_FEATURE,
       PRT_ERROR_UNSUPPORTED_FEATURE},
      {"informational flag", PRT_BLOB_OFF_FLAGS, 4, 1u << 16, PRT_OK, PRT_ERROR_CHECKSUM_MISMATCH},
      {"total size + 16", PRT_BLOB_OFF_TOTAL_SIZE, 8, size + 16, PRT_ERROR_TRUNCATED,
       PRT_ERROR_TRUNCATED},
      {"total size max", PRT_BLOB_OFF_TOTAL_SIZE, 8, kMax, PRT_ERROR_TRUNCATED,
       PRT_ERROR_TRUNCATED},
      {"total size - 16", PRT_BLOB_OFF_TOTAL_SIZE, 8, size - 16, PRT_ERROR_SIZE_MISMATCH,
       PRT_ERROR_SIZE_MISMATCH},
      {"total size 0", PRT_BLOB_OFF_TOTAL_SIZE, 8, 0, PRT_ERROR_SIZE_MISMATCH,
       PRT_ERROR_SIZE_MISMATCH},
      {"table offset 80", PRT_BLOB_OFF_TABLE_OFFSET, 8, 80, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"table offset max", PRT_BLOB_OFF_TABLE_OFFSET, 8, kMax - 15, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"section count + 1", PRT_BLOB_OFF_SECTION_COUNT, 4, 5, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"section count 0", PRT_BLOB_OFF_SECTION_COUNT, 4, 0, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"section count 3", PRT_BLOB_OFF_SECTION_COUNT, 4, 3, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"section count huge", PRT_BLOB_OFF_SECTION_COUNT, 4, 0xFFFFFFFFu, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"checksum", PRT_BLOB_OFF_CHECKSUM, 1, golden[PRT_BLOB_OFF_CHECKSUM] ^ 0x01u, PRT_OK,
       PRT_ERROR_CHECKSUM_MISMATCH},
      {"producer", PRT_BLOB_OFF_PRODUCER + 15, 1, 'x', PRT_OK, PRT_ERROR_CHECKSUM_MISMATCH},
      {"reserved first", PRT_BLOB_OFF_RESERVED, 1, 1, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"reserved last", PRT_BLOB_OFF_RESERVED + 7, 1, 0x80, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
  };
  for (const Case& c : cases) {
    Bytes b = golden;
    switch (c.width) {
      case 1:
        b[c.offset] = static_cast<uint8_t>(c.value);
        break;
      case 2:
        put_u16(b, c.offset, static_cast<uint16_t>(c.value));
        break;
      case 4:
        put_u32(b, c.offset, static_cast<uint32_t>(c.value));
        break;
      default:
        put_u64(b, c.offset, c.value);
        break;
    }
    expect(b, c.quick, c.full, c.what);
  }
}

// Forward compatibility: a newer minor version and unknown informational flags are accepted.
TEST_F(BadBlob, NewerMinorAndInformationalFlagsAreAccepted) {
  Bytes b = golden;
  put_u16(b, PRT_BLOB_OFF_VERSION_MINOR, 7);
  put_u32(b, PRT_BLOB_OFF_FLAGS, 0xABCD0000u);
  fix_header_checksum(b);
  expect(b, PRT_OK, PRT_OK, "minor 7, informational flags");
}

TEST_F(BadBlob, SectionTableFields) {
  struct Case {
    const char* what;
    uint32_t section;
    size_t field;
    int width;
    uint64_t value;
    prt_result quick, full;  // full: with the header checksum recomputed
  };
  const uint64_t kMax = std::numeric_limits<uint64_t>::max();
  const Case cases[] = {
      {"required tag unknown", kVpos, PRT_BLOB_SEC_OFF_TAG, 1, 'X', PRT_ERROR_UNSUPPORTED_FEATURE,
       PRT_ERROR_UNSUPPORTED_FEATURE},
      {"optional tag unknown", kInfo, PRT_BLOB_SEC_OFF_TAG, 1, 'X', PRT_OK, PRT_OK},
      {"tag not printable", kInfo, PRT_BLOB_SEC_OFF_TAG, 1, 0x01, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"duplicate tag", kVnrm, PRT_BLOB_SEC_OFF_TAG, 4, PRT_BLOB_TAG_TRIS, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"required tag renamed", kVpos, PRT_BLOB_SEC_OFF_TAG, 4, PRT_BLOB_TAG('V', 'P', 'O', 'Z'),
       PRT_ERROR_UNSUPPORTED_FEATURE, PRT_ERROR_UNSUPPORTED_FEATURE},
      {"unknown flag bit", kInfo, PRT_BLOB_SEC_OFF_FLAGS, 2, 0x0002, PRT_ERROR_UNSUPPORTED_FEATURE,
       PRT_ERROR_UNSUPPORTED_FEATURE},
      {"known section marked required", kInfo, PRT_BLOB_SEC_OFF_FLAGS, 2, 0x0001, PRT_OK, PRT_OK},
      {"unknown codec", kVpos, PRT_BLOB_SEC_OFF_CODEC, 1, 7, PRT_ERROR_UNSUPPORTED_FEATURE,
       PRT_ERROR_UNSUPPORTED_FEATURE},
      {"zstd section marked raw", kVnrm, PRT_BLOB_SEC_OFF_CODEC, 1, PRT_BLOB_CODEC_NONE,
       PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"required layout version 2", kTris, PRT_BLOB_SEC_OFF_LAYOUT_VERSION, 1, 2,
       PRT_ERROR_UNSUPPORTED_FEATURE, PRT_ERROR_UNSUPPORTED_FEATURE},
      {"optional layout version 2", kInfo, PRT_BLOB_SEC_OFF_LAYOUT_VERSION, 1, 2, PRT_OK, PRT_OK},
      {"section checksum", kTris, PRT_BLOB_SEC_OFF_CHECKSUM, 4, 0x12345678u, PRT_OK,
       PRT_ERROR_CHECKSUM_MISMATCH},
      {"reserved", kVpos, PRT_BLOB_SEC_OFF_RESERVED, 4, 1, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"offset + 16", kVpos, PRT_BLOB_SEC_OFF_OFFSET, 8, 288 + 16, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"offset unaligned", kInfo, PRT_BLOB_SEC_OFF_OFFSET, 8, 257, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"offset max", kTris, PRT_BLOB_SEC_OFF_OFFSET, 8, kMax - 15, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"offset into table", kInfo, PRT_BLOB_SEC_OFF_OFFSET, 8, 64, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"stored size past end", kTris, PRT_BLOB_SEC_OFF_STORED_SIZE, 8, 97, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"stored size max", kTris, PRT_BLOB_SEC_OFF_STORED_SIZE, 8, kMax, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"stored != raw", kVpos, PRT_BLOB_SEC_OFF_STORED_SIZE, 8, 104, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"raw size beyond zstd ratio", kVnrm, PRT_BLOB_SEC_OFF_RAW_SIZE, 8, uint64_t{1} << 40,
       PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"raw size != count x 12", kVnrm, PRT_BLOB_SEC_OFF_RAW_SIZE, 8, 120, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"element count", kVpos, PRT_BLOB_SEC_OFF_ELEMENT_COUNT, 8, 10, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
      {"element count overflow", kVpos, PRT_BLOB_SEC_OFF_ELEMENT_COUNT, 8, (kMax / 12) + 2,
       PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT},
      {"count x 1 != raw size", kInfo, PRT_BLOB_SEC_OFF_ELEMENT_COUNT, 8, 33, PRT_ERROR_CORRUPT,
       PRT_ERROR_CORRUPT},
  };
  for (const Case& c : cases) {
    Bytes b = golden;
    const size_t at = entry(c.section) + c.field;
    switch (c.width) {
      case 1:
        b[at] = static_cast<uint8_t>(c.value);
        break;
      case 2:
        put_u16(b, at, static_cast<uint16_t>(c.value));
        break;
      case 4:
        put_u32(b, at, static_cast<uint32_t>(c.value));
        break;
      default:
        put_u64(b, at, c.value);
        break;
    }
    SCOPED_TRACE(c.what);
    // Without a fixed header checksum, whatever passes the quick checks fails on the checksum.
    EXPECT_EQ(validate(ctx.ctx, b, PRT_VALIDATE_QUICK), c.quick);
    EXPECT_EQ(validate(ctx.ctx, b, PRT_VALIDATE_FULL),
              c.quick == PRT_OK ? PRT_ERROR_CHECKSUM_MISMATCH : c.quick);
    fix_header_checksum(b);
    expect(b, c.quick, c.full, c.what);
  }
}

// Relations between kinds: TRIS and VNRM need VPOS, with one normal per vertex.
TEST_F(BadBlob, MissingDependency) {
  Bytes b = golden;
  put_u32(b, entry(kVpos) + PRT_BLOB_SEC_OFF_TAG, PRT_BLOB_TAG('V', 'P', 'O', 'Z'));
  put_u16(b, entry(kVpos) + PRT_BLOB_SEC_OFF_FLAGS, 0);  // now an unknown optional section
  fix_header_checksum(b);
  expect(b, PRT_ERROR_CORRUPT, PRT_ERROR_CORRUPT, "TRIS and VNRM without VPOS");
}

// A raw section relabelled as zstd passes the quick checks but cannot be decoded: loading (which
// decodes) fails at both levels, quick validation alone (which does not decode) passes.
TEST_F(BadBlob, RawBytesLabelledZstd) {
  Bytes b = golden;
  b[entry(kVpos) + PRT_BLOB_SEC_OFF_CODEC] = PRT_BLOB_CODEC_ZSTD;
  fix_header_checksum(b);
  EXPECT_EQ(validate(ctx.ctx, b, PRT_VALIDATE_QUICK), PRT_OK);
  EXPECT_EQ(validate(ctx.ctx, b, PRT_VALIDATE_FULL), PRT_ERROR_CORRUPT);
  EXPECT_EQ(load(ctx.ctx, b, PRT_VALIDATE_QUICK), PRT_ERROR_CORRUPT);
  EXPECT_EQ(load(ctx.ctx, b, PRT_VALIDATE_FULL), PRT_ERROR_CORRUPT);
}

// An empty zstd section still has to be one well-formed frame.
TEST_F(BadBlob, EmptyZstdSectionMustBeAFrame) {
  Bytes b = golden;
  b[entry(kInfo) + PRT_BLOB_SEC_OFF_CODEC] = PRT_BLOB_CODEC_ZSTD;
  put_u64(b, entry(kInfo) + PRT_BLOB_SEC_OFF_RAW_SIZE, 0);
  put_u64(b, entry(kInfo) + PRT_BLOB_SEC_OFF_ELEMENT_COUNT, 0);
  fix_header_checksum(b);
  EXPECT_EQ(validate(ctx.ctx, b, PRT_VALIDATE_QUICK), PRT_OK);
  EXPECT_EQ(validate(ctx.ctx, b, PRT_VALIDATE_FULL), PRT_ERROR_CORRUPT);
  EXPECT_EQ(load(ctx.ctx, b, PRT_VALIDATE_QUICK), PRT_ERROR_CORRUPT);
}

TEST_F(BadBlob, ContentChecks) {
  const uint64_t vpos = get_u64(golden, entry(kVpos) + PRT_BLOB_SEC_OFF_OFFSET);
  const uint64_t tris = get_u64(golden, entry(kTris) + PRT_BLOB_SEC_OFF_OFFSET);
  const uint64_t info = get_u64(golden, entry(kInfo) + PRT_BLOB_SEC_OFF_OFFSET);
  const uint32_t kNan = 0x7FC00000u, kInf = 0x7F800000u, kNegInf = 0xFF800000u;
  for (uint32_t bits : {kNan, kInf, kNegInf}) {
    Bytes b = golden;
    put_u32(b, vpos + 4 * 13, bits);
    fix_section_checksum(b, kVpos);
    expect(b, PRT_OK, PRT_ERROR_NON_FINITE, "non-finite position");
  }
  {
    Bytes b = golden;
    put_u32(b, tris + 4 * 23, 9);  // the vertex count: one past the last vertex
    fix_section_checksum(b, kTris);
    expect(b, PRT_OK, PRT_ERROR_INDEX_OUT_OF_RANGE, "index = vertex count");
    put_u32(b, tris + 4 * 23, 0xFFFFFFFFu);
    fix_section_checksum(b, kTris);
    expect(b, PRT_OK, PRT_ERROR_INDEX_OUT_OF_RANGE, "index max");
  }
  {
    Bytes b = golden;
    b[info + 5] = 0xFF;  // never valid in UTF-8
    fix_section_checksum(b, kInfo);
    expect(b, PRT_OK, PRT_ERROR_CORRUPT, "INFO not UTF-8");
  }
  {
    Bytes b = golden;
    b[vpos + 108 + 1] = 0x20;  // the padding after VPOS (108 bytes, padded to 112)
    expect(b, PRT_OK, PRT_ERROR_CORRUPT, "non-zero padding");
  }
}

// Content checks also run on decompressed sections.
TEST_F(BadBlob, NonFiniteInsideCompressedSection) {
  prt::format::BlobWriter writer;
  std::vector<float> positions(3 * 64, 1.0f);
  positions[100] = std::numeric_limits<float>::quiet_NaN();
  prt::format::SectionOptions packed;
  packed.compression = prt::format::Compression::kZstd;
  writer.add_section(PRT_BLOB_TAG_VPOS, positions.data(), positions.size() * 4, 64, packed);
  const Bytes b = writer.finish();
  ASSERT_EQ(b[entry(0) + PRT_BLOB_SEC_OFF_CODEC], PRT_BLOB_CODEC_ZSTD);
  expect(b, PRT_OK, PRT_ERROR_NON_FINITE, "NaN in zstd VPOS");
}

// Every single-bit flip of the golden blob is detected by full validation, and no flip crashes
// quick validation or loading.
TEST_F(BadBlob, EverySingleBitFlip) {
  for (size_t bit = 0; bit < golden.size() * 8; ++bit) {
    Bytes b = golden;
    b[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    ASSERT_NE(validate(ctx.ctx, b, PRT_VALIDATE_FULL), PRT_OK) << "bit " << bit;
    ASSERT_NE(load(ctx.ctx, b, PRT_VALIDATE_FULL), PRT_OK) << "bit " << bit;
    load(ctx.ctx, b, PRT_VALIDATE_QUICK);  // any result, but no crash or over-read
  }
}

TEST_F(BadBlob, RandomMultiBitFlips) {
  std::mt19937 rng(20261121u);  // fixed seed: the same cases every run
  std::uniform_int_distribution<size_t> pick_bit(0, golden.size() * 8 - 1);
  std::uniform_int_distribution<int> pick_count(2, 12);
  for (int trial = 0; trial < 5000; ++trial) {
    Bytes b = golden;
    const int flips = pick_count(rng);
    for (int k = 0; k < flips; ++k) {
      const size_t bit = pick_bit(rng);
      b[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    }
    if (b == golden) continue;  // flips that cancelled out
    ASSERT_NE(validate(ctx.ctx, b, PRT_VALIDATE_FULL), PRT_OK) << "trial " << trial;
    ASSERT_NE(load(ctx.ctx, b, PRT_VALIDATE_FULL), PRT_OK) << "trial " << trial;
    validate(ctx.ctx, b, PRT_VALIDATE_QUICK);
    load(ctx.ctx, b, PRT_VALIDATE_QUICK);
  }
}

TEST_F(BadBlob, NullAndEmptyInput) {
  char msg[64];
  EXPECT_EQ(prt_asset_validate(ctx.ctx, nullptr, 0, PRT_VALIDATE_FULL, msg, sizeof msg),
            PRT_ERROR_TRUNCATED);
  EXPECT_EQ(prt_asset_validate(ctx.ctx, nullptr, 10, PRT_VALIDATE_FULL, msg, sizeof msg),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_asset_validate(ctx.ctx, golden.data(), golden.size(),
                               static_cast<prt_validation>(5), msg, sizeof msg),
            PRT_ERROR_INVALID_ARGUMENT);
}

}  // namespace
