// SPDX-License-Identifier: MIT
// The frozen `cloth` golden blobs (formats/golden/README.md): cloth_quad.prtk as baked (zstd) and
// cloth_quad_raw.prtk (every section uncompressed). Every number below was read from a hex dump of
// the files (xxd, python struct) and the SPEC's §7.4 layout, or from the bake command (fabrics
// linen_plain and velvet, --xi-size 5 --levels 3 --view-theta 3 --view-phi 4 --bits 8) and the
// baker's presets (Sadeghi et al.'s table: eta, the volume albedo as colour times scale, k_d, the
// lobe widths and tangent offsets in degrees, the coverage); none is computed by the code under
// test. The properties checked over the whole tables follow from the SPEC §7.4 grids and
// quantiser, written out here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "format/golden_scene.hpp"

namespace {

using namespace prt_golden;

const File kZstd = {"cloth_quad.prtk",
                    2528,
                    0x717F900Au,
                    0x1C129913u,
                    {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0xD4D6D52Bu, 352, 89, 89, 89},
                     {PRT_SECTION_VPOS, 1, PRT_CODEC_ZSTD, 0xA83C6EE7u, 448, 55, 96, 8},
                     {PRT_SECTION_VNRM, 0, PRT_CODEC_ZSTD, 0x89EAE844u, 512, 24, 96, 8},
                     {PRT_SECTION_VTAN, 0, PRT_CODEC_ZSTD, 0x2C27F135u, 544, 22, 96, 8},
                     {PRT_SECTION_TRIS, 1, PRT_CODEC_NONE, 0x2ED79746u, 576, 48, 48, 4},
                     {PRT_SECTION_CLTH, 1, PRT_CODEC_ZSTD, 0x6F9ABD7Eu, 624, 1899, 2832, 2}}};
const File kRaw = {"cloth_quad_raw.prtk",
                   3616,
                   0xB627733Eu,
                   0x4C09FAA5u,
                   {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0xD4D6D52Bu, 352, 89, 89, 89},
                    {PRT_SECTION_VPOS, 1, PRT_CODEC_NONE, 0xD22CFB3Au, 448, 96, 96, 8},
                    {PRT_SECTION_VNRM, 0, PRT_CODEC_NONE, 0x6C35E163u, 544, 96, 96, 8},
                    {PRT_SECTION_VTAN, 0, PRT_CODEC_NONE, 0x395B3BA5u, 640, 96, 96, 8},
                    {PRT_SECTION_TRIS, 1, PRT_CODEC_NONE, 0x2ED79746u, 736, 48, 48, 4},
                    {PRT_SECTION_CLTH, 1, PRT_CODEC_NONE, 0x21720E50u, 784, 2832, 2832, 2}}};

const char kInfo[] =
    "prtkit cloth bake: formats/golden/scenes/quad_over_ground.obj, fabrics linen_plain velvet";

// F = 2, G = 10, Q = 5 (SPEC §7.4): fabrics from 64, tangents from 64 + 2 x 160 = 384, tables
// from 384 + 10 x 16 = 544, data from 544 + 5 x 16 = 624. N_xi = 5, L = 3: rows = 3 x 25 = 75;
// N_theta = 3, N_phi = 4: columns = 12; 8 bits. A factorisation of rank R takes 8 R +
// align4(12 R) + align4(75 R) bytes: 96 for R = 1 (1 byte of padding after U), 192 for R = 2,
// 288 for R = 3 (3 bytes of padding after U).
constexpr size_t kFabrics = 64, kTangents = 384, kTables = 544, kData = 624, kSize = 2832;
constexpr size_t kRows = 75, kColumns = 12, kXi = 5, kPhi = 4;

// The table records' ranks (T, T_c), where each factorisation starts (624 plus the sizes of those
// before it) and the size of one by its rank.
const uint32_t kRanks[5][2] = {{3, 3}, {2, 1}, {2, 3}, {2, 1}, {3, 3}};
const size_t kFactorAt[5][2] = {{624, 912}, {1200, 1392}, {1488, 1680}, {1968, 2160}, {2256, 2544}};
const size_t kFactorBytes[4] = {0, 96, 192, 288};

constexpr uint32_t kEta = 0x3FBAE148u;  // 1.46f

