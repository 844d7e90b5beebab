/* SPDX-License-Identifier: MIT */
/* Private to the x86 `wavelet` kernels (wavelet_shade_sse41.c, wavelet_shade_avx2.c): the vertex
 * loop both share, compiled with the including file's ISA flags (SSE4.1 at least). The includer
 * defines, before including this file,
 *   PRT_WAVELET_KERNEL_NAME  the entry point (see wavelet_shade_simd.h),
 *   kernel_acc               its accumulator type,
 *   PRT_KERNEL_INLINE void acc_clear(kernel_acc* acc);
 *   PRT_KERNEL_INLINE void acc_add_pairs(kernel_acc* acc, const float* light,
 *                                        const uint8_t* pair, const uint16_t* block_of,
 *                                        uint32_t n);
 *     (adds q * light[4 j .. 4 j + 3], j = 256 block_of[p] + i, for the n (i, q) pairs at
 *     `pair`, reading only those bytes)
 *   PRT_KERNEL_INLINE __m128 acc_total(const kernel_acc* acc);  (r, g, b, -) */
#ifndef PRT_WAVELET_SHADE_X86_H
#define PRT_WAVELET_SHADE_X86_H

#include <smmintrin.h>

#include "wavelet_shade_simd.h"

/* Pairs whose block numbers are gathered before they are shaded (a stack window). */
#define PRT_WAVELET_WINDOW 1024u

/* Writes k into block_of[0 .. n + 15]: 16 at a time, the excess overwritten by the next block's
 * numbers (or left unused), so the usual block of fewer than 16 pairs costs two stores and no
 * branch that depends on its count. */
PRT_KERNEL_INLINE void fill_block_number(uint16_t* block_of, uint32_t k, uint32_t n) {
  const __m128i number = _mm_set1_epi16((short)k);
  uint32_t c = 0;
  do {
    _mm_storeu_si128((__m128i*)(void*)(block_of + c), number);
    _mm_storeu_si128((__m128i*)(void*)(block_of + c + 8), number);
    c += 16;
  } while (c < n);
}

/* Sums of row v's pairs into *rgb; 0 when a block count is above 256 or disagrees with the row
 * starts. Blocks of zero light are skipped (their pairs add exactly 0). Blocks are taken a window
 * at a time: first the block number of every pair (from the counts alone), then one flat loop
 * over the window's pairs, so the shading loop does not stop and mispredict at each block's end
 * while its light loads are in flight. */
PRT_KERNEL_INLINE int shade_row(const prt_wavelet_rows* rows, uint32_t v, __m128* rgb) {
  const uint8_t* counts = rows->counts + 2u * (size_t)v * rows->blocks;
  uint16_t block_of[PRT_WAVELET_WINDOW + 16u];
  uint32_t start, end, at, k = 0;
  kernel_acc acc;
  if (!prt_wavelet_row_range(rows, v, &start, &end)) return 0;
  acc_clear(&acc);
  at = start;
  while (k < rows->blocks) {
    uint32_t window_start = at, filled = 0;
    for (; k < rows->blocks; ++k) {
      const uint32_t n = prt_le_load_u16(counts + 2u * k);
      if (n > PRT_BLOB_WVLT_BLOCK || n > end - at) return 0;
      if (rows->skip[k]) { /* zero light: skipped, but a window's pairs must be contiguous */
        if (filled > 0) break;
        at += n;
        window_start = at;
        continue;
      }
      if (filled + n > PRT_WAVELET_WINDOW) break; /* block k starts the next window */
      fill_block_number(block_of + filled, k, n);
      filled += n;
      at += n;
    }
    if (filled > 0)
      acc_add_pairs(&acc, rows->light, rows->pairs + 2u * (size_t)window_start, block_of, filled);
  }
  *rgb = acc_total(&acc);
  return at == end;
}

prt_result PRT_WAVELET_KERNEL_NAME(const prt_wavelet_rows* rows, uint32_t first, uint32_t count,
                                   float* out_rgb) {
  uint32_t v;
  for (v = 0; v < count; ++v) {
    const uint32_t vertex = first + v;
    const __m128 scale = _mm_setr_ps(prt_wavelet_vertex_scale(rows, vertex, 0),
                                     prt_wavelet_vertex_scale(rows, vertex, 1),
                                     prt_wavelet_vertex_scale(rows, vertex, 2), 0.0f);
    float lanes[4];
    __m128 sums;
    if (!shade_row(rows, vertex, &sums)) return PRT_ERROR_CORRUPT;
    _mm_storeu_ps(lanes, _mm_mul_ps(scale, sums));
    memcpy(out_rgb + 3u * (size_t)v, lanes, 3 * sizeof(float));
  }
  return PRT_OK;
}

#endif /* PRT_WAVELET_SHADE_X86_H */
