/* SPDX-License-Identifier: MIT */
/* `sh` shading kernel for AVX2 + FMA (this file is compiled with -mavx2 -mfma and only called
 * when the CPU has both): per vertex and channel, a dot product of the quantised values with the
 * light folded into the scale (sh_shade_simd.h), eight coefficients at a time and a block of
 * four when the padded count is not a multiple of eight, the lanes summed by one tree for a
 * group of vertices. */
#include <immintrin.h>

#include "sh_shade_x86.h"

/* Eight stored values (u8 or u16 little-endian, any alignment) as floats. */
PRT_KERNEL_INLINE __m256 load8(const uint8_t* p, int bits) {
  if (bits == 8) {
    return _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(load_low8(p)));
  }
  return _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_loadu_si128((const __m128i*)(const void*)p)));
}

/* Four stored values as floats in the low lanes, zeros above. */
PRT_KERNEL_INLINE __m256 load4_low(const uint8_t* p, int bits) {
  return _mm256_set_m128(_mm_setzero_ps(), load4(p, bits));
}

/* Four weights in the low lanes, zeros above. */
PRT_KERNEL_INLINE __m256 weight4_low(const float* w) {
  return _mm256_set_m128(_mm_setzero_ps(), _mm_loadu_ps(w));
}

/* (a, b, c, d) of four accumulators' 128-bit halves summed: lanes 0-3 each the sum of the low
 * half of a, b, c, d, lanes 4-7 of the high half. Unpacks and adds rather than horizontal adds,
 * which take several shuffles each. Every accumulator's lanes add in the same order whichever
 * slot it has. */
PRT_KERNEL_INLINE __m256 sum_halves4(__m256 a, __m256 b, __m256 c, __m256 d) {
  const __m256 ab = _mm256_add_ps(_mm256_unpacklo_ps(a, b), _mm256_unpackhi_ps(a, b));
  const __m256 cd = _mm256_add_ps(_mm256_unpacklo_ps(c, d), _mm256_unpackhi_ps(c, d));
  const __m256d ab2 = _mm256_castps_pd(ab), cd2 = _mm256_castps_pd(cd);
  return _mm256_add_ps(_mm256_castpd_ps(_mm256_unpacklo_pd(ab2, cd2)),
                       _mm256_castpd_ps(_mm256_unpackhi_pd(ab2, cd2)));
}

/* The halves of h added: four sums. */
PRT_KERNEL_INLINE __m128 add_halves(__m256 h) {
  return _mm_add_ps(_mm256_castps256_ps128(h), _mm256_extractf128_ps(h, 1));
}

/* sums[j] = (sum r, sum g, sum b, any) of acc[j][0..2] for j < n, by one tree shared by the
 * vertices: with four vertices the twelve sums come out in output order (r0 g0 b0 r1 | g1 b1 r2
 * g2 | b2 r3 g3 b3) and are spread into sums[] with the bias added by the caller. Each vertex's
 * lanes add in the same order whatever n is. */
PRT_KERNEL_INLINE void reduce(__m256 acc[][3], int n, __m128 sums[]) {
  if (n == 1) {
    sums[0] = add_halves(sum_halves4(acc[0][0], acc[0][1], acc[0][2], _mm256_setzero_ps()));
  } else {
    const __m128 s0 = add_halves(sum_halves4(acc[0][0], acc[0][1], acc[0][2], acc[1][0]));
    const __m128 s1 = add_halves(sum_halves4(acc[1][1], acc[1][2], acc[2][0], acc[2][1]));
    const __m128 s2 = add_halves(sum_halves4(acc[2][2], acc[3][0], acc[3][1], acc[3][2]));
    sums[0] = s0;
    sums[1] = _mm_castsi128_ps(_mm_alignr_epi8(_mm_castps_si128(s1), _mm_castps_si128(s0), 12));
    sums[2] = _mm_castsi128_ps(_mm_alignr_epi8(_mm_castps_si128(s2), _mm_castps_si128(s1), 8));
    sums[3] = _mm_castsi128_ps(_mm_srli_si128(_mm_castps_si128(s2), 4));
  }
}

/* For each of the n vertices, (sum r, sum g, sum b, any) of its channel runs (the contract in
 * sh_shade_x86.h). Each weight block is loaded once for all n vertices; the block of four, if
 * any, goes into the low lanes of the same accumulators after the blocks of eight. */
PRT_KERNEL_INLINE void shade_runs(const prt_sh_simd_job* job, const uint8_t* const run[][3], int n,
                                  int bits, __m128 sums[]) {
  const size_t size = (size_t)bits / 8u;
  const uint32_t blocks8 = job->padded / 8u * 8u; /* the rest, if any, is one block of 4 */
  __m256 acc[PRT_SH_X86_GROUP][3];
  uint32_t k;
  int j, c;
  for (j = 0; j < n; ++j)
    for (c = 0; c < 3; ++c) acc[j][c] = _mm256_setzero_ps();
  for (k = 0; k < blocks8; k += 8) {
    const __m256 w[3] = {_mm256_loadu_ps(job->weight[0] + k), _mm256_loadu_ps(job->weight[1] + k),
                         _mm256_loadu_ps(job->weight[2] + k)};
    for (j = 0; j < n; ++j)
      for (c = 0; c < 3; ++c)
        acc[j][c] = _mm256_fmadd_ps(load8(run[j][c] + size * k, bits), w[c], acc[j][c]);
  }
  if (blocks8 < job->padded) {
    const __m256 w[3] = {weight4_low(job->weight[0] + blocks8),
                         weight4_low(job->weight[1] + blocks8),
                         weight4_low(job->weight[2] + blocks8)};
    for (j = 0; j < n; ++j)
      for (c = 0; c < 3; ++c)
        acc[j][c] = _mm256_fmadd_ps(load4_low(run[j][c] + size * blocks8, bits), w[c], acc[j][c]);
  }
  reduce(acc, n, sums);
}

#define PRT_SH_KERNEL_NAME prt_sh_shade_avx2
#define PRT_SH_X86_LOOP
#include "sh_shade_x86.h"
