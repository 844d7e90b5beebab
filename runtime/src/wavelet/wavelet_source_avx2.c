/* SPDX-License-Identifier: MIT */
/* Resampling a prepared lat-long source onto the cube with AVX2 + FMA (this file is compiled
 * with -mavx2 -mfma and only called when the CPU has both). A band's 16 rows are two halves of 8
 * lanes, walked over the columns together, so a run of texels of a row that land in one target
 * is summed in its lane's registers and only a finished run is written out; see
 * wavelet_source_simd.h for how the texels are located and why every texel lands where
 * prt_wavelet_resample puts it. */
#include <immintrin.h>
#include <stdint.h>

#include "wavelet_source_internal.h"
#include "wavelet_source_simd.h"

#define LANES 8u /* of a half */

typedef struct located {
  __m256i index; /* target texel f S^2 + y S + x */
  int uncertain; /* lane bits: within EDGE_MARGIN of a texel edge */
} located;

/* A constant expression, as the rounding intrinsics need (clang checks). */
#define PRT_NEAREST (_MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC)

PRT_SOURCE_INLINE __m256 abs_ps(__m256 v) {
  return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v);
}

/* The texel of coordinates (ts, tt) (already (c + 1) S / 2) on the face at face_offset. Every
 * lane whose truncation could leave 0..S-1 is within the margin of an edge, so it is uncertain
 * and located again: no clamp is needed. */
PRT_SOURCE_INLINE located texel_of(__m256 ts, __m256 tt, __m256i face_offset, __m128i log2_size) {
  const __m256 ds = abs_ps(_mm256_sub_ps(ts, _mm256_round_ps(ts, PRT_NEAREST)));
  const __m256 dt = abs_ps(_mm256_sub_ps(tt, _mm256_round_ps(tt, PRT_NEAREST)));
  const __m256i tx = _mm256_cvttps_epi32(ts), ty = _mm256_cvttps_epi32(tt);
  located out;
  out.uncertain = _mm256_movemask_ps(
      _mm256_cmp_ps(_mm256_min_ps(ds, dt), _mm256_set1_ps(EDGE_MARGIN), _CMP_LT_OQ));
  out.index = _mm256_add_epi32(_mm256_add_epi32(face_offset, _mm256_sll_epi32(ty, log2_size)), tx);
  return out;
}

/* prt_cube_face_coords and prt_face_texel on 8 directions, any face each. */
PRT_SOURCE_INLINE located locate_any(__m256 x, __m256 y, __m256 z, __m256 half_size, __m256i area,
                                     __m128i log2_size) {
  const __m256 sign = _mm256_set1_ps(-0.0f), zero = _mm256_setzero_ps();
  const __m256 ax = abs_ps(x), ay = abs_ps(y), az = abs_ps(z);
  const __m256 x_major =
      _mm256_and_ps(_mm256_cmp_ps(ax, ay, _CMP_GE_OQ), _mm256_cmp_ps(ax, az, _CMP_GE_OQ));
  const __m256 y_major = _mm256_andnot_ps(x_major, _mm256_cmp_ps(ay, az, _CMP_GE_OQ));
  const __m256 x_positive = _mm256_cmp_ps(x, zero, _CMP_GT_OQ);
  const __m256 y_positive = _mm256_cmp_ps(y, zero, _CMP_GT_OQ);
  const __m256 z_positive = _mm256_cmp_ps(z, zero, _CMP_GT_OQ);
  /* Faces +X -X +Y -Y +Z -Z: sc = -z, z, x, x, x, -x; tc = -y, -y, z, -z, -y, -y. */
  const __m256 sc_x = _mm256_xor_ps(z, _mm256_and_ps(x_positive, sign));
  const __m256 sc_z = _mm256_xor_ps(x, _mm256_andnot_ps(z_positive, sign));
  const __m256 tc_y = _mm256_xor_ps(z, _mm256_andnot_ps(y_positive, sign));
  const __m256 sc = _mm256_blendv_ps(_mm256_blendv_ps(sc_z, x, y_major), sc_x, x_major);
  const __m256 tc = _mm256_blendv_ps(_mm256_xor_ps(y, sign), tc_y, y_major);
  const __m256 major = _mm256_blendv_ps(_mm256_blendv_ps(az, ay, y_major), ax, x_major);
  const __m256 positive =
      _mm256_blendv_ps(_mm256_blendv_ps(z_positive, y_positive, y_major), x_positive, x_major);
  /* Face 4, 2 or 0 by the major axis, + 1 where it is negative; times S^2. */
  const __m256i face = _mm256_add_epi32(
      _mm256_andnot_si256(_mm256_castps_si256(positive), area),
      _mm256_blendv_epi8(_mm256_blendv_epi8(_mm256_slli_epi32(area, 2), _mm256_slli_epi32(area, 1),
                                            _mm256_castps_si256(y_major)),
                         _mm256_setzero_si256(), _mm256_castps_si256(x_major)));
  const __m256 q = _mm256_div_ps(half_size, major);
  return texel_of(_mm256_fmadd_ps(sc, q, half_size), _mm256_fmadd_ps(tc, q, half_size), face,
                  log2_size);
}

