// SPDX-License-Identifier: MIT
// The `shadowfield` golden blobs (formats/golden/README.md): shadowfield_quad.prtk as baked (zstd)
// and shadowfield_quad_raw.prtk (every section uncompressed), the quad scene baked as one glossy
// object. Every number below was read from a hex dump of the files (python struct) and the SPEC's
// §7.5 layout, or follows from the bake command (order 3, phong:16 in 2 terms on a 4 x 4 grid,
// OOF 2 shells of 2 x 2 faces, SRF 2 shells of 1 x 1, from 0.25 to 4 bounding radii, basis 2,
// 8 bits, albedo 0.8, 0.6, 0.4) and the scene (its bounding box, its triangles' areas); none is
// computed by the code under test. Where a decoded value is checked, the test recomputes it in
// double from the stored numbers with the SPEC §7.5 formula written out here.
//
// The g table, the transfer, the basis and the source fields depend on the BRDF's separation:
// the constants marked "(BRDF)" are to be read again from the files whenever the blobs are
// regenerated (formats/golden/README.md gives the command); the others do not move.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "format/golden_scene.hpp"

namespace {

using namespace prt_golden;

const double kPi = 3.14159265358979323846;

// (BRDF) sizes and checksums of the files and of the compressed SFLD.
const File kZstd = {"shadowfield_quad.prtk",
                    2112,
                    0x5583FF85u,
                    0xC5CE82A2u,
                    {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0x12F74ED2u, 304, 86, 86, 86},
                     {PRT_SECTION_VPOS, 1, PRT_CODEC_ZSTD, 0xA83C6EE7u, 400, 55, 96, 8},
                     {PRT_SECTION_VNRM, 1, PRT_CODEC_ZSTD, 0x89EAE844u, 464, 24, 96, 8},
                     {PRT_SECTION_TRIS, 1, PRT_CODEC_NONE, 0x2ED79746u, 496, 48, 48, 4},
                     {PRT_SECTION_SFLD, 1, PRT_CODEC_ZSTD, 0x8715EA68u, 544, 1567, 1944, 1}}};
const File kRaw = {"shadowfield_quad_raw.prtk",
                   2592,
                   0x6198D855u,
                   0x9BC9DAD3u,
                   {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0x12F74ED2u, 304, 86, 86, 86},
                    {PRT_SECTION_VPOS, 1, PRT_CODEC_NONE, 0xD22CFB3Au, 400, 96, 96, 8},
                    {PRT_SECTION_VNRM, 1, PRT_CODEC_NONE, 0x6C35E163u, 496, 96, 96, 8},
                    {PRT_SECTION_TRIS, 1, PRT_CODEC_NONE, 0x2ED79746u, 592, 48, 48, 4},
                    {PRT_SECTION_SFLD, 1, PRT_CODEC_NONE, 0x54846392u, 640, 1944, 1944, 1}}};

const char kInfo[] =
    "prtkit shadowfield bake: formats/golden/scenes/quad_over_ground.obj, order 3, phong:16";

// n = 3 (9 coefficients), K = 2, V = 8, N = 2, G = 4, P_oof = 2 x 6 x 2 x 2 = 48,
// P_srf = 2 x 6 x 1 x 1 = 12, 8 bits (SPEC §7.5, Q(R, C) = 8 R + align4(C)):
//   albedo 128 + 12 x 8 = 224, g table 224 + 4 x 2 x 16 = 352,
//   transfer Q(18, 144) = 288: 352 .. 640, OOF Q(9, 432) = 504: 640 .. 1144,
//   basis Q(2, 16) = 32: 1144 .. 1176, weights 1176 + 32 = 1208, A^-1 1208 + 16 = 1224,
//   SRF Q(36, 432) = 720: 1224 .. 1944 = raw_size. Every count is a multiple of 4: no padding.
constexpr size_t kC = 9, kK = 2, kV = 8, kN = 2, kG = 4, kOofPoints = 48, kSrfPoints = 12;
constexpr size_t kAlbedo = 128, kGTable = 224, kTransfer = 352, kOof = 640, kBasis = 1144,
                 kWeights = 1176, kInverse = 1208, kSrf = 1224, kSize = 1944;

// The shells of both grids: the quad scene's box is x in [-1.25, 1], y in [0, 0.4], z in
// [-1, 1.25], its centre (-0.125, 0.2, 0.125) and the largest distance from it, to a corner,
// sqrt(1.125^2 + 0.2^2 + 1.125^2) = sqrt(2.57125).
const float kCentre[3] = {-0.125f, 0.2f, 0.125f};
const double kRadius = std::sqrt(2.57125);

