// SPDX-License-Identifier: MIT
// The frozen `wavelet` golden blobs (formats/golden/README.md): wavelet_quad.prtk as baked (zstd)
// and wavelet_quad_raw.prtk (every section uncompressed). Every number below was read from a hex
// dump of the files and the SPEC's §7.2 layout, or from the bake command (cube 16, keep 24, band
// quantiser, albedo 0.8, 0.6, 0.4); none is computed by the code under test.
#include <gtest/gtest.h>

#include <vector>

#include "format/golden_scene.hpp"

namespace {

using namespace prt_golden;

const File kZstd = {"wavelet_quad.prtk",
                    1024,
                    0x750A6AE4u,
                    0x3AA4966Eu,
                    {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0xEAFD37F6u, 304, 97, 97, 97},
                     {PRT_SECTION_VPOS, 1, PRT_CODEC_ZSTD, 0xA83C6EE7u, 416, 55, 96, 8},
                     {PRT_SECTION_VNRM, 0, PRT_CODEC_ZSTD, 0x89EAE844u, 480, 24, 96, 8},
                     {PRT_SECTION_TRIS, 1, PRT_CODEC_NONE, 0x2ED79746u, 512, 48, 48, 4},
                     {PRT_SECTION_WVLT, 1, PRT_CODEC_ZSTD, 0x9B44BBF0u, 560, 462, 764, 8}}};
const File kRaw = {"wavelet_quad_raw.prtk",
                   1424,
                   0x0CF854EEu,
                   0x726BC4CCu,
                   {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0xEAFD37F6u, 304, 97, 97, 97},
                    {PRT_SECTION_VPOS, 1, PRT_CODEC_NONE, 0xD22CFB3Au, 416, 96, 96, 8},
                    {PRT_SECTION_VNRM, 0, PRT_CODEC_NONE, 0x6C35E163u, 512, 96, 96, 8},
                    {PRT_SECTION_TRIS, 1, PRT_CODEC_NONE, 0x2ED79746u, 608, 48, 48, 4},
                    {PRT_SECTION_WVLT, 1, PRT_CODEC_NONE, 0xB6C70567u, 656, 764, 764, 8}}};

const char kInfo[] =
    "prtkit wavelet bake: formats/golden/scenes/quad_over_ground.obj, cube 16, keep 24, "
    "quantizer band";

// Cube 16 (SPEC §7.2): F = 6, log2 S + 1 = 5 levels, 30 band scales from byte 32; 8 vertex
// scales from 32 + 120 = 152; 9 row starts from 152 + 96 = 248; 8 x 6 block counts from
// 248 + 36 = 284; 192 pairs from 284 + 96 = 380, ending at 764 (no padding). One 256-coefficient
// block is one face.
constexpr size_t kBandScales = 32, kVertexScales = 152, kRowStarts = 248, kCounts = 284,
                 kPairs = 380, kBlocks = 6;

// A few band scales bs[b] as stored bits, b = face * 5 + level + 1.
const struct {
  uint32_t band, bits;
} kBandScalesByHand[] = {{0, 0x3BFA3F2Du},  {1, 0x3BFA3F2Du},  {2, 0x3B6CAF9Au},
                         {3, 0x3AA7EBDEu},  {4, 0x00000000u},  {10, 0x3D027AC5u},
                         {14, 0x3B08C2CAu}, {23, 0x3AB77ECDu}, {29, 0x00000000u}};

// Band quantiser: vs[v] is the albedo (SPEC §7.2, "quantiser 1 ... vs[v][c] = ρ_c(v)").
const float kAlbedo[3] = {0.8f, 0.6f, 0.4f};

// Block counts of three vertices: face 3 (-Y) is below every normal (+Y), so it holds nothing.
const struct {
  uint32_t v;
  uint16_t counts[kBlocks];
} kCountsByHand[] = {{0, {3, 4, 10, 0, 4, 3}}, {3, {4, 4, 7, 0, 5, 4}}, {5, {5, 5, 5, 0, 4, 5}}};

// A few stored pairs: (vertex, index of the pair in the section, block, index in block, value).
struct Stored {
  uint32_t v, pair, block, index;
  int value;
};
const Stored kPairsByHand[] = {
    {0, 0, 0, 0, 46},   {0, 1, 0, 2, 80},    {0, 2, 0, 16, 46},    {0, 16, 2, 228, -126},
    {0, 20, 4, 33, 95}, {3, 91, 4, 67, 127}, {5, 124, 0, 82, 127}, {7, 191, 5, 33, 119},
};

// The band of each pair above, from its place in the face (x = i mod 16, y = i / 16; level l
// is the l with max(x, y) in [2^l, 2^(l+1)), -1 for (0, 0)): band = face * 5 + l + 1.
//   block 0 i 0   (0, 0)  l -1 -> band 0     block 0 i 2  (2, 0) l 1 -> band 2
//   block 0 i 16  (0, 1)  l 0  -> band 1     block 2 i 228 (4, 14) l 3 -> band 14
//   block 4 i 33  (1, 2)  l 1  -> band 22    block 4 i 67 (3, 4) l 2 -> band 23
//   block 0 i 82  (2, 5)  l 2  -> band 3     block 5 i 33 (1, 2) l 1 -> band 27
const uint32_t kBandOfPair[] = {0, 2, 1, 14, 22, 23, 3, 27};
const uint32_t kBandScaleBits[30] = {
    0x3BFA3F2Du, 0x3BFA3F2Du, 0x3B6CAF9Au, 0x3AA7EBDEu, 0,           0x3BF97E1Du,
    0x3BF97E1Du, 0x3BA47B92u, 0x3AA4015Au, 0,           0x3D027AC5u, 0x3B928D29u,
    0x3BB053E0u, 0,           0x3B08C2CAu, 0,           0,           0,
    0,           0,           0x3BF994B5u, 0x3BF994B5u, 0x3B91BCB5u, 0x3AB77ECDu,
    0,           0x3BF935CDu, 0x3BF935CDu, 0x3B6D89ACu, 0x3AA25390u, 0};