// Thread records as stored bits: eta, albedo, k_d, gamma_s, gamma_v, coverage; then first, count.
struct Thread {
  uint32_t bits[8];
  uint32_t first, count;
};
// linen_plain: colour (0.2, 0.8, 1.0) x 0.3, k_d 0.3, gamma 12 and 24 degrees, coverage 0.33;
// both threads alike.
const Thread kLinen[2] = {{{kEta, 0x3D75C28Fu, 0x3E75C28Fu, 0x3E99999Au, 0x3E99999Au, 0x3E567750u,
                            0x3ED67750u, 0x3EA8F5C3u},
                           0,
                           2},
                          {{kEta, 0x3D75C28Fu, 0x3E75C28Fu, 0x3E99999Au, 0x3E99999Au, 0x3E567750u,
                            0x3ED67750u, 0x3EA8F5C3u},
                           2,
                           2}};
// velvet: colour (0.05, 0.02, 0) x 0.3, k_d 0.1, gamma 6 and 12 degrees, coverage 0.5.
const Thread kVelvet[2] = {
    {{kEta, 0x3C75C28Fu, 0x3BC49BA6u, 0, 0x3DCCCCCDu, 0x3DD67750u, 0x3E567750u, 0x3F000000u}, 4, 2},
    {{kEta, 0x3C75C28Fu, 0x3BC49BA6u, 0, 0x3DCCCCCDu, 0x3DD67750u, 0x3E567750u, 0x3F000000u},
     6,
     4}};

// Tangent records: offset bits, multiplicity, table, mirror. Linen's -25 and +25 degrees read
// table 0 (the negative one mirrored), in both threads; velvet's warp -90 and -50 degrees,
// its weft -90 (mirrored), -55 (mirrored), +55 and +90, a mirrored offset sharing its positive
// twin's table.
struct Tangent {
  uint32_t offset_bits, multiplicity, table, mirror;
};
const Tangent kTangentRecords[10] = {
    {0xBEDF66F3u, 1, 0, 1}, {0x3EDF66F3u, 1, 0, 0}, {0xBEDF66F3u, 1, 0, 1}, {0x3EDF66F3u, 1, 0, 0},
    {0xBFC90FDBu, 1, 1, 0}, {0xBF5F66F3u, 1, 2, 0}, {0xBFC90FDBu, 1, 3, 1}, {0xBF75BE0Bu, 1, 4, 1},
    {0x3F75BE0Bu, 1, 4, 0}, {0x3FC90FDBu, 1, 3, 0}};

// Table 0's T: u_scale, v_scale as stored bits, and a few 8-bit values.
const uint32_t kTable0UScale[3] = {0x3CB5CAF9u, 0x3B899E24u, 0x3AB3ECD6u};
const uint32_t kTable0VScale[3] = {0x3B64D8AEu, 0x3BC3C6DFu, 0x3BBF906Cu};
const int kTable0V0[3] = {95, -30, -33};   // view node (0, 0)
const int kTable0V11[3] = {127, 127, 48};  // view node (2, 3)
const int kTable0U0[3] = {59, 28, -4};     // lobe node (0, 0) of level 0
const int kTable0U62[3] = {75, 90, -60};   // lobe node (2, 2) of level 2

int i8_at(const Bytes& b, size_t offset) {
  return static_cast<int8_t>(b[offset]);
}

TEST(GoldenCloth, Containers) {
  expect_container(kZstd);
  expect_container(kRaw);
}

// The quad scene's mesh, and VTAN: the OBJ has no texture coordinates, so each vertex's warp is
// the world axis least aligned with its normal +y: x and z tie, and the baker takes x first.
TEST(GoldenCloth, MeshSections) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    expect_mesh(a, kInfo);
    const Bytes vtan = a.section(PRT_SECTION_VTAN);
    ASSERT_EQ(vtan.size(), 96u);
    for (size_t v = 0; v < 8; ++v) {
      EXPECT_EQ(f32_at(vtan, 12 * v), 1.0f) << v;
      EXPECT_EQ(f32_at(vtan, 12 * v + 4), 0.0f) << v;
      EXPECT_EQ(f32_at(vtan, 12 * v + 8), 0.0f) << v;
    }
  }
}

TEST(GoldenCloth, ZstdAndRawDecodeToTheSameSections) {
  expect_same_sections(kZstd, kRaw);
}