// (BRDF) As stored bits: transfer rows 0 (term 0, y_00) and 9 (term 1, y_00), OOF row 0, the
// basis rows, SRF row 0 (offset, scale each).
const uint32_t kTransferRow0[2] = {0x3E38CA8Eu, 0x3A156B51u};
const uint32_t kTransferRow9[2] = {0xBD9831A2u, 0x39BD42B6u};
const uint32_t kOofRow0[2] = {0x3F3855D0u, 0x3C357FD1u};
const uint32_t kBasisRows[2][2] = {{0x3E813CDEu, 0x3A5CC8ABu}, {0xBF062F99u, 0x3B917CA2u}};
const uint32_t kSrfRow0[2] = {0x00000000u, 0x3A6C4A50u};
// (BRDF) Values as stored: vertex 0's and vertex 4's transfer (term-major, 2 x 9), the basis, the
// first SRF values.
const uint8_t kTransferV0[18] = {0, 0, 0, 0, 0, 0, 0, 0, 170, 0, 0, 0, 0, 0, 0, 157, 0, 0};
const uint8_t kTransferV4[18] = {255, 201, 253, 192, 172, 220, 224, 209, 152,
                                 205, 212, 220, 255, 203, 227, 181, 251, 158};
const uint8_t kBasisValues[16] = {0,   162, 255, 174, 240, 188, 195, 206,
                                  225, 81,  0,   126, 255, 133, 81,  166};
const uint8_t kSrfFirst[12] = {253, 149, 2, 119, 102, 85, 1, 98, 41, 222, 180, 33};
// (BRDF) g_0 on its 4 x 4 grid as stored bits: corner, edge and centre cells.
constexpr uint32_t kGCorner = 0x3F0F0E59u, kGEdge = 0x3F0EDFE1u, kGCentre = 0x3DD1D6D7u;

uint8_t u8(const Bytes& b, size_t at) {
  return b[at];
}

// offset + scale q of row `row` of the block whose params start at `params`.
double dequantised(const Bytes& b, size_t params, size_t values, size_t row, size_t index) {
  return double(f32_at(b, params + 8 * row)) +
         double(f32_at(b, params + 8 * row + 4)) * double(u8(b, values + index));
}

TEST(GoldenShadowfield, Containers) {
  expect_container(kZstd);
  expect_container(kRaw);
}

TEST(GoldenShadowfield, MeshSections) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    expect_mesh(a, kInfo);
  }
}

TEST(GoldenShadowfield, ZstdAndRawDecodeToTheSameSections) {
  expect_same_sections(kZstd, kRaw);
}

TEST(GoldenShadowfield, SfldHeader) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    prt_shadowfield_info info = prt::sized<prt_shadowfield_info>();
    ASSERT_EQ(prt_shadowfield_get_info(a.get(), &info), PRT_OK);
    EXPECT_EQ(info.order, 3u);
    EXPECT_EQ(info.terms, 2u);
    EXPECT_EQ(info.glossy, 1u);
    EXPECT_EQ(info.vertex_count, 8u);
    EXPECT_EQ(info.basis_size, 2u);
    EXPECT_EQ(info.brdf_grid, 4u);
    EXPECT_EQ(info.bits, 8u);
    EXPECT_EQ(info.bytes, kSize);
    // Floats the object decodes to: positions, normals, albedo (3 V each) and weights (V), the
    // g table, every quantised value, A^-1: 80 + 32 + 144 + 432 + 16 + 4 + 432 = 1140.
    EXPECT_EQ(info.decoded_bytes, 4u * 1140u);
    const prt_shadowfield_shells* grids[2] = {&info.oof_shells, &info.srf_shells};
    const uint32_t faces[2] = {2, 1};
    for (int g = 0; g < 2; ++g) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(grids[g]->centre[c], kCentre[c]) << g << "," << c;
      EXPECT_NEAR(grids[g]->radius, kRadius, 1e-6 * kRadius) << g;
      EXPECT_EQ(grids[g]->inner, 0.25f) << g;
      EXPECT_EQ(grids[g]->outer, 4.0f) << g;
      EXPECT_EQ(grids[g]->shells, 2u) << g;
      EXPECT_EQ(grids[g]->face_size, faces[g]) << g;
    }
    const Bytes sfld = a.section(PRT_SECTION_SFLD);
    ASSERT_EQ(sfld.size(), kSize);
    const uint32_t header[8] = {3, 2, 1, 8, 2, 4, 8, 0};
    for (size_t k = 0; k < 8; ++k) EXPECT_EQ(prt_test::get_u32(sfld, 4 * k), header[k]) << k;
    EXPECT_EQ(prt_test::get_u32(sfld, 32 + 12), 0x3FCD3FE0u);  // the radius as stored
    for (size_t k = 0; k < 8; ++k) EXPECT_EQ(prt_test::get_u32(sfld, 96 + 4 * k), 0u) << k;
  }
}

