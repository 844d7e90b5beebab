// SPDX-License-Identifier: MIT
// The section layouts (prt_blob_shtr_layout_of, prt_blob_wvlt_layout_of) and the kind table
// against formats/SPEC.md §7, with every offset worked out by hand from the SPEC's tables.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <set>

#include <prt/format/pose_layout.h>
#include <prt/format/section_kinds.h>
#include <prt/format/sh_layout.h>
#include <prt/format/wavelet_layout.h>

#include "support/blob_test_util.hpp"

namespace {

using namespace prt_test;

TEST(ShtrLayout, HeaderFieldOffsetsAreTheSpecs) {
  // SPEC §7.1: order, vertex_count, channels, bits, kind, bounces, two reserved u32.
  EXPECT_EQ(PRT_BLOB_SHTR_OFF_ORDER, 0u);
  EXPECT_EQ(PRT_BLOB_SHTR_OFF_VERTICES, 4u);
  EXPECT_EQ(PRT_BLOB_SHTR_OFF_CHANNELS, 8u);
  EXPECT_EQ(PRT_BLOB_SHTR_OFF_BITS, 12u);
  EXPECT_EQ(PRT_BLOB_SHTR_OFF_KIND, 16u);
  EXPECT_EQ(PRT_BLOB_SHTR_OFF_BOUNCES, 20u);
  EXPECT_EQ(PRT_BLOB_SHTR_OFF_RESERVED, 24u);
  EXPECT_EQ(PRT_BLOB_SHTR_RESERVED_SIZE, 8u);
  EXPECT_EQ(PRT_BLOB_SHTR_HEADER_SIZE, 32u);
  EXPECT_EQ(PRT_BLOB_TAG_SHTR, 0x52544853u);  // "SHTR" little-endian
}

TEST(ShtrLayout, ReadHeaderTakesEachFieldFromItsOffset) {
  const uint8_t bytes[32] = {3, 0, 0, 0, 7, 1, 0, 0, 3, 0, 0, 0, 16, 0, 0, 0,
                             2, 0, 0, 0, 5, 0, 0, 0, 0, 0, 0, 0, 0,  0, 0, 0};
  prt_blob_shtr_header h;
  prt_blob_shtr_read_header(bytes, &h);
  EXPECT_EQ(h.order, 3u);
  EXPECT_EQ(h.vertices, 263u);
  EXPECT_EQ(h.channels, 3u);
  EXPECT_EQ(h.bits, 16u);
  EXPECT_EQ(h.kind, PRT_BLOB_SHTR_KIND_INTERREFLECTED);
  EXPECT_EQ(h.bounces, 5u);
}

TEST(ShtrLayout, SmallLayoutsByHand) {
  prt_blob_shtr_layout l;
  // Order 2, RGB, 8 bits, 5 vertices: 12 pairs of 8 bytes after the header, then 5 x 12 bytes.
  ASSERT_EQ(prt_blob_shtr_layout_of(2, 5, 3, 8, &l), 1);
  EXPECT_EQ(l.coefficients, 12u);
  EXPECT_EQ(l.value_size, 1u);
  EXPECT_EQ(l.params, 32u);
  EXPECT_EQ(l.values, 128u);
  EXPECT_EQ(l.payload_end, 188u);
  EXPECT_EQ(l.raw_size, 188u);
  // Order 3, grey, 8 bits, 3 vertices: 9 pairs (72 bytes), 27 values, one padding byte.
  ASSERT_EQ(prt_blob_shtr_layout_of(3, 3, 1, 8, &l), 1);
  EXPECT_EQ(l.coefficients, 9u);
  EXPECT_EQ(l.values, 104u);
  EXPECT_EQ(l.payload_end, 131u);
  EXPECT_EQ(l.raw_size, 132u);
  // Order 2, RGB, 16 bits, 5 vertices: 5 x 12 values of 2 bytes.
  ASSERT_EQ(prt_blob_shtr_layout_of(2, 5, 3, 16, &l), 1);
  EXPECT_EQ(l.value_size, 2u);
  EXPECT_EQ(l.payload_end, 248u);
  // Order 1, grey, 16 bits, 1 vertex: 32 + 8 + 2 = 42, padded to 44.
  ASSERT_EQ(prt_blob_shtr_layout_of(1, 1, 1, 16, &l), 1);
  EXPECT_EQ(l.payload_end, 42u);
  EXPECT_EQ(l.raw_size, 44u);
  // No vertices: the header and the pairs only.
  ASSERT_EQ(prt_blob_shtr_layout_of(4, 0, 3, 8, &l), 1);
  EXPECT_EQ(l.raw_size, 32u + 8u * 48u);
}

TEST(ShtrLayout, LargestFieldsDoNotOverflow) {
  prt_blob_shtr_layout l;
  // Order 16, RGB, 16 bits, 2^32 - 1 vertices: 768 pairs; 6176 + (2^32 - 1) * 1536 bytes.
  ASSERT_EQ(prt_blob_shtr_layout_of(16, 0xFFFFFFFFu, 3, 16, &l), 1);
  EXPECT_EQ(l.coefficients, 768u);
  EXPECT_EQ(l.values, 6176u);
  EXPECT_EQ(l.payload_end, 6597069771296ull);
  EXPECT_EQ(l.raw_size, 6597069771296ull);
}

TEST(ShtrLayout, InvalidFieldsLeaveTheLayoutUntouched) {
  prt_blob_shtr_layout l;
  std::memset(&l, 0xAB, sizeof l);
  const prt_blob_shtr_layout before = l;
  EXPECT_EQ(prt_blob_shtr_layout_of(0, 1, 3, 8, &l), 0);   // order 0
  EXPECT_EQ(prt_blob_shtr_layout_of(17, 1, 3, 8, &l), 0);  // order above 16
  EXPECT_EQ(prt_blob_shtr_layout_of(3, 1, 2, 8, &l), 0);   // 2 channels
  EXPECT_EQ(prt_blob_shtr_layout_of(3, 1, 0, 8, &l), 0);   // no channel
  EXPECT_EQ(prt_blob_shtr_layout_of(3, 1, 3, 12, &l), 0);  // 12 bits
  EXPECT_EQ(prt_blob_shtr_layout_of(3, 1, 3, 0, &l), 0);   // 0 bits
  EXPECT_EQ(std::memcmp(&l, &before, sizeof l), 0);
  EXPECT_EQ(prt_blob_shtr_layout_of(16, 1, 3, 16, &l), 1);  // the limits are valid
  EXPECT_EQ(prt_blob_shtr_layout_of(1, 1, 1, 8, &l), 1);
}

TEST(WvltLayout, HeaderFieldOffsetsAreTheSpecs) {
  // SPEC §7.2: param, S, V, quantiser, keep, bounces, pair_count, reserved.
  EXPECT_EQ(PRT_BLOB_WVLT_OFF_PARAM, 0u);
  EXPECT_EQ(PRT_BLOB_WVLT_OFF_SIZE, 4u);
  EXPECT_EQ(PRT_BLOB_WVLT_OFF_VERTICES, 8u);
  EXPECT_EQ(PRT_BLOB_WVLT_OFF_QUANTIZER, 12u);
  EXPECT_EQ(PRT_BLOB_WVLT_OFF_KEEP, 16u);
  EXPECT_EQ(PRT_BLOB_WVLT_OFF_BOUNCES, 20u);
  EXPECT_EQ(PRT_BLOB_WVLT_OFF_PAIR_COUNT, 24u);
  EXPECT_EQ(PRT_BLOB_WVLT_OFF_RESERVED, 28u);
  EXPECT_EQ(PRT_BLOB_WVLT_HEADER_SIZE, 32u);
  EXPECT_EQ(PRT_BLOB_TAG_WVLT, 0x544C5657u);  // "WVLT" little-endian
}

TEST(WvltLayout, ReadHeaderTakesEachFieldFromItsOffset) {
  const uint8_t bytes[32] = {1,   0, 0, 0, 32, 0, 0, 0, 2,    1,    0, 0, 1, 0, 0, 0,
                             200, 0, 0, 0, 3,  0, 0, 0, 0x10, 0x27, 0, 0, 9, 0, 0, 0};
  prt_blob_wvlt_header h;
  prt_blob_wvlt_read_header(bytes, &h);
  EXPECT_EQ(h.param, PRT_BLOB_WVLT_PARAM_DUAL_PARABOLOID);
  EXPECT_EQ(h.size, 32u);
  EXPECT_EQ(h.vertices, 258u);
  EXPECT_EQ(h.quantizer, PRT_BLOB_WVLT_QUANTIZER_BAND);
  EXPECT_EQ(h.keep, 200u);
  EXPECT_EQ(h.bounces, 3u);
  EXPECT_EQ(h.pair_count, 10000u);
  EXPECT_EQ(h.reserved, 9u);
}

TEST(WvltLayout, SmallLayoutsByHand) {
  prt_blob_wvlt_layout l;
  // Cube 16, 2 vertices, 5 pairs: 6 faces x 5 levels = 30 band scales, 1536 coefficients in 6
  // blocks; 32 + 120 = 152, + 2 x 12 = 176, + 3 x 4 = 188, + 2 x 6 x 2 = 212, + 10 = 222 -> 224.
  ASSERT_EQ(prt_blob_wvlt_layout_of(PRT_BLOB_WVLT_PARAM_CUBE, 16, 2, 5, &l), 1);
  EXPECT_EQ(l.faces, 6u);
  EXPECT_EQ(l.bands, 30u);
  EXPECT_EQ(l.coefficients, 1536u);
  EXPECT_EQ(l.blocks, 6u);
  EXPECT_EQ(l.band_scale, 32u);
  EXPECT_EQ(l.vertex_scale, 152u);
  EXPECT_EQ(l.row_start, 176u);
  EXPECT_EQ(l.counts, 188u);
  EXPECT_EQ(l.pairs, 212u);
  EXPECT_EQ(l.payload_end, 222u);
  EXPECT_EQ(l.raw_size, 224u);
  // Dual paraboloid 32, 1 vertex, no pairs: 2 x 6 = 12 band scales, 2048 coefficients in 8
  // blocks; 32 + 48 = 80, + 12 = 92, + 8 = 100, + 16 = 116.
  ASSERT_EQ(prt_blob_wvlt_layout_of(PRT_BLOB_WVLT_PARAM_DUAL_PARABOLOID, 32, 1, 0, &l), 1);
  EXPECT_EQ(l.faces, 2u);
  EXPECT_EQ(l.bands, 12u);
  EXPECT_EQ(l.coefficients, 2048u);
  EXPECT_EQ(l.blocks, 8u);
  EXPECT_EQ(l.vertex_scale, 80u);
  EXPECT_EQ(l.row_start, 92u);
  EXPECT_EQ(l.counts, 100u);
  EXPECT_EQ(l.pairs, 116u);
  EXPECT_EQ(l.raw_size, 116u);
}

TEST(WvltLayout, LargestFieldsDoNotOverflow) {
  prt_blob_wvlt_layout l;
  // Cube 128, 2^32 - 1 vertices and pairs: 48 bands, 384 blocks.
  ASSERT_EQ(prt_blob_wvlt_layout_of(PRT_BLOB_WVLT_PARAM_CUBE, 128, 0xFFFFFFFFu, 0xFFFFFFFFu, &l),
            1);
  EXPECT_EQ(l.bands, 48u);
  EXPECT_EQ(l.blocks, 384u);
  EXPECT_EQ(l.vertex_scale, 224u);
  EXPECT_EQ(l.row_start, 51539607764ull);
  EXPECT_EQ(l.counts, 68719476948ull);
  EXPECT_EQ(l.pairs, 3367254359508ull);
  EXPECT_EQ(l.payload_end, 3375844294098ull);
  EXPECT_EQ(l.raw_size, 3375844294100ull);
}

TEST(WvltLayout, InvalidFieldsLeaveTheLayoutUntouched) {
  prt_blob_wvlt_layout l;
  std::memset(&l, 0xAB, sizeof l);
  const prt_blob_wvlt_layout before = l;
  EXPECT_EQ(prt_blob_wvlt_layout_of(2, 16, 1, 0, &l), 0);   // unknown param
  EXPECT_EQ(prt_blob_wvlt_layout_of(0, 8, 1, 0, &l), 0);    // below 16
  EXPECT_EQ(prt_blob_wvlt_layout_of(0, 256, 1, 0, &l), 0);  // above 128
  EXPECT_EQ(prt_blob_wvlt_layout_of(0, 48, 1, 0, &l), 0);   // not a power of two
  EXPECT_EQ(std::memcmp(&l, &before, sizeof l), 0);
}

TEST(PstrLayout, HeaderFieldOffsetsAreTheSpecs) {
  // SPEC §7.3: n, V, J, p, q, model, bits, model joint, kind, bounces, albedo, flags, reserved.
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_ORDER, 0u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_VERTICES, 4u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_JOINTS, 8u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_POSE_DIMS, 12u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_BASIS_DIMS, 16u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_MODEL, 20u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_BITS, 24u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_MODEL_JOINT, 28u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_KIND, 32u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_BOUNCES, 36u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_ALBEDO, 40u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_FLAGS, 44u);
  EXPECT_EQ(PRT_BLOB_PSTR_OFF_RESERVED, 48u);
  EXPECT_EQ(PRT_BLOB_PSTR_HEADER_SIZE, 64u);
  // A joint: parent, bind rotation (4), translation (3), scale (3), pre (12), inverse bind (12).
  EXPECT_EQ(PRT_BLOB_PSTR_JOINT_OFF_BIND_ROTATION, 4u);
  EXPECT_EQ(PRT_BLOB_PSTR_JOINT_OFF_TRANSLATION, 20u);
  EXPECT_EQ(PRT_BLOB_PSTR_JOINT_OFF_SCALE, 32u);
  EXPECT_EQ(PRT_BLOB_PSTR_JOINT_OFF_PRE, 44u);
  EXPECT_EQ(PRT_BLOB_PSTR_JOINT_OFF_INVERSE_BIND, 92u);
  EXPECT_EQ(PRT_BLOB_PSTR_JOINT_SIZE, 140u);
  // A skin record: position (3), normal (3), 4 u8 joints, 4 u16 weights.
  EXPECT_EQ(PRT_BLOB_PSTR_SKIN_OFF_JOINTS, 24u);
  EXPECT_EQ(PRT_BLOB_PSTR_SKIN_OFF_WEIGHTS, 28u);
  EXPECT_EQ(PRT_BLOB_PSTR_SKIN_SIZE, 36u);
  EXPECT_EQ(PRT_BLOB_TAG_PSTR, 0x52545350u);  // "PSTR" little-endian
}