/* 1 when every lane's m is at least |a| and |b|. */
PRT_SOURCE_INLINE int all_major(__m256 m, __m256 a, __m256 b) {
  return _mm256_movemask_ps(_mm256_cmp_ps(m, _mm256_max_ps(abs_ps(a), abs_ps(b)), _CMP_GE_OQ)) ==
         0xFF;
}

/* The same when every lane is on face f, which the lanes of a column mostly are: the face test
 * is one compare per lane and the signs fold into the multiply-adds. 0 when some lane is on
 * another face. A lane on a tie between two faces may be taken for this face where
 * prt_cube_face_coords picks the other: its coordinate along the other is then +-1, an edge, so
 * it is located again exactly. */
PRT_SOURCE_INLINE int locate_on(uint32_t f, __m256 x, __m256 y, __m256 z, __m256 half_size,
                                uint32_t area, __m128i log2_size, located* out) {
  const __m256 sign = _mm256_set1_ps(-0.0f);
  const __m256i offset = _mm256_set1_epi32((int)(f * area));
  __m256 m, q;
  switch (f) {
    case 0:
      if (!all_major(x, y, z)) return 0;
      q = _mm256_div_ps(half_size, x);
      *out = texel_of(_mm256_fnmadd_ps(z, q, half_size), _mm256_fnmadd_ps(y, q, half_size), offset,
                      log2_size);
      return 1;
    case 1:
      m = _mm256_xor_ps(x, sign);
      if (!all_major(m, y, z)) return 0;
      q = _mm256_div_ps(half_size, m);
      *out = texel_of(_mm256_fmadd_ps(z, q, half_size), _mm256_fnmadd_ps(y, q, half_size), offset,
                      log2_size);
      return 1;
    case 2:
      if (!all_major(y, x, z)) return 0;
      q = _mm256_div_ps(half_size, y);
      *out = texel_of(_mm256_fmadd_ps(x, q, half_size), _mm256_fmadd_ps(z, q, half_size), offset,
                      log2_size);
      return 1;
    case 3:
      m = _mm256_xor_ps(y, sign);
      if (!all_major(m, x, z)) return 0;
      q = _mm256_div_ps(half_size, m);
      *out = texel_of(_mm256_fmadd_ps(x, q, half_size), _mm256_fnmadd_ps(z, q, half_size), offset,
                      log2_size);
      return 1;
    case 4:
      if (!all_major(z, x, y)) return 0;
      q = _mm256_div_ps(half_size, z);
      *out = texel_of(_mm256_fmadd_ps(x, q, half_size), _mm256_fnmadd_ps(y, q, half_size), offset,
                      log2_size);
      return 1;
    default:
      m = _mm256_xor_ps(z, sign);
      if (!all_major(m, x, y)) return 0;
      q = _mm256_div_ps(half_size, m);
      *out = texel_of(_mm256_fnmadd_ps(x, q, half_size), _mm256_fnmadd_ps(y, q, half_size), offset,
                      log2_size);
      return 1;
  }
}