// The albedo the command gave, every vertex; the area weights a third of the vertex's triangles'
// areas: the ground's fan (0, 1, 2), (0, 2, 3) of two triangles of area 2, the occluder's of two
// of 1.125.
TEST(GoldenShadowfield, AlbedoAndAreaWeights) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes sfld = a.section(PRT_SECTION_SFLD);
  ASSERT_EQ(sfld.size(), kSize);
  const float albedo[3] = {0.8f, 0.6f, 0.4f};
  for (size_t v = 0; v < kV; ++v)
    for (size_t c = 0; c < 3; ++c) EXPECT_EQ(f32_at(sfld, kAlbedo + 12 * v + 4 * c), albedo[c]);
  const double weights[8] = {4.0 / 3, 2.0 / 3, 4.0 / 3, 2.0 / 3, 0.75, 0.375, 0.75, 0.375};
  for (size_t v = 0; v < kV; ++v)
    EXPECT_NEAR(f32_at(sfld, kWeights + 4 * v), weights[v], 1e-7 * weights[v]) << v;
}

TEST(GoldenShadowfield, QuantisedValuesByHand) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes sfld = a.section(PRT_SECTION_SFLD);
  ASSERT_EQ(sfld.size(), kSize);
  const size_t transfer_values = kTransfer + 8 * kK * kC, oof_values = kOof + 8 * kC;
  const size_t basis_values = kBasis + 8 * kN, srf_values = kSrf + 8 * kN * kK * kC;
  for (int e = 0; e < 2; ++e) {
    EXPECT_EQ(prt_test::get_u32(sfld, kTransfer + 4 * e), kTransferRow0[e]) << e;
    EXPECT_EQ(prt_test::get_u32(sfld, kTransfer + 72 + 4 * e), kTransferRow9[e]) << e;
    EXPECT_EQ(prt_test::get_u32(sfld, kOof + 4 * e), kOofRow0[e]) << e;
    EXPECT_EQ(prt_test::get_u32(sfld, kSrf + 4 * e), kSrfRow0[e]) << e;
    for (size_t j = 0; j < kN; ++j)
      EXPECT_EQ(prt_test::get_u32(sfld, kBasis + 8 * j + 4 * e), kBasisRows[j][e]) << j;
  }
  for (size_t i = 0; i < 18; ++i) {
    EXPECT_EQ(u8(sfld, transfer_values + i), kTransferV0[i]) << i;
    EXPECT_EQ(u8(sfld, transfer_values + 4 * 18 + i), kTransferV4[i]) << i;
  }
  for (size_t i = 0; i < 16; ++i) EXPECT_EQ(u8(sfld, basis_values + i), kBasisValues[i]) << i;
  for (size_t i = 0; i < 12; ++i) EXPECT_EQ(u8(sfld, srf_values + i), kSrfFirst[i]) << i;
  // The SPEC's quantiser: every row of these blocks spans its values, so each has a 0 and a 255.
  struct Block {
    size_t values, rows, count;
    size_t (*row)(size_t);
  };
  const Block blocks[4] = {
      {transfer_values, kK * kC, kV * kK * kC, [](size_t i) { return i % (kK * kC); }},
      {oof_values, kC, kOofPoints * kC, [](size_t i) { return i % kC; }},
      {basis_values, kN, kN * kV, [](size_t i) { return i / kV; }},
      {srf_values, kN * kK * kC, kN * kK * kSrfPoints * kC,
       [](size_t i) { return (i / (kSrfPoints * kC)) * kC + i % kC; }}};
  for (const Block& block : blocks) {
    std::vector<int> lo(block.rows, 256), hi(block.rows, -1);
    for (size_t i = 0; i < block.count; ++i) {
      const int q = u8(sfld, block.values + i);
      lo[block.row(i)] = std::min(lo[block.row(i)], q);
      hi[block.row(i)] = std::max(hi[block.row(i)], q);
    }
    for (size_t r = 0; r < block.rows; ++r) {
      EXPECT_EQ(lo[r], 0) << block.values << " row " << r;
      EXPECT_EQ(hi[r], 255) << block.values << " row " << r;
    }
  }
}

