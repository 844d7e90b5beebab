/* SPDX-License-Identifier: MIT */
/* Technique `pose` in the test-side table of exercises (support/technique_exercises.h): every
 * read of an asset's PSTR section, on every CPU-side backend. Plain C99 (the fuzzer is C). */
#ifndef PRT_TEST_POSE_EXERCISE_H
#define PRT_TEST_POSE_EXERCISE_H

#include <prt/prt.h>

#define PRT_TEST_POSE_VERTICES 16u

/* Features, coefficients, skin, transfer and shading of the first vertices at the identity
 * pose. Returns 0 when a call that must succeed failed: every call once the load accepted the
 * PSTR header, parents and evaluation order (a backend may only be unsupported). */
static int prt_test_exercise_pose(const prt_asset* asset, prt_validation level) {
  static const prt_backend backends[3] = {PRT_BACKEND_CPU, PRT_BACKEND_SIMD, PRT_BACKEND_AUTO};
  /* Static: the largest model's coefficients (256 x 64 floats) would crowd the fuzzer's stack. */
  static float rotations[4 * 256], features[3 * 256], coordinates[3 * 256], coefficients[256 * 64];
  static float transfer[PRT_TEST_POSE_VERTICES * 64];
  float light_rgb[3 * 64] = {0.0f}, positions[3 * PRT_TEST_POSE_VERTICES];
  float normals[3 * PRT_TEST_POSE_VERTICES], frame[12], rgb[3 * PRT_TEST_POSE_VERTICES];
  prt_pose_info info;
  prt_pose_input pose;
  prt_pose_light light;
  uint32_t count, j;
  int b;
  prt_result r;
  (void)level; /* the header, parents and order were checked at load, whatever the level */
  info.struct_size = sizeof info;
  if (prt_pose_get_info(asset, &info) != PRT_OK || info.joint_count > 256u) return 0;
  count = info.vertex_count < PRT_TEST_POSE_VERTICES ? info.vertex_count : PRT_TEST_POSE_VERTICES;
  for (j = 0; j < 4u * info.joint_count; ++j) rotations[j] = j % 4u == 3u ? 1.0f : 0.0f;
  pose.struct_size = sizeof pose;
  pose.joint_rotations = rotations;
  pose.joint_translations = NULL;
  pose.joint_scales = NULL;
  light_rgb[0] = light_rgb[1] = light_rgb[2] = 1.0f;
  light.struct_size = sizeof light;
  light.light_rgb = light_rgb;
  light.world_from_character = NULL;
  light.normals = NULL;
  if (prt_pose_bind_pose(asset, coefficients, features, coordinates) != PRT_OK) return 0;
  if (prt_pose_features(asset, &pose, features) != PRT_OK) return 0;
  if (prt_pose_coefficients(asset, &pose, coordinates, coefficients) != PRT_OK) return 0;
  if (prt_pose_skin(asset, &pose, 0, count, positions, normals, frame) != PRT_OK) return 0;
  for (b = 0; b < 3; ++b) {
    r = prt_pose_transfer(asset, backends[b], &pose, NULL, 0, count, transfer);
    if (r != PRT_OK && r != PRT_ERROR_UNSUPPORTED_BACKEND) return 0;
    r = prt_pose_shade(asset, backends[b], &pose, &light, 0, count, rgb);
    if (r != PRT_OK && r != PRT_ERROR_UNSUPPORTED_BACKEND) return 0;
  }
  if (prt_pose_shade(asset, PRT_BACKEND_GL, &pose, &light, 0, count, rgb) !=
      PRT_ERROR_UNSUPPORTED_BACKEND)
    return 0;
  return 1;
}

#endif /* PRT_TEST_POSE_EXERCISE_H */
