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

/* sums[j] = (sum r, sum g, sum b, any) of acc[j][0..2] for j < n, by a tree of pairwise adds
 * shared by the vertices (fewer instructions than folding each accumulator on its own). Each
 * vertex's lanes add in the same order whatever n is and whichever slot it has: the other
 * slots only feed other lanes. */
PRT_KERNEL_INLINE void reduce(__m256 acc[][3], int n, __m128 sums[]) {
  if (n == 1) {
    const __m256 v = _mm256_hadd_ps(_mm256_hadd_ps(acc[0][0], acc[0][1]),
                                    _mm256_hadd_ps(acc[0][2], _mm256_setzero_ps()));
    sums[0] = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  } else {
    /* v0, v1 = (r, g, blue of the pair's first, blue of its second) of each vertex of a pair,
     * each 128-bit half a partial sum: the halves of both are added at once, then the second's
     * blue moves to lane 2. */
    const __m256i blue_of_second = _mm256_setr_epi32(0, 1, 2, 3, 0, 1, 3, 3);
    int j;
    for (j = 0; j < n; j += 2) {
      const __m256 blue = _mm256_hadd_ps(acc[j][2], acc[j + 1][2]);
      const __m256 v0 = _mm256_hadd_ps(_mm256_hadd_ps(acc[j][0], acc[j][1]), blue);
      const __m256 v1 = _mm256_hadd_ps(_mm256_hadd_ps(acc[j + 1][0], acc[j + 1][1]), blue);
      const __m256 halves =
          _mm256_add_ps(_mm256_permute2f128_ps(v0, v1, 0x20), _mm256_permute2f128_ps(v0, v1, 0x31));
      const __m256 pair = _mm256_permutevar_ps(halves, blue_of_second);
      sums[j] = _mm256_castps256_ps128(pair);
      sums[j + 1] = _mm256_extractf128_ps(pair, 1);
    }
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
