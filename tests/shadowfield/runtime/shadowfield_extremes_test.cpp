// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s scene at the extremes of its inputs (issue 15, "Extremes"): a
// receiver inside a blocker's inner shell (the stated fallback), a blocker scaled 10x, 50
// instances of one object, a single object, no instances, glossy views from behind and at grazing
// angles; and the errors of bad arguments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "shadowfield/runtime/shadowfield_test_scene.hpp"

namespace prt::test {
namespace {

const float kEye[3] = {2.0f, 30.0f, 1.0f};

// An OOF that varies over the shell points, its function within [mean - swing, mean + swing]
// by construction: mean + swing (d . w) with d a unit direction per point.
void lobe_oof(SyntheticObject& o, float mean = 0.5f, float swing = 0.4f) {
  const uint64_t points = prt_sf_point_count(&o.oof_shells);
  const uint32_t n2 = o.coefficients();
  o.oof.assign(points * n2, 0.0f);
  for (uint64_t p = 0; p < points; ++p) {
    const float angle = 0.7f * float(p);
    const float d[3] = {std::cos(angle) * 0.6f, 0.8f, std::sin(angle) * 0.6f};  // SH frame
    o.oof[p * n2] = float(mean * std::sqrt(4.0 * kSfPi));
    const float scale = float(swing * std::sqrt(4.0 * kSfPi / 3.0));
    o.oof[p * n2 + 1] = scale * d[1];  // Y_1,-1 ~ y
    o.oof[p * n2 + 2] = scale * d[2];  // Y_10 ~ z
    o.oof[p * n2 + 3] = scale * d[0];  // Y_11 ~ x
  }
}

bool all_finite(const std::vector<float>& values) {
  for (const float v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

// The largest radiance of the receiver alone (no blocker, no bounce).
double unblocked_peak(SyntheticObject& object, const std::vector<float>& light) {
  TestScene s(1);
  s.add_instance(s.add_object(object), make_transform(identity_rotation(), 0, 0, 0));
  return max_abs(s.shade(light, kEye, 0)[0]);
}

TEST(ShadowfieldExtremes, AReceiverInsideTheInnerShellSeesTheInnermostShell) {
  // A one-vertex receiver at the blocker's centre and at two points inside its inner shell
  // (radius 0.15) along one direction: the same reading, the innermost shell's.
  SyntheticObject blocker = make_patch(4, 3);
  lobe_oof(blocker);
  const std::vector<float> light = test_light(4);
  std::vector<float> out[2];
  const float offsets[2] = {0.02f, 0.08f};  // |offset| < 0.15
  for (int case_index = 0; case_index < 2; ++case_index) {
    SyntheticObject receiver = make_patch(4, 1);
    TestScene s(2);
    const float at = offsets[case_index];
    s.add_instance(s.add_object(receiver), make_transform(identity_rotation(), at, at, -at));
    s.add_instance(s.add_object(blocker), make_transform(identity_rotation(), 0, 0, 0));
    out[case_index] = s.shade(light, kEye, 3)[0];
    ASSERT_TRUE(all_finite(out[case_index]));
  }
  EXPECT_EQ(max_difference(out[0], out[1]), 0.0);
  SyntheticObject receiver = make_patch(4, 1);
  EXPECT_LT(max_abs(out[0]), unblocked_peak(receiver, light));
  EXPECT_GT(max_abs(out[0]), 0.0);
}

TEST(ShadowfieldExtremes, ABlockerScaledTenTimesReachesTenTimesFarther) {
  // Outer shell 8 x 0.75 x 10 = 60 around the blocker: the receiver's vertices (within 0.71 of
  // its centre) are all inside it at 30 and 59; at 60.5 the pair is kept (within 60 + 0.75) but
  // every vertex is beyond the shell; at 61 the pair is culled.
  SyntheticObject receiver = make_patch(4, 3), blocker = make_patch(4, 3);
  blocker.set_constant_oof(std::vector<float>(16, 0.0f));
  const std::vector<float> light = test_light(4);
  for (const float distance : {30.0f, 59.0f, 60.5f, 61.0f}) {
    TestScene s(2);
    s.add_instance(s.add_object(receiver), make_transform(identity_rotation(), 0, 0, 0));
    s.add_instance(s.add_object(blocker),
                   make_transform(identity_rotation(), 0.0f, distance, 0.0f, 10.0f));
    const std::vector<float> out = s.shade(light, kEye, 3)[0];
    ASSERT_TRUE(all_finite(out));
    if (distance < 60.0f)
      EXPECT_EQ(max_abs(out), 0.0) << distance;
    else
      EXPECT_EQ(max_abs(out), unblocked_peak(receiver, light)) << distance;
  }
}

TEST(ShadowfieldExtremes, FiftyInstancesOfOneObjectStayFiniteAndBounded) {
  // Each blocker passes 0.95 to 0.99 of the light, so that 49 of them leave some.
  SyntheticObject box = make_patch(4, 3);
  lobe_oof(box, 0.97f, 0.02f);
  // Sources whose radiance falls off as their solid angle, 1 / r^2 across the shells.
  const uint64_t per_shell = prt_sf_points_per_shell(&box.srf_shells);
  const float ratio = box.srf_shells.outer / box.srf_shells.inner;
  box.set_basis(2, [&](uint32_t i, uint32_t, uint64_t p, uint32_t c) {
    const float falloff =
        std::pow(ratio, -2.0f * float(p / per_shell) / float(box.srf_shells.shells - 1));
    return falloff * (c == 0 ? 0.2f + 0.05f * float(i) : 0.02f * std::sin(float(p + c)));
  });
  const std::vector<float> light = test_light(4);
  TestScene s(50);
  const uint32_t object = s.add_object(box);
  for (uint32_t i = 0; i < 50; ++i) {
    float rotation[9];
    const float axis[3] = {0.0f, 1.0f, 0.0f};
    axis_rotation(axis, 0.3f * float(i), rotation);
    s.add_instance(object, make_transform(rotation, float(i % 7) * 0.9f, float(i / 7) * 0.3f,
                                          float(i % 3) * 0.5f));
  }
  const auto out = s.shade(light, kEye, 3);
  const double peak = unblocked_peak(box, light);
  double worst = 0.0;
  for (const auto& radiance : out) {
    ASSERT_TRUE(all_finite(radiance));
    worst = std::max(worst, max_abs(radiance));
  }
  std::printf("50 instances, %u pairs: largest radiance %.3f, %.2f x one instance alone\n",
              s.scene->pair_count, worst, worst / peak);
  for (uint32_t pass = 0; pass <= 3; ++pass) {
    double largest = 0.0;
    for (uint32_t i = 0; i < 50; ++i) largest = std::max(largest, max_abs(s.pass_output(i, pass)));
    std::printf("  after %u bounces: largest radiance %.3f\n", pass, largest);
  }
  // Every blocker passes at most 0.99 of the light and the sources are dim: no blow-up.
  EXPECT_LT(worst, 2.0 * peak);
  EXPECT_GT(worst, 0.0);
}

TEST(ShadowfieldExtremes, AnEmptySceneShadesNothing) {
  TestScene s(1);
  const float light[3] = {1.0f, 1.0f, 1.0f};
  EXPECT_EQ(prt_shadowfield_shade(s.scene, light, kEye, nullptr, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  float* none = nullptr;
  EXPECT_EQ(prt_shadowfield_shade(s.scene, light, kEye, nullptr, &none), PRT_OK);
}

TEST(ShadowfieldExtremes, BadArgumentsAreRefused) {
  SyntheticObject patch = make_patch(4, 2);
  TestScene s(2);
  const uint32_t object = s.add_object(patch);
  prt_shadowfield_transform t = make_transform(identity_rotation(), 0, 0, 0);
  uint32_t instance = 0;
  ASSERT_EQ(prt_shadowfield_scene_add_instance(s.scene, object, &t, &instance), PRT_OK);

  // Transforms.
  prt_shadowfield_transform bad = t;
  bad.scale = 0.0f;
  EXPECT_EQ(prt_shadowfield_scene_set_transform(s.scene, 0, &bad), PRT_ERROR_INVALID_ARGUMENT);
  bad = t;
  bad.translation[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(prt_shadowfield_scene_set_transform(s.scene, 0, &bad), PRT_ERROR_INVALID_ARGUMENT);
  bad = t;
  bad.rotation[0] = -1.0f;  // a reflection
  EXPECT_EQ(prt_shadowfield_scene_set_transform(s.scene, 0, &bad), PRT_ERROR_INVALID_ARGUMENT);
  bad = t;
  bad.rotation[1] = 0.1f;
  EXPECT_EQ(prt_shadowfield_scene_set_transform(s.scene, 0, &bad), PRT_ERROR_INVALID_ARGUMENT);
  bad = t;
  bad.struct_size = 4;
  EXPECT_EQ(prt_shadowfield_scene_set_transform(s.scene, 0, &bad), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_scene_set_transform(s.scene, 1, &t), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_shadowfield_scene_add_instance(s.scene, 5, &t, &instance), PRT_ERROR_NOT_FOUND);

  // Objects: another order, a full scene.
  SyntheticObject other = make_patch(3, 2);
  uint32_t id = 0;
  EXPECT_EQ(prt_internal_sf_scene_add_object(s.scene, other.view(), &id),
            PRT_ERROR_INVALID_ARGUMENT);
  SyntheticObject broken = make_patch(4, 2);
  broken.order = 7;
  EXPECT_EQ(prt_internal_sf_scene_add_object(s.scene, broken.view(), &id),
            PRT_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(prt_shadowfield_scene_add_instance(s.scene, object, &t, &instance), PRT_OK);
  EXPECT_EQ(prt_shadowfield_scene_add_instance(s.scene, object, &t, &instance),
            PRT_ERROR_BUFFER_TOO_SMALL);

  // The stages before a frame is prepared, and after a transform changed.
  EXPECT_EQ(prt_shadowfield_gather(s.scene, 0, 0, 0, 1), PRT_ERROR_INVALID_OPERATION);
  std::vector<float> light = test_light(4), out(12);
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = 1;
  ASSERT_EQ(prt_shadowfield_prepare(s.scene, light.data(), kEye, &settings), PRT_OK);
  EXPECT_EQ(prt_shadowfield_gather(s.scene, 2, 0, 0, 1), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_gather(s.scene, 0, 2, 0, 1), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_gather(s.scene, 0, 0, 3, 2), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_gather(s.scene, 0, 0, 1, UINT32_MAX), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_project(s.scene, 1, 0, 1), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_output(s.scene, 0, 2, 0, 4, out.data()), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_output(s.scene, 0, 1, 0, 4, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_output(s.scene, 0, 1, 0, 4, out.data()), PRT_OK);
  ASSERT_EQ(prt_shadowfield_scene_set_transform(s.scene, 0, &t), PRT_OK);
  EXPECT_EQ(prt_shadowfield_output(s.scene, 0, 1, 0, 4, out.data()), PRT_ERROR_INVALID_OPERATION);

  // Lights, eyes and settings.
  light[5] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(prt_shadowfield_prepare(s.scene, light.data(), kEye, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  light = test_light(4);
  const float nan_eye[3] = {0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f};
  EXPECT_EQ(prt_shadowfield_prepare(s.scene, light.data(), nan_eye, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  settings.bounces = PRT_SHADOWFIELD_MAX_BOUNCES + 1;
  EXPECT_EQ(prt_shadowfield_prepare(s.scene, light.data(), kEye, &settings),
            PRT_ERROR_INVALID_ARGUMENT);
  settings.bounces = 0;
  settings.backend = PRT_BACKEND_GL;
  EXPECT_EQ(prt_shadowfield_prepare(s.scene, light.data(), kEye, &settings),
            PRT_ERROR_UNSUPPORTED_BACKEND);
  settings.backend = prt_backend(9);
  EXPECT_EQ(prt_shadowfield_prepare(s.scene, light.data(), kEye, &settings),
            PRT_ERROR_INVALID_ARGUMENT);
  settings.backend = PRT_BACKEND_CPU;
  settings.struct_size = 4;
  EXPECT_EQ(prt_shadowfield_prepare(s.scene, light.data(), kEye, &settings),
            PRT_ERROR_INVALID_ARGUMENT);

  prt_shadowfield_scene* none = s.scene;
  EXPECT_EQ(prt_shadowfield_scene_create(s.context, 0, &none), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(none, nullptr);
}

TEST(ShadowfieldExtremes, AGlossyVertexSeenFromBelowIsBlackAndFromItselfIsLit) {
  // Seen from behind, a glossy surface reflects nothing towards the eye (as the reference renderer
  // has it); seen from the vertex itself, the view is read along the normal.
  SyntheticObject patch = make_patch(4, 1);  // one vertex at the origin, normal +Y
  patch.glossy = 1;
  patch.brdf_grid = 4;
  for (uint32_t cell = 0; cell < 16; ++cell) patch.g_table.push_back(1.0f + 0.1f * float(cell));
  const std::vector<float> light = test_light(4);
  for (const float eye_y : {-3.0f, 0.0f}) {
    TestScene s(1);
    s.add_instance(s.add_object(patch), make_transform(identity_rotation(), 0, 0, 0));
    const float eye[3] = {0.0f, eye_y, 0.0f};
    const std::vector<float> out = s.shade(light, eye, 0)[0];
    ASSERT_TRUE(all_finite(out)) << eye_y;
    if (eye_y < 0.0f)
      for (float value : out) EXPECT_EQ(value, 0.0f);
    else
      EXPECT_GT(out[0], 0.0f);
  }
}

// The glossy output at views from just above the tangent plane to just below it: one BRDF term,
// so the output is g(wo) times the term's light, and g is read between its table's smallest and
// largest entries (bilinear weights are convex). Against the same vertex under a constant table.
TEST(ShadowfieldExtremes, AGlossyVertexAtGrazingViewsStaysWithinItsTable) {
  SyntheticObject patch = make_patch(4, 1);  // one vertex at the origin, normal +Y
  patch.glossy = 1;
  patch.brdf_grid = 4;
  const std::vector<float> light = test_light(4);
  const float above[3] = {0.0f, 3.0f, 0.0f};
  patch.g_table.assign(16, 1.0f);
  std::vector<float> unit;
  {
    TestScene s(1);
    s.add_instance(s.add_object(patch), make_transform(identity_rotation(), 0, 0, 0));
    unit = s.shade(light, above, 0)[0];
  }
  ASSERT_GT(unit[0], 0.0f);
  float smallest = 1e30f, largest = 0.0f;
  patch.g_table.clear();
  for (uint32_t cell = 0; cell < 16; ++cell) {
    patch.g_table.push_back(1.0f + 0.1f * float(cell));
    smallest = std::min(smallest, patch.g_table.back());
    largest = std::max(largest, patch.g_table.back());
  }
  const float rounding = 4.0f * std::numeric_limits<float>::epsilon();
  std::vector<float> near_horizon;
  for (const float height : {1e-2f, 1e-5f, 1e-9f, 1e-30f, 0.0f, -1e-30f, -1e-5f}) {
    TestScene s(1);
    s.add_instance(s.add_object(patch), make_transform(identity_rotation(), 0, 0, 0));
    const float eye[3] = {3.0f, height, 1.0f};
    const std::vector<float> out = s.shade(light, eye, 0)[0];
    ASSERT_TRUE(all_finite(out)) << height;
    for (int c = 0; c < 3; ++c) {
      if (height <= 0.0f) {
        EXPECT_EQ(out[c], 0.0f) << height;  // in the plane or behind: seen from behind
        continue;
      }
      EXPECT_GE(out[c], smallest * unit[c] * (1.0f - rounding)) << height;
      EXPECT_LE(out[c], largest * unit[c] * (1.0f + rounding)) << height;
    }
    if (height == 1e-5f) near_horizon = out;
    if (height == 1e-30f) {  // the read converges to the table's rim as the view sinks
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[c], near_horizon[c], 4e-6f * unit[c]) << c;
    }
  }
}

}  // namespace
}  // namespace prt::test
