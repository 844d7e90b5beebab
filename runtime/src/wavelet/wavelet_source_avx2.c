/* SPDX-License-Identifier: MIT */
/* Resampling a prepared lat-long source onto the cube with AVX2 + FMA (this file is compiled
 * with -mavx2 -mfma and only called when the CPU has both): eight columns of a row at a time,
 * their turned directions sin t g(f) + cos t R e_y from a float table of g per column block,
 * the cube face and texel found in float. A float texel can differ from the double one of
 * prt_wavelet_resample only for a direction near a texel edge or near a face boundary: such
 * lanes (a small margin around every texel edge, far wider than the float error) are located again
 * by the scalar path's exact function, so every source texel lands where it does there. */
#include <immintrin.h>
#include <stdint.h>

#include "wavelet_source_internal.h"

/* The margin, in texels, around a texel edge within which a float texel coordinate is taken
 * from the exact path; the float error is orders of magnitude smaller. It also covers the face
 * choice: float and double can only pick different faces where two |components| are nearly
 * equal, and there the face coordinate is nearly +-1, a texel edge. */
#define EDGE_MARGIN (1.0f / 2048.0f)

typedef struct cube_lanes {
  __m256i index;    /* target texel f S^2 + y S + x */
  __m256 uncertain; /* all-ones where the float texel may differ from the exact one */
} cube_lanes;

static inline __m256 abs_ps(__m256 v) {
  return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v);
}

/* 1 near an integer (a texel edge) of t, the texel coordinate. */
static inline __m256 near_edge(__m256 t) {
  const __m256 fraction = _mm256_sub_ps(t, _mm256_floor_ps(t));
  return _mm256_or_ps(_mm256_cmp_ps(fraction, _mm256_set1_ps(EDGE_MARGIN), _CMP_LT_OQ),
                      _mm256_cmp_ps(fraction, _mm256_set1_ps(1.0f - EDGE_MARGIN), _CMP_GT_OQ));
}

/* prt_cube_face_coords and prt_face_texel on eight directions. */
static inline cube_lanes locate_cube(__m256 x, __m256 y, __m256 z, __m256 half_size, __m256i last,
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
  const __m256 face_base =
      _mm256_blendv_ps(_mm256_blendv_ps(_mm256_set1_ps(5.0f), _mm256_set1_ps(3.0f), y_major),
                       _mm256_set1_ps(1.0f), x_major);
  const __m256 face = _mm256_sub_ps(face_base, _mm256_and_ps(positive, _mm256_set1_ps(1.0f)));
  const __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), major);
  /* Texel coordinate (c + 1) S / 2, its texel clamped to 0..S-1 (max also turns NaN to 0). */
  const __m256 ts = _mm256_mul_ps(_mm256_fmadd_ps(sc, inv, _mm256_set1_ps(1.0f)), half_size);
  const __m256 tt = _mm256_mul_ps(_mm256_fmadd_ps(tc, inv, _mm256_set1_ps(1.0f)), half_size);
  const __m256i tx = _mm256_min_epi32(_mm256_cvttps_epi32(_mm256_max_ps(ts, zero)), last);
  const __m256i ty = _mm256_min_epi32(_mm256_cvttps_epi32(_mm256_max_ps(tt, zero)), last);
  cube_lanes out;
  out.index = _mm256_add_epi32(
      _mm256_sll_epi32(_mm256_add_epi32(_mm256_sll_epi32(_mm256_cvttps_epi32(face), log2_size), ty),
                       log2_size),
      tx);
  out.uncertain = _mm256_or_ps(near_edge(ts), near_edge(tt));
  return out;
}

/* out[target] += (L dw, dw) of one source texel. */
static inline void accumulate(float* out_rgba, uint32_t target, const float* radiance,
                              __m128 solid_angle) {
  float* to = out_rgba + 4u * (size_t)target;
  _mm_storeu_ps(to, _mm_add_ps(_mm_loadu_ps(to), _mm_mul_ps(_mm_loadu_ps(radiance), solid_angle)));
}