TEST(PstrLayout, SmallLayoutsByHand) {
  prt_blob_pstr_layout l;
  // n 2 (C 4), V 3, J 2 (F 6), p 1, q 2, 8 bits: 64 + 280 = 344, + 8 = 352, + 24 = 376,
  // + 24 = 400, + 8 = 408, + 2 x 2 x 4 x 4 = 472, + 16 = 488, + 6 values -> 8 = 496, + 108 = 604.
  ASSERT_EQ(prt_blob_pstr_layout_of(2, 3, 2, 1, 2, 8, &l), 1);
  EXPECT_EQ(l.coefficients, 4u);
  EXPECT_EQ(l.features, 6u);
  EXPECT_EQ(l.value_size, 1u);
  EXPECT_EQ(l.joints, 64u);
  EXPECT_EQ(l.eval_order, 344u);
  EXPECT_EQ(l.pose_mean, 352u);
  EXPECT_EQ(l.pose_basis, 376u);
  EXPECT_EQ(l.pose_range, 400u);
  EXPECT_EQ(l.regression, 408u);
  EXPECT_EQ(l.basis_params, 472u);
  EXPECT_EQ(l.basis_values, 488u);
  EXPECT_EQ(l.skin, 496u);
  EXPECT_EQ(l.payload_end, 604u);
  EXPECT_EQ(l.raw_size, 604u);
  // n 1, V 1, J 1, p 0, q 1, 16 bits: 64 + 140 + 4 + 12 + 0 + 0 + 4 + 8 = 232, 2 bytes -> 4.
  ASSERT_EQ(prt_blob_pstr_layout_of(1, 1, 1, 0, 1, 16, &l), 1);
  EXPECT_EQ(l.basis_values, 232u);
  EXPECT_EQ(l.skin, 236u);
  EXPECT_EQ(l.raw_size, 272u);
}

