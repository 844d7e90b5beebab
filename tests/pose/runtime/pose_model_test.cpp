// SPDX-License-Identifier: MIT
// Features, skin, model frame, coordinates and coefficients of the `pose` runtime against closed
// forms (quarter turns, a scaled joint, a Gram-Schmidt frame) and against the SPEC's formulas
// restated in double in pose/pose_blob.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pose/pose_blob.hpp"

namespace {

using namespace prt_test;

const double kPi = 3.14159265358979323846;

// Two joints: 0 the model joint (root), 1 its child; one vertex, q = 1, no pose PCA.
PoseSection two_joints() {
  PoseSection s;
  s.joints.assign(2, PoseJoint{});
  s.joints[1].parent = 0;
  s.eval_order = {0, 1};
  s.fit();
  s.basis_params = {0.0f, 1.0f};
  return s;
}

struct Loaded {
  Context ctx;
  LoadedAsset asset;
  explicit Loaded(const PoseSection& s, prt_validation level = PRT_VALIDATE_FULL)
      : asset(ctx.ctx, pose_blob(s), level) {
    EXPECT_EQ(asset.result, PRT_OK) << prt_context_last_message(ctx.ctx);
  }
  const prt_asset* get() const { return asset.asset; }
};

std::vector<float> feature_of(const Loaded& a, const std::vector<float>& rotations) {
  std::vector<float> out(3 * (rotations.size() / 4), -99.0f);
  const prt_pose_input pose = pose_of(rotations);
  EXPECT_EQ(prt_pose_features(a.get(), &pose, out.data()), PRT_OK);
  return out;
}

std::vector<float> rotations_of(const std::vector<Quat>& q) {
  std::vector<float> r;
  for (const Quat& x : q)
    for (double c : x) r.push_back(float(c));
  return r;
}

// A quarter turn about an axis is the rotation vector pi/2 along it; the model joint has none.
TEST(PoseFeatures, QuarterTurnIsHalfPiAlongTheAxis) {
  const Loaded a(two_joints());
  const double axes[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, -2, 2}};
  for (const auto& axis : axes) {
    const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const Quat quarter = axis_angle(axis[0], axis[1], axis[2], kPi / 2);
    const std::vector<float> f = feature_of(a, rotations_of({quarter, quarter}));
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(f[i], 0.0f);  // the model joint
      EXPECT_NEAR(f[3 + i], kPi / 2 * axis[i] / len, 1e-6);
    }
  }
}

// Features are relative to the bind rotation: q = b (x) quarter turn gives the quarter turn's
// vector, q = b gives zero, and a three-quarter turn is the quarter turn the other way.
TEST(PoseFeatures, RelativeToANonIdentityBindRotation) {
  PoseSection s = two_joints();
  const Quat bind = axis_angle(0.3, 1.0, -0.5, 0.9);
  s.joints[1].bind = to_float4(bind);
  const Loaded a(s);
  const Quat b{s.joints[1].bind[0], s.joints[1].bind[1], s.joints[1].bind[2], s.joints[1].bind[3]};
  const Quat id{0, 0, 0, 1};
  const std::vector<float> turned =
      feature_of(a, rotations_of({id, quat_mul(b, axis_angle(0, 0, 1, kPi / 2))}));
  EXPECT_NEAR(turned[3], 0.0, 1e-6);
  EXPECT_NEAR(turned[4], 0.0, 1e-6);
  EXPECT_NEAR(turned[5], kPi / 2, 1e-6);
  const std::vector<float> rest = feature_of(a, rotations_of({id, b}));
  for (int i = 3; i < 6; ++i) EXPECT_NEAR(rest[i], 0.0, 1e-6);
  const std::vector<float> back =
      feature_of(a, rotations_of({id, quat_mul(b, axis_angle(1, 0, 0, 1.5 * kPi))}));
  EXPECT_NEAR(back[3], -kPi / 2, 1e-6);
  EXPECT_NEAR(back[4], 0.0, 1e-6);
}