static inline void add_to(float* to, __m128 value) {
  _mm_storeu_ps(to, _mm_add_ps(_mm_loadu_ps(to), value));
}

/* A lane mask spread over the texel pairs of register k (lanes 2k, 2k + 1, four floats each). */
static inline __m256 spread(__m256i mask, int k) {
  return _mm256_castsi256_ps(_mm256_permutevar8x32_epi32(
      mask,
      _mm256_setr_epi32(2 * k, 2 * k, 2 * k, 2 * k, 2 * k + 1, 2 * k + 1, 2 * k + 1, 2 * k + 1)));
}

/* Accumulates eight consecutive texels (RGBA x dw in pairs[0..3], two texels each) into their
 * targets. Neighbouring columns mostly share a target (near the poles a whole block of them
 * does), and adding each into memory would chain every add on the previous store. So runs of
 * equal targets are summed in registers first (a segmented prefix sum over the lanes, steps of
 * 1, 2, 4), and only each run's last lane goes to memory; the other lanes add into a scratch
 * slot of their own, which keeps the loop free of data-dependent branches. */
static inline void accumulate_runs(float* out_rgba, float* scratch, __m256i index,
                                   __m256 pairs[4]) {
  const __m256i previous =
      _mm256_permutevar8x32_epi32(index, _mm256_setr_epi32(0, 0, 1, 2, 3, 4, 5, 6));
  const __m256i not_first = _mm256_setr_epi32(0, -1, -1, -1, -1, -1, -1, -1);
  /* same1[l]: lane l - 1 has the same target; same2: lanes l - 3 .. l; same4: l - 7 .. l.
   * Lane 0 of each is 0, so a shift that reads lane 0 for an underflow reads 0. */
  const __m256i same1 = _mm256_and_si256(_mm256_cmpeq_epi32(index, previous), not_first);
  const __m256i same2 = _mm256_and_si256(
      same1, _mm256_permutevar8x32_epi32(same1, _mm256_setr_epi32(0, 0, 1, 2, 3, 4, 5, 6)));
  const __m256i same4 = _mm256_and_si256(
      same2, _mm256_permutevar8x32_epi32(same2, _mm256_setr_epi32(0, 0, 0, 1, 2, 3, 4, 5)));
  /* A run ends where the next lane does not continue it; lane 7 always ends one. */
  const int continued = _mm256_movemask_ps(_mm256_castsi256_ps(same1)) >> 1;
  uint32_t target[8];
  int k;
  for (k = 3; k >= 0; --k) { /* one texel back: (t[2k-1], t[2k]) */
    const __m256 back = k > 0 ? _mm256_permute2f128_ps(pairs[k - 1], pairs[k], 0x21)
                              : _mm256_permute2f128_ps(pairs[0], pairs[0], 0x08);
    pairs[k] = _mm256_add_ps(pairs[k], _mm256_and_ps(spread(same1, k), back));
  }
  for (k = 3; k >= 1; --k)
    pairs[k] = _mm256_add_ps(pairs[k], _mm256_and_ps(spread(same2, k), pairs[k - 1]));
  for (k = 3; k >= 2; --k)
    pairs[k] = _mm256_add_ps(pairs[k], _mm256_and_ps(spread(same4, k), pairs[k - 2]));
  _mm256_storeu_si256((__m256i*)(void*)target, index);
  for (k = 0; k < 4; ++k) {
    float* low =
        (continued >> (2 * k)) & 1 ? scratch + 8 * k : out_rgba + 4u * (size_t)target[2 * k];
    float* high = (continued >> (2 * k + 1)) & 1 ? scratch + 8 * k + 4
                                                 : out_rgba + 4u * (size_t)target[2 * k + 1];
    add_to(low, _mm256_castps256_ps128(pairs[k]));
    add_to(high, _mm256_extractf128_ps(pairs[k], 1));
  }
}

