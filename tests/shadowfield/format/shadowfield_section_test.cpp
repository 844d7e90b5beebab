// SPDX-License-Identifier: MIT
// The SFLD checks (formats/SPEC.md §7.5): each header field out of range, the element count, a
// wrong size, a non-finite or out-of-range float, a negative scale, non-zero padding or reserved
// words, each changed in the encoder's bytes and stored raw, fails the load with the stated
// status and a message naming the field. Header failures fail at quick validation too (the load
// checks the header, CORRUPT); content failures only at full validation.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

#include "shadowfield/sfld_test_object.hpp"
#include "support/mesh_blob.hpp"

namespace {

using namespace prt_test;
using prt::bake::ShadowfieldObject;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

Bytes encoded(const ShadowfieldObject& o, int bits = 16) {
  return prt::bake::encode_sfld_section(o, prt::bake::quantize_shadowfield(o, bits));
}

void put_f32(Bytes& b, std::size_t off, float f) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  put_u32(b, off, bits);
}

struct Outcome {
  prt_result result;
  std::string message;
};

Outcome load_blob(const Bytes& blob, prt_validation level) {
  Context ctx;
  const LoadedAsset a(ctx.ctx, blob, level);
  return {a.result, a.result == PRT_OK ? "" : prt_context_last_message(ctx.ctx)};
}

// Full validation fails with `full` naming `field`; quick validation with CORRUPT (header) or
// not at all (contents: header_only false).
void expect_rejected(const ShadowfieldObject& o, const Bytes& sfld, prt_result full,
                     const char* field, bool header = true) {
  SCOPED_TRACE(field);
  const Bytes blob = sf_raw_blob(o, sfld);
  const Outcome f = load_blob(blob, PRT_VALIDATE_FULL);
  EXPECT_EQ(f.result, full) << f.message;
  EXPECT_NE(f.message.find("SFLD"), std::string::npos) << f.message;
  EXPECT_NE(f.message.find(field), std::string::npos) << f.message;
  const Outcome q = load_blob(blob, PRT_VALIDATE_QUICK);
  EXPECT_EQ(q.result, header ? PRT_ERROR_CORRUPT : PRT_OK) << q.message;
  if (header) {
    EXPECT_NE(q.message.find(field), std::string::npos) << q.message;
  }
}

void expect_header_u32(std::size_t offset, std::uint32_t value, const char* field,
                       bool glossy = true) {
  const ShadowfieldObject o = sf_test_object(glossy);
  Bytes sfld = encoded(o);
  put_u32(sfld, offset, value);
  expect_rejected(o, sfld, PRT_ERROR_CORRUPT, field);
}

TEST(ShadowfieldSection, BaselineLoadsAtBothLevels) {
  for (bool glossy : {true, false}) {
    const ShadowfieldObject o = sf_test_object(glossy);
    for (int bits : {8, 16}) {
      const Bytes blob = sf_raw_blob(o, encoded(o, bits));
      EXPECT_EQ(load_blob(blob, PRT_VALIDATE_FULL).result, PRT_OK);
      EXPECT_EQ(load_blob(blob, PRT_VALIDATE_QUICK).result, PRT_OK);
    }
  }
}

TEST(ShadowfieldSection, HeaderFieldsOutOfRange) {
  expect_header_u32(PRT_BLOB_SFLD_OFF_ORDER, 1, "order");
  expect_header_u32(PRT_BLOB_SFLD_OFF_ORDER, 7, "order");
  expect_header_u32(PRT_BLOB_SFLD_OFF_TERMS, 0, "terms");
  expect_header_u32(PRT_BLOB_SFLD_OFF_TERMS, 9, "terms");
  expect_header_u32(PRT_BLOB_SFLD_OFF_TERMS, 2, "diffuse", false);
  expect_header_u32(PRT_BLOB_SFLD_OFF_GLOSSY, 2, "glossy");
  expect_header_u32(PRT_BLOB_SFLD_OFF_VERTICES, 0, "vertices");
  expect_header_u32(PRT_BLOB_SFLD_OFF_BASIS, 0, "basis size");
  expect_header_u32(PRT_BLOB_SFLD_OFF_BASIS, 65, "basis size");
  expect_header_u32(PRT_BLOB_SFLD_OFF_BASIS, 7, "basis size");  // more than the 6 vertices
  expect_header_u32(PRT_BLOB_SFLD_OFF_BRDF_GRID, 3, "BRDF grid");
  expect_header_u32(PRT_BLOB_SFLD_OFF_BRDF_GRID, 65, "BRDF grid");
  expect_header_u32(PRT_BLOB_SFLD_OFF_BRDF_GRID, 4, "BRDF grid", false);
  expect_header_u32(PRT_BLOB_SFLD_OFF_BITS, 12, "bits");
  expect_header_u32(PRT_BLOB_SFLD_OFF_FLAGS, 1, "flags");
  for (std::size_t r = 0; r < PRT_BLOB_SFLD_RESERVED_SIZE; r += 4)
    expect_header_u32(PRT_BLOB_SFLD_OFF_RESERVED + r, 1, "reserved");
}

