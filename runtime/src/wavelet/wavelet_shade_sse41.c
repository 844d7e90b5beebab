/* SPDX-License-Identifier: MIT */
/* `wavelet` shading kernel for SSE4.1 (this file is compiled with -msse4.1 and only called when
 * the CPU has it): one pair per step over a window of a row's pairs (wavelet_shade_x86.h), a
 * 16-byte load of the prepared RGBA light times the broadcast value, into two accumulators taken
 * in turn so consecutive pairs do not wait on each other's additions. */
#include <prt/format/blob_layout.h>
#include <smmintrin.h>
#include <stddef.h>
#include <stdint.h>

#if defined(__GNUC__)
#define PRT_KERNEL_INLINE static inline __attribute__((always_inline))
#else
#define PRT_KERNEL_INLINE static inline
#endif

typedef struct kernel_acc {
  __m128 even, odd;
} kernel_acc;

PRT_KERNEL_INLINE void acc_clear(kernel_acc* acc) {
  acc->even = acc->odd = _mm_setzero_ps();
}

/* q * light of pair p. */
PRT_KERNEL_INLINE __m128 pair_term(const float* light, const uint8_t* pair,
                                   const uint16_t* block_of, uint32_t p) {
  const size_t j = PRT_BLOB_WVLT_BLOCK * (size_t)block_of[p] + pair[2u * p];
  return _mm_mul_ps(_mm_set1_ps((float)(int8_t)pair[2u * p + 1u]), _mm_loadu_ps(light + 4u * j));
}

PRT_KERNEL_INLINE void acc_add_pairs(kernel_acc* acc, const float* light, const uint8_t* pair,
                                     const uint16_t* block_of, uint32_t n) {
  uint32_t p = 0;
  for (; p + 2 <= n; p += 2) {
    acc->even = _mm_add_ps(acc->even, pair_term(light, pair, block_of, p));
    acc->odd = _mm_add_ps(acc->odd, pair_term(light, pair, block_of, p + 1));
  }
  if (p < n) acc->even = _mm_add_ps(acc->even, pair_term(light, pair, block_of, p));
}

PRT_KERNEL_INLINE __m128 acc_total(const kernel_acc* acc) {
  return _mm_add_ps(acc->even, acc->odd);
}

#define PRT_WAVELET_KERNEL_NAME prt_wavelet_shade_sse41
#include "wavelet_shade_x86.h"
