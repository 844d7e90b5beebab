// SPDX-License-Identifier: MIT
// What the load and full validation reject in a PSTR section (formats/SPEC.md §7.3): the header,
// the size, the parents and the evaluation order at both levels (the open hook and the formats
// checker say the same), and the contents (non-finite floats, joint indices >= J, padding,
// scales, ranges) at full validation only, with quick validation still reading inside the section.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "pose/pose_blob.hpp"
#include "support/technique_exercises.h"

namespace {

using namespace prt_test;

// V = 3, J = 3, p = 2, q = 1, 8 bits: three value bytes and one byte of padding.
PoseSection small_section() {
  return random_section(2, 3, 3, 2, 1, 8, 1, 11);
}

struct Outcome {
  prt_result result;
  std::string message;
};

Outcome validate_with_message(const Bytes& blob, prt_validation level) {
  Context ctx;
  auto copy = exact_copy(blob);
  char msg[256] = "";
  const prt_result r = prt_asset_validate(ctx.ctx, copy.get(), blob.size(), level, msg, sizeof msg);
  return {r, msg};
}

using Edit = std::function<void(Bytes& section, const prt_blob_pstr_layout& l)>;

Bytes edited_blob(const PoseSection& s, const Edit& edit) {
  Bytes section = encode(s);
  edit(section, pstr_layout(s));
  return mesh_blob(PRT_BLOB_TAG_PSTR, section, s.vertices);
}

size_t parent_at(const prt_blob_pstr_layout& l, uint32_t j) {
  return l.joints + PRT_BLOB_PSTR_JOINT_SIZE * j;
}

TEST(PoseValidation, TheTestSectionIsValidAtBothLevels) {
  const PoseSection s = small_section();
  for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
    const Outcome o = validate_with_message(pose_blob(s), level);
    EXPECT_EQ(o.result, PRT_OK) << o.message;
  }
  // Also compressed, and with the pose asset's techniques reported.
  Context ctx;
  const LoadedAsset a(ctx.ctx, mesh_blob(PRT_BLOB_TAG_PSTR, encode(s), s.vertices, true));
  ASSERT_EQ(a.result, PRT_OK);
  EXPECT_EQ(prt_asset_techniques(a.asset), 1u << PRT_TECHNIQUE_POSE);
}

// Header, size, parents and evaluation order: CORRUPT at quick validation as at full, the
// message naming the field.
TEST(PoseValidation, LoadRejectsHeaderSizeParentsAndOrderAtBothLevels) {
  const PoseSection s = small_section();
  const struct {
    const char* name;
    Edit edit;
    const char* words;
  } cases[] = {
      {"order 0", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_ORDER, 0); }, "order 0"},
      {"order 9", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_ORDER, 9); }, "order 9"},
      {"no joints", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_JOINTS, 0); }, "0 joints"},
      {"257 joints", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_JOINTS, 257); },
       "257 joints"},
      {"p above 3 J", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_POSE_DIMS, 10); },
       "10 pose dimensions"},
      {"q 0", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_BASIS_DIMS, 0); },
       "0 basis dimensions"},
      {"q 257", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_BASIS_DIMS, 257); },
       "257 basis dimensions"},
      {"model 2", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_MODEL, 2); }, "model 2"},
      {"12 bits", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_BITS, 12); }, "12 bits"},
      {"model joint J", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_MODEL_JOINT, 3); },
       "model joint 3"},
      {"negative albedo", [](Bytes& b, auto&) { put_f32(b, PRT_BLOB_PSTR_OFF_ALBEDO, -0.5f); },
       "albedo is negative"},
      {"unknown flag", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_FLAGS, 2); },
       "unknown flags"},
      {"reserved", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_RESERVED + 12, 1); },
       "reserved"},
      {"vertex count", [](Bytes& b, auto&) { put_u32(b, PRT_BLOB_PSTR_OFF_VERTICES, 2); },
       "header says 2 vertices"},
      {"size", [](Bytes& b, auto&) { b.resize(b.size() + 4, 0); }, "raw bytes"},
      {"parent J", [](Bytes& b, auto& l) { put_u32(b, parent_at(l, 2), 3); },
       "joint 2 has parent 3"},
      {"parent self", [](Bytes& b, auto& l) { put_u32(b, parent_at(l, 1), 1); },
       "joint 1 has parent 1"},
      {"parent -2", [](Bytes& b, auto& l) { put_u32(b, parent_at(l, 1), uint32_t(-2)); },
       "joint 1 has parent -2"},
      {"model joint parented", [](Bytes& b, auto& l) { put_u32(b, parent_at(l, 0), 2); },
       "model joint 0 has parent 2"},
      {"order repeats", [](Bytes& b, auto& l) { put_u32(b, l.eval_order + 8, 1); },
       "not a permutation"},
      {"order past J", [](Bytes& b, auto& l) { put_u32(b, l.eval_order, 7); }, "not a permutation"},
      {"child first",
       [](Bytes& b, auto& l) {
         put_u32(b, l.eval_order, 1);
         put_u32(b, l.eval_order + 4, 0);
       },
       "comes before its parent"},
  };
  for (const auto& c : cases) {
    const Bytes blob = edited_blob(s, c.edit);
    for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
      const Outcome o = validate_with_message(blob, level);
      EXPECT_EQ(o.result, PRT_ERROR_CORRUPT) << c.name << " at level " << level;
      EXPECT_NE(o.message.find(c.words), std::string::npos) << c.name << ": " << o.message;
      EXPECT_NE(o.message.find("'PSTR'"), std::string::npos) << c.name << ": " << o.message;
    }
  }
}

