// SPDX-License-Identifier: MIT
// The frozen `pose` golden blobs (formats/golden/README.md): pose_hinge.prtk as baked (zstd) and
// pose_hinge_raw.prtk (every section uncompressed). Every number below was read from a hex dump of
// the files (xxd, python struct) and the SPEC's §7.3 layout, or from the bake command (order 3,
// --basis-dims 3, --bits 8, clip `swing` at 4 frames per second) and the hinge scene as
// formats/golden/scenes/make_hinge.py writes it; none is computed by the code under test. Where a
// decoded value is checked, the test recomputes it in double from the hand-read stored numbers
// with the SPEC §7.3 formula written out here.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "format/golden_scene.hpp"

namespace {

using namespace prt_golden;

const double kPi = 3.14159265358979323846;

const File kZstd = {"pose_hinge.prtk",
                    912,
                    0xFCC64F9Eu,
                    0x48635053u,
                    {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0xDADEC480u, 304, 75, 75, 75},
                     {PRT_SECTION_VPOS, 1, PRT_CODEC_ZSTD, 0x683BD8D2u, 384, 37, 96, 8},
                     {PRT_SECTION_VNRM, 0, PRT_CODEC_ZSTD, 0x6B5A2CA2u, 432, 28, 96, 8},
                     {PRT_SECTION_TRIS, 1, PRT_CODEC_ZSTD, 0x06B0275Eu, 464, 47, 48, 4},
                     {PRT_SECTION_PSTR, 1, PRT_CODEC_ZSTD, 0xABA149ECu, 512, 390, 960, 8}}};
const File kRaw = {"pose_hinge_raw.prtk",
                   1584,
                   0xE234BC69u,
                   0xE7E599B5u,
                   {{PRT_SECTION_INFO, 0, PRT_CODEC_NONE, 0xDADEC480u, 304, 75, 75, 75},
                    {PRT_SECTION_VPOS, 1, PRT_CODEC_NONE, 0xD37DF8DDu, 384, 96, 96, 8},
                    {PRT_SECTION_VNRM, 0, PRT_CODEC_NONE, 0x8A1F3C99u, 480, 96, 96, 8},
                    {PRT_SECTION_TRIS, 1, PRT_CODEC_NONE, 0x74E83D67u, 576, 48, 48, 4},
                    {PRT_SECTION_PSTR, 1, PRT_CODEC_NONE, 0x6C4ECCCDu, 624, 960, 960, 8}}};

const char kInfo[] = "prtkit pose bake: formats/golden/scenes/hinge.gltf, order 3, residual model";

// make_hinge.py: the floor quad (vertices 0-3, normal +y, joint 0) and the flap quad (vertices
// 4-7, normal +x, upright, joint 1) share the hinge edge x = y = 0 along z.
const float kPositions[8][3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 0, 1},
                                {0, 0, 0}, {0, 0, 1}, {0, 1, 0}, {0, 1, 1}};
