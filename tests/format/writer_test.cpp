// SPDX-License-Identifier: MIT
// The writer: round trip through the runtime, determinism, zstd only where it pays, refusals.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <stdexcept>
#include <string>

#include <prt/format/blob_writer.hpp>

#include "support/blob_test_util.hpp"

namespace {

using namespace prt_test;
using prt::format::BlobWriter;
using prt::format::Compression;
using prt::format::SectionOptions;

SectionOptions zstd_options() {
  SectionOptions o;
  o.compression = Compression::kZstd;
  return o;
}

// A mesh-like blob: a fan of `n` triangles around vertex 0, plus an unknown optional section.
Bytes make_blob(uint32_t n, Compression compression) {
  std::vector<float> positions;
  std::vector<uint32_t> triangles;
  for (uint32_t v = 0; v <= n + 1; ++v) positions.insert(positions.end(), {float(v), 2.0f, -1.0f});
  for (uint32_t t = 0; t < n; ++t) triangles.insert(triangles.end(), {0, t + 1, t + 2});
  SectionOptions mesh;
  mesh.required = true;
  mesh.compression = compression;
  BlobWriter w;
  w.set_producer("writer-test");
  w.add_section(PRT_BLOB_TAG_VPOS, positions.data(), positions.size() * 4, n + 2, mesh);
  w.add_section(PRT_BLOB_TAG_TRIS, triangles.data(), triangles.size() * 4, n, mesh);
  const std::string note = "an optional section this runtime does not know";
  w.add_section(prt::format::make_tag('N', 'O', 'T', 'E'), note.data(), note.size(), 1);
  return w.finish();
}

TEST(BlobWriter, RoundTripThroughTheRuntime) {
  for (Compression compression : {Compression::kNone, Compression::kZstd}) {
    const uint32_t n = 1000;
    const Bytes blob = make_blob(n, compression);
    Context ctx;
    prt_asset* asset = nullptr;
    ASSERT_EQ(prt_asset_load_memory(ctx.ctx, blob.data(), blob.size(), PRT_VALIDATE_FULL, &asset),
              PRT_OK)
        << prt_context_last_message(ctx.ctx);
    ASSERT_EQ(prt_asset_section_count(asset), 3u);
    prt_section_info info = prt::sized<prt_section_info>();
    ASSERT_EQ(prt_asset_get_section_info(asset, 0, &info), PRT_OK);
    EXPECT_EQ(info.codec, compression == Compression::kZstd ? PRT_CODEC_ZSTD : PRT_CODEC_NONE);
    EXPECT_EQ(info.flags, PRT_SECTION_FLAG_REQUIRED);
    ASSERT_EQ(prt_asset_get_section_info(asset, 2, &info), PRT_OK);
    EXPECT_EQ(info.known, 0u);
    EXPECT_EQ(info.flags, 0u);

    const void* data;
    size_t size;
    ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_TRIS, &data, &size), PRT_OK);
    ASSERT_EQ(size, size_t{n} * 12);
    std::vector<uint32_t> triangles(3 * n);
    std::memcpy(triangles.data(), data, size);
    for (uint32_t t = 0; t < n; ++t) {
      EXPECT_EQ(triangles[3 * t], 0u);
      EXPECT_EQ(triangles[3 * t + 1], t + 1);
      EXPECT_EQ(triangles[3 * t + 2], t + 2);
    }
    ASSERT_EQ(prt_asset_section_data(asset, PRT_SECTION_VPOS, &data, &size), PRT_OK);
    std::vector<float> positions(size / 4);
    std::memcpy(positions.data(), data, size);
    for (uint32_t v = 0; v <= n + 1; ++v) EXPECT_EQ(positions[3 * v], float(v));
    prt_asset_destroy(asset);
  }
}

TEST(BlobWriter, Deterministic) {
  for (Compression compression : {Compression::kNone, Compression::kZstd}) {
    const Bytes a = make_blob(5000, compression);
    const Bytes b = make_blob(5000, compression);
    EXPECT_EQ(a, b);
  }
  BlobWriter w;
  const char text[] = "same writer, finished twice";
  w.add_section(PRT_BLOB_TAG_INFO, text, sizeof text - 1, sizeof text - 1, zstd_options());
  EXPECT_EQ(w.finish(), w.finish());
}

TEST(BlobWriter, ZstdOnlyWherePays) {
  std::vector<uint8_t> noise(4096);
  std::mt19937 rng(7);
  for (auto& byte : noise) byte = static_cast<uint8_t>(rng());
  std::vector<uint8_t> zeros(4096, 0);
  BlobWriter w;
  w.add_section(prt::format::make_tag('N', 'O', 'I', 'S'), noise.data(), noise.size(), 0,
                zstd_options());
  w.add_section(prt::format::make_tag('Z', 'E', 'R', 'O'), zeros.data(), zeros.size(), 0,
                zstd_options());
  const Bytes blob = w.finish();
  EXPECT_EQ(blob[entry(0) + PRT_BLOB_SEC_OFF_CODEC], PRT_BLOB_CODEC_NONE);
  EXPECT_EQ(get_u64(blob, entry(0) + PRT_BLOB_SEC_OFF_STORED_SIZE), 4096u);
  EXPECT_EQ(blob[entry(1) + PRT_BLOB_SEC_OFF_CODEC], PRT_BLOB_CODEC_ZSTD);
  EXPECT_LT(get_u64(blob, entry(1) + PRT_BLOB_SEC_OFF_STORED_SIZE), 100u);
  Context ctx;
  EXPECT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_FULL), PRT_OK);
}

