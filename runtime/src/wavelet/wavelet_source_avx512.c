/* SPDX-License-Identifier: MIT */
/* Resampling a prepared lat-long source onto the cube with AVX-512 F + DQ (this file is compiled
 * with those flags and only called when the context's SIMD ISA is AVX512). The 16 lanes are
 * the 16 rows of a band of the banded copy and the loop walks the columns, so a run of texels of
 * a row that land in one target is summed in its lane's registers (one masked add per channel and
 * column) and only a finished run is written out; see wavelet_source_simd.h for how the texels
 * are located and why every texel lands where prt_wavelet_resample puts it. */
#include <immintrin.h>
#include <stdint.h>

#include "wavelet_source_internal.h"
#include "wavelet_source_simd.h"

#define LANES 16u

typedef struct located {
  __m512i index;       /* target texel f S^2 + y S + x */
  __mmask16 uncertain; /* the lanes within EDGE_MARGIN of a texel edge */
} located;

/* The texel of coordinates (ts, tt) (already (c + 1) S / 2) on the face at face_offset. Every
 * lane whose truncation could leave 0..S-1 (a coordinate a rounding below 0 or at S) is within
 * the margin of an edge, so it is uncertain and located again: no clamp is needed. */
PRT_SOURCE_INLINE located texel_of(__m512 ts, __m512 tt, __m512i face_offset, __m128i log2_size) {
  /* reduce: t - round(t); range 0x0A: the smaller magnitude of the two, sign cleared. */
  const __m512 distance =
      _mm512_range_ps(_mm512_reduce_ps(ts, 0x08), _mm512_reduce_ps(tt, 0x08), 0x0A);
  const __m512i tx = _mm512_cvttps_epi32(ts), ty = _mm512_cvttps_epi32(tt);
  located out;
  out.uncertain = _mm512_cmp_ps_mask(distance, _mm512_set1_ps(EDGE_MARGIN), _CMP_LT_OQ);
  out.index = _mm512_add_epi32(_mm512_add_epi32(face_offset, _mm512_sll_epi32(ty, log2_size)), tx);
  return out;
}

/* prt_cube_face_coords and prt_face_texel on 16 directions, any face each. */
PRT_SOURCE_INLINE located locate_any(__m512 x, __m512 y, __m512 z, __m512 half_size, __m512i area,
                                     __m128i log2_size) {
  const __m512 sign = _mm512_set1_ps(-0.0f), zero = _mm512_setzero_ps();
  const __m512 ax = _mm512_abs_ps(x), ay = _mm512_abs_ps(y), az = _mm512_abs_ps(z);
  const __mmask16 x_major =
      _mm512_mask_cmp_ps_mask(_mm512_cmp_ps_mask(ax, ay, _CMP_GE_OQ), ax, az, _CMP_GE_OQ);
  const __mmask16 y_major = _mm512_mask_cmp_ps_mask(_knot_mask16(x_major), ay, az, _CMP_GE_OQ);
  const __mmask16 z_major = _knot_mask16(_kor_mask16(x_major, y_major));
  const __mmask16 x_positive = _mm512_cmp_ps_mask(x, zero, _CMP_GT_OQ);
  const __mmask16 y_positive = _mm512_cmp_ps_mask(y, zero, _CMP_GT_OQ);
  const __mmask16 z_positive = _mm512_cmp_ps_mask(z, zero, _CMP_GT_OQ);
  const __mmask16 negative = _knot_mask16(
      _kor_mask16(_kor_mask16(_kand_mask16(x_major, x_positive), _kand_mask16(y_major, y_positive)),
                  _kand_mask16(z_major, z_positive)));
  /* Faces +X -X +Y -Y +Z -Z: sc = -z, z, x, x, x, -x; tc = -y, -y, z, -z, -y, -y. */
  __m512 major = _mm512_mask_blend_ps(y_major, az, ay);
  __m512 sc = _mm512_mask_xor_ps(x, _knot_mask16(z_positive), x, sign);
  __m512 tc = _mm512_xor_ps(y, sign);
  __m512i face = _mm512_maskz_mov_epi32(z_major, _mm512_slli_epi32(area, 2));
  __m512 q;
  major = _mm512_mask_blend_ps(x_major, major, ax);
  sc = _mm512_mask_mov_ps(sc, y_major, x);
  sc = _mm512_mask_xor_ps(sc, x_major, z, _mm512_maskz_mov_ps(x_positive, sign));
  tc = _mm512_mask_xor_ps(tc, y_major, z, _mm512_maskz_mov_ps(_knot_mask16(y_positive), sign));
  face = _mm512_mask_mov_epi32(face, y_major, _mm512_slli_epi32(area, 1));
  face = _mm512_mask_add_epi32(face, negative, face, area);
  q = _mm512_div_ps(half_size, major);
  return texel_of(_mm512_fmadd_ps(sc, q, half_size), _mm512_fmadd_ps(tc, q, half_size), face,
                  log2_size);
}