const float kNormals[8][3] = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0},
                              {1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
const uint32_t kTriangles[12] = {0, 1, 2, 2, 1, 3, 4, 6, 5, 5, 6, 7};
const Mesh kHinge = {8, kPositions, kNormals, 4, kTriangles};

// Order 3 (C = 9), V = 8, J = 2 (F = 6), p = 1, q = 3, 8 bits (SPEC §7.3):
//   joints 64 + 2 x 140 = 344, eval order 344 + 8 = 352, pose mean 352 + 24 = 376,
//   pose basis 376 + 24 = 400, range 400 + 8 = 408, regression 408 + 2 x 3 x 9 x 4 = 624,
//   basis offset/scale 624 + 24 = 648, values 648 + 24 (no padding) = 672, skin 672 + 8 x 36 =
//   960 = raw_size.
constexpr size_t kJoints = 64, kEvalOrder = 344, kPoseMean = 352, kPoseBasis = 376,
                 kPoseRange = 400, kRegression = 408, kBasisParams = 624, kValues = 648,
                 kSkin = 672, kSize = 960, kC = 9, kQ = 3, kV = 8;

constexpr uint32_t kOne = 0x3F800000u;        // 1.0f
constexpr uint32_t kQuarterPi = 0x3F490FDBu;  // 0.7853982f: the clip swings the flap +-45 degrees

// X[0][k][c] (the bias row, k-major) and X[1][k][c] for k = 0 as stored bits.
const uint32_t kBias[kQ][kC] = {{0xBE279FFAu, 0xB96EEAE7u, 0xBDB945FCu, 0xBDC036A7u, 0x3A3AC684u,
                                 0x3B882DDDu, 0x39AAFAABu, 0x3AF919E9u, 0xBD558CB1u},
                                {0x3A6B4DD7u, 0xBB9F4E18u, 0x3DB9F68Eu, 0xBDCD5B4Du, 0xBBF096A4u,
                                 0xBB779BF1u, 0x3D7B9EB7u, 0xBB378422u, 0xBD0EB87Fu},
                                {0xBD058D06u, 0x3AA8D791u, 0x3C4EF5C3u, 0x3C68B00Fu, 0xBAB023E4u,
                                 0x3C0F7D57u, 0xBCE8CFBCu, 0x3D0CAF8Bu, 0xBC2C8386u}};
const uint32_t kWeights0[kC] = {0xB3D32B40u, 0xB4FE9FB9u, 0x361038B8u, 0x36A1E4ECu, 0xB4D784E1u,
                                0xB513408Eu, 0xB3AF8DD6u, 0x371CB0CCu, 0xB5060513u};
// X[1][2][c] for two c.
const struct { uint32_t c, bits; } kWeights2ByHand[] = {{0, 0x369DEBC7u}, {8, 0x34515E25u}};

// Basis column k: offset, scale as stored bits.
const uint32_t kBasisOffset[kQ] = {0x3B8F8690u, 0xBF00A014u, 0xBD20FDFDu};
const uint32_t kBasisScale[kQ] = {0x3B02337Au, 0x3B821114u, 0x3B2869B4u};
// The 8-bit basis values value[v][k]; each column has a 0 and a 255 (min and max, SPEC §7.1).
const uint8_t kBasisValues[kV][kQ] = {{255, 0, 26},   {249, 5, 0},   {3, 117, 224}, {0, 121, 155},
                                      {248, 252, 20}, {245, 255, 4}, {1, 132, 190}, {1, 136, 255}};

float bits(uint32_t b) {
  return f32_of_bits(b);
}

TEST(GoldenPose, Containers) {
  expect_container(kZstd);
  expect_container(kRaw);
}

TEST(GoldenPose, MeshSections) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    expect_mesh(a, kInfo, kHinge);
  }
}

TEST(GoldenPose, ZstdAndRawDecodeToTheSameSections) {
  expect_same_sections(kZstd, kRaw);
}

TEST(GoldenPose, PstrHeader) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    prt_pose_info info = prt::sized<prt_pose_info>();
    ASSERT_EQ(prt_pose_get_info(a.get(), &info), PRT_OK);
    EXPECT_EQ(info.order, 3u);
    EXPECT_EQ(info.vertex_count, 8u);
    EXPECT_EQ(info.joint_count, 2u);
    EXPECT_EQ(info.feature_count, 6u);
    EXPECT_EQ(info.pose_dims, 1u);
    EXPECT_EQ(info.basis_dims, 3u);
    EXPECT_EQ(info.model, PRT_POSE_MODEL_RESIDUAL);
    EXPECT_EQ(info.bits, 8u);
    EXPECT_EQ(info.model_joint, 0u);
    EXPECT_EQ(info.kind, 1u);  // shadowed
    EXPECT_EQ(info.bounces, 0u);
    EXPECT_EQ(info.albedo, 1.0f);
    EXPECT_EQ(info.clamps_pose, 1);
    EXPECT_EQ(info.model_bytes, kSkin - kPoseMean);  // pose PCA, regression, basis: 320
    const Bytes pstr = a.section(PRT_SECTION_PSTR);
    ASSERT_EQ(pstr.size(), kSize);
    // order, V, J, p, q, model, bits, model joint, kind, bounces, albedo 1.0f, flags (clamp),
    // reserved.
    const uint32_t header[16] = {3, 8, 2, 1, 3, 1, 8, 0, 1, 0, kOne, 1, 0, 0, 0, 0};
    for (size_t k = 0; k < 16; ++k) EXPECT_EQ(prt_test::get_u32(pstr, 4 * k), header[k]) << k;
  }
}