// Contents: rejected by full validation only; quick validation loads and every function still
// reads inside the section.
TEST(PoseValidation, FullValidationRejectsTheContents) {
  const PoseSection s = small_section();
  const float nan = std::nanf("");
  const struct {
    const char* name;
    Edit edit;
    prt_result full;
    const char* words;
  } cases[] = {
      {"NaN regression", [&](Bytes& b, auto& l) { put_f32(b, l.regression + 8, nan); },
       PRT_ERROR_NON_FINITE, "model float"},
      {"inf pose mean", [&](Bytes& b, auto& l) { put_f32(b, l.pose_mean, INFINITY); },
       PRT_ERROR_NON_FINITE, "model float 0"},
      {"NaN basis offset", [&](Bytes& b, auto& l) { put_f32(b, l.basis_params, nan); },
       PRT_ERROR_NON_FINITE, "model float"},
      {"NaN joint pre",
       [&](Bytes& b, auto& l) {
         put_f32(b, parent_at(l, 2) + PRT_BLOB_PSTR_JOINT_OFF_PRE + 20, nan);
       },
       PRT_ERROR_NON_FINITE, "joint 2"},
      {"NaN skin normal",
       [&](Bytes& b, auto& l) {
         put_f32(b, l.skin + PRT_BLOB_PSTR_SKIN_SIZE + PRT_BLOB_PSTR_SKIN_OFF_NORMAL, nan);
       },
       PRT_ERROR_NON_FINITE, "vertex 1"},
      {"joint index J",
       [&](Bytes& b, auto& l) {
         b[l.skin + 2 * PRT_BLOB_PSTR_SKIN_SIZE + PRT_BLOB_PSTR_SKIN_OFF_JOINTS + 3] = 3;
       },
       PRT_ERROR_CORRUPT, "vertex 2 names joint 3"},
      {"padding", [&](Bytes& b, auto& l) { b[l.skin - 1] = 1; }, PRT_ERROR_CORRUPT, "padding"},
      {"negative scale", [&](Bytes& b, auto& l) { put_f32(b, l.basis_params + 4, -1.0f); },
       PRT_ERROR_CORRUPT, "scale of basis column 0"},
      {"min above max", [&](Bytes& b, auto& l) { put_f32(b, l.pose_range + 8, 9.0f); },
       PRT_ERROR_CORRUPT, "pose coordinate 1"},
  };
  for (const auto& c : cases) {
    const Bytes blob = edited_blob(s, c.edit);
    const Outcome full = validate_with_message(blob, PRT_VALIDATE_FULL);
    EXPECT_EQ(full.result, c.full) << c.name << ": " << full.message;
    EXPECT_NE(full.message.find(c.words), std::string::npos) << c.name << ": " << full.message;
    Context ctx;
    const LoadedAsset quick(ctx.ctx, blob, PRT_VALIDATE_QUICK);
    ASSERT_EQ(quick.result, PRT_OK) << c.name;
    const std::vector<float> r = random_rotations(3, 5);
    const prt_pose_input pose = pose_of(r);
    std::vector<float> out(3 * 4 * 3), light(4 * 3, 1.0f);
    prt_pose_light l{};
    l.struct_size = sizeof l;
    l.light_rgb = light.data();
    EXPECT_EQ(prt_pose_transfer(quick.asset, PRT_BACKEND_AUTO, &pose, nullptr, 0, 3, out.data()),
              PRT_OK);
    EXPECT_EQ(prt_pose_shade(quick.asset, PRT_BACKEND_AUTO, &pose, &l, 0, 3, out.data()), PRT_OK);
    EXPECT_EQ(prt_pose_skin(quick.asset, &pose, 0, 3, out.data(), out.data() + 9, nullptr), PRT_OK);
  }
}