void prt_wavelet_source_splat_cube_avx2(const prt_wavelet_source* source, const double r[9],
                                        float* out_rgba) {
  const uint32_t width = source->env.width, height = source->env.height, size = source->size;
  const __m256 half_size = _mm256_set1_ps(0.5f * (float)size);
  const __m256i last = _mm256_set1_epi32((int)size - 1);
  float gx[PRT_WAVELET_SOURCE_COLUMN_BLOCK], gy[PRT_WAVELET_SOURCE_COLUMN_BLOCK],
      gz[PRT_WAVELET_SOURCE_COLUMN_BLOCK];
  uint32_t index[8];
  float scratch[32] = {0}; /* the run sums that do not end a run go here, never read */
  uint32_t log2_size = 0, first, x, y, lane;
  __m128i shift;
  while ((1u << log2_size) < size) ++log2_size;
  shift = _mm_cvtsi32_si128((int)log2_size);
  for (first = 0; first < width; first += PRT_WAVELET_SOURCE_COLUMN_BLOCK) {
    const uint32_t count = width - first < PRT_WAVELET_SOURCE_COLUMN_BLOCK
                               ? width - first
                               : PRT_WAVELET_SOURCE_COLUMN_BLOCK;
    const uint32_t whole = count & ~7u;
    for (x = 0; x < count; ++x) {
      const double sin_phi = source->column_sin[first + x], cos_phi = source->column_cos[first + x];
      gx[x] = (float)(r[0] * sin_phi - r[2] * cos_phi);
      gy[x] = (float)(r[3] * sin_phi - r[5] * cos_phi);
      gz[x] = (float)(r[6] * sin_phi - r[8] * cos_phi);
    }
    for (y = 0; y < height; ++y) {
      const double cos_theta = source->row_cos[y];
      const __m256 sin_theta = _mm256_set1_ps((float)source->row_sin[y]);
      const __m256 up_x = _mm256_set1_ps((float)(cos_theta * r[1]));
      const __m256 up_y = _mm256_set1_ps((float)(cos_theta * r[4]));
      const __m256 up_z = _mm256_set1_ps((float)(cos_theta * r[7]));
      const __m128 solid_angle = _mm_set1_ps(source->texel_solid_angle[y]);
      const __m256 solid_angle8 = _mm256_set1_ps(source->texel_solid_angle[y]);
      const float* radiance = source->radiance + 4u * ((size_t)y * width + first);
      for (x = 0; x < whole; x += 8u) {
        const cube_lanes lanes = locate_cube(
            _mm256_fmadd_ps(sin_theta, _mm256_loadu_ps(gx + x), up_x),
            _mm256_fmadd_ps(sin_theta, _mm256_loadu_ps(gy + x), up_y),
            _mm256_fmadd_ps(sin_theta, _mm256_loadu_ps(gz + x), up_z), half_size, last, shift);
        int uncertain = _mm256_movemask_ps(lanes.uncertain);
        __m256i exact = lanes.index;
        __m256 pairs[4];
        if (uncertain) {
          _mm256_storeu_si256((__m256i*)(void*)index, lanes.index);
          while (uncertain) {
            lane = (uint32_t)__builtin_ctz((unsigned)uncertain);
            index[lane] = prt_wavelet_source_locate_latlong(source, r, first + x + lane, y);
            uncertain &= uncertain - 1;
          }
          exact = _mm256_loadu_si256((const __m256i*)(const void*)index);
        }
        for (lane = 0; lane < 4u; ++lane)
          pairs[lane] = _mm256_mul_ps(_mm256_loadu_ps(radiance + 4u * x + 8u * lane), solid_angle8);
        accumulate_runs(out_rgba, scratch, exact, pairs);
      }
      for (x = whole; x < count; ++x)
        accumulate(out_rgba, prt_wavelet_source_locate_latlong(source, r, first + x, y),
                   radiance + 4u * x, solid_angle);
    }
  }
}
