/* SPDX-License-Identifier: MIT */
/* `sh` shading kernel for AVX2 + FMA (this file is compiled with -mavx2 -mfma and only called
 * when the CPU has both): per vertex and channel, a dot product of the quantised values with the
 * light folded into the scale (sh_shade_simd.h), eight coefficients at a time and a block of
 * four when the padded count is not a multiple of eight. */
#include <immintrin.h>

#include "sh_shade_x86.h"

/* Eight stored values (u8 or u16 little-endian, any alignment) as floats. */
PRT_KERNEL_INLINE __m256 load8(const uint8_t* p, int bits) {
  if (bits == 8) {
    return _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(load_low8(p)));
  }
  return _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_loadu_si128((const __m128i*)(const void*)p)));
}

PRT_KERNEL_INLINE __m128 fold_halves(__m256 x) {
  return _mm_add_ps(_mm256_castps256_ps128(x), _mm256_extractf128_ps(x, 1));
}

/* (sum r, sum g, sum b, sum b) of the channels' runs starting at pr, pg, pb (equal for grey
 * transfer, where the compiler shares the loads). */
PRT_KERNEL_INLINE __m128 shade_runs(const prt_sh_simd_job* job, const uint8_t* pr,
                                    const uint8_t* pg, const uint8_t* pb, int bits) {
  const size_t size = (size_t)bits / 8u;
  const float* wr = job->weight[0];
  const float* wg = job->weight[1];
  const float* wb = job->weight[2];
  const uint32_t blocks8 = job->padded / 8u * 8u; /* the rest, if any, is one block of 4 */
  __m128 r, g, b;
  uint32_t k;
  if (blocks8 < job->padded) {
    r = _mm_mul_ps(load4(pr + size * blocks8, bits), _mm_loadu_ps(wr + blocks8));
    g = _mm_mul_ps(load4(pg + size * blocks8, bits), _mm_loadu_ps(wg + blocks8));
    b = _mm_mul_ps(load4(pb + size * blocks8, bits), _mm_loadu_ps(wb + blocks8));
  } else {
    r = g = b = _mm_setzero_ps();
  }
  if (blocks8 > 0) { /* skipped for orders 1 and 2, where folding 8 lanes would be wasted */
    __m256 r8 = _mm256_setzero_ps(), g8 = _mm256_setzero_ps(), b8 = _mm256_setzero_ps();
    for (k = 0; k < blocks8; k += 8) {
      r8 = _mm256_fmadd_ps(load8(pr + size * k, bits), _mm256_loadu_ps(wr + k), r8);
      g8 = _mm256_fmadd_ps(load8(pg + size * k, bits), _mm256_loadu_ps(wg + k), g8);
      b8 = _mm256_fmadd_ps(load8(pb + size * k, bits), _mm256_loadu_ps(wb + k), b8);
    }
    r = _mm_add_ps(r, fold_halves(r8));
    g = _mm_add_ps(g, fold_halves(g8));
    b = _mm_add_ps(b, fold_halves(b8));
  }
  return _mm_hadd_ps(_mm_hadd_ps(r, g), _mm_hadd_ps(b, b));
}

#define PRT_SH_KERNEL_NAME prt_sh_shade_avx2
#define PRT_SH_X86_LOOP
#include "sh_shade_x86.h"