// q and -q are the same rotation; so is 3 q (rotations are normalised).
TEST(PoseFeatures, SignAndLengthOfTheQuaternionDoNotMatter) {
  const Loaded a(two_joints());
  const Quat q = axis_angle(0.2, -0.7, 0.4, 2.1);
  const std::vector<float> plus = feature_of(a, rotations_of({q, q}));
  const std::vector<float> minus = feature_of(a, rotations_of({q, {-q[0], -q[1], -q[2], -q[3]}}));
  const std::vector<float> longer =
      feature_of(a, rotations_of({q, {3 * q[0], 3 * q[1], 3 * q[2], 3 * q[3]}}));
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(plus[i], minus[i]) << i;
    EXPECT_NEAR(plus[i], longer[i], 1e-6) << i;
  }
  EXPECT_NEAR(std::sqrt(plus[3] * plus[3] + plus[4] * plus[4] + plus[5] * plus[5]), 2.1, 1e-6);
}

// Random skeletons: every feature matches the SPEC's formula in double.
TEST(PoseFeatures, MatchTheSpecsFormulaOnRandomSkeletons) {
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    const PoseSection s = random_section(2, 5, 7, 4, 3, 8, 0, seed);
    const Loaded a(s);
    const std::vector<float> r = random_rotations(7, seed + 10);
    const std::vector<double> expected = features(s, r);
    const std::vector<float> got = feature_of(a, r);
    for (size_t f = 0; f < expected.size(); ++f) EXPECT_NEAR(got[f], expected[f], 2e-6) << f;
  }
}