// make_hinge.py gives the joint nodes no transform: each bind rotation is the identity, rest
// translation 0, rest scale 1; the skin node and the joints sit at the scene root, so `pre` is
// the identity, and both inverse-bind matrices are the identity. Joint 0 (floor_joint) is the
// root, joint 1 (flap_joint) its child.
TEST(GoldenPose, JointsAndEvalOrder) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes pstr = a.section(PRT_SECTION_PSTR);
  ASSERT_EQ(pstr.size(), kSize);
  const uint32_t parents[2] = {0xFFFFFFFFu, 0u};  // -1, 0
  const uint32_t identity34[12] = {kOne, 0, 0, 0, 0, kOne, 0, 0, 0, 0, kOne, 0};
  for (uint32_t j = 0; j < 2; ++j) {
    SCOPED_TRACE(j);
    const size_t at = kJoints + 140 * j;
    EXPECT_EQ(prt_test::get_u32(pstr, at), parents[j]);
    const uint32_t bind[4] = {0, 0, 0, kOne};  // x y z w
    for (size_t k = 0; k < 4; ++k) EXPECT_EQ(prt_test::get_u32(pstr, at + 4 + 4 * k), bind[k]);
    for (size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(prt_test::get_u32(pstr, at + 20 + 4 * k), 0u) << k;    // rest translation
      EXPECT_EQ(prt_test::get_u32(pstr, at + 32 + 4 * k), kOne) << k;  // rest scale
    }
    for (size_t k = 0; k < 12; ++k) {
      EXPECT_EQ(prt_test::get_u32(pstr, at + 44 + 4 * k), identity34[k]) << k;  // pre
      EXPECT_EQ(prt_test::get_u32(pstr, at + 92 + 4 * k), identity34[k]) << k;  // inverse bind
    }
  }
  EXPECT_EQ(prt_test::get_u32(pstr, kEvalOrder), 0u);
  EXPECT_EQ(prt_test::get_u32(pstr, kEvalOrder + 4), 1u);

  // The runtime's bind pose is the stored one.
  float rotations[8], translations[6], scales[6];
  ASSERT_EQ(prt_pose_bind_pose(a.get(), rotations, translations, scales), PRT_OK);
  for (size_t j = 0; j < 2; ++j) {
    const float q[4] = {0, 0, 0, 1};
    for (size_t k = 0; k < 4; ++k) EXPECT_EQ(rotations[4 * j + k], q[k]) << j << "," << k;
    for (size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(translations[3 * j + k], 0.0f) << j << "," << k;
      EXPECT_EQ(scales[3 * j + k], 1.0f) << j << "," << k;
    }
  }
}

// Five training frames of one joint angle about z: the mean feature is 0 (the clip is symmetric,
// -45..45 degrees), the one pose direction is feature 5 (joint 1's z), range +-pi/4.
TEST(GoldenPose, PosePca) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes pstr = a.section(PRT_SECTION_PSTR);
  ASSERT_EQ(pstr.size(), kSize);
  for (size_t f = 0; f < 6; ++f) {
    EXPECT_EQ(prt_test::get_u32(pstr, kPoseMean + 4 * f), 0u) << f;
    EXPECT_EQ(prt_test::get_u32(pstr, kPoseBasis + 4 * f), f == 5 ? kOne : 0u) << f;
  }
  EXPECT_EQ(prt_test::get_u32(pstr, kPoseRange), kQuarterPi | 0x80000000u);  // -pi/4
  EXPECT_EQ(prt_test::get_u32(pstr, kPoseRange + 4), kQuarterPi);
}