// The header's vertex count against VPOS's: full validation compares them in the checker;
// quick validation sees a size that does not follow from the header first.
TEST(ShadowfieldSection, VertexCountIsVposCount) {
  const ShadowfieldObject o = sf_test_object();
  Bytes sfld = encoded(o);
  put_u32(sfld, PRT_BLOB_SFLD_OFF_VERTICES, 5);
  const Bytes blob = sf_raw_blob(o, sfld);
  const Outcome f = load_blob(blob, PRT_VALIDATE_FULL);
  EXPECT_EQ(f.result, PRT_ERROR_CORRUPT);
  EXPECT_NE(f.message.find("'VPOS' has 6"), std::string::npos) << f.message;
  EXPECT_EQ(load_blob(blob, PRT_VALIDATE_QUICK).result, PRT_ERROR_CORRUPT);
}

// The same object with one vertex fewer in the mesh: the SFLD bytes are self-consistent, so
// only the comparison with the mesh catches it, at full validation in the checker and at quick
// validation when the load decodes the object.
TEST(ShadowfieldSection, MeshOfAnotherSizeFailsBothLevels) {
  const ShadowfieldObject o = sf_test_object();
  ShadowfieldObject smaller = o;
  smaller.positions.pop_back();
  smaller.normals.pop_back();
  smaller.indices = {0, 1, 2};
  const Bytes blob = sf_raw_blob(smaller, encoded(o));
  const Outcome f = load_blob(blob, PRT_VALIDATE_FULL);
  EXPECT_EQ(f.result, PRT_ERROR_CORRUPT);
  EXPECT_NE(f.message.find("'VPOS' has 5"), std::string::npos) << f.message;
  const Outcome q = load_blob(blob, PRT_VALIDATE_QUICK);
  EXPECT_EQ(q.result, PRT_ERROR_CORRUPT);
  EXPECT_NE(q.message.find("'VPOS' has 5"), std::string::npos) << q.message;
}

TEST(ShadowfieldSection, ShellGridsOutOfRange) {
  struct Case {
    std::size_t offset;
    float value;
    prt_result full;
    const char* field;
  };
  const Case cases[] = {
      {PRT_BLOB_SFLD_SHELL_OFF_CENTRE + 4, kNaN, PRT_ERROR_NON_FINITE, "centre"},
      {PRT_BLOB_SFLD_SHELL_OFF_RADIUS, kInf, PRT_ERROR_NON_FINITE, "radius"},
      {PRT_BLOB_SFLD_SHELL_OFF_RADIUS, 0.0f, PRT_ERROR_CORRUPT, "radius"},
      {PRT_BLOB_SFLD_SHELL_OFF_RADIUS, -1.0f, PRT_ERROR_CORRUPT, "radius"},
      {PRT_BLOB_SFLD_SHELL_OFF_RADIUS, 3e38f, PRT_ERROR_CORRUPT, "radius x outer"},
      {PRT_BLOB_SFLD_SHELL_OFF_INNER, kNaN, PRT_ERROR_NON_FINITE, "inner"},
      {PRT_BLOB_SFLD_SHELL_OFF_INNER, 0.0f, PRT_ERROR_CORRUPT, "inner"},
      {PRT_BLOB_SFLD_SHELL_OFF_OUTER, -kInf, PRT_ERROR_NON_FINITE, "outer"},
  };
  for (std::size_t grid : {PRT_BLOB_SFLD_OFF_OOF_SHELLS, PRT_BLOB_SFLD_OFF_SRF_SHELLS})
    for (const Case& c : cases) {
      const ShadowfieldObject o = sf_test_object();
      Bytes sfld = encoded(o);
      put_f32(sfld, grid + c.offset, c.value);
      expect_rejected(o, sfld, c.full, c.field);
    }
  // Outer against inner: the OOF has 2 shells (outer must exceed inner), the SRF 1 (equal).
  const ShadowfieldObject o = sf_test_object();
  Bytes sfld = encoded(o);
  put_f32(sfld, PRT_BLOB_SFLD_OFF_OOF_SHELLS + PRT_BLOB_SFLD_SHELL_OFF_OUTER, 0.5f);
  expect_rejected(o, sfld, PRT_ERROR_CORRUPT, "OOF shells' outer");
  sfld = encoded(o);
  put_f32(sfld, PRT_BLOB_SFLD_OFF_SRF_SHELLS + PRT_BLOB_SFLD_SHELL_OFF_OUTER, 2.0f);
  expect_rejected(o, sfld, PRT_ERROR_CORRUPT, "SRF shells' outer");
  for (std::uint32_t bad : {0u, 65u}) {
    for (std::size_t field : {PRT_BLOB_SFLD_SHELL_OFF_SHELLS, PRT_BLOB_SFLD_SHELL_OFF_FACE_SIZE}) {
      sfld = encoded(o);
      put_u32(sfld, PRT_BLOB_SFLD_OFF_OOF_SHELLS + field, bad);
      expect_rejected(o, sfld, PRT_ERROR_CORRUPT,
                      field == PRT_BLOB_SFLD_SHELL_OFF_SHELLS ? "count" : "face size");
    }
  }
}

