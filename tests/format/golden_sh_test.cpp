// SPDX-License-Identifier: MIT
// The frozen `sh` golden blobs (formats/golden/README.md): sh_quad.prtk as baked (zstd) and
// sh_quad_raw.prtk (every section uncompressed). Every number below was read from a hex dump of
// the files and the SPEC's §7.1 layout, or from the bake command (albedo, order, bits); none is
// computed by the code under test, so a reader or writer change that moves one byte or reads one
// field differently fails here.
#include <gtest/gtest.h>

#include <vector>

#include "format/golden_scene.hpp"

namespace {

using namespace prt_golden;

const File kZstd = {"sh_quad.prtk",
                    864,
                    0x427325B3u,
                    0x071D4FD3u,
                    {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0x71950DCBu, 304, 77, 77, 77},
                     {PRT_SECTION_VPOS, 1, PRT_CODEC_ZSTD, 0xA83C6EE7u, 384, 55, 96, 8},
                     {PRT_SECTION_VNRM, 0, PRT_CODEC_ZSTD, 0x89EAE844u, 448, 24, 96, 8},
                     {PRT_SECTION_TRIS, 1, PRT_CODEC_NONE, 0x2ED79746u, 480, 48, 48, 4},
                     {PRT_SECTION_SHTR, 1, PRT_CODEC_ZSTD, 0xFC4733B3u, 528, 324, 464, 8}}};
const File kRaw = {"sh_quad_raw.prtk",
                   1088,
                   0xDE2C62BDu,
                   0x8ADBB245u,
                   {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0x71950DCBu, 304, 77, 77, 77},
                    {PRT_SECTION_VPOS, 1, PRT_CODEC_NONE, 0xD22CFB3Au, 384, 96, 96, 8},
                    {PRT_SECTION_VNRM, 0, PRT_CODEC_NONE, 0x6C35E163u, 480, 96, 96, 8},
                    {PRT_SECTION_TRIS, 1, PRT_CODEC_NONE, 0x2ED79746u, 576, 48, 48, 4},
                    {PRT_SECTION_SHTR, 1, PRT_CODEC_NONE, 0x8C650C01u, 624, 464, 464, 8}}};

const char kInfo[] =
    "prtkit sh bake: formats/golden/scenes/quad_over_ground.obj, order 3, shadowed";

// Order 3, RGB, 8 bits: 27 (offset, scale) pairs from byte 32, then 8 x 27 one-byte values from
// byte 32 + 8 x 27 = 248, ending at 464 (a multiple of 4: no padding).
constexpr size_t kPairs = 32, kValues = 248, kCoefficients = 27;

// A few pairs (j = c * 9 + k) as stored bits. The albedo 0.8, 0.6, 0.4 scales the grey transfer,
// so channel 2's pair is exactly half of channel 0's (one less in the exponent).
struct Pair {
  uint32_t j, offset_bits, scale_bits;
};
const Pair kPairsByHand[] = {
    {0, 0x3DC4CA12u, 0x3A0537C1u},  {1, 0xBD241914u, 0x395EAAF8u},  {3, 0xBD1157A4u, 0x3937EAEBu},
    {4, 0xBC658F70u, 0x38AA2F95u},  {8, 0xBBE8D19Eu, 0x388C22BDu},  {9, 0x3D93978Eu, 0x39C7D3A2u},
    {10, 0xBCF6259Eu, 0x3927003Au}, {18, 0x3D44CA12u, 0x398537C1u}, {26, 0xBB68D19Eu, 0x380C22BDu}};

const Pair& pair_of(uint32_t j) {
  for (const Pair& p : kPairsByHand)
    if (p.j == j) return p;
  ADD_FAILURE() << "no pair " << j << " typed in";
  return kPairsByHand[0];
}

// A few quantised values q[v][j]. Vertex 0 (the ground corner under the occluder) has the
// smallest coefficient 0 of all vertices (q = 0 is the minimum), vertex 4 (on the occluder, open
// sky) the largest (q = 255).
struct Value {
  uint32_t v, j, q;
};
const Value kValuesByHand[] = {{0, 0, 0},   {0, 8, 137}, {1, 1, 176},  {2, 4, 103},
                               {3, 3, 177}, {4, 0, 255}, {7, 26, 107}, {5, 10, 188}};

TEST(GoldenSh, Containers) {
  expect_container(kZstd);
  expect_container(kRaw);
}

TEST(GoldenSh, MeshSections) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    expect_mesh(a, kInfo);
  }
}

TEST(GoldenSh, ZstdAndRawDecodeToTheSameSections) {
  expect_same_sections(kZstd, kRaw);
}

TEST(GoldenSh, ShtrHeader) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    prt_sh_info info = prt::sized<prt_sh_info>();
    ASSERT_EQ(prt_sh_get_info(a.get(), &info), PRT_OK);
    EXPECT_EQ(info.order, 3u);
    EXPECT_EQ(info.vertex_count, 8u);
    EXPECT_EQ(info.channels, 3u);
    EXPECT_EQ(info.bits, 8u);
    EXPECT_EQ(info.kind, 1u);  // shadowed
    EXPECT_EQ(info.bounces, 0u);
    const Bytes shtr = a.section(PRT_SECTION_SHTR);
    ASSERT_EQ(shtr.size(), 464u);
    const uint32_t header[8] = {3, 8, 3, 8, 1, 0, 0, 0};
    for (size_t k = 0; k < 8; ++k) EXPECT_EQ(prt_test::get_u32(shtr, 4 * k), header[k]) << k;
  }
}

TEST(GoldenSh, PairsAndValues) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes shtr = a.section(PRT_SECTION_SHTR);
  ASSERT_EQ(shtr.size(), 464u);
  for (const Pair& p : kPairsByHand) {
    EXPECT_EQ(prt_test::get_u32(shtr, kPairs + 8 * p.j), p.offset_bits) << p.j;
    EXPECT_EQ(prt_test::get_u32(shtr, kPairs + 8 * p.j + 4), p.scale_bits) << p.j;
  }
  for (const Value& x : kValuesByHand)
    EXPECT_EQ(shtr[kValues + kCoefficients * x.v + x.j], x.q) << x.v << "," << x.j;
}

// prt_sh_decode_transfer gives t = offset + scale q (SPEC §7.1) for the values above.
TEST(GoldenSh, DecodedTransfer) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    std::vector<float> t(8 * kCoefficients);
    ASSERT_EQ(prt_sh_decode_transfer(a.get(), 0, 8, t.data()), PRT_OK);
    for (const Value& x : kValuesByHand) {
      const Pair& p = pair_of(x.j);
      const float expected = f32_of_bits(p.offset_bits) + f32_of_bits(p.scale_bits) * float(x.q);
      EXPECT_FLOAT_EQ(t[kCoefficients * x.v + x.j], expected) << x.v << "," << x.j;
    }
    // Coefficient 0 of vertex 0 is the column minimum: exactly its offset.
    EXPECT_EQ(t[0], f32_of_bits(0x3DC4CA12u));
    // Vertex 4's coefficient 0 is the column maximum: offset + 255 scale.
    EXPECT_FLOAT_EQ(t[kCoefficients * 4],
                    f32_of_bits(0x3DC4CA12u) + 255.0f * f32_of_bits(0x3A0537C1u));
  }
}

}  // namespace