TEST(GoldenCloth, ClthHeader) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    prt_cloth_info info = prt::sized<prt_cloth_info>();
    ASSERT_EQ(prt_cloth_get_info(a.get(), &info), PRT_OK);
    EXPECT_EQ(info.fabric_count, 2u);
    EXPECT_EQ(info.table_count, 5u);
    EXPECT_EQ(info.xi_size, 5u);
    EXPECT_EQ(info.lambda_levels, 3u);
    EXPECT_EQ(info.lambda_min, 0.25f);
    EXPECT_EQ(info.lambda_max, 1.0e4f);
    EXPECT_EQ(info.view_theta, 3u);
    EXPECT_EQ(info.view_phi, 4u);
    EXPECT_EQ(info.bits, 8u);
    EXPECT_EQ(info.table_bytes, kSize - kData);  // 2208 = 4 x 288 + 4 x 192 + 2 x 96
    const Bytes clth = a.section(PRT_SECTION_CLTH);
    ASSERT_EQ(clth.size(), kSize);
    // F, G, Q, N_xi, L, 0.25f, 1e4f, N_theta, N_phi, bits, flags, reserved.
    const uint32_t header[16] = {2, 10, 5, 5, 3, 0x3E800000u, 0x461C4000u, 3,
                                 4, 8,  0, 0, 0, 0,           0,           0};
    for (size_t k = 0; k < 16; ++k) EXPECT_EQ(prt_test::get_u32(clth, 4 * k), header[k]) << k;
  }
}

TEST(GoldenCloth, FabricRecords) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes clth = a.section(PRT_SECTION_CLTH);
  ASSERT_EQ(clth.size(), kSize);
  const char* names[2] = {"linen_plain", "velvet"};
  const Thread* threads[2] = {kLinen, kVelvet};
  for (size_t f = 0; f < 2; ++f) {
    SCOPED_TRACE(names[f]);
    const size_t at = kFabrics + 160 * f;
    char name[33] = {0};
    std::memcpy(name, clth.data() + at, 32);
    EXPECT_STREQ(name, names[f]);
    for (size_t k = std::strlen(names[f]); k < 32; ++k) EXPECT_EQ(clth[at + k], 0) << k;
    for (size_t t = 0; t < 2; ++t) {
      const size_t thread = at + 32 + 64 * t;
      for (size_t k = 0; k < 8; ++k)
        EXPECT_EQ(prt_test::get_u32(clth, thread + 4 * k), threads[f][t].bits[k]) << t << "," << k;
      EXPECT_EQ(prt_test::get_u32(clth, thread + 32), threads[f][t].first) << t;
      EXPECT_EQ(prt_test::get_u32(clth, thread + 36), threads[f][t].count) << t;
      for (size_t k = 0; k < 6; ++k) EXPECT_EQ(prt_test::get_u32(clth, thread + 40 + 4 * k), 0u);
    }
  }
}

TEST(GoldenCloth, TangentAndTableRecords) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes clth = a.section(PRT_SECTION_CLTH);
  ASSERT_EQ(clth.size(), kSize);
  for (size_t g = 0; g < 10; ++g) {
    const Tangent& t = kTangentRecords[g];
    const size_t at = kTangents + 16 * g;
    EXPECT_EQ(prt_test::get_u32(clth, at), t.offset_bits) << g;
    EXPECT_EQ(prt_test::get_u32(clth, at + 4), t.multiplicity) << g;
    EXPECT_EQ(prt_test::get_u32(clth, at + 8), t.table) << g;
    EXPECT_EQ(prt_test::get_u32(clth, at + 12), t.mirror) << g;
  }
  for (size_t q = 0; q < 5; ++q) {
    const size_t at = kTables + 16 * q;
    EXPECT_EQ(prt_test::get_u32(clth, at), kRanks[q][0]) << q;
    EXPECT_EQ(prt_test::get_u32(clth, at + 4), kRanks[q][1]) << q;
    EXPECT_EQ(prt_test::get_u32(clth, at + 8), 0u) << q;
    EXPECT_EQ(prt_test::get_u32(clth, at + 12), 0u) << q;
  }
  // Each factorisation follows the previous one, to the end, its value blocks padded with zeros.
  size_t at = kData;
  for (size_t q = 0; q < 5; ++q)
    for (size_t w = 0; w < 2; ++w) {
      const size_t rank = kRanks[q][w];
      EXPECT_EQ(kFactorAt[q][w], at) << q << "," << w;
      at += kFactorBytes[rank];
      for (size_t k = 8 * rank + 12 * rank + 75 * rank; k < kFactorBytes[rank]; ++k)
        EXPECT_EQ(clth[kFactorAt[q][w] + k], 0) << q << "," << w << "," << k;
    }
  EXPECT_EQ(at, kSize);
}

