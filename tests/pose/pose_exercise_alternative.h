/* SPDX-License-Identifier: MIT */
/* Technique `pose` in the test-side table of exercises (support/technique_exercises.h): every
 * read of an asset's PSTR section, on every CPU-side backend, at the bind pose and at a pose
 * bent far outside any training range. Plain C99 (the fuzzer is C). */
#ifndef PRT_TEST_POSE_EXERCISE_H
#define PRT_TEST_POSE_EXERCISE_H

#include <prt/prt.h>

#define PRT_TEST_POSE_VERTICES 8u
#define PRT_TEST_POSE_MAX_COEFFICIENTS 64u

/* One pose through every function; 0 when a call that must succeed failed. */
static int prt_test_exercise_pose_at(const prt_asset* asset, const prt_pose_info* info,
                                     const float* rotations) {
  static const prt_backend backends[2] = {PRT_BACKEND_CPU, PRT_BACKEND_SIMD};
  static float features[3 * 256], coordinates[3 * 256];
  static float coefficients[256 * PRT_TEST_POSE_MAX_COEFFICIENTS];
  float positions[3 * PRT_TEST_POSE_VERTICES], normals[3 * PRT_TEST_POSE_VERTICES], frame[12];
  float transfer[PRT_TEST_POSE_VERTICES * PRT_TEST_POSE_MAX_COEFFICIENTS];
  float light_rgb[3 * PRT_TEST_POSE_MAX_COEFFICIENTS] = {0.0f};
  float rgb[3 * PRT_TEST_POSE_VERTICES];
  const uint32_t count =
      info->vertex_count < PRT_TEST_POSE_VERTICES ? info->vertex_count : PRT_TEST_POSE_VERTICES;
  prt_pose_input pose = {0};
  prt_pose_light light = {0};
  prt_result r;
  int b;
  pose.struct_size = sizeof pose;
  pose.joint_rotations = rotations;
  light.struct_size = sizeof light;
  light.light_rgb = light_rgb;
  light_rgb[0] = light_rgb[1] = light_rgb[2] = 1.0f;
  if (prt_pose_features(asset, &pose, features) != PRT_OK) return 0;
  if (prt_pose_coefficients(asset, &pose, coordinates, coefficients) != PRT_OK) return 0;
  if (prt_pose_skin(asset, &pose, 0, count, positions, normals, frame) != PRT_OK) return 0;
  for (b = 0; b < 2; ++b) {
    r = prt_pose_transfer(asset, backends[b], &pose, NULL, 0, count, transfer);
    if (r != PRT_OK && r != PRT_ERROR_UNSUPPORTED_BACKEND) return 0;
    r = prt_pose_shade(asset, backends[b], &pose, &light, 0, count, rgb);
    if (r != PRT_OK && r != PRT_ERROR_UNSUPPORTED_BACKEND) return 0;
  }
  return prt_pose_shade(asset, PRT_BACKEND_GL, &pose, &light, 0, count, rgb) ==
         PRT_ERROR_UNSUPPORTED_BACKEND;
}

/* The bind pose, then every joint turned 170 degrees about x from it. */
static int prt_test_exercise_pose(const prt_asset* asset, prt_validation level) {
  static float rotations[4 * 256];
  prt_pose_info info;
  uint32_t j;
  (void)level; /* the header, joints and evaluation order were checked at load */
  info.struct_size = sizeof info;
  if (prt_pose_get_info(asset, &info) != PRT_OK) return 0;
  if (info.order * info.order > PRT_TEST_POSE_MAX_COEFFICIENTS || info.joint_count > 256u)
    return 0;
  if (prt_pose_bind_pose(asset, rotations, NULL, NULL) != PRT_OK) return 0;
  /* A bind rotation read at quick validation may be zero or not finite; the exercise then uses
   * the identity, which every rotation check accepts. */
  for (j = 0; j < info.joint_count; ++j) {
    float* q = rotations + 4 * j;
    const float n = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (!(n > 1e-12f && n < 1e30f)) q[0] = q[1] = q[2] = 0.0f, q[3] = 1.0f;
  }
  if (!prt_test_exercise_pose_at(asset, &info, rotations)) return 0;
  for (j = 0; j < info.joint_count; ++j) {
    float* q = rotations + 4 * j;
    q[0] = 0.9962f, q[1] = 0.0f, q[2] = 0.0f, q[3] = 0.0872f; /* 170 degrees about x */
  }
  return prt_test_exercise_pose_at(asset, &info, rotations);
}

#endif /* PRT_TEST_POSE_EXERCISE_H */
