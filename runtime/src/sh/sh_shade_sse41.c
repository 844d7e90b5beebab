/* SPDX-License-Identifier: MIT */
/* `sh` shading kernel for SSE4.1 (this file is compiled with -msse4.1 and only called when the
 * CPU has it): per vertex and channel, a dot product of the quantised values with the light
 * folded into the scale (sh_shade_simd.h), four coefficients at a time. */
#include "sh_shade_x86.h"

/* (sum r, sum g, sum b, sum b) of three accumulators. */
PRT_KERNEL_INLINE __m128 horizontal_sums(__m128 r, __m128 g, __m128 b) {
  return _mm_hadd_ps(_mm_hadd_ps(r, g), _mm_hadd_ps(b, b));
}

/* For each of the n vertices, (sum r, sum g, sum b, sum b) of its channel runs (the contract in
 * sh_shade_x86.h). Each weight block is loaded once for all n vertices. */
PRT_KERNEL_INLINE void shade_runs(const prt_sh_simd_job* job, const uint8_t* const run[][3], int n,
                                  int bits, __m128 sums[]) {
  const size_t size = (size_t)bits / 8u;
  __m128 acc[PRT_SH_X86_GROUP][3];
  uint32_t k;
  int j, c;
  for (j = 0; j < n; ++j)
    for (c = 0; c < 3; ++c) acc[j][c] = _mm_setzero_ps();
  for (k = 0; k < job->padded; k += 4) {
    const __m128 w[3] = {_mm_loadu_ps(job->weight[0] + k), _mm_loadu_ps(job->weight[1] + k),
                         _mm_loadu_ps(job->weight[2] + k)};
    for (j = 0; j < n; ++j)
      for (c = 0; c < 3; ++c)
        acc[j][c] = _mm_add_ps(acc[j][c], _mm_mul_ps(load4(run[j][c] + size * k, bits), w[c]));
  }
  for (j = 0; j < n; ++j) sums[j] = horizontal_sums(acc[j][0], acc[j][1], acc[j][2]);
}

#define PRT_SH_KERNEL_NAME prt_sh_shade_sse41
#define PRT_SH_X86_LOOP
#include "sh_shade_x86.h"