// The API's view of the records above: names, default parameters, weaves and each fabric's table
// bytes (linen: table 0, 2 x 288; velvet: tables 1 to 4, 192 + 96 + 192 + 288 + 192 + 96 +
// 2 x 288).
TEST(GoldenCloth, FabricsThroughTheApi) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    const char* names[2] = {"linen_plain", "velvet"};
    const Thread* threads[2] = {kLinen, kVelvet};
    const size_t table_bytes[2] = {576, 1632};
    for (uint32_t fabric = 0; fabric < 2; ++fabric) {
      SCOPED_TRACE(names[fabric]);
      const char* name = nullptr;
      prt_cloth_params params = prt::sized<prt_cloth_params>();
      prt_cloth_weave weave = prt::sized<prt_cloth_weave>();
      size_t bytes = 0;
      ASSERT_EQ(prt_cloth_get_fabric(a.get(), fabric, &name, &params, &weave, &bytes), PRT_OK);
      EXPECT_STREQ(name, names[fabric]);
      EXPECT_EQ(bytes, table_bytes[fabric]);
      uint32_t found = 99;
      EXPECT_EQ(prt_cloth_find_fabric(a.get(), names[fabric], &found), PRT_OK);
      EXPECT_EQ(found, fabric);
      for (uint32_t t = 0; t < 2; ++t) {
        const prt_cloth_thread& p = params.threads[t];
        const uint32_t* b = threads[fabric][t].bits;
        EXPECT_EQ(p.eta, f32_of_bits(b[0]));
        for (int c = 0; c < 3; ++c) EXPECT_EQ(p.albedo[c], f32_of_bits(b[1 + c])) << c;
        EXPECT_EQ(p.kd, f32_of_bits(b[4]));
        EXPECT_EQ(p.gamma_s, f32_of_bits(b[5]));
        EXPECT_EQ(p.gamma_v, f32_of_bits(b[6]));
        EXPECT_EQ(p.coverage, f32_of_bits(b[7]));
        ASSERT_EQ(weave.tangent_count[t], threads[fabric][t].count) << t;
        for (uint32_t i = 0; i < weave.tangent_count[t]; ++i) {
          const Tangent& record = kTangentRecords[threads[fabric][t].first + i];
          EXPECT_EQ(weave.offsets[t][i], f32_of_bits(record.offset_bits)) << t << "," << i;
          EXPECT_EQ(weave.multiplicity[t][i], record.multiplicity) << t << "," << i;
        }
      }
    }
    uint32_t found = 99;
    EXPECT_EQ(prt_cloth_find_fabric(a.get(), "silk_shot", &found), PRT_ERROR_NOT_FOUND);
    EXPECT_EQ(found, 99u);
  }
}

TEST(GoldenCloth, Table0ValuesByHand) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes clth = a.section(PRT_SECTION_CLTH);
  ASSERT_EQ(clth.size(), kSize);
  const size_t at = kFactorAt[0][0], v_values = at + 24, u_values = v_values + 36;
  for (size_t r = 0; r < 3; ++r) {
    EXPECT_EQ(prt_test::get_u32(clth, at + 4 * r), kTable0UScale[r]) << r;
    EXPECT_EQ(prt_test::get_u32(clth, at + 12 + 4 * r), kTable0VScale[r]) << r;
    EXPECT_EQ(i8_at(clth, v_values + r), kTable0V0[r]) << r;
    EXPECT_EQ(i8_at(clth, v_values + 11 * 3 + r), kTable0V11[r]) << r;
    EXPECT_EQ(i8_at(clth, u_values + r), kTable0U0[r]) << r;
    EXPECT_EQ(i8_at(clth, u_values + 62 * 3 + r), kTable0U62[r]) << r;
  }
}

// One factorisation's values as stored: q[node][r] for `nodes` nodes of rank `rank` from `at`.
std::vector<int> values_at(const Bytes& b, size_t at, size_t nodes, size_t rank) {
  std::vector<int> q(nodes * rank);
  for (size_t k = 0; k < q.size(); ++k) q[k] = i8_at(b, at + k);
  return q;
}

// SPEC §7.4's quantiser: a column r whose largest |value| is m has scale m / 127, so its largest
// |q| is 127; a column of zeros has scale 0 and q = 0. -128 is never stored.
void expect_columns_quantised(const Bytes& b, size_t scales, const std::vector<int>& q,
                              size_t rank) {
  for (size_t r = 0; r < rank; ++r) {
    int largest = 0;
    for (size_t k = r; k < q.size(); k += rank) {
      EXPECT_NE(q[k], -128);
      largest = std::max(largest, std::abs(q[k]));
    }
    const float scale = f32_at(b, scales + 4 * r);
    if (scale == 0.0f)
      EXPECT_EQ(largest, 0) << r;
    else
      EXPECT_EQ(largest, 127) << r;
  }
}

