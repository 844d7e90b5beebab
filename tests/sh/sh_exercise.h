/* SPDX-License-Identifier: MIT */
/* Technique `sh` in the test-side table of exercises (support/technique_exercises.h): every read
 * of an asset's SHTR section, on every CPU-side backend. Plain C99 (the fuzzer is C). */
#ifndef PRT_TEST_SH_EXERCISE_H
#define PRT_TEST_SH_EXERCISE_H

#include <prt/prt.h>

/* Shades and decodes the first vertices. Returns 0 when a call that must succeed failed: every
 * call once the load accepted the SHTR header (a shading backend may only be unsupported). */
static int prt_test_exercise_sh(const prt_asset* asset, prt_validation level) {
  static const prt_backend backends[2] = {PRT_BACKEND_CPU, PRT_BACKEND_SIMD};
  float light[3 * PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER] = {0.0f};
  float out[3 * 16];
  float transfer[3 * PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER];
  prt_sh_info info;
  uint32_t count;
  int b;
  prt_result r;
  (void)level; /* the header was checked at load, whatever the level */
  info.struct_size = sizeof info;
  if (prt_sh_get_info(asset, &info) != PRT_OK) return 0;
  count = info.vertex_count < 16u ? info.vertex_count : 16u;
  light[0] = light[1] = light[2] = 1.0f;
  for (b = 0; b < 2; ++b) {
    r = prt_sh_shade(asset, backends[b], light, 0, count, out);
    if (r != PRT_OK && r != PRT_ERROR_UNSUPPORTED_BACKEND) return 0;
  }
  if (prt_sh_shade(asset, PRT_BACKEND_GL, light, 0, count, out) != PRT_ERROR_UNSUPPORTED_BACKEND)
    return 0;
  if (info.vertex_count > 0 && prt_sh_decode_transfer(asset, 0, 1, transfer) != PRT_OK) return 0;
  return 1;
}

#endif /* PRT_TEST_SH_EXERCISE_H */
