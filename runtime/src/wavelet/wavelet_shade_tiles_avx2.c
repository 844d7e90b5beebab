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
static inline __m128 pair_light(const float* block, uint32_t index) {
  return _mm_loadu_ps(block + 4u * index);
}

/* The number of pairs the 8 lane counts at `count` add up to. */
static inline uint32_t group_pairs(const uint8_t* count) {
  const __m128i c = _mm_loadl_epi64((const __m128i*)(const void*)count);
  return (uint32_t)_mm_cvtsi128_si32(_mm_sad_epu8(c, _mm_setzero_si128()));
}

/* Pair k of a lane's run is kept in the 128-bit half k of step (k / 2) when k < n. */
static inline __m256 add_four_pairs(__m256 a, const float* group, const uint8_t* pair, __m256i n) {
  const __m128i bytes = _mm_loadl_epi64((const __m128i*)(const void*)pair);
  const __m128i q01 = _mm_shuffle_epi8(
      bytes, _mm_setr_epi8(1, 1, 1, 1, 3, 3, 3, 3, -1, -1, -1, -1, -1, -1, -1, -1));
  const __m128i q23 = _mm_shuffle_epi8(
      bytes, _mm_setr_epi8(5, 5, 5, 5, 7, 7, 7, 7, -1, -1, -1, -1, -1, -1, -1, -1));
  const __m256 keep01 =
      _mm256_castsi256_ps(_mm256_cmpgt_epi32(n, _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1)));
  const __m256 keep23 =
      _mm256_castsi256_ps(_mm256_cmpgt_epi32(n, _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3)));
  /* Indices past the run belong to the next run (or the padding): masked to the group, and
   * their light masked to +0, so they add exactly 0 even where the light is not finite. */
  const __m256 l01 = _mm256_and_ps(
      keep01, _mm256_set_m128(pair_light(group, pair[2] & 63u), pair_light(group, pair[0] & 63u)));
  const __m256 l23 = _mm256_and_ps(
      keep23, _mm256_set_m128(pair_light(group, pair[6] & 63u), pair_light(group, pair[4] & 63u)));
  a = _mm256_fmadd_ps(_mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(q01)), l01, a);
  return _mm256_fmadd_ps(_mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(q23)), l23, a);
}

/* Adds a lane's n pairs of one group into a, four pairs per step: a run of up to four pairs (the
 * common case) takes one step and no branch that depends on its length. */
static inline __m256 add_lane_pairs(__m256 a, const float* group, const uint8_t* pair, uint32_t n) {
  uint32_t p = 0;
  do {
    a = add_four_pairs(a, group, pair + 2u * p, _mm256_set1_epi32((int)(n - p)));
    p += 4;
  } while (p < n);
  return a;
}

/* Lit groups a tile collects (and prefetches) before it shades them. */
#define PRT_WAVELET_LIT_WINDOW 32u

/* A lit group of one tile: its light, its 8 lane counts and its first pair. */
typedef struct lit_group {
  const float* light;
  const uint8_t* count;
  const uint8_t* pair;
} lit_group;

/* Adds the fine pairs of one tile's lit groups into sums[lane] (RGBA). A tile's lit groups lie
 * scattered through its pairs, so the loop first finds a window of them and prefetches their
 * pairs, then shades them: the cache misses overlap. */
static inline void shade_fine(const prt_wavelet_tiles* t, const prt_wavelet_tile_light* light,
                              uint32_t tile, float sums[PRT_WAVELET_TILE][4]) {
  const uint8_t* count = t->fine_count + (size_t)tile * t->groups * PRT_WAVELET_TILE;
  const uint8_t* pair = t->fine_pairs + 2u * (size_t)t->fine_start[tile];
  __m256 acc[PRT_WAVELET_TILE];
  lit_group window[PRT_WAVELET_LIT_WINDOW];
  uint32_t g = 0, lane, i;
  for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) acc[lane] = _mm256_setzero_ps();
  while (g < t->groups) {
    uint32_t found = 0;
    for (; g < t->groups && found < PRT_WAVELET_LIT_WINDOW; ++g, count += PRT_WAVELET_TILE) {
      const uint32_t total = group_pairs(count);
      if (light->group_lit[g] && total != 0) {
        lit_group* w = &window[found++];
        w->light = light->light + 4u * PRT_WAVELET_GROUP * (size_t)g;
        w->count = count;
        w->pair = pair;
        _mm_prefetch((const char*)pair, _MM_HINT_T0);
        if (total > 16u) _mm_prefetch((const char*)(pair + 2u * total - 1u), _MM_HINT_T0);
      }
      pair += 2u * total;
    }
    for (i = 0; i < found; ++i) {
      const uint8_t* p = window[i].pair;
      for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) {
        const uint32_t n = window[i].count[lane];
        acc[lane] = add_lane_pairs(acc[lane], window[i].light, p, n);
        p += 2u * n;
      }
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