// The U rows of lobe nodes (i, j) and (i2, j2) of every level are equal.
void expect_same_lobe_rows(const std::vector<int>& u, size_t rank, size_t i, size_t j, size_t i2,
                           size_t j2) {
  for (size_t level = 0; level < 3; ++level)
    for (size_t r = 0; r < rank; ++r)
      EXPECT_EQ(u[(level * kXi * kXi + j * kXi + i) * rank + r],
                u[(level * kXi * kXi + j2 * kXi + i2) * rank + r])
          << "level " << level << " node " << i << "," << j << " and " << i2 << "," << j2;
}

// Whole-table properties of every stored factorisation: the quantiser's scales, and the grids'
// repeated nodes (SPEC §7.4). The N_phi view nodes at theta_v = 0 (a = 0) are all the normal, so
// their V rows are equal. The octahedral map folds its border: on the edge p_x = +-1 the axis is
// normalise((1 - |p_y|) sign(p_x), 0, -|p_y|) (or (p_x, 0, 0) at p_y = 0), which depends on |p_y|
// alone, so nodes (i, j) and (i, N_xi - 1 - j) there are one direction; likewise on p_y = +-1.
TEST(GoldenCloth, FactorisationsFollowTheGridsAndTheQuantiser) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes clth = a.section(PRT_SECTION_CLTH);
  ASSERT_EQ(clth.size(), kSize);
  for (size_t q = 0; q < 5; ++q)
    for (size_t w = 0; w < 2; ++w) {
      SCOPED_TRACE(::testing::Message() << "table " << q << (w ? " T_c" : " T"));
      const size_t rank = kRanks[q][w], at = kFactorAt[q][w];
      const size_t v_at = at + 8 * rank, u_at = v_at + 12 * rank;  // 12 R bytes: no padding
      const std::vector<int> v = values_at(clth, v_at, kColumns, rank);
      const std::vector<int> u = values_at(clth, u_at, kRows, rank);
      expect_columns_quantised(clth, at, u, rank);
      expect_columns_quantised(clth, at + 4 * rank, v, rank);
      // A term whose U column is zero (T_c of the +-90 degree offsets is) leaves its V unused.
      for (size_t r = 0; r < rank; ++r)
        if (f32_at(clth, at + 4 * r) != 0.0f) {
          for (size_t b = 1; b < kPhi; ++b) EXPECT_EQ(v[b * rank + r], v[r]) << b << "," << r;
        }
      for (size_t k = 0; k < kXi / 2; ++k)
        for (size_t edge : {size_t(0), kXi - 1}) {
          expect_same_lobe_rows(u, rank, edge, k, edge, kXi - 1 - k);
          expect_same_lobe_rows(u, rank, k, edge, kXi - 1 - k, edge);
        }
    }
}

// The blob shades through the runtime: under one lobe straight above a flat sample seen from
// above, each fabric reflects some light (finite, positive), and nothing when the view is below
// the surface.
TEST(GoldenCloth, ShadesAboveTheSurfaceOnly) {
  Asset a(kZstd);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const prt_cloth_lobe lobe = {{0.0f, 1.0f, 0.0f}, 8.0f, {1.0f, 1.0f, 1.0f}};
  prt_cloth_light light = prt::sized<prt_cloth_light>();
  light.lobe_count = 1;
  light.lobes = &lobe;
  const float normals[6] = {0, 1, 0, 0, 1, 0};
  const float warps[6] = {1, 0, 0, 1, 0, 0};
  const float views[6] = {0.0f, 1.0f, 0.0f, 0.6f, -0.8f, 0.0f};
  prt_cloth_pixels pixels = prt::sized<prt_cloth_pixels>();
  pixels.normals = normals;
  pixels.warps = warps;
  pixels.views = views;
  for (uint32_t fabric = 0; fabric < 2; ++fabric) {
    float rgb[6] = {-1, -1, -1, -1, -1, -1};
    ASSERT_EQ(prt_cloth_shade(a.get(), PRT_BACKEND_CPU, fabric, nullptr, &light, nullptr, &pixels,
                              0, 2, rgb),
              PRT_OK);
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(rgb[c])) << fabric << "," << c;
      EXPECT_EQ(rgb[3 + c], 0.0f) << fabric << "," << c;
    }
    EXPECT_GT(rgb[0] + rgb[1] + rgb[2], 0.0f) << fabric;
  }
}

}  // namespace
