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

/* For each of the n vertices, (sum r, sum g, sum b, sum b) of its channel runs (the contract in
 * sh_shade_x86.h). Each weight block is loaded once for all n vertices; the block of four, if
 * any, is taken after the blocks of eight so that its accumulators need no registers meanwhile. */
PRT_KERNEL_INLINE void shade_runs(const prt_sh_simd_job* job, const uint8_t* const run[][3], int n,
                                  int bits, __m128 sums[]) {
  const size_t size = (size_t)bits / 8u;
  const uint32_t blocks8 = job->padded / 8u * 8u; /* the rest, if any, is one block of 4 */
  __m128 acc[PRT_SH_X86_GROUP][3];
  uint32_t k;
  int j, c;
  for (j = 0; j < n; ++j)
    for (c = 0; c < 3; ++c) acc[j][c] = _mm_setzero_ps();
  if (blocks8 > 0) { /* skipped for orders 1 and 2, where folding 8 lanes would be wasted */
    __m256 acc8[PRT_SH_X86_GROUP][3];
    for (j = 0; j < n; ++j)
      for (c = 0; c < 3; ++c) acc8[j][c] = _mm256_setzero_ps();
    for (k = 0; k < blocks8; k += 8) {
      const __m256 w[3] = {_mm256_loadu_ps(job->weight[0] + k), _mm256_loadu_ps(job->weight[1] + k),
                           _mm256_loadu_ps(job->weight[2] + k)};
      for (j = 0; j < n; ++j)
        for (c = 0; c < 3; ++c)
          acc8[j][c] = _mm256_fmadd_ps(load8(run[j][c] + size * k, bits), w[c], acc8[j][c]);
    }
    for (j = 0; j < n; ++j)
      for (c = 0; c < 3; ++c) acc[j][c] = fold_halves(acc8[j][c]);
  }
  if (blocks8 < job->padded) {
    const __m128 w[3] = {_mm_loadu_ps(job->weight[0] + blocks8),
                         _mm_loadu_ps(job->weight[1] + blocks8),
                         _mm_loadu_ps(job->weight[2] + blocks8)};
    for (j = 0; j < n; ++j)
      for (c = 0; c < 3; ++c)
        acc[j][c] = _mm_fmadd_ps(load4(run[j][c] + size * blocks8, bits), w[c], acc[j][c]);
  }
  for (j = 0; j < n; ++j)
    sums[j] = _mm_hadd_ps(_mm_hadd_ps(acc[j][0], acc[j][1]), _mm_hadd_ps(acc[j][2], acc[j][2]));
}

#define PRT_SH_KERNEL_NAME prt_sh_shade_avx2
#define PRT_SH_X86_LOOP
#include "sh_shade_x86.h"