/* 1 when every lane's m is at least |a| and |b|: range 0x0B is the larger magnitude. */
PRT_SOURCE_INLINE int all_major(__m512 m, __m512 a, __m512 b) {
  return _mm512_cmp_ps_mask(m, _mm512_range_ps(a, b, 0x0B), _CMP_GE_OQ) == 0xFFFFu;
}

/* The same when every lane is on face f, which the lanes of a column mostly are: the face test
 * is one compare per lane and the signs fold into the multiply-adds. 0 when some lane is on
 * another face. A lane on a tie between two faces may be taken for this face where
 * prt_cube_face_coords picks the other: its coordinate along the other is then +-1, an edge, so
 * it is located again exactly. */
PRT_SOURCE_INLINE int locate_on(uint32_t f, __m512 x, __m512 y, __m512 z, __m512 half_size,
                                uint32_t area, __m128i log2_size, located* out) {
  const __m512 sign = _mm512_set1_ps(-0.0f);
  const __m512i offset = _mm512_set1_epi32((int)(f * area));
  __m512 m, q;
  switch (f) {
    case 0:
      if (!all_major(x, y, z)) return 0;
      q = _mm512_div_ps(half_size, x);
      *out = texel_of(_mm512_fnmadd_ps(z, q, half_size), _mm512_fnmadd_ps(y, q, half_size), offset,
                      log2_size);
      return 1;
    case 1:
      m = _mm512_xor_ps(x, sign);
      if (!all_major(m, y, z)) return 0;
      q = _mm512_div_ps(half_size, m);
      *out = texel_of(_mm512_fmadd_ps(z, q, half_size), _mm512_fnmadd_ps(y, q, half_size), offset,
                      log2_size);
      return 1;
    case 2:
      if (!all_major(y, x, z)) return 0;
      q = _mm512_div_ps(half_size, y);
      *out = texel_of(_mm512_fmadd_ps(x, q, half_size), _mm512_fmadd_ps(z, q, half_size), offset,
                      log2_size);
      return 1;
    case 3:
      m = _mm512_xor_ps(y, sign);
      if (!all_major(m, x, z)) return 0;
      q = _mm512_div_ps(half_size, m);
      *out = texel_of(_mm512_fmadd_ps(x, q, half_size), _mm512_fnmadd_ps(z, q, half_size), offset,
                      log2_size);
      return 1;
    case 4:
      if (!all_major(z, x, y)) return 0;
      q = _mm512_div_ps(half_size, z);
      *out = texel_of(_mm512_fmadd_ps(x, q, half_size), _mm512_fnmadd_ps(y, q, half_size), offset,
                      log2_size);
      return 1;
    default:
      m = _mm512_xor_ps(z, sign);
      if (!all_major(m, x, y)) return 0;
      q = _mm512_div_ps(half_size, m);
      *out = texel_of(_mm512_fnmadd_ps(x, q, half_size), _mm512_fnmadd_ps(y, q, half_size), offset,
                      log2_size);
      return 1;
  }
}

/* What stays fixed over a column block's band. */
typedef struct band {
  const prt_wavelet_source* source;
  const double* r;
  __m512 sin_theta, up_x, up_y, up_z, solid_angle;
  __m512 half_size;
  __m512i area;
  __m128i log2_size;
  uint32_t first_row, face_area, log2_area;
  __mmask16 rows; /* the lanes that are rows of the map */
} band;

/* The exact target texels of column x's 16 rows; *face: the face the last column's lanes were
 * on, the guess tried first. */