TEST(ShadowfieldSection, SizeAndElementCount) {
  const ShadowfieldObject o = sf_test_object();
  Bytes longer = encoded(o);
  longer.insert(longer.end(), 4, 0);
  expect_rejected(o, longer, PRT_ERROR_CORRUPT, "raw bytes");
  Bytes shorter = encoded(o);
  shorter.resize(shorter.size() - 4);
  expect_rejected(o, shorter, PRT_ERROR_CORRUPT, "raw bytes");
  Bytes header_only = encoded(o);
  header_only.resize(100);
  expect_rejected(o, header_only, PRT_ERROR_CORRUPT, "128-byte header");
  const Bytes two = sf_raw_blob(o, encoded(o), 2);
  const Outcome f = load_blob(two, PRT_VALIDATE_FULL);
  EXPECT_EQ(f.result, PRT_ERROR_CORRUPT);
  EXPECT_NE(f.message.find("element count 2"), std::string::npos) << f.message;
  EXPECT_EQ(load_blob(two, PRT_VALIDATE_QUICK).result, PRT_ERROR_CORRUPT);
}

// Every count at its limit: the size the header implies is far beyond the 128 bytes there are,
// and the load says which size without overflowing or allocating (quick validation: full
// compares the vertex count with VPOS's first).
TEST(ShadowfieldSection, LargestHeaderImpliesItsSize) {
  const ShadowfieldObject o = sf_test_object();
  Bytes sfld = encoded(o);
  sfld.resize(PRT_BLOB_SFLD_HEADER_SIZE);
  const std::uint64_t v = 0xffffffffu, n2 = 36, k = 8, g = 64, n = 64, p = 64 * 6 * 64 * 64;
  put_u32(sfld, PRT_BLOB_SFLD_OFF_ORDER, 6);
  put_u32(sfld, PRT_BLOB_SFLD_OFF_TERMS, std::uint32_t(k));
  put_u32(sfld, PRT_BLOB_SFLD_OFF_VERTICES, std::uint32_t(v));
  put_u32(sfld, PRT_BLOB_SFLD_OFF_BASIS, std::uint32_t(n));
  put_u32(sfld, PRT_BLOB_SFLD_OFF_BRDF_GRID, std::uint32_t(g));
  for (std::size_t grid : {PRT_BLOB_SFLD_OFF_OOF_SHELLS, PRT_BLOB_SFLD_OFF_SRF_SHELLS}) {
    put_u32(sfld, grid + PRT_BLOB_SFLD_SHELL_OFF_SHELLS, 64);
    put_u32(sfld, grid + PRT_BLOB_SFLD_SHELL_OFF_FACE_SIZE, 64);
    put_f32(sfld, grid + PRT_BLOB_SFLD_SHELL_OFF_OUTER, 4.0f);
  }
  // SPEC §7.5 at 16 bits: Q(R, C) = 8 R + 2 C (even, so no padding).
  auto q = [](std::uint64_t rows, std::uint64_t count) { return 8 * rows + 2 * count; };
  const std::uint64_t size = 128 + 12 * v + 4 * k * g * g + q(k * n2, v * k * n2) + q(n2, p * n2) +
                             q(n, n * v) + 4 * v + 4 * n * n + q(n * k * n2, n * k * p * n2);
  const Outcome r = load_blob(sf_raw_blob(o, sfld), PRT_VALIDATE_QUICK);
  EXPECT_EQ(r.result, PRT_ERROR_CORRUPT);
  EXPECT_NE(r.message.find("header implies " + std::to_string(size)), std::string::npos)
      << r.message;
}

// The writer refuses a blob without VNRM, so its section (1) is renamed to an optional unknown
// tag afterwards.
TEST(ShadowfieldSection, NeedsNormals) {
  const ShadowfieldObject o = sf_test_object();
  Bytes blob = sf_raw_blob(o, encoded(o));
  ASSERT_EQ(get_u32(blob, entry(1) + PRT_BLOB_SEC_OFF_TAG), PRT_BLOB_TAG_VNRM);
  put_u32(blob, entry(1) + PRT_BLOB_SEC_OFF_TAG, PRT_BLOB_TAG('X', 'N', 'R', 'M'));
  put_u16(blob, entry(1) + PRT_BLOB_SEC_OFF_FLAGS, 0);
  fix_header_checksum(blob);
  const Outcome q = load_blob(blob, PRT_VALIDATE_QUICK);
  EXPECT_EQ(q.result, PRT_ERROR_CORRUPT);
  EXPECT_NE(q.message.find("needs a 'VNRM'"), std::string::npos) << q.message;
}

