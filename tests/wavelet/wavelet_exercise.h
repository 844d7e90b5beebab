/* SPDX-License-Identifier: MIT */
/* Technique `wavelet` in the test-side table of exercises (support/technique_exercises.h): every
 * read of an asset's WVLT section, on every CPU-side backend, with and without the zero-block
 * mask. Plain C99 (the fuzzer is C). */
#ifndef PRT_TEST_WAVELET_EXERCISE_H
#define PRT_TEST_WAVELET_EXERCISE_H

#include <prt/prt.h>

#include <stdlib.h>

/* Prepares a light and shades and decodes the first vertices. Returns 0 when a call that must
 * succeed failed: at full validation every call (a shading backend may only be unsupported); at
 * quick validation the rows are unchecked, so shading and decoding may return CORRUPT. */
static int prt_test_exercise_wavelet(const prt_asset* asset, prt_validation level) {
  static const prt_backend backends[2] = {PRT_BACKEND_CPU, PRT_BACKEND_SIMD};
  const int full = level == PRT_VALIDATE_FULL;
  float out[3 * 16];
  prt_wavelet_info info;
  float* light;
  float* row;
  uint8_t* zero_blocks;
  uint32_t count;
  int b, mask, ok = 1;
  prt_result r;
  info.struct_size = sizeof info;
  if (prt_wavelet_get_info(asset, &info) != PRT_OK) return 0;
  count = info.vertex_count < 16u ? info.vertex_count : 16u;
  light = (float*)calloc(4u * (size_t)info.coefficient_count, sizeof(float));
  row = (float*)malloc(3u * (size_t)info.coefficient_count * sizeof(float));
  zero_blocks = (uint8_t*)malloc(info.block_count);
  if (!light || !row || !zero_blocks) abort();
  light[0] = light[1] = light[2] = 1.0f;
  if (prt_wavelet_prepare_light(asset, light, light, zero_blocks) != PRT_OK) ok = 0;
  for (b = 0; b < 2; ++b)
    for (mask = 0; mask < 2; ++mask) {
      r = prt_wavelet_shade(asset, backends[b], light, mask ? zero_blocks : NULL, 0, count, out);
      if (r != PRT_OK && r != PRT_ERROR_UNSUPPORTED_BACKEND && (full || r != PRT_ERROR_CORRUPT))
        ok = 0;
    }
  if (info.vertex_count > 0) {
    r = prt_wavelet_decode_transfer(asset, 0, 1, row);
    if (r != PRT_OK && (full || r != PRT_ERROR_CORRUPT)) ok = 0;
  }
  free(zero_blocks);
  free(row);
  free(light);
  return ok;
}

#endif /* PRT_TEST_WAVELET_EXERCISE_H */