/* What stays fixed over a column block's half band. */
typedef struct half_band {
  __m256 sin_theta, up_x, up_y, up_z, solid_angle;
  uint32_t first_row; /* of the half */
  int rows;           /* lane bits: the lanes that are rows of the map */
} half_band;

typedef struct frame {
  const prt_wavelet_source* source;
  const double* r;
  __m256 half_size;
  __m256i area;
  __m128i log2_size;
  uint32_t face_area, log2_area;
  /* compress[m]: the set lanes of m in order, a lane index per 4 bits (AVX2 has no compress). */
  uint32_t compress[256];
} frame;

/* The exact target texels of column x's 8 rows; *face: the face tried first. */
PRT_SOURCE_INLINE __m256i locate_column(const frame* fr, const half_band* h,
                                        const prt_wavelet_column_block* block, uint32_t x,
                                        uint32_t* face) {
  const __m256 dx = _mm256_fmadd_ps(h->sin_theta, _mm256_set1_ps(block->gx[x]), h->up_x);
  const __m256 dy = _mm256_fmadd_ps(h->sin_theta, _mm256_set1_ps(block->gy[x]), h->up_y);
  const __m256 dz = _mm256_fmadd_ps(h->sin_theta, _mm256_set1_ps(block->gz[x]), h->up_z);
  located lanes;
  int uncertain;
  if (!locate_on(*face, dx, dy, dz, fr->half_size, fr->face_area, fr->log2_size, &lanes)) {
    uint32_t lane0;
    lanes = locate_any(dx, dy, dz, fr->half_size, fr->area, fr->log2_size);
    lane0 = (uint32_t)_mm_cvtsi128_si32(_mm256_castsi256_si128(lanes.index)) >> fr->log2_area;
    *face = lane0 < 5u ? lane0 : 5u; /* a guess only: locate_on checks it */
  }
  uncertain = lanes.uncertain & h->rows;
  if (uncertain) {
    uint32_t index[LANES];
    _mm256_storeu_si256((__m256i*)(void*)index, lanes.index);
    while (uncertain) {
      const uint32_t lane = (uint32_t)__builtin_ctz((unsigned)uncertain);
      index[lane] = prt_wavelet_source_locate_latlong(fr->source, fr->r, block->first + x,
                                                      h->first_row + lane);
      uncertain &= uncertain - 1;
    }
    return _mm256_loadu_si256((const __m256i*)(const void*)index);
  }
  return lanes.index;
}

/* Finished runs waiting to be added to the targets: their (L dw, dw) sums, transposed to texels
 * in `sums` by 16 lanes per column, and per run its slot there and its target. The counts stay
 * in the caller's registers. */
#define CHUNK 32u /* columns between flushes */
typedef struct pending {
  float sums[4u * 2u * LANES * CHUNK];
  uint32_t slot[2u * LANES * CHUNK + LANES], target[2u * LANES * CHUNK + LANES];
} pending;

static void flush(const pending* p, uint32_t runs, float* out_rgba) {
  uint32_t k;
  for (k = 0; k < runs; ++k) {
    float* to = out_rgba + 4u * (size_t)p->target[k];
    _mm_storeu_ps(to, _mm_add_ps(_mm_loadu_ps(to), _mm_loadu_ps(p->sums + 4u * p->slot[k])));
  }
}

/* Queues the runs of the lanes in `ended` (their sums so far in r, g, b, w; their target in
 * `target`) of half `half` of column `column` of the chunk, after `runs` others; returns the new
 * count. All 8 lanes are transposed and stored, which costs less than picking the few. */
