/* SPDX-License-Identifier: MIT */
/* `wavelet` tiled shading for AVX2 + FMA (compiled with -mavx2 -mfma, called only when the CPU
 * has both) over the repack of wavelet_tiles.c: per tile of 8 vertices, the lit faces' dense
 * corners as an 8-lane product with the broadcast corner light (no gathers), then the fine pairs
 * of the groups whose light is not zero, lane by lane, two pairs per 256-bit step. */
#include <immintrin.h>
#include <prt/format/blob_layout.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "wavelet_shade_simd.h"

/* The 8 corner values of coefficient c of a slab, as floats. */
static inline __m256 corner_values(const int8_t* slab, uint32_t c) {
  const __m128i q = _mm_loadl_epi64((const __m128i*)(const void*)(slab + PRT_WAVELET_TILE * c));
  return _mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(q));
}

/* Adds the lit faces' corners of one tile into rgb[3] (8 lanes each). Two sets of accumulators,
 * for even and odd coefficients, so consecutive multiply-adds do not wait on each other. */
static inline void shade_corners(const prt_wavelet_tiles* t, const prt_wavelet_tile_light* light,
                                 uint32_t tile, __m256 rgb[3]) {
  const uint32_t mask = t->face_mask[tile];
  const int8_t* slab =
      t->slabs + (size_t)PRT_WAVELET_CORNER_COEFFICIENTS * PRT_WAVELET_TILE * t->slab_start[tile];
  __m256 r0 = _mm256_setzero_ps(), g0 = r0, b0 = r0, r1 = r0, g1 = r0, b1 = r0;
  uint32_t f, c;
  for (f = 0; f < t->faces; ++f) {
    if (!(mask & (1u << f))) continue;
    if (light->face_lit[f]) {
      const float(*l)[4] = light->corner[f];
      for (c = 0; c < PRT_WAVELET_CORNER_COEFFICIENTS; c += 2) {
        const __m256 q0 = corner_values(slab, c), q1 = corner_values(slab, c + 1);
        r0 = _mm256_fmadd_ps(q0, _mm256_set1_ps(l[c][0]), r0);
        g0 = _mm256_fmadd_ps(q0, _mm256_set1_ps(l[c][1]), g0);
        b0 = _mm256_fmadd_ps(q0, _mm256_set1_ps(l[c][2]), b0);
        r1 = _mm256_fmadd_ps(q1, _mm256_set1_ps(l[c + 1][0]), r1);
        g1 = _mm256_fmadd_ps(q1, _mm256_set1_ps(l[c + 1][1]), g1);
        b1 = _mm256_fmadd_ps(q1, _mm256_set1_ps(l[c + 1][2]), b1);
      }
    }
    slab += PRT_WAVELET_CORNER_COEFFICIENTS * PRT_WAVELET_TILE;
  }
  rgb[0] = _mm256_add_ps(r0, r1);
  rgb[1] = _mm256_add_ps(g0, g1);
  rgb[2] = _mm256_add_ps(b0, b1);
}

/* The RGBA light of the pair at `pair` in the group whose light starts at `block`. */
static inline __m128 pair_light(const float* block, const uint8_t* pair) {
  return _mm_loadu_ps(block + 4u * pair[0]);
}

/* The number of pairs the 8 lane counts at `count` add up to. */
static inline uint32_t group_pairs(const uint8_t* count) {
  const __m128i c = _mm_loadl_epi64((const __m128i*)(const void*)count);
  return (uint32_t)_mm_cvtsi128_si32(_mm_sad_epu8(c, _mm_setzero_si128()));
}

/* Adds the fine pairs of one tile's lit groups into sums[lane] (RGBA). */
static inline void shade_fine(const prt_wavelet_tiles* t, const prt_wavelet_tile_light* light,
                              uint32_t tile, float sums[PRT_WAVELET_TILE][4]) {
  const uint8_t* count = t->fine_count + (size_t)tile * t->groups * PRT_WAVELET_TILE;
  const uint8_t* pair = t->fine_pairs + 2u * (size_t)t->fine_start[tile];
  __m256 acc[PRT_WAVELET_TILE];
  uint32_t g, lane;
  for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) acc[lane] = _mm256_setzero_ps();
  for (g = 0; g < t->groups; ++g, count += PRT_WAVELET_TILE) {
    const uint32_t total = group_pairs(count);
    const float* group = light->light + 4u * PRT_WAVELET_GROUP * (size_t)g;
    if (!light->group_lit[g] || total == 0) {
      pair += 2u * total;
      continue;
    }
    for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) {
      const uint32_t n = count[lane];
      __m256 a = acc[lane];
      uint32_t p = 0;
      for (; p + 2 <= n; p += 2, pair += 4) {
        const __m256 q = _mm256_set_m128(_mm_set1_ps((float)(int8_t)pair[3]),
                                         _mm_set1_ps((float)(int8_t)pair[1]));
        const __m256 l = _mm256_set_m128(pair_light(group, pair + 2), pair_light(group, pair));
        a = _mm256_fmadd_ps(q, l, a);
      }
      if (p < n) { /* the odd pair in the low half */
        const __m128 zero = _mm_setzero_ps();
        const __m256 q = _mm256_set_m128(zero, _mm_set1_ps((float)(int8_t)pair[1]));
        a = _mm256_fmadd_ps(q, _mm256_set_m128(zero, pair_light(group, pair)), a);
        pair += 2;
      }
      acc[lane] = a;
    }
  }
  for (lane = 0; lane < PRT_WAVELET_TILE; ++lane)
    _mm_storeu_ps(sums[lane], _mm_add_ps(_mm256_castps256_ps128(acc[lane]),
                                         _mm256_extractf128_ps(acc[lane], 1)));
}

void prt_wavelet_shade_tiles_avx2(const prt_wavelet_tiles* t, const prt_wavelet_tile_light* light,
                                  uint32_t first, uint32_t count, float* out_rgb) {
  const uint32_t end = first + count;
  uint32_t tile;
  for (tile = first / PRT_WAVELET_TILE; tile * PRT_WAVELET_TILE < end; ++tile) {
    const float* scale = t->scale + 3u * PRT_WAVELET_TILE * (size_t)tile;
    float corner[3][PRT_WAVELET_TILE], fine[PRT_WAVELET_TILE][4];
    __m256 rgb[3];
    uint32_t lane, c;
    shade_corners(t, light, tile, rgb);
    for (c = 0; c < 3; ++c) _mm256_storeu_ps(corner[c], rgb[c]);
    shade_fine(t, light, tile, fine);
    for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) {
      const uint32_t v = tile * PRT_WAVELET_TILE + lane;
      if (v < first || v >= end) continue;
      for (c = 0; c < 3; ++c)
        out_rgb[3u * (size_t)(v - first) + c] =
            scale[c * PRT_WAVELET_TILE + lane] * (corner[c][lane] + fine[lane][c]);
    }
  }
}
