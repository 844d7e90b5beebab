/* SPDX-License-Identifier: MIT */
/* `wavelet` tiled shading for AVX2 + FMA (compiled with -mavx2 -mfma, called only when the CPU
 * has both) over the repack of wavelet_tiles.c: per tile of 8 vertices, the lit faces' dense
 * corners as an 8-lane product with the broadcast corner light (no gathers), then each fine
 * coefficient that is both lit and stored by some lane of the tile, its values expanded into the
 * lanes, as the same 8-lane product. */
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

/* The byte shuffle that expands a record's values into its lanes: for lane mask m, lane i takes
 * value (the number of lanes of m below i) when m has lane i, else 0 (index 0x80). A constant
 * table: 256 masks of 8 bytes. */
#define RANK(m, i) ((((m) >> (i)) & 1u) ? (int8_t)(POP(((m) & ((1u << (i)) - 1u)))) : (int8_t)-128)
#define POP(x)                                                                                \
  (((x)&1u) + (((x) >> 1) & 1u) + (((x) >> 2) & 1u) + (((x) >> 3) & 1u) + (((x) >> 4) & 1u) + \
   (((x) >> 5) & 1u) + (((x) >> 6) & 1u) + (((x) >> 7) & 1u))
#define E1(m) \
  { RANK(m, 0), RANK(m, 1), RANK(m, 2), RANK(m, 3), RANK(m, 4), RANK(m, 5), RANK(m, 6), RANK(m, 7) }
#define E4(m) E1(m), E1((m) + 1u), E1((m) + 2u), E1((m) + 3u)
#define E16(m) E4(m), E4((m) + 4u), E4((m) + 8u), E4((m) + 12u)
#define E64(m) E16(m), E16((m) + 16u), E16((m) + 32u), E16((m) + 48u)
static const int8_t kExpand[256][8] = {E64(0u), E64(64u), E64(128u), E64(192u)};
#undef E64
#undef E16
#undef E4
#undef E1
#undef POP
#undef RANK

/* Adds, per lit unit, the coefficients some lane of the tile stores into rgb[3]: each one's
 * values expanded into the 8 lanes (zero in the lanes that do not store it) times the broadcast
 * light. The units come in index order and their coefficients too, so a vertex's sum has one
 * order whatever the range. */
static inline void shade_fine(const prt_wavelet_tiles* t, const prt_wavelet_tile_light* light,
                              uint32_t tile, __m256 rgb[3]) {
  const uint32_t* stored = t->unit_stored + (size_t)tile * t->units;
  const uint16_t* first = t->unit_first + 2u * (size_t)tile * t->units;
  const uint8_t* records = t->records + 2u * (size_t)t->tile_first[2u * tile];
  const int8_t* values = t->values + t->tile_first[2u * tile + 1u];
  __m256 r = rgb[0], g = rgb[1], b = rgb[2];
  uint32_t i;
  for (i = 0; i < light->lit_units; ++i) {
    const uint32_t u = light->unit[i], have = stored[u];
    uint32_t m = have & light->lit[i];
    if (!m) continue;
    {
      const uint8_t* record = records + 2u * first[2u * u];
      const int8_t* value = values + first[2u * u + 1u];
      const float* l = light->light + 4u * PRT_WAVELET_UNIT * (size_t)u;
      do {
        const uint32_t j = (uint32_t)__builtin_ctz(m);
        const uint8_t* rec = record + 2u * (uint32_t)__builtin_popcount(have & ((1u << j) - 1u));
        const __m128i q =
            _mm_shuffle_epi8(_mm_loadl_epi64((const __m128i*)(const void*)(value + rec[1])),
                             _mm_loadl_epi64((const __m128i*)(const void*)kExpand[rec[0]]));
        const __m256 qf = _mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(q));
        r = _mm256_fmadd_ps(qf, _mm256_broadcast_ss(l + 4u * j), r);
        g = _mm256_fmadd_ps(qf, _mm256_broadcast_ss(l + 4u * j + 1u), g);
        b = _mm256_fmadd_ps(qf, _mm256_broadcast_ss(l + 4u * j + 2u), b);
        m &= m - 1u;
      } while (m);
    }
  }
  rgb[0] = r;
  rgb[1] = g;
  rgb[2] = b;
}

void prt_wavelet_shade_tiles_avx2(const prt_wavelet_tiles* t, const prt_wavelet_tile_light* light,
                                  uint32_t first, uint32_t count, float* out_rgb) {
  const uint32_t end = first + count;
  uint32_t tile;
  for (tile = first / PRT_WAVELET_TILE; tile * PRT_WAVELET_TILE < end; ++tile) {
    const float* scale = t->scale + 3u * PRT_WAVELET_TILE * (size_t)tile;
    float sum[3][PRT_WAVELET_TILE];
    __m256 rgb[3];
    uint32_t lane, c;
    shade_corners(t, light, tile, rgb);
    shade_fine(t, light, tile, rgb);
    for (c = 0; c < 3; ++c)
      _mm256_storeu_ps(sum[c],
                       _mm256_mul_ps(_mm256_loadu_ps(scale + c * PRT_WAVELET_TILE), rgb[c]));
    for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) {
      const uint32_t v = tile * PRT_WAVELET_TILE + lane;
      if (v < first || v >= end) continue;
      for (c = 0; c < 3; ++c) out_rgb[3u * (size_t)(v - first) + c] = sum[c][lane];
    }
  }
}