TEST(PstrLayout, InvalidFieldsLeaveTheLayoutUntouched) {
  prt_blob_pstr_layout l;
  std::memset(&l, 0xAB, sizeof l);
  const prt_blob_pstr_layout before = l;
  EXPECT_EQ(prt_blob_pstr_layout_of(0, 1, 1, 0, 1, 8, &l), 0);    // order 0
  EXPECT_EQ(prt_blob_pstr_layout_of(9, 1, 1, 0, 1, 8, &l), 0);    // order above 8
  EXPECT_EQ(prt_blob_pstr_layout_of(2, 1, 0, 0, 1, 8, &l), 0);    // no joint
  EXPECT_EQ(prt_blob_pstr_layout_of(2, 1, 257, 0, 1, 8, &l), 0);  // above 256 joints
  EXPECT_EQ(prt_blob_pstr_layout_of(2, 1, 2, 7, 1, 8, &l), 0);    // p above 3 J
  EXPECT_EQ(prt_blob_pstr_layout_of(2, 1, 2, 0, 0, 8, &l), 0);    // q 0
  EXPECT_EQ(prt_blob_pstr_layout_of(2, 1, 2, 0, 257, 8, &l), 0);  // q above 256
  EXPECT_EQ(prt_blob_pstr_layout_of(2, 1, 2, 0, 1, 12, &l), 0);   // 12 bits
  EXPECT_EQ(std::memcmp(&l, &before, sizeof l), 0);
  EXPECT_EQ(prt_blob_pstr_layout_of(8, 1, 256, 768, 256, 16, &l), 1);  // the limits are valid
}