// g_0, the leading term of an isotropic BRDF, has the square grid's symmetry (cells of equal
// angle from the normal under the concentric map): its 4 corners, 8 edge cells and 4 centre cells
// are each one value.
TEST(GoldenShadowfield, LeadingBrdfTermIsIsotropic) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes sfld = a.section(PRT_SECTION_SFLD);
  ASSERT_EQ(sfld.size(), kSize);
  for (size_t y = 0; y < kG; ++y)
    for (size_t x = 0; x < kG; ++x) {
      const bool edge_x = x == 0 || x == kG - 1, edge_y = y == 0 || y == kG - 1;
      const uint32_t expected = edge_x && edge_y ? kGCorner : edge_x || edge_y ? kGEdge : kGCentre;
      EXPECT_EQ(prt_test::get_u32(sfld, kGTable + 4 * (y * kG + x)), expected) << x << "," << y;
    }
}

// The inverse normal matrix inverts A = B W B^T of the stored (dequantised) basis and weights, to
// within what 8-bit rounding of B can move A: |dB| <= scale / 2 per value, so |dA_ij| <= sum_v
// W_v (|B_iv| s_j + s_i |B_jv| + s_i s_j / 2) / 2, and |(A^-1 A - I)_ij| <= sum_k |A^-1_ik|
// |dA_kj|.
TEST(GoldenShadowfield, InverseNormalMatrixInvertsTheBasis) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes sfld = a.section(PRT_SECTION_SFLD);
  ASSERT_EQ(sfld.size(), kSize);
  const size_t values = kBasis + 8 * kN;
  double b[kN][kV], w[kV], s[kN], inverse[kN][kN];
  for (size_t j = 0; j < kN; ++j) {
    s[j] = f32_at(sfld, kBasis + 8 * j + 4);
    for (size_t v = 0; v < kV; ++v) b[j][v] = dequantised(sfld, kBasis, values, j, j * kV + v);
  }
  for (size_t v = 0; v < kV; ++v) w[v] = f32_at(sfld, kWeights + 4 * v);
  for (size_t i = 0; i < kN; ++i)
    for (size_t j = 0; j < kN; ++j) inverse[i][j] = f32_at(sfld, kInverse + 4 * (i * kN + j));
  double normal[kN][kN], moved[kN][kN];
  for (size_t i = 0; i < kN; ++i)
    for (size_t j = 0; j < kN; ++j) {
      normal[i][j] = moved[i][j] = 0.0;
      for (size_t v = 0; v < kV; ++v) {
        normal[i][j] += b[i][v] * w[v] * b[j][v];
        moved[i][j] +=
            w[v] * (std::fabs(b[i][v]) * s[j] + s[i] * std::fabs(b[j][v]) + 0.5 * s[i] * s[j]) / 2;
      }
    }
  for (size_t i = 0; i < kN; ++i)
    for (size_t j = 0; j < kN; ++j) {
      double product = 0.0, bound = 0.0;
      for (size_t k = 0; k < kN; ++k) {
        product += inverse[i][k] * normal[k][j];
        bound += std::fabs(inverse[i][k]) * moved[k][j];
      }
      EXPECT_NEAR(product, i == j ? 1.0 : 0.0, bound) << i << "," << j;
    }
}

// Self-shadowing in the transfer's constant term of term 0: the ground corner under the occluder
// (vertex 0) gets less than the other ground corners, which see the occluder from aside, and they
// less than the occluder's own corners, which nothing covers.
TEST(GoldenShadowfield, TransferFollowsTheOcclusion) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes sfld = a.section(PRT_SECTION_SFLD);
  ASSERT_EQ(sfld.size(), kSize);
  const size_t values = kTransfer + 8 * kK * kC;
  double t00[kV];
  for (size_t v = 0; v < kV; ++v) t00[v] = dequantised(sfld, kTransfer, values, 0, v * kK * kC);
  const double side_min = std::min({t00[1], t00[2], t00[3]});
  const double side_max = std::max({t00[1], t00[2], t00[3]});
  const double open_min = std::min({t00[4], t00[5], t00[6], t00[7]});
  EXPECT_LT(t00[0], side_min);
  EXPECT_LT(side_max, open_min);
}