TEST(GoldenPose, RegressionAndBasis) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes pstr = a.section(PRT_SECTION_PSTR);
  ASSERT_EQ(pstr.size(), kSize);
  for (size_t k = 0; k < kQ; ++k)
    for (size_t c = 0; c < kC; ++c)
      EXPECT_EQ(prt_test::get_u32(pstr, kRegression + 4 * (kC * k + c)), kBias[k][c])
          << k << "," << c;
  for (size_t c = 0; c < kC; ++c)
    EXPECT_EQ(prt_test::get_u32(pstr, kRegression + 4 * (kQ * kC + c)), kWeights0[c]) << c;
  for (const auto& w : kWeights2ByHand)
    EXPECT_EQ(prt_test::get_u32(pstr, kRegression + 4 * (kQ * kC + 2 * kC + w.c)), w.bits) << w.c;
  for (size_t k = 0; k < kQ; ++k) {
    EXPECT_EQ(prt_test::get_u32(pstr, kBasisParams + 8 * k), kBasisOffset[k]) << k;
    EXPECT_EQ(prt_test::get_u32(pstr, kBasisParams + 8 * k + 4), kBasisScale[k]) << k;
  }
  for (size_t v = 0; v < kV; ++v)
    for (size_t k = 0; k < kQ; ++k)
      EXPECT_EQ(pstr[kValues + kQ * v + k], kBasisValues[v][k]) << v << "," << k;
}

// Every vertex is bound to one joint with the whole weight 65535: the floor to joint 0, the flap
// to joint 1; local position and normal are the mesh's own (the inverse binds are identities).
TEST(GoldenPose, Skin) {
  Asset a(kRaw);
  ASSERT_EQ(a.result(), PRT_OK) << a.message();
  const Bytes pstr = a.section(PRT_SECTION_PSTR);
  ASSERT_EQ(pstr.size(), kSize);
  for (size_t v = 0; v < kV; ++v) {
    SCOPED_TRACE(v);
    const size_t at = kSkin + 36 * v;
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(f32_at(pstr, at + 4 * c), kPositions[v][c]) << c;
      EXPECT_EQ(f32_at(pstr, at + 12 + 4 * c), kNormals[v][c]) << c;
    }
    const uint8_t joints[4] = {uint8_t(v < 4 ? 0 : 1), 0, 0, 0};
    const uint16_t weights[4] = {65535, 0, 0, 0};
    for (size_t k = 0; k < 4; ++k) {
      EXPECT_EQ(pstr[at + 24 + k], joints[k]) << k;
      EXPECT_EQ(prt_le_load_u16(pstr.data() + at + 28 + 2 * k), weights[k]) << k;
    }
  }
}

prt_pose_input pose_of(const float* rotations) {
  prt_pose_input in = prt::sized<prt_pose_input>();
  in.joint_rotations = rotations;
  return in;
}

// a[3j..3j+2] is the rotation vector of r = conj(b_j) q_j (negated when r.w < 0); b_j is the
// identity here, and a[0..2] = 0 for the model joint 0 whatever its rotation.
TEST(GoldenPose, Features) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    // Joint 0 turned by 90 degrees about x; joint 1 by 60 degrees about z, given as
    // -2 (0, 0, sin 30, cos 30): not unit (normalised) and w < 0 (negated): r = (0, 0, 1/2,
    // sqrt 3/2), 2 atan2(1/2, sqrt 3/2) = pi/3 about +z.
    const float rotations[8] = {0.70710678f, 0, 0, 0.70710678f, 0, 0, -1.0f, -1.7320508f};
    const prt_pose_input pose = pose_of(rotations);
    float features[6];
    ASSERT_EQ(prt_pose_features(a.get(), &pose, features), PRT_OK);
    const double expected[6] = {0, 0, 0, 0, 0, kPi / 3};
    for (size_t k = 0; k < 6; ++k) EXPECT_NEAR(features[k], expected[k], 1e-6) << k;
    // 30 degrees about -z: (0, 0, -sin 15, cos 15) -> -pi/6 about z.
    const float back[8] = {0, 0, 0, 1, 0, 0, -0.25881905f, 0.96592583f};
    const prt_pose_input pose_back = pose_of(back);
    ASSERT_EQ(prt_pose_features(a.get(), &pose_back, features), PRT_OK);
    for (size_t k = 0; k < 5; ++k) EXPECT_EQ(features[k], 0.0f) << k;
    EXPECT_NEAR(features[5], -kPi / 6, 1e-6);
  }
}