PRT_SOURCE_INLINE __m512i locate_column(const band* b, const prt_wavelet_column_block* block,
                                        uint32_t x, uint32_t* face) {
  const __m512 dx = _mm512_fmadd_ps(b->sin_theta, _mm512_set1_ps(block->gx[x]), b->up_x);
  const __m512 dy = _mm512_fmadd_ps(b->sin_theta, _mm512_set1_ps(block->gy[x]), b->up_y);
  const __m512 dz = _mm512_fmadd_ps(b->sin_theta, _mm512_set1_ps(block->gz[x]), b->up_z);
  located lanes;
  __mmask16 uncertain;
  if (!locate_on(*face, dx, dy, dz, b->half_size, b->face_area, b->log2_size, &lanes)) {
    uint32_t lane0;
    lanes = locate_any(dx, dy, dz, b->half_size, b->area, b->log2_size);
    lane0 = (uint32_t)_mm_cvtsi128_si32(_mm512_castsi512_si128(lanes.index)) >> b->log2_area;
    *face = lane0 < 5u ? lane0 : 5u; /* a guess only: locate_on checks it */
  }
  uncertain = (__mmask16)(lanes.uncertain & b->rows);
  if (uncertain) {
    uint32_t index[LANES];
    unsigned left = uncertain;
    _mm512_storeu_si512(index, lanes.index);
    while (left) {
      const uint32_t lane = (uint32_t)__builtin_ctz(left);
      index[lane] =
          prt_wavelet_source_locate_latlong(b->source, b->r, block->first + x, b->first_row + lane);
      left &= left - 1u;
    }
    return _mm512_loadu_si512(index);
  }
  return lanes.index;
}

/* Finished runs waiting to be added to the targets: their (L dw, dw) sums, transposed to texels
 * in `sums` by 16 lanes per column, and per run its slot there and its target. The counts stay
 * in the caller's registers. */
#define CHUNK 32u /* columns between flushes */
typedef struct pending {
  float sums[4u * LANES * CHUNK];
  uint32_t slot[LANES * CHUNK + LANES], target[LANES * CHUNK + LANES];
} pending;

static void flush(const pending* p, uint32_t runs, float* out_rgba) {
  uint32_t k;
  for (k = 0; k < runs; ++k) {
    float* to = out_rgba + 4u * (size_t)p->target[k];
    _mm_storeu_ps(to, _mm_add_ps(_mm_loadu_ps(to), _mm_loadu_ps(p->sums + 4u * p->slot[k])));
  }
}

/* Queues the runs of the lanes in `ended` (their sums so far in r, g, b, w; their target in
 * `target`) as column `column` of the chunk, after `runs` others; returns the new count. All 16
 * lanes are transposed and stored, which costs less than picking the few. */