// Block contents: only full validation reads them.
TEST(ShadowfieldSection, BlockFloats) {
  const ShadowfieldObject o = sf_test_object();
  const Bytes base = encoded(o);
  const prt_blob_sfld_layout l = sf_layout(base);
  struct Case {
    std::uint64_t offset;
    float value;
    prt_result full;
    const char* field;
  };
  const Case cases[] = {
      {l.albedo + 20, kNaN, PRT_ERROR_NON_FINITE, "albedo"},
      {l.albedo + 4, 1.5f, PRT_ERROR_CORRUPT, "albedo"},
      {l.albedo, -0.25f, PRT_ERROR_CORRUPT, "albedo"},
      {l.g_table + 12, kInf, PRT_ERROR_NON_FINITE, "g table"},
      {l.transfer.params + 8 * 3, kNaN, PRT_ERROR_NON_FINITE, "transfer offset or scale"},
      {l.transfer.params + 8 * 3 + 4, -0.5f, PRT_ERROR_CORRUPT, "transfer scale of row 3"},
      {l.oof.params + 8 * 8 + 4, kInf, PRT_ERROR_NON_FINITE, "OOF offset or scale"},
      {l.oof.params + 4, -1e-3f, PRT_ERROR_CORRUPT, "OOF scale"},
      {l.basis.params + 8 * 2, -kInf, PRT_ERROR_NON_FINITE, "basis offset or scale"},
      {l.basis.params + 4, -1.0f, PRT_ERROR_CORRUPT, "basis scale"},
      {l.vertex_weights + 8, kNaN, PRT_ERROR_NON_FINITE, "vertex weight"},
      {l.vertex_weights + 4, -0.5f, PRT_ERROR_CORRUPT, "vertex weight"},
      {l.basis_inverse + 16, kInf, PRT_ERROR_NON_FINITE, "inverse normal matrix"},
      {l.srf.params + 8 * (l.srf.rows - 1), kNaN, PRT_ERROR_NON_FINITE, "SRF offset or scale"},
      {l.srf.params + 4, -2.0f, PRT_ERROR_CORRUPT, "SRF scale"},
  };
  for (const Case& c : cases) {
    Bytes sfld = base;
    put_f32(sfld, std::size_t(c.offset), c.value);
    expect_rejected(o, sfld, c.full, c.field, false);
  }
}

// 8-bit blocks of an odd value count end in padding, which must be zero.
TEST(ShadowfieldSection, BlockPadding) {
  ShadowfieldObject o = sf_test_object();
  o.basis_size = 1;  // 6 basis values: 2 bytes of padding at 8 bits
  o.basis.resize(6);
  o.basis_inverse = {2.0f};
  o.srf.resize(o.srf.size() / 3);
  const Bytes base = encoded(o, 8);
  const prt_blob_sfld_layout l = sf_layout(base);
  ASSERT_EQ(l.basis.end - l.basis.payload_end, 2u);
  Bytes sfld = base;
  sfld[std::size_t(l.basis.payload_end) + 1] = 1;
  expect_rejected(o, sfld, PRT_ERROR_CORRUPT, "basis padding", false);
}

// The encoder's 8-bit section stored raw, and the same with a negative SRF scale, for the
// second reader written from SPEC.md alone (tests/format/spec_reader.py; the CTest tests in
// CMakeLists.txt run it on the files written when PRT_SHADOWFIELD_RAW_BLOB names one).
TEST(ShadowfieldSection, RawBlobsForTheSpecReader) {
  const ShadowfieldObject o = sf_test_object();
  Bytes sfld = encoded(o, 8);
  const Bytes good = sf_raw_blob(o, sfld);
  put_f32(sfld, std::size_t(sf_layout(sfld).srf.params + 4), -1.0f);
  const Bytes bad = sf_raw_blob(o, sfld);
  EXPECT_EQ(load_blob(good, PRT_VALIDATE_FULL).result, PRT_OK);
  EXPECT_EQ(load_blob(bad, PRT_VALIDATE_FULL).result, PRT_ERROR_CORRUPT);
  const char* path = std::getenv("PRT_SHADOWFIELD_RAW_BLOB");
  if (!path) return;
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(good.data()), std::streamsize(good.size()));
  std::ofstream(std::string(path) + ".bad", std::ios::binary)
      .write(reinterpret_cast<const char*>(bad.data()), std::streamsize(bad.size()));
}

}  // namespace
