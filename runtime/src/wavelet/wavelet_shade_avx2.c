/* SPDX-License-Identifier: MIT */
/* `wavelet` shading kernel for AVX2 + FMA (this file is compiled with -mavx2 -mfma and only
 * called when the CPU has both): two pairs per 256-bit register (their two RGBA lights in the
 * two halves), four pairs per step into two accumulators; the four values are widened to floats
 * in vector registers from one 8-byte load of the pairs. The last 0..3 pairs of a window take
 * the 128-bit path. */
#include <immintrin.h>
#include <prt/format/blob_layout.h>
#include <stddef.h>
#include <stdint.h>

#if defined(__GNUC__)
#define PRT_KERNEL_INLINE static inline __attribute__((always_inline))
#else
#define PRT_KERNEL_INLINE static inline
#endif

typedef struct kernel_acc {
  __m256 low, high; /* pairs 0, 1 and 2, 3 of each step of four */
  __m128 tail;      /* pairs after the last full step of a block */
} kernel_acc;

PRT_KERNEL_INLINE void acc_clear(kernel_acc* acc) {
  acc->low = acc->high = _mm256_setzero_ps();
  acc->tail = _mm_setzero_ps();
}

/* The RGBA light of pair p. */
PRT_KERNEL_INLINE __m128 pair_light(const float* light, const uint8_t* pair,
                                    const uint16_t* block_of, uint32_t p) {
  return _mm_loadu_ps(light + 4u * (PRT_BLOB_WVLT_BLOCK * (size_t)block_of[p] + pair[2u * p]));
}

/* The RGBA lights of pairs p and p + 1 in the low and high halves. */
PRT_KERNEL_INLINE __m256 light_two(const float* light, const uint8_t* pair,
                                   const uint16_t* block_of, uint32_t p) {
  return _mm256_insertf128_ps(_mm256_castps128_ps256(pair_light(light, pair, block_of, p)),
                              pair_light(light, pair, block_of, p + 1u), 1);
}

PRT_KERNEL_INLINE void acc_add_pairs(kernel_acc* acc, const float* light, const uint8_t* pair,
                                     const uint16_t* block_of, uint32_t n) {
  /* Bytes 1, 3, 5, 7 of (i0 q0 i1 q1 i2 q2 i3 q3), each repeated four times. */
  const __m128i spread = _mm_setr_epi8(1, 1, 1, 1, 3, 3, 3, 3, 5, 5, 5, 5, 7, 7, 7, 7);
  uint32_t p = 0;
  for (; p + 4 <= n; p += 4) {
    const __m128i q =
        _mm_shuffle_epi8(_mm_loadl_epi64((const __m128i*)(const void*)(pair + 2u * p)), spread);
    const __m256 q01 = _mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(q));
    const __m256 q23 = _mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(_mm_srli_si128(q, 8)));
    acc->low = _mm256_fmadd_ps(q01, light_two(light, pair, block_of, p), acc->low);
    acc->high = _mm256_fmadd_ps(q23, light_two(light, pair, block_of, p + 2u), acc->high);
  }
  for (; p < n; ++p)
    acc->tail = _mm_fmadd_ps(_mm_set1_ps((float)(int8_t)pair[2u * p + 1u]),
                             pair_light(light, pair, block_of, p), acc->tail);
}

PRT_KERNEL_INLINE __m128 acc_total(const kernel_acc* acc) {
  const __m256 both = _mm256_add_ps(acc->low, acc->high);
  return _mm_add_ps(acc->tail,
                    _mm_add_ps(_mm256_castps256_ps128(both), _mm256_extractf128_ps(both, 1)));
}

#define PRT_WAVELET_KERNEL_NAME prt_wavelet_shade_avx2
#include "wavelet_shade_x86.h"
