/* SPDX-License-Identifier: MIT */
/* `sh` shading kernel for SSE4.1 (this file is compiled with -msse4.1 and only called when the
 * CPU has it): per vertex and channel, a dot product of the quantised values with the light
 * folded into the scale (sh_shade_simd.h), four coefficients at a time. */
#include "sh_shade_x86.h"

/* (sum r, sum g, sum b, sum b) of three accumulators. */
PRT_KERNEL_INLINE __m128 horizontal_sums(__m128 r, __m128 g, __m128 b) {
  return _mm_hadd_ps(_mm_hadd_ps(r, g), _mm_hadd_ps(b, b));
}

/* (sum r, sum g, sum b, sum b) of the channels' runs starting at pr, pg, pb (equal for grey
 * transfer, where the compiler shares the loads). */
PRT_KERNEL_INLINE __m128 shade_runs(const prt_sh_simd_job* job, const uint8_t* pr,
                                    const uint8_t* pg, const uint8_t* pb, int bits) {
  const size_t size = (size_t)bits / 8u;
  __m128 r = _mm_setzero_ps(), g = _mm_setzero_ps(), b = _mm_setzero_ps();
  uint32_t k;
  for (k = 0; k < job->padded; k += 4) {
    r = _mm_add_ps(r, _mm_mul_ps(load4(pr + size * k, bits), _mm_loadu_ps(job->weight[0] + k)));
    g = _mm_add_ps(g, _mm_mul_ps(load4(pg + size * k, bits), _mm_loadu_ps(job->weight[1] + k)));
    b = _mm_add_ps(b, _mm_mul_ps(load4(pb + size * k, bits), _mm_loadu_ps(job->weight[2] + k)));
  }
  return horizontal_sums(r, g, b);
}

#define PRT_SH_KERNEL_NAME prt_sh_shade_sse41
#define PRT_SH_X86_LOOP
#include "sh_shade_x86.h"