PRT_SOURCE_INLINE uint32_t queue_runs(const frame* fr, pending* p, uint32_t runs, uint32_t column,
                                      uint32_t half, int ended, __m256i target, __m256 r, __m256 g,
                                      __m256 b, __m256 w) {
  /* 4x4 transposes in each 128-bit lane: lane j's texel goes to slot 2 (j & 3) + (j >> 2). */
  const __m256i slot = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  const __m256d rg_low = _mm256_castps_pd(_mm256_unpacklo_ps(r, g));
  const __m256d rg_high = _mm256_castps_pd(_mm256_unpackhi_ps(r, g));
  const __m256d bw_low = _mm256_castps_pd(_mm256_unpacklo_ps(b, w));
  const __m256d bw_high = _mm256_castps_pd(_mm256_unpackhi_ps(b, w));
  const uint32_t base = 2u * LANES * column + LANES * half;
  const uint32_t packed = fr->compress[ended];
  const __m256i order =
      _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32((int)packed),
                                         _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28)),
                       _mm256_set1_epi32(15));
  float* to = p->sums + 4u * base;
  _mm256_storeu_pd((double*)(void*)to, _mm256_unpacklo_pd(rg_low, bw_low));
  _mm256_storeu_pd((double*)(void*)(to + 8), _mm256_unpackhi_pd(rg_low, bw_low));
  _mm256_storeu_pd((double*)(void*)(to + 16), _mm256_unpacklo_pd(rg_high, bw_high));
  _mm256_storeu_pd((double*)(void*)(to + 24), _mm256_unpackhi_pd(rg_high, bw_high));
  _mm256_storeu_si256(
      (__m256i*)(void*)(p->slot + runs),
      _mm256_add_epi32(_mm256_permutevar8x32_epi32(slot, order), _mm256_set1_epi32((int)base)));
  _mm256_storeu_si256((__m256i*)(void*)(p->target + runs),
                      _mm256_permutevar8x32_epi32(target, order));
  return runs + (uint32_t)__builtin_popcount((unsigned)ended);
}

/* A half band's runs in progress. */
typedef struct runs {
  __m256i previous;
  __m256 r, g, b, w;
  uint32_t face;
} run_state;

PRT_SOURCE_INLINE void start_runs(const frame* fr, const half_band* h,
                                  const prt_wavelet_column_block* block, const float* texel,
                                  run_state* s) {
  s->face = 0u;
  s->previous = locate_column(fr, h, block, 0u, &s->face);
  s->r = _mm256_mul_ps(_mm256_loadu_ps(texel), h->solid_angle);
  s->g = _mm256_mul_ps(_mm256_loadu_ps(texel + 2u * LANES), h->solid_angle);
  s->b = _mm256_mul_ps(_mm256_loadu_ps(texel + 4u * LANES), h->solid_angle);
  s->w = h->solid_angle;
}

/* Column x of a half band: queues the runs it ends as column `column` of the chunk, after `runs`
 * others, then adds its texels to the runs; returns the new count. */
PRT_SOURCE_INLINE uint32_t step_runs(const frame* fr, const half_band* h,
                                     const prt_wavelet_column_block* block, uint32_t x,
                                     const float* texel, uint32_t half, pending* p, uint32_t runs,
                                     uint32_t column, run_state* s) {
  const __m256i index = locate_column(fr, h, block, x, &s->face);
  const __m256 same = _mm256_castsi256_ps(_mm256_cmpeq_epi32(index, s->previous));
  /* L dw rounds as prt_wavelet_resample's product; only the order of the sums differs. */
  const __m256 r = _mm256_mul_ps(_mm256_loadu_ps(texel), h->solid_angle);
  const __m256 g = _mm256_mul_ps(_mm256_loadu_ps(texel + 2u * LANES), h->solid_angle);
  const __m256 b = _mm256_mul_ps(_mm256_loadu_ps(texel + 4u * LANES), h->solid_angle);
  runs = queue_runs(fr, p, runs, column, half, ~_mm256_movemask_ps(same) & h->rows, s->previous,
                    s->r, s->g, s->b, s->w);
  s->r = _mm256_blendv_ps(r, _mm256_add_ps(s->r, r), same);
  s->g = _mm256_blendv_ps(g, _mm256_add_ps(s->g, g), same);
  s->b = _mm256_blendv_ps(b, _mm256_add_ps(s->b, b), same);
  s->w = _mm256_blendv_ps(h->solid_angle, _mm256_add_ps(s->w, h->solid_angle), same);
  s->previous = index;
  return runs;
}