// Model frame: joint 0 at rest, the identity. At rest every vertex is at its bind position with
// its bind normal; with the flap turned 90 degrees about z (x, y, z) -> (-y, x, z): the flap lies
// flat on the -x side of the hinge, facing up.
TEST(GoldenPose, Skinning) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    const float rest[8] = {0, 0, 0, 1, 0, 0, 0, 1};
    const prt_pose_input pose_rest = pose_of(rest);
    float positions[24], normals[24], frame[12];
    ASSERT_EQ(prt_pose_skin(a.get(), &pose_rest, 0, 8, positions, normals, frame), PRT_OK);
    const float identity34[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    for (size_t k = 0; k < 12; ++k) EXPECT_EQ(frame[k], identity34[k]) << k;
    for (size_t v = 0; v < kV; ++v)
      for (size_t c = 0; c < 3; ++c) {
        EXPECT_EQ(positions[3 * v + c], kPositions[v][c]) << v << "," << c;
        EXPECT_EQ(normals[3 * v + c], kNormals[v][c]) << v << "," << c;
      }

    const float s = 0.70710678f;
    const float hinge90[8] = {0, 0, 0, 1, 0, 0, s, s};
    const prt_pose_input pose_90 = pose_of(hinge90);
    ASSERT_EQ(prt_pose_skin(a.get(), &pose_90, 0, 8, positions, normals, frame), PRT_OK);
    for (size_t k = 0; k < 12; ++k) EXPECT_NEAR(frame[k], identity34[k], 1e-6) << k;
    const float turned[8][3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0},  {1, 0, 1},
                                {0, 0, 0}, {0, 0, 1}, {-1, 0, 0}, {-1, 0, 1}};
    for (size_t v = 0; v < kV; ++v)
      for (size_t c = 0; c < 3; ++c) {
        EXPECT_NEAR(positions[3 * v + c], turned[v][c], 1e-6) << v << "," << c;
        EXPECT_NEAR(normals[3 * v + c], c == 1 ? 1.0f : 0.0f, 1e-6) << v << "," << c;
      }
  }
}

// z = pose_basis^T (a - mean) = a[5] (mean 0, basis e5), clamped to [-pi/4, pi/4] (flag bit 0);
// y[k][c] = X[0][k][c] + z X[1][k][c].
TEST(GoldenPose, Coefficients) {
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    float z = -1;
    std::vector<float> y(kQ * kC);
    const float rest[8] = {0, 0, 0, 1, 0, 0, 0, 1};
    const prt_pose_input pose_rest = pose_of(rest);
    ASSERT_EQ(prt_pose_coefficients(a.get(), &pose_rest, &z, y.data()), PRT_OK);
    EXPECT_EQ(z, 0.0f);
    for (size_t k = 0; k < kQ; ++k)
      for (size_t c = 0; c < kC; ++c) EXPECT_EQ(y[kC * k + c], bits(kBias[k][c])) << k << c;

    // 30 degrees about z: z = pi/6, inside the range.
    const float thirty[8] = {0, 0, 0, 1, 0, 0, 0.25881905f, 0.96592583f};
    const prt_pose_input pose_30 = pose_of(thirty);
    ASSERT_EQ(prt_pose_coefficients(a.get(), &pose_30, &z, y.data()), PRT_OK);
    EXPECT_NEAR(z, kPi / 6, 1e-6);
    for (size_t c = 0; c < kC; ++c)
      EXPECT_NEAR(y[c], double(bits(kBias[0][c])) + kPi / 6 * double(bits(kWeights0[c])), 1e-7)
          << c;

    // 90 degrees about z: z = pi/2 clamped to the stored max pi/4.
    const float s = 0.70710678f;
    const float ninety[8] = {0, 0, 0, 1, 0, 0, s, s};
    const prt_pose_input pose_90 = pose_of(ninety);
    ASSERT_EQ(prt_pose_coefficients(a.get(), &pose_90, &z, y.data()), PRT_OK);
    EXPECT_EQ(z, bits(kQuarterPi));
    for (size_t c = 0; c < kC; ++c)
      EXPECT_NEAR(y[c],
                  double(bits(kBias[0][c])) + double(bits(kQuarterPi)) * double(bits(kWeights0[c])),
                  1e-7)
          << c;
  }
}