TEST(GoldenWavelet, Containers) {
  expect_container(kZstd);
  expect_container(kRaw);
}

TEST(GoldenWavelet, MeshSections) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    expect_mesh(a, kInfo);
  }
}

TEST(GoldenWavelet, ZstdAndRawDecodeToTheSameSections) {
  expect_same_sections(kZstd, kRaw);
}

TEST(GoldenWavelet, WvltHeader) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    prt_wavelet_info info = prt::sized<prt_wavelet_info>();
    ASSERT_EQ(prt_wavelet_get_info(a.get(), &info), PRT_OK);
    EXPECT_EQ(info.param, 0u);  // cube
    EXPECT_EQ(info.size, 16u);
    EXPECT_EQ(info.faces, 6u);
    EXPECT_EQ(info.coefficient_count, 1536u);
    EXPECT_EQ(info.block_count, 6u);
    EXPECT_EQ(info.vertex_count, 8u);
    EXPECT_EQ(info.quantizer, 1u);  // band
    EXPECT_EQ(info.keep, 24u);
    EXPECT_EQ(info.bounces, 0u);
    EXPECT_EQ(info.pair_count, 192u);
    const Bytes wvlt = a.section(PRT_SECTION_WVLT);
    ASSERT_EQ(wvlt.size(), 764u);
    const uint32_t header[8] = {0, 16, 8, 1, 24, 0, 192, 0};
    for (size_t k = 0; k < 8; ++k) EXPECT_EQ(prt_test::get_u32(wvlt, 4 * k), header[k]) << k;
  }
}

TEST(GoldenWavelet, ScalesRowsBlocksAndPairs) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes w = a.section(PRT_SECTION_WVLT);
  ASSERT_EQ(w.size(), 764u);
  for (const auto& b : kBandScalesByHand)
    EXPECT_EQ(prt_test::get_u32(w, kBandScales + 4 * b.band), b.bits) << b.band;
  for (uint32_t k = 0; k < 30; ++k)
    EXPECT_EQ(prt_test::get_u32(w, kBandScales + 4 * k), kBandScaleBits[k]) << k;
  for (size_t v = 0; v < 8; ++v)
    for (size_t c = 0; c < 3; ++c)
      EXPECT_EQ(f32_at(w, kVertexScales + 12 * v + 4 * c), kAlbedo[c]) << v << "," << c;
  // Every vertex keeps exactly 24 non-zeros: rs[v] = 24 v.
  for (uint32_t v = 0; v <= 8; ++v) EXPECT_EQ(prt_test::get_u32(w, kRowStarts + 4 * v), 24 * v);
  for (const auto& row : kCountsByHand)
    for (size_t k = 0; k < kBlocks; ++k)
      EXPECT_EQ(prt_le_load_u16(w.data() + kCounts + 2 * (kBlocks * row.v + k)), row.counts[k])
          << row.v << "," << k;
  for (const Stored& p : kPairsByHand) {
    EXPECT_EQ(w[kPairs + 2 * p.pair], p.index) << p.pair;
    EXPECT_EQ(int(int8_t(w[kPairs + 2 * p.pair + 1])), p.value) << p.pair;
  }
}

// prt_wavelet_decode_transfer gives t[j][c] = q bs[band] vs[v][c] (SPEC §7.2) at j = 256 block +
// index, and 0 wherever nothing is stored.
TEST(GoldenWavelet, DecodedRows) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    std::vector<float> row(3 * 1536);
    for (size_t n = 0; n < sizeof kPairsByHand / sizeof kPairsByHand[0]; ++n) {
      const Stored& p = kPairsByHand[n];
      ASSERT_EQ(prt_wavelet_decode_transfer(a.get(), p.v, 1, row.data()), PRT_OK);
      const size_t j = 256 * p.block + p.index;
      const float bs = f32_of_bits(kBandScaleBits[kBandOfPair[n]]);
      for (size_t c = 0; c < 3; ++c)
        EXPECT_FLOAT_EQ(row[3 * j + c], float(p.value) * bs * kAlbedo[c]) << p.pair << "," << c;
    }
    ASSERT_EQ(prt_wavelet_decode_transfer(a.get(), 0, 1, row.data()), PRT_OK);
    size_t non_zero = 0;
    for (float x : row) non_zero += x != 0.0f;
    EXPECT_EQ(non_zero, 3u * 24u);  // 24 stored coefficients, three channels each
    EXPECT_EQ(row[3 * 1], 0.0f);    // block 0 index 1 is not stored
    for (size_t j = 768; j < 1024; ++j) EXPECT_EQ(row[3 * j], 0.0f) << j;  // face 3
  }
}

}  // namespace