// The fuzzer's exercise (support/technique_exercises.h) accepts a pose asset at both levels,
// also one whose contents only quick validation lets through.
TEST(PoseValidation, TheExerciseRunsEveryFunction) {
  const PoseSection s = random_section(8, 20, 256, 12, 256, 16, 1, 3);
  Context ctx;
  for (prt_validation level : {PRT_VALIDATE_QUICK, PRT_VALIDATE_FULL}) {
    const LoadedAsset a(ctx.ctx, pose_blob(s), level);
    ASSERT_EQ(a.result, PRT_OK);
    EXPECT_EQ(prt_test_exercise_techniques(a.asset, level), 1);
  }
  const Bytes bad = edited_blob(small_section(), [](Bytes& b, auto& l) {
    put_f32(b, l.regression, std::nanf(""));
    b[l.skin + PRT_BLOB_PSTR_SKIN_OFF_JOINTS] = 250;
  });
  const LoadedAsset quick(ctx.ctx, bad, PRT_VALIDATE_QUICK);
  ASSERT_EQ(quick.result, PRT_OK);
  EXPECT_EQ(prt_test_exercise_techniques(quick.asset, PRT_VALIDATE_QUICK), 1);
}

// A NaN albedo: NON_FINITE at full validation (the checker), CORRUPT at quick (the load).
TEST(PoseValidation, NonFiniteAlbedo) {
  const Bytes blob = edited_blob(small_section(), [](Bytes& b, auto&) {
    put_f32(b, PRT_BLOB_PSTR_OFF_ALBEDO, std::nanf(""));
  });
  EXPECT_EQ(validate_with_message(blob, PRT_VALIDATE_FULL).result, PRT_ERROR_NON_FINITE);
  EXPECT_EQ(validate_with_message(blob, PRT_VALIDATE_QUICK).result, PRT_ERROR_CORRUPT);
}

// A joint index >= J read at quick validation counts as weight 0: a vertex whose only weight
// names joint 200 of 3 keeps its stored position.
TEST(PoseValidation, QuickValidationIgnoresJointIndicesPastJ) {
  PoseSection s = small_section();
  s.skin[0].joints = {200, 0, 0, 0};
  s.skin[0].weights = {65535, 0, 0, 0};
  s.skin[0].position = {0.5f, -0.25f, 2.0f};
  Context ctx;
  const LoadedAsset quick(ctx.ctx, pose_blob(s), PRT_VALIDATE_QUICK);
  ASSERT_EQ(quick.result, PRT_OK);
  const std::vector<float> r = random_rotations(3, 6);
  const prt_pose_input pose = pose_of(r);
  float position[3];
  ASSERT_EQ(prt_pose_skin(quick.asset, &pose, 0, 1, position, nullptr, nullptr), PRT_OK);
  EXPECT_EQ(position[0], 0.5f);
  EXPECT_EQ(position[1], -0.25f);
  EXPECT_EQ(position[2], 2.0f);
}

}  // namespace