// The transfer at the bind pose (z = 0, y = X[0]), model 1, albedo 1, SPEC §7.3:
//   t[v][c] = rho (A_l / pi) y_c(n_v) + sum_k U[v][k] y[k][c],  U[v][k] = offset_k + scale_k
//   value[v][k],
// computed here in double from the hand-read stored numbers above. A_l / pi = 1, 2/3, 1/4 for
// bands 0, 1, 2 (SPEC §13). The SH frame of a direction (X, Y, Z) is x = X, y = -Z, z = Y, so
// the floor normal +Y is SH z = 1 and the flap normal +X is SH x = 1; §13's band 0-2 table gives
// y_c at those (c = l(l+1) + m): Y_00 = 1/(2 sqrt pi), Y_10 = sqrt(3/(4 pi)) z,
// Y_11 = sqrt(3/(4 pi)) x, Y_20 = sqrt(5/(16 pi)) (3z^2 - 1), Y_22 = sqrt(15/(16 pi)) (x^2 - y^2).
TEST(GoldenPose, TransferAtTheBindPose) {
  const double y00 = 0.5 / std::sqrt(kPi), y1 = std::sqrt(3 / (4 * kPi)),
               y20 = std::sqrt(5 / (16 * kPi)), y22 = std::sqrt(15 / (16 * kPi));
  const double floor_sh[kC] = {y00, 0, y1, 0, 0, 0, 2 * y20, 0, 0};  // SH z = 1
  const double flap_sh[kC] = {y00, 0, 0, y1, 0, 0, -y20, 0, y22};    // SH x = 1
  const double band[kC] = {1, 2. / 3, 2. / 3, 2. / 3, .25, .25, .25, .25, .25};
  for (const File* f : {&kZstd, &kRaw}) {
    SCOPED_TRACE(f->name);
    Asset a(*f);
    ASSERT_EQ(a.result(), PRT_OK) << a.message();
    const float rest[8] = {0, 0, 0, 1, 0, 0, 0, 1};
    const prt_pose_input pose_rest = pose_of(rest);
    std::vector<float> t(kV * kC);
    ASSERT_EQ(prt_pose_transfer(a.get(), PRT_BACKEND_CPU, &pose_rest, nullptr, 0, 8, t.data()),
              PRT_OK);
    for (size_t v = 0; v < kV; ++v)
      for (size_t c = 0; c < kC; ++c) {
        double expected = 1.0 * band[c] * (v < 4 ? floor_sh[c] : flap_sh[c]);
        for (size_t k = 0; k < kQ; ++k) {
          const double u = double(bits(kBasisOffset[k])) +
                           double(bits(kBasisScale[k])) * double(kBasisValues[v][k]);
          expected += u * double(bits(kBias[k][c]));
        }
        EXPECT_NEAR(t[kC * v + c], expected, 1e-6) << v << "," << c;
      }
    // One range of vertices gives the same values as the whole.
    std::vector<float> part(2 * kC);
    ASSERT_EQ(prt_pose_transfer(a.get(), PRT_BACKEND_CPU, &pose_rest, nullptr, 5, 2, part.data()),
              PRT_OK);
    for (size_t k = 0; k < 2 * kC; ++k) EXPECT_EQ(part[k], t[5 * kC + k]) << k;
  }
}

}  // namespace