// The OOF's constant term at a point is (4 pi - the solid angle the object hides) / sqrt(4 pi).
// On the outer shell (4 radii) the object, inside its bounding sphere, hides at most the cap
// 2 pi (1 - sqrt(1 - 1/16)); so every outer point lies between that and sqrt(4 pi), widened by one
// quantisation step (a ray of the bake's 256 hides 4 pi / 256, under a step). Every inner point
// (0.25 radii, inside the sphere) sees the object hide more than any outer point does.
TEST(GoldenShadowfield, OcclusionFieldSeesTheObjectShrinkWithDistance) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes sfld = a.section(PRT_SECTION_SFLD);
  ASSERT_EQ(sfld.size(), kSize);
  const size_t values = kOof + 8 * kC;
  const double step = f32_at(sfld, kOof + 4), open = std::sqrt(4.0 * kPi);
  const double cap = 2.0 * kPi * (1.0 - std::sqrt(1.0 - 1.0 / 16.0));
  double inner_max = 0.0, outer_min = open;
  for (size_t p = 0; p < kOofPoints; ++p) {
    const double dc = dequantised(sfld, kOof, values, 0, p * kC);
    if (p < kOofPoints / 2) {
      inner_max = std::max(inner_max, dc);
    } else {
      outer_min = std::min(outer_min, dc);
      EXPECT_LE(dc, open + 0.5 * step) << p;
      EXPECT_GE(dc, (4.0 * kPi - cap) / open - step) << p;
    }
  }
  EXPECT_LT(inner_max, outer_min);
}

// The blob shades through the runtime as SPEC §7.5 and the design's outgoing radiance say: one
// instance in its own frame, no bounces, a light of band 0 alone (L_00 per channel), the eye
// straight above vertex v (wo = the normal, the g table's centre, read bilinearly from its four
// central cells): B_c(v) = albedo_c sum_k g_k(centre) T_k,00(v) L_00,c.
TEST(GoldenShadowfield, ShadesAsTheSpecSays) {
  Asset a(kZstd);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes sfld = a.section(PRT_SECTION_SFLD);
  ASSERT_EQ(sfld.size(), kSize);
  auto [context, made] = prt::create_context();
  ASSERT_EQ(made, PRT_OK);
  prt_shadowfield_scene* scene = nullptr;
  ASSERT_EQ(prt_shadowfield_scene_create(context.get(), 1, &scene), PRT_OK);
  uint32_t object = 0, instance = 0;
  ASSERT_EQ(prt_shadowfield_scene_add_object(scene, a.get(), &object), PRT_OK);
  prt_shadowfield_transform identity = prt::sized<prt_shadowfield_transform>();
  identity.rotation[0] = identity.rotation[4] = identity.rotation[8] = 1.0f;
  identity.scale = 1.0f;
  ASSERT_EQ(prt_shadowfield_scene_add_instance(scene, object, &identity, &instance), PRT_OK);
  std::vector<float> light(3 * kC, 0.0f);
  light[0] = 1.5f, light[1] = 1.0f, light[2] = 0.5f;
  prt_shadowfield_settings settings = prt::sized<prt_shadowfield_settings>();
  settings.backend = PRT_BACKEND_CPU;
  const float positions[8][3] = {{-1, 0, 1},
                                 {1, 0, 1},
                                 {1, 0, -1},
                                 {-1, 0, -1},
                                 {-1.25f, 0.4f, 1.25f},
                                 {0.25f, 0.4f, 1.25f},
                                 {0.25f, 0.4f, -0.25f},
                                 {-1.25f, 0.4f, -0.25f}};
  const float albedo[3] = {0.8f, 0.6f, 0.4f};
  const size_t values = kTransfer + 8 * kK * kC;
  double g_centre[kK];
  for (size_t k = 0; k < kK; ++k) {
    g_centre[k] = 0.0;
    for (const size_t cell : {5u, 6u, 9u, 10u})
      g_centre[k] += 0.25 * f32_at(sfld, kGTable + 4 * (k * kG * kG + cell));
  }
  for (size_t v = 0; v < kV; ++v) {
    const float eye[3] = {positions[v][0], positions[v][1] + 5.0f, positions[v][2]};
    std::vector<float> rgb(3 * kV, -1.0f);
    float* out[1] = {rgb.data()};
    ASSERT_EQ(prt_shadowfield_shade(scene, light.data(), eye, &settings, out), PRT_OK);
    double sum = 0.0;
    for (size_t k = 0; k < kK; ++k)
      sum += g_centre[k] * dequantised(sfld, kTransfer, values, k * kC, (v * kK + k) * kC);
    for (size_t c = 0; c < 3; ++c) {
      const double expected = albedo[c] * sum * light[c];
      EXPECT_NEAR(rgb[3 * v + c], expected, 1e-6 * std::fabs(expected) + 1e-9) << v << "," << c;
    }
  }
  prt_shadowfield_scene_destroy(scene);
}

}  // namespace