// SPEC §7's table: tag, element size and domain of every 1.0 kind, and its relations.
TEST(SectionKinds, TableIsTheSpecs) {
  struct Row {
    uint32_t tag;
    uint32_t element_size;
    prt_blob_domain domain;
  };
  const Row spec[] = {
      {PRT_BLOB_TAG('I', 'N', 'F', 'O'), 1, PRT_BLOB_DOMAIN_NONE},
      {PRT_BLOB_TAG('V', 'P', 'O', 'S'), 12, PRT_BLOB_DOMAIN_VERTEX},
      {PRT_BLOB_TAG('V', 'N', 'R', 'M'), 12, PRT_BLOB_DOMAIN_VERTEX},
      {PRT_BLOB_TAG('V', 'T', 'A', 'N'), 12, PRT_BLOB_DOMAIN_VERTEX},
      {PRT_BLOB_TAG('T', 'R', 'I', 'S'), 12, PRT_BLOB_DOMAIN_TRIANGLE},
      {PRT_BLOB_TAG('S', 'H', 'T', 'R'), 0, PRT_BLOB_DOMAIN_VERTEX},
      {PRT_BLOB_TAG('W', 'V', 'L', 'T'), 0, PRT_BLOB_DOMAIN_VERTEX},
      {PRT_BLOB_TAG('P', 'S', 'T', 'R'), 0, PRT_BLOB_DOMAIN_VERTEX},
      {PRT_BLOB_TAG('C', 'L', 'T', 'H'), 0, PRT_BLOB_DOMAIN_MATERIAL},
      {PRT_BLOB_TAG('S', 'F', 'L', 'D'), 0, PRT_BLOB_DOMAIN_OBJECT},
      {PRT_BLOB_TAG('S', 'C', 'N', 'E'), 0, PRT_BLOB_DOMAIN_NONE},
  };
  EXPECT_EQ(prt_blob_kind_count(), sizeof spec / sizeof spec[0]);
  for (const Row& row : spec) {
    const prt_blob_kind* kind = prt_blob_find_kind(row.tag, 1);
    ASSERT_NE(kind, nullptr) << row.tag;
    EXPECT_EQ(kind->element_size, row.element_size) << kind->name;
    EXPECT_EQ(kind->domain, row.domain) << kind->name;
    EXPECT_NE(kind->check_content, nullptr) << kind->name;
    EXPECT_EQ(prt_blob_find_kind(row.tag, 2), nullptr) << kind->name;
  }
  EXPECT_EQ(prt_blob_domain_counter(PRT_BLOB_DOMAIN_VERTEX)->tag, PRT_BLOB_TAG_VPOS);
  EXPECT_EQ(prt_blob_domain_counter(PRT_BLOB_DOMAIN_TRIANGLE)->tag, PRT_BLOB_TAG_TRIS);
  EXPECT_EQ(prt_blob_domain_counter(PRT_BLOB_DOMAIN_MATERIAL)->tag,
            PRT_BLOB_TAG('C', 'L', 'T', 'H'));
  EXPECT_EQ(prt_blob_domain_counter(PRT_BLOB_DOMAIN_OBJECT)->tag, PRT_BLOB_TAG('S', 'F', 'L', 'D'));
  EXPECT_EQ(prt_blob_domain_counter(PRT_BLOB_DOMAIN_NONE), nullptr);
  EXPECT_EQ(prt_blob_find_kind(PRT_BLOB_TAG_TRIS, 1)->depends_on[0], PRT_BLOB_TAG_VPOS);
  const prt_blob_kind* sfld = prt_blob_find_kind(PRT_BLOB_TAG('S', 'F', 'L', 'D'), 1);
  EXPECT_EQ(sfld->depends_on[0], PRT_BLOB_TAG_VPOS);
  EXPECT_EQ(sfld->depends_on[1], PRT_BLOB_TAG_VNRM);
  EXPECT_EQ(sfld->depends_on[2], 0u);
  // The scene manifest needs nothing and counts nothing: it holds no mesh.
  const prt_blob_kind* scne = prt_blob_find_kind(PRT_BLOB_TAG('S', 'C', 'N', 'E'), 1);
  EXPECT_EQ(scne->depends_on[0], 0u);
  EXPECT_EQ(scne->counts_domain, 0u);
}