TEST(BlobWriter, EmptyBlobAndEmptySection) {
  BlobWriter empty;
  const Bytes header_only = empty.finish();
  EXPECT_EQ(header_only.size(), 64u);
  Context ctx;
  EXPECT_EQ(validate(ctx.ctx, header_only, PRT_VALIDATE_FULL), PRT_OK);

  BlobWriter w;
  w.add_section(PRT_BLOB_TAG_INFO, nullptr, 0, 0, zstd_options());
  const Bytes blob = w.finish();
  EXPECT_EQ(blob.size(), 64u + 48u);
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_asset_load_memory(ctx.ctx, blob.data(), blob.size(), PRT_VALIDATE_FULL, &asset),
            PRT_OK);
  const void* data = &blob;
  size_t size = 1;
  EXPECT_EQ(prt_asset_section_data(asset, PRT_SECTION_INFO, &data, &size), PRT_OK);
  EXPECT_EQ(size, 0u);
  prt_asset_destroy(asset);
}

TEST(BlobWriter, UnknownRequiredSectionIsRejectedByReaders) {
  BlobWriter w;
  SectionOptions required;
  required.required = true;
  const uint32_t payload = 42;
  w.add_section(prt::format::make_tag('F', 'U', 'T', 'R'), &payload, 4, 1, required);
  const Bytes blob = w.finish();
  Context ctx;
  EXPECT_EQ(validate(ctx.ctx, blob, PRT_VALIDATE_QUICK), PRT_ERROR_UNSUPPORTED_FEATURE);
  EXPECT_EQ(load(ctx.ctx, blob, PRT_VALIDATE_FULL), PRT_ERROR_UNSUPPORTED_FEATURE);
}

TEST(BlobWriter, Refusals) {
  BlobWriter w;
  const float xyz[3] = {1, 2, 3};
  EXPECT_THROW(w.add_section(PRT_BLOB_TAG('a', 'b', 'c', '\n'), xyz, 12, 1), std::invalid_argument);
  EXPECT_THROW(w.add_section(PRT_BLOB_TAG_VPOS, xyz, 12, 2),
               std::invalid_argument);  // 2 x 12 != 12
  EXPECT_THROW(w.add_section(prt::format::make_tag('U', 'N', 'K', 'N'), xyz, 12, 13),
               std::invalid_argument);  // more elements than bytes
  EXPECT_THROW(w.add_section(PRT_BLOB_TAG_VPOS, nullptr, 12, 1), std::invalid_argument);
  w.add_section(PRT_BLOB_TAG_VPOS, xyz, 12, 1);
  EXPECT_THROW(w.add_section(PRT_BLOB_TAG_VPOS, xyz, 12, 1), std::invalid_argument);  // twice

  BlobWriter orphan;  // TRIS needs VPOS
  const uint32_t tri[3] = {0, 0, 0};
  orphan.add_section(PRT_BLOB_TAG_TRIS, tri, 12, 1);
  EXPECT_THROW(orphan.finish(), std::invalid_argument);
}

TEST(BlobWriter, WriteFileAndLoadFile) {
  const std::string path = ::testing::TempDir() + "prt_writer_test.prtk";
  BlobWriter w;
  const char text[] = "file round trip";
  w.add_section(PRT_BLOB_TAG_INFO, text, sizeof text - 1, sizeof text - 1);
  w.write_file(path);
  EXPECT_EQ(read_file(path), w.finish());
  Context ctx;
  prt_asset* asset = nullptr;
  ASSERT_EQ(prt_asset_load_file(ctx.ctx, path.c_str(), PRT_VALIDATE_FULL, &asset), PRT_OK);
  char out[32] = {};
  size_t size = 0;
  EXPECT_EQ(prt_asset_copy_section(asset, PRT_SECTION_INFO, out, sizeof out, &size), PRT_OK);
  EXPECT_EQ(std::string(out, size), "file round trip");
  prt_asset_destroy(asset);
  EXPECT_THROW(w.write_file("/nonexistent-dir/x.prtk"), std::runtime_error);
}

// Published CRC-32C check values (RFC 3720 appendix B.4 and the common "123456789" check).
TEST(Crc32c, PublishedCheckValues) {
  EXPECT_EQ(prt_crc32c(0, "123456789", 9), 0xE3069283u);
  uint8_t buf[32];
  std::memset(buf, 0, sizeof buf);
  EXPECT_EQ(prt_crc32c(0, buf, 32), 0x8A9136AAu);
  std::memset(buf, 0xFF, sizeof buf);
  EXPECT_EQ(prt_crc32c(0, buf, 32), 0x62A8AB43u);
  for (int i = 0; i < 32; ++i) buf[i] = static_cast<uint8_t>(i);
  EXPECT_EQ(prt_crc32c(0, buf, 32), 0x46DD794Eu);
  // Chaining equals one pass.
  EXPECT_EQ(prt_crc32c(prt_crc32c(0, buf, 10), buf + 10, 22), 0x46DD794Eu);
}

TEST(LittleEndian, ByteOrderIndependentOfHost) {
  uint8_t b[8];
  prt_le_store_u64(b, 0x0102030405060708ull);
  const uint8_t expected[8] = {8, 7, 6, 5, 4, 3, 2, 1};
  EXPECT_EQ(std::memcmp(b, expected, 8), 0);
  EXPECT_EQ(prt_le_load_u32(b + 1), 0x04050607u);  // unaligned load
  EXPECT_EQ(prt_le_load_u16(b + 3), 0x0405u);
  EXPECT_EQ(PRT_BLOB_TAG_VPOS, prt_le_load_u32(reinterpret_cast<const uint8_t*>("VPOS")));
}

}  // namespace