PRT_SOURCE_INLINE uint32_t queue_runs(pending* p, uint32_t runs, uint32_t column, __mmask16 ended,
                                      __m512i target, __m512 r, __m512 g, __m512 b, __m512 w) {
  /* 4x4 transposes in each 128-bit lane: lane j's texel goes to slot 4 (j & 3) + (j >> 2). */
  const __m512i slot = _mm512_setr_epi32(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
  const __m512d rg_low = _mm512_castps_pd(_mm512_unpacklo_ps(r, g));
  const __m512d rg_high = _mm512_castps_pd(_mm512_unpackhi_ps(r, g));
  const __m512d bw_low = _mm512_castps_pd(_mm512_unpacklo_ps(b, w));
  const __m512d bw_high = _mm512_castps_pd(_mm512_unpackhi_ps(b, w));
  const uint32_t base = LANES * column;
  float* to = p->sums + 4u * base;
  _mm512_storeu_pd((double*)(void*)to, _mm512_unpacklo_pd(rg_low, bw_low));
  _mm512_storeu_pd((double*)(void*)(to + 16), _mm512_unpackhi_pd(rg_low, bw_low));
  _mm512_storeu_pd((double*)(void*)(to + 32), _mm512_unpacklo_pd(rg_high, bw_high));
  _mm512_storeu_pd((double*)(void*)(to + 48), _mm512_unpackhi_pd(rg_high, bw_high));
  _mm512_storeu_si512(
      p->slot + runs,
      _mm512_maskz_compress_epi32(ended, _mm512_add_epi32(slot, _mm512_set1_epi32((int)base))));
  _mm512_storeu_si512(p->target + runs, _mm512_maskz_compress_epi32(ended, target));
  return runs + (uint32_t)__builtin_popcount((unsigned)ended);
}

/* One band over one column block. */
static void splat_band(const band* b, const prt_wavelet_column_block* block, pending* p,
                       float* out_rgba) {
  const float* texels =
      b->source->banded + prt_wavelet_banded_at(b->source->env.width, block->first, b->first_row);
  const size_t column_step = 3u * LANES;
  uint32_t face = 0u, runs = 0u, column = 0u, x;
  __m512i previous = locate_column(b, block, 0u, &face);
  __m512 sum_r = _mm512_mul_ps(_mm512_loadu_ps(texels), b->solid_angle);
  __m512 sum_g = _mm512_mul_ps(_mm512_loadu_ps(texels + LANES), b->solid_angle);
  __m512 sum_b = _mm512_mul_ps(_mm512_loadu_ps(texels + 2u * LANES), b->solid_angle);
  __m512 sum_w = b->solid_angle;
  for (x = 1u; x < block->count; ++x) {
    const float* texel = texels + column_step * x;
    const __m512i index = locate_column(b, block, x, &face);
    const __mmask16 same = _mm512_cmpeq_epi32_mask(index, previous);
    /* L dw rounds as prt_wavelet_resample's product; only the order of the sums differs. */
    const __m512 r = _mm512_mul_ps(_mm512_loadu_ps(texel), b->solid_angle);
    const __m512 g = _mm512_mul_ps(_mm512_loadu_ps(texel + LANES), b->solid_angle);
    const __m512 bl = _mm512_mul_ps(_mm512_loadu_ps(texel + 2u * LANES), b->solid_angle);
    runs = queue_runs(p, runs, column, (__mmask16)(~same & b->rows), previous, sum_r, sum_g, sum_b,
                      sum_w);
    if (++column == CHUNK) {
      flush(p, runs, out_rgba);
      runs = column = 0u;
    }
    sum_r = _mm512_mask_add_ps(r, same, sum_r, r);
    sum_g = _mm512_mask_add_ps(g, same, sum_g, g);
    sum_b = _mm512_mask_add_ps(bl, same, sum_b, bl);
    sum_w = _mm512_mask_add_ps(b->solid_angle, same, sum_w, b->solid_angle);
    previous = index;
  }
  runs = queue_runs(p, runs, column, b->rows, previous, sum_r, sum_g, sum_b, sum_w);
  flush(p, runs, out_rgba);
}

void prt_wavelet_source_splat_cube_avx512(const prt_wavelet_source* source, const double r[9],
                                          float* out_rgba) {
  const uint32_t width = source->env.width, height = source->env.height, size = source->size;
  prt_wavelet_column_block block;
  prt_wavelet_band_rows rows;
  pending p;
  band b;
  uint32_t log2_size = 0, first, first_row;
  while ((1u << log2_size) < size) ++log2_size;
  b.source = source;
  b.r = r;
  b.half_size = _mm512_set1_ps(0.5f * (float)size);
  b.face_area = size * size;
  b.area = _mm512_set1_epi32((int)b.face_area);
  b.log2_area = 2u * log2_size;
  b.log2_size = _mm_cvtsi32_si128((int)log2_size);
  for (first = 0; first < width; first += PRT_WAVELET_SOURCE_COLUMN_BLOCK) {
    prt_wavelet_source_column_block(source, r, first, &block);
    for (first_row = 0; first_row < height; first_row += LANES) {
      prt_wavelet_source_band_rows(source, r, first_row, &rows);
      b.first_row = first_row;
      b.rows = (__mmask16)rows.mask;
      b.sin_theta = _mm512_loadu_ps(rows.sin_theta);
      b.up_x = _mm512_loadu_ps(rows.up[0]);
      b.up_y = _mm512_loadu_ps(rows.up[1]);
      b.up_z = _mm512_loadu_ps(rows.up[2]);
      b.solid_angle = _mm512_loadu_ps(rows.solid_angle);
      splat_band(&b, &block, &p, out_rgba);
    }
  }
}