static void load_half(const prt_wavelet_band_rows* rows, uint32_t first_row, uint32_t half,
                      half_band* h) {
  const uint32_t at = LANES * half;
  h->first_row = first_row + at;
  h->rows = (int)((rows->mask >> at) & 0xFFu);
  h->sin_theta = _mm256_loadu_ps(rows->sin_theta + at);
  h->up_x = _mm256_loadu_ps(rows->up[0] + at);
  h->up_y = _mm256_loadu_ps(rows->up[1] + at);
  h->up_z = _mm256_loadu_ps(rows->up[2] + at);
  h->solid_angle = _mm256_loadu_ps(rows->solid_angle + at);
}

/* One band (both halves, interleaved for independent work) over one column block. */
static void splat_band(const frame* fr, const prt_wavelet_band_rows* rows, uint32_t first_row,
                       const prt_wavelet_column_block* block, pending* p, float* out_rgba) {
  const float* texels =
      fr->source->banded + prt_wavelet_banded_at(fr->source->env.width, block->first, first_row);
  const size_t column_step = 3u * PRT_WAVELET_BAND_ROWS;
  half_band low, high;
  run_state a, b;
  uint32_t runs = 0u, column = 0u, x;
  load_half(rows, first_row, 0u, &low);
  load_half(rows, first_row, 1u, &high);
  start_runs(fr, &low, block, texels, &a);
  start_runs(fr, &high, block, texels + LANES, &b);
  for (x = 1u; x < block->count; ++x) {
    const float* texel = texels + column_step * x;
    runs = step_runs(fr, &low, block, x, texel, 0u, p, runs, column, &a);
    runs = step_runs(fr, &high, block, x, texel + LANES, 1u, p, runs, column, &b);
    if (++column == CHUNK) {
      flush(p, runs, out_rgba);
      runs = column = 0u;
    }
  }
  runs = queue_runs(fr, p, runs, column, 0u, low.rows, a.previous, a.r, a.g, a.b, a.w);
  runs = queue_runs(fr, p, runs, column, 1u, high.rows, b.previous, b.r, b.g, b.b, b.w);
  flush(p, runs, out_rgba);
}

void prt_wavelet_source_splat_cube_avx2(const prt_wavelet_source* source, const double r[9],
                                        float* out_rgba) {
  const uint32_t width = source->env.width, height = source->env.height, size = source->size;
  prt_wavelet_column_block block;
  prt_wavelet_band_rows rows;
  pending p;
  frame fr;
  uint32_t log2_size = 0, first, first_row, m;
  while ((1u << log2_size) < size) ++log2_size;
  fr.source = source;
  fr.r = r;
  fr.half_size = _mm256_set1_ps(0.5f * (float)size);
  fr.face_area = size * size;
  fr.area = _mm256_set1_epi32((int)fr.face_area);
  fr.log2_area = 2u * log2_size;
  fr.log2_size = _mm_cvtsi32_si128((int)log2_size);
  for (m = 0; m < 256u; ++m) {
    uint32_t packed = 0u, n = 0u, lane;
    for (lane = 0; lane < LANES; ++lane)
      if (m >> lane & 1u) packed |= lane << (4u * n++);
    fr.compress[m] = packed;
  }
  for (first = 0; first < width; first += PRT_WAVELET_SOURCE_COLUMN_BLOCK) {
    prt_wavelet_source_column_block(source, r, first, &block);
    for (first_row = 0; first_row < height; first_row += PRT_WAVELET_BAND_ROWS) {
      prt_wavelet_source_band_rows(source, r, first_row, &rows);
      splat_band(&fr, &rows, first_row, &block, &p, out_rgba);
    }
  }
}