// Properties every future row must keep too.
TEST(SectionKinds, RowsAreConsistent) {
  std::set<std::pair<uint32_t, uint8_t>> seen;
  std::set<int> counted;
  for (size_t i = 0; i < prt_blob_kind_count(); ++i) {
    const prt_blob_kind* kind = prt_blob_kind_at(i);
    ASSERT_NE(kind, nullptr);
    SCOPED_TRACE(kind->name);
    EXPECT_TRUE(seen.insert({kind->tag, kind->layout_version}).second) << "row twice";
    EXPECT_EQ(prt_blob_find_kind(kind->tag, kind->layout_version), kind);
    EXPECT_NE(kind->name, nullptr);
    EXPECT_NE(kind->element_noun, nullptr);
    if (kind->counts_domain) {
      EXPECT_NE(kind->domain, PRT_BLOB_DOMAIN_NONE);
      EXPECT_TRUE(counted.insert(kind->domain).second) << "two kinds count one domain";
      EXPECT_EQ(prt_blob_domain_counter(kind->domain), kind);
    }
    for (uint32_t tag : kind->depends_on) {
      if (tag == 0) break;
      bool known = false;
      for (size_t j = 0; j < prt_blob_kind_count(); ++j)
        known = known || prt_blob_kind_at(j)->tag == tag;
      EXPECT_TRUE(known) << "depends on an unknown tag";
    }
  }
  EXPECT_EQ(prt_blob_kind_at(prt_blob_kind_count()), nullptr);
}

TEST(SectionKinds, DomainCountsOfTheGoldenMesh) {
  const Bytes blob = read_file(golden_path());
  prt_blob_header h;
  ASSERT_EQ(prt_blob_validate_structure(blob.data(), blob.size(), &h, nullptr, 0), PRT_BLOB_OK);
  EXPECT_EQ(prt_blob_domain_count(blob.data(), &h, PRT_BLOB_DOMAIN_VERTEX), 9u);    // 3 x 3 grid
  EXPECT_EQ(prt_blob_domain_count(blob.data(), &h, PRT_BLOB_DOMAIN_TRIANGLE), 8u);  // 2 per cell
  EXPECT_EQ(prt_blob_domain_count(blob.data(), &h, PRT_BLOB_DOMAIN_NONE), 0u);
  EXPECT_EQ(prt_blob_domain_count(blob.data(), &h, PRT_BLOB_DOMAIN_MATERIAL), 0u);
}

}  // namespace