TEST(PoseFeatures, RejectZeroAndNonFiniteRotations) {
  const Loaded a(two_joints());
  std::vector<float> out(6);
  std::vector<float> r = {0, 0, 0, 1, 0, 0, 0, 0};
  prt_pose_input pose = pose_of(r);
  EXPECT_EQ(prt_pose_features(a.get(), &pose, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  r[7] = NAN;
  EXPECT_EQ(prt_pose_features(a.get(), &pose, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  r[7] = INFINITY;
  EXPECT_EQ(prt_pose_features(a.get(), &pose, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  r[7] = 1;
  EXPECT_EQ(prt_pose_features(a.get(), &pose, out.data()), PRT_OK);
  EXPECT_EQ(prt_pose_features(a.get(), &pose, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_pose_features(a.get(), nullptr, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_pose_features(nullptr, &pose, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  pose.joint_rotations = nullptr;
  EXPECT_EQ(prt_pose_features(a.get(), &pose, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  pose = pose_of(r);
  pose.struct_size = 8;
  EXPECT_EQ(prt_pose_features(a.get(), &pose, out.data()), PRT_ERROR_INVALID_ARGUMENT);
}

struct Skinned {
  std::vector<float> positions, normals, frame;
};

Skinned skin_all(const Loaded& a, const PoseSection& s, const prt_pose_input& pose) {
  Skinned out{std::vector<float>(3 * s.vertices), std::vector<float>(3 * s.vertices),
              std::vector<float>(12)};
  EXPECT_EQ(prt_pose_skin(a.get(), &pose, 0, s.vertices, out.positions.data(), out.normals.data(),
                          out.frame.data()),
            PRT_OK);
  return out;
}

// A two-joint chain under a moved and turned model joint, with pre and inverse-bind matrices and
// weights split between the joints: positions and normals match the SPEC's formulas in double
// (independent code: a general inverse, the inverse transpose for normals).
TEST(PoseSkin, TwoJointChainWithPreMatricesMatchesTheSpec) {
  PoseSection s = two_joints();
  s.vertices = 4;
  s.fit();
  s.joints[0].translation = {0.5f, 1.0f, -2.0f};
  s.joints[1].translation = {0.0f, 1.5f, 0.0f};
  s.joints[1].scale = {1.0f, 1.3f, 0.8f};
  const Affine pre0 = trs({1, 0, 2}, axis_angle(0, 1, 0, 0.6), {1, 1, 1});
  const Affine pre1 = trs({0, 0.25, 0}, axis_angle(1, 0, 0, 0.3), {1, 2, 1});
  const Affine ib1 = affine_inverse(trs({0, 1.5, 0}, axis_angle(1, 1, 0, 0.2), {1, 1, 1}));
  for (int e = 0; e < 12; ++e)
    s.joints[0].pre[e] = float(pre0[e]), s.joints[1].pre[e] = float(pre1[e]),
    s.joints[1].inverse_bind[e] = float(ib1[e]);
  const uint16_t weights[4][2] = {{65535, 0}, {0, 65535}, {30000, 10000}, {1, 65534}};
  for (uint32_t v = 0; v < 4; ++v) {
    s.skin[v].position = {0.1f * v, 1.0f + v, -0.5f};
    s.skin[v].normal = {0.3f, 1.0f, 0.2f * v};
    s.skin[v].joints = {0, 1, 0, 0};
    s.skin[v].weights = {weights[v][0], weights[v][1], 0, 0};
  }
  const Loaded a(s);
  const std::vector<float> r = rotations_of({axis_angle(0, 1, 0, 1.1), axis_angle(0, 0, 1, -0.7)});
  const Skinned got = skin_all(a, s, pose_of(r));
  for (uint32_t v = 0; v < 4; ++v) {
    const SkinnedVertex e = skin_vertex(s, r, v);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(got.positions[3 * v + i], e.position[i], 4e-6) << v << " " << i;
      EXPECT_NEAR(got.normals[3 * v + i], e.normal[i], 2e-6) << v << " " << i;
    }
  }
  // The model frame is G_0's: the rotation of pre0 * R(q0), origin pre0's t plus pre0's turn of
  // the translation.
  const Affine g0 = affine_mul(pre0, trs({0.5, 1.0, -2.0}, axis_angle(0, 1, 0, 1.1), {1, 1, 1}));
  for (int e = 0; e < 12; ++e) EXPECT_NEAR(got.frame[e], g0[e], 2e-6) << e;
}

// A joint scaled by (2, 1, 1) at rest: normals go through the inverse transpose,
// normalize(1/2, 1, 0) for (1, 1, 0), positions through the scale.
TEST(PoseSkin, NonUniformScaleMapsNormalsByTheInverseTranspose) {
  PoseSection s = two_joints();
  s.joints[1].scale = {2.0f, 1.0f, 1.0f};
  s.skin[0].position = {1.0f, 1.0f, 1.0f};
  s.skin[0].normal = {1.0f, 1.0f, 0.0f};
  s.skin[0].joints = {1, 0, 0, 0};
  const Loaded a(s);
  const std::vector<float> r = {0, 0, 0, 1, 0, 0, 0, 1};
  const Skinned got = skin_all(a, s, pose_of(r));
  EXPECT_NEAR(got.positions[0], 2.0, 1e-7);
  EXPECT_NEAR(got.positions[1], 1.0, 1e-7);
  EXPECT_NEAR(got.positions[2], 1.0, 1e-7);
  EXPECT_NEAR(got.normals[0], 0.5 / std::sqrt(1.25), 1e-7);
  EXPECT_NEAR(got.normals[1], 1.0 / std::sqrt(1.25), 1e-7);
  EXPECT_EQ(got.normals[2], 0.0f);
  // The caller's scale replaces the rest one: (1, 1, 1) leaves the vertex where it is.
  const std::vector<float> unit_scale = {1, 1, 1, 1, 1, 1};
  prt_pose_input pose = pose_of(r);
  pose.joint_scales = unit_scale.data();
  const Skinned rest = skin_all(a, s, pose);
  EXPECT_NEAR(rest.positions[0], 1.0, 1e-7);
  EXPECT_NEAR(rest.normals[0], std::sqrt(0.5), 1e-7);
  // A zero scale makes K singular: the normal is 0.
  const std::vector<float> flat = {1, 1, 1, 0, 1, 1};
  pose.joint_scales = flat.data();
  const Skinned singular = skin_all(a, s, pose);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(singular.normals[i], 0.0f);
}

// All weights zero: K is the identity, whatever the pose.
TEST(PoseSkin, ZeroWeightsLeaveTheVertexAsStored) {
  PoseSection s = random_section(2, 3, 4, 2, 2, 8, 0, 3);
  s.skin[1].weights = {0, 0, 0, 0};
  s.skin[1].position = {0.25f, -1.5f, 2.0f};
  s.skin[1].normal = {0.0f, 3.0f, 4.0f};
  const Loaded a(s);
  const std::vector<float> r = random_rotations(4, 9);
  const Skinned got = skin_all(a, s, pose_of(r));
  EXPECT_EQ(got.positions[3], 0.25f);
  EXPECT_EQ(got.positions[4], -1.5f);
  EXPECT_EQ(got.positions[5], 2.0f);
  EXPECT_NEAR(got.normals[3], 0.0, 1e-7);
  EXPECT_NEAR(got.normals[4], 0.6, 1e-7);
  EXPECT_NEAR(got.normals[5], 0.8, 1e-7);
}

// The model frame is the Gram-Schmidt rotation of G_m's 3x3 part: for Rz(t) times an upper
// triangular shear and scale, the axes of Rz(t) exactly; its origin is G_m's translation.
TEST(PoseSkin, ModelFrameIsGramSchmidtOfTheModelJoint) {
  PoseSection s = two_joints();
  const Affine rz = trs({1, 2, 3}, axis_angle(0, 0, 1, 0.5), {1, 1, 1});
  const Affine shear = {2, 0.5, 0.25, 0, 0, 1.5, -0.75, 0, 0, 0, 3, 0};
  const Affine pre = affine_mul(rz, shear);
  for (int e = 0; e < 12; ++e) s.joints[0].pre[e] = float(pre[e]);
  const Loaded a(s);
  const std::vector<float> r = {0, 0, 0, 1, 0, 0, 0, 1};
  const Skinned got = skin_all(a, s, pose_of(r));
  const double c = std::cos(0.5), sn = std::sin(0.5);
  const double expected[12] = {c, -sn, 0, 1, sn, c, 0, 2, 0, 0, 1, 3};
  for (int e = 0; e < 12; ++e) EXPECT_NEAR(got.frame[e], expected[e], 2e-7) << e;
}

TEST(PoseSkin, RangesAndArguments) {
  const PoseSection s = random_section(2, 5, 3, 2, 2, 8, 0, 4);
  const Loaded a(s);
  const std::vector<float> r = random_rotations(3, 1);
  const prt_pose_input pose = pose_of(r);
  std::vector<float> p(15), n(15);
  EXPECT_EQ(prt_pose_skin(a.get(), &pose, 0, 5, p.data(), n.data(), nullptr), PRT_OK);
  std::vector<float> p2(6), n2(6);
  EXPECT_EQ(prt_pose_skin(a.get(), &pose, 3, 2, p2.data(), n2.data(), nullptr), PRT_OK);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(p2[i], p[9 + i]);
    EXPECT_EQ(n2[i], n[9 + i]);
  }
  EXPECT_EQ(prt_pose_skin(a.get(), &pose, 5, 0, nullptr, nullptr, nullptr), PRT_OK);
  EXPECT_EQ(prt_pose_skin(a.get(), &pose, 4, 2, p.data(), nullptr, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_pose_skin(a.get(), &pose, 6, 0, p.data(), nullptr, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_pose_skin(a.get(), &pose, 1, 0xFFFFFFFFu, p.data(), nullptr, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
}

// Coordinates and coefficients match the SPEC's model in double.
TEST(PoseModel, CoordinatesAndCoefficientsMatchTheSpec) {
  const PoseSection s = random_section(3, 2, 5, 6, 4, 16, 0, 21);
  const Loaded a(s);
  const std::vector<float> r = random_rotations(5, 22);
  const prt_pose_input pose = pose_of(r);
  std::vector<float> z(6), y(4 * 9);
  ASSERT_EQ(prt_pose_coefficients(a.get(), &pose, z.data(), y.data()), PRT_OK);
  const std::vector<double> ez = coordinates(s, r), ey = coefficients(s, r);
  for (size_t i = 0; i < z.size(); ++i) EXPECT_NEAR(z[i], ez[i], 1e-5 * (1 + std::fabs(ez[i])));
  for (size_t i = 0; i < y.size(); ++i) EXPECT_NEAR(y[i], ey[i], 1e-5 * (1 + std::fabs(ey[i])));
  EXPECT_EQ(prt_pose_coefficients(a.get(), &pose, nullptr, nullptr), PRT_OK);
}

// A pose far outside the training range: with the clamp flag the coordinates are exactly the
// range's ends, without it they are not.
TEST(PoseModel, ClampedCoordinatesAreTheRangesEnds) {
  PoseSection s = random_section(2, 1, 3, 2, 1, 8, 0, 5);
  s.pose_basis.assign(s.pose_basis.size(), 0.0f);
  s.pose_mean.assign(s.pose_mean.size(), 0.0f);
  s.pose_basis[3 * 2 + 0] = 1.0f;   // z_0 = feature 3 (joint 1, x)
  s.pose_basis[4 * 2 + 1] = -1.0f;  // z_1 = -feature 4 (joint 1, y)
  s.pose_range = {-0.25f, 0.125f, -0.5f, 0.375f};
  s.joints[1].bind = {0, 0, 0, 1};
  const std::vector<float> r =
      rotations_of({{0, 0, 0, 1}, axis_angle(1, 1, 0, 2.5), {0, 0, 0, 1}});  // x, y both 2.5/sqrt 2
  std::vector<float> z(2);
  const prt_pose_input pose = pose_of(r);
  {
    const Loaded free_model(s);
    ASSERT_EQ(prt_pose_coefficients(free_model.get(), &pose, z.data(), nullptr), PRT_OK);
    EXPECT_NEAR(z[0], 2.5 / std::sqrt(2.0), 1e-6);
    EXPECT_NEAR(z[1], -2.5 / std::sqrt(2.0), 1e-6);
  }
  s.flags = PRT_BLOB_PSTR_FLAG_CLAMP;
  const Loaded clamped(s);
  prt_pose_info info = prt::sized<prt_pose_info>();
  ASSERT_EQ(prt_pose_get_info(clamped.get(), &info), PRT_OK);
  EXPECT_EQ(info.clamps_pose, 1);
  ASSERT_EQ(prt_pose_coefficients(clamped.get(), &pose, z.data(), nullptr), PRT_OK);
  EXPECT_EQ(z[0], 0.125f);
  EXPECT_EQ(z[1], -0.5f);
}

TEST(PoseModel, InfoIsTheHeader) {
  PoseSection s = random_section(4, 6, 5, 7, 9, 16, 1, 8);
  s.model_joint = 0, s.kind = 2, s.bounces = 3, s.albedo = 0.625f;
  const Loaded a(s);
  prt_pose_info info = prt::sized<prt_pose_info>();
  ASSERT_EQ(prt_pose_get_info(a.get(), &info), PRT_OK);
  EXPECT_EQ(info.order, 4u);
  EXPECT_EQ(info.vertex_count, 6u);
  EXPECT_EQ(info.joint_count, 5u);
  EXPECT_EQ(info.feature_count, 15u);
  EXPECT_EQ(info.pose_dims, 7u);
  EXPECT_EQ(info.basis_dims, 9u);
  EXPECT_EQ(info.model, PRT_POSE_MODEL_RESIDUAL);
  EXPECT_EQ(info.bits, 16u);
  EXPECT_EQ(info.model_joint, 0u);
  EXPECT_EQ(info.kind, 2u);
  EXPECT_EQ(info.bounces, 3u);
  EXPECT_EQ(info.albedo, 0.625f);
  EXPECT_EQ(info.clamps_pose, 0);
  // Pose PCA (15 + 15 x 7 + 2 x 7 floats), regression (8 x 9 x 16), basis (2 x 9 + 6 x 9 x 2 B).
  EXPECT_EQ(info.model_bytes, 4u * (15 + 105 + 14) + 4u * 8 * 9 * 16 + 8u * 9 + 108u);
  info.struct_size = 8;
  EXPECT_EQ(prt_pose_get_info(a.get(), &info), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_pose_get_info(a.get(), nullptr), PRT_ERROR_INVALID_ARGUMENT);
}

// The bind pose is each joint record's bind rotation, rest translation and rest scale, as
// stored; every output may be left out.
TEST(PoseModel, BindPoseIsTheJointRecords) {
  PoseSection s = two_joints();
  s.joints[0].bind = {0.0f, 0.6f, 0.0f, 0.8f};
  s.joints[1].bind = {0.28f, 0.0f, 0.0f, 0.96f};
  s.joints[1].translation = {0.5f, 1.5f, -2.0f};
  s.joints[1].scale = {1.0f, 2.0f, 0.25f};
  const Loaded a(s);
  std::vector<float> rotations(8, -1.0f), translations(6, -1.0f), scales(6, -1.0f);
  ASSERT_EQ(prt_pose_bind_pose(a.get(), rotations.data(), translations.data(), scales.data()),
            PRT_OK);
  EXPECT_EQ(rotations, (std::vector<float>{0.0f, 0.6f, 0.0f, 0.8f, 0.28f, 0.0f, 0.0f, 0.96f}));
  EXPECT_EQ(translations, (std::vector<float>{0, 0, 0, 0.5f, 1.5f, -2.0f}));
  EXPECT_EQ(scales, (std::vector<float>{1, 1, 1, 1.0f, 2.0f, 0.25f}));
  EXPECT_EQ(prt_pose_bind_pose(a.get(), nullptr, nullptr, nullptr), PRT_OK);
  EXPECT_EQ(prt_pose_bind_pose(nullptr, rotations.data(), nullptr, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  // At the bind pose every feature is zero (the model's own reference).
  const std::vector<float> features = feature_of(a, rotations);
  for (float f : features) EXPECT_NEAR(f, 0.0f, 1e-7f);
}

}  // namespace
