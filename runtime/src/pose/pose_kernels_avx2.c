/* SPDX-License-Identifier: MIT */
/* `pose` kernels for AVX2 + FMA (compiled with -mavx2 -mfma, called only when the CPU has both;
 * pose_simd.h). Shading: per vertex three dot products of its q values with the folded light
 * weights, eight at a time, the last partial block read so that nothing past the vertex's row
 * is read, the three sums reduced together. Transfer: per vertex one FMA chain over k of its
 * value broadcast against a block of eight coefficients, four vertices interleaved to hide the
 * FMA latency. Model 1's exact part: eight vertices per register, from the skin records to the
 * folded SH sum (pose_simd.h). */
#include <immintrin.h>
#include <math.h>
#include <string.h>

#include "pose_simd.h"

#if defined(__GNUC__)
#define PRT_KERNEL_INLINE static inline __attribute__((always_inline))
#else
#define PRT_KERNEL_INLINE static inline
#endif

#define TRANSFER_GROUP 4

/* Eight stored values (u8 or u16 little-endian, any alignment) as floats. */
PRT_KERNEL_INLINE __m256 load8(const uint8_t* p, uint32_t bits) {
  if (bits == 8)
    return _mm256_cvtepi32_ps(
        _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i*)(const void*)p)));
  return _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_loadu_si128((const __m128i*)(const void*)p)));
}

/* (r, g, b, b) of three accumulators' lanes, each summed by a tree of three additions. */
PRT_KERNEL_INLINE __m128 sum8x3(__m256 r, __m256 g, __m256 b) {
  const __m256 s = _mm256_hadd_ps(_mm256_hadd_ps(r, g), _mm256_hadd_ps(b, b));
  return _mm_add_ps(_mm256_castps256_ps128(s), _mm256_extractf128_ps(s, 1));
}

void prt_pose_shade_avx2(const prt_pose_shade_job* job, uint32_t count, float* out_rgb) {
  const size_t size = job->bits / 8u;
  const uint32_t q = job->basis_dims, full = q / 8u * 8u;
  /* With q >= 8 the partial last block is read as the row's last eight values, whose first
   * ones (already summed) get weight 0: no copy, and nothing past the row is read. */
  const int overlap = full < q && q >= 8u;
  const __m128 bias = _mm_setr_ps(job->bias[0], job->bias[1], job->bias[2], 0.0f);
  const uint8_t* row = job->values;
  float tail[3][8];
  uint32_t v, k;
  int ch;
  if (overlap)
    for (ch = 0; ch < 3; ++ch)
      for (k = 0; k < 8u; ++k)
        tail[ch][k] = q - 8u + k >= full ? job->weight[ch][q - 8u + k] : 0.0f;
  for (v = 0; v < count; ++v, row += job->stride) {
    __m256 acc[3] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
    __m128 rgb;
    for (k = 0; k < full; k += 8) {
      const __m256 values = load8(row + size * k, job->bits);
      for (ch = 0; ch < 3; ++ch)
        acc[ch] = _mm256_fmadd_ps(values, _mm256_loadu_ps(job->weight[ch] + k), acc[ch]);
    }
    if (overlap) {
      const __m256 values = load8(row + size * (q - 8u), job->bits);
      for (ch = 0; ch < 3; ++ch)
        acc[ch] = _mm256_fmadd_ps(values, _mm256_loadu_ps(tail[ch]), acc[ch]);
    } else if (full < q) {
      uint8_t copy[16] = {0};
      __m256 values;
      memcpy(copy, row + size * full, size * (q - full));
      values = load8(copy, job->bits);
      for (ch = 0; ch < 3; ++ch)
        acc[ch] = _mm256_fmadd_ps(values, _mm256_loadu_ps(job->weight[ch] + full), acc[ch]);
    }
    rgb = _mm_add_ps(bias, sum8x3(acc[0], acc[1], acc[2]));
    if (v + 1u < count) { /* the fourth float is the next vertex's, written next */
      _mm_storeu_ps(out_rgb + 3u * (size_t)v, rgb);
    } else {
      float last[4];
      _mm_storeu_ps(last, rgb);
      memcpy(out_rgb + 3u * (size_t)v, last, 3 * sizeof(float));
    }
  }
}

PRT_KERNEL_INLINE float value_at(const uint8_t* row, uint32_t k, uint32_t bits) {
  if (bits == 8) return (float)row[k];
  return (float)((uint32_t)row[2u * k] | (uint32_t)row[2u * k + 1u] << 8);
}

PRT_KERNEL_INLINE void store_block(const prt_pose_transfer_job* job, float* out, __m256 t) {
  float lanes[PRT_POSE_SIMD_BLOCK];
  if (job->width == PRT_POSE_SIMD_BLOCK) {
    _mm256_storeu_ps(out, t);
    return;
  }
  _mm256_storeu_ps(lanes, t);
  memcpy(out, lanes, job->width * sizeof(float));
}

/* n vertices (1 or TRANSFER_GROUP) from `row` on, each an FMA chain from the bias. */
PRT_KERNEL_INLINE void transfer_group(const prt_pose_transfer_job* job, const uint8_t* row, int n,
                                      float* out) {
  const __m256 bias = _mm256_loadu_ps(job->bias);
  __m256 acc[TRANSFER_GROUP];
  uint32_t k;
  int j;
  for (j = 0; j < n; ++j) acc[j] = bias;
  for (k = 0; k < job->basis_dims; ++k) {
    const __m256 column = _mm256_loadu_ps(job->column + PRT_POSE_SIMD_BLOCK * (size_t)k);
    for (j = 0; j < n; ++j)
      acc[j] = _mm256_fmadd_ps(_mm256_set1_ps(value_at(row + job->stride * j, k, job->bits)),
                               column, acc[j]);
  }
  for (j = 0; j < n; ++j) store_block(job, out + job->out_stride * j, acc[j]);
}

void prt_pose_transfer_avx2(const prt_pose_transfer_job* job, uint32_t count, float* out) {
  uint32_t v = 0;
  for (; v + TRANSFER_GROUP <= count; v += TRANSFER_GROUP)
    transfer_group(job, job->values + job->stride * v, TRANSFER_GROUP, out + job->out_stride * v);
  for (; v < count; ++v)
    transfer_group(job, job->values + job->stride * v, 1, out + job->out_stride * v);
}

/* ---- model 1's exact part ---- */

/* clang-format off */
/* sh_eval.c's recurrence constants (its tables, formulas there) for l, m < 8, as floats: the
 * three-term step's a_lm and b_lm at l (l + 1) / 2 + m, Q_m^m and sqrt(2 m + 3). */
static const float kExactA[36] = {
    0.0f, 0.0f, 0.0f, 1.93649167f, 0.0f, 0.0f, 1.97202659f, 2.09165007f, 0.0f, 0.0f, 1.98431348f,
    2.04939015f, 2.29128785f, 0.0f, 0.0f, 1.98997487f, 2.0310096f, 2.17124059f, 2.48746859f, 0.0f,
    0.0f, 1.99304346f, 2.02131499f, 2.11394182f, 2.30136835f, 2.67394839f, 0.0f, 0.0f, 1.99489143f,
    2.01556444f, 2.081666f, 2.20794022f, 2.43086217f, 2.85043856f, 0.0f, 0.0f};
static const float kExactB[36] = {
    0.0f, 0.0f, 0.0f, 0.577350269f, 0.0f, 0.0f, 0.516397779f, 0.447213595f, 0.0f, 0.0f,
    0.507092553f, 0.478091444f, 0.377964473f, 0.0f, 0.0f, 0.503952631f, 0.487950036f, 0.43643578f,
    0.333333333f, 0.0f, 0.0f, 0.502518908f, 0.492365964f, 0.460566186f, 0.402015126f, 0.301511345f,
    0.0f, 0.0f, 0.501745206f, 0.494727445f, 0.473049917f, 0.434524095f, 0.373978796f, 0.277350098f,
    0.0f, 0.0f};
static const float kExactDiag[8] = {0.282094792f, 0.345494149f, 0.386274202f, 0.417223824f,
                                    0.442532692f, 0.464132203f, 0.483084114f, 0.500039564f};
static const float kExactSub[8] = {1.73205081f, 2.23606798f, 2.64575131f, 3.0f,
                                   3.31662479f, 3.60555128f, 3.87298335f, 4.12310563f};
/* clang-format on */

#define EXACT_MAX_C 64 /* order 8 */

/* m / |m| where |m| is > 0 and finite (and `ok` where given), else 0. */
PRT_KERNEL_INLINE void normalize_or_zero(__m256 m[3], __m256 ok) {
  const __m256 len = _mm256_sqrt_ps(
      _mm256_fmadd_ps(m[0], m[0], _mm256_fmadd_ps(m[1], m[1], _mm256_mul_ps(m[2], m[2]))));
  int a;
  ok = _mm256_and_ps(ok, _mm256_and_ps(_mm256_cmp_ps(len, _mm256_setzero_ps(), _CMP_GT_OQ),
                                       _mm256_cmp_ps(len, _mm256_set1_ps(INFINITY), _CMP_LT_OQ)));
  for (a = 0; a < 3; ++a) m[a] = _mm256_and_ps(ok, _mm256_div_ps(m[a], len));
}

/* c[e] lane i = element e of a[i], for 8 rows of 4: a 4x4 transpose in each 128-bit half. */
PRT_KERNEL_INLINE void transpose8x4(const __m128 a[8], __m256 c[4]) {
  __m256 x[4], t[4];
  int i;
  for (i = 0; i < 4; ++i) x[i] = _mm256_insertf128_ps(_mm256_castps128_ps256(a[i]), a[i + 4], 1);
  t[0] = _mm256_unpacklo_ps(x[0], x[1]);
  t[1] = _mm256_unpackhi_ps(x[0], x[1]);
  t[2] = _mm256_unpacklo_ps(x[2], x[3]);
  t[3] = _mm256_unpackhi_ps(x[2], x[3]);
  c[0] = _mm256_shuffle_ps(t[0], t[2], _MM_SHUFFLE(1, 0, 1, 0));
  c[1] = _mm256_shuffle_ps(t[0], t[2], _MM_SHUFFLE(3, 2, 3, 2));
  c[2] = _mm256_shuffle_ps(t[1], t[3], _MM_SHUFFLE(1, 0, 1, 0));
  c[3] = _mm256_shuffle_ps(t[1], t[3], _MM_SHUFFLE(3, 2, 3, 2));
}

/* The model-frame normals of the batch of vertices first + lane[i] (lane[i] < 8) of the range.
 * Gathers are slow on some CPUs, so the skinned path loads each vertex's record and joint rows
 * whole and transposes. */
PRT_KERNEL_INLINE void exact_normals(const prt_pose_exact_job* job, size_t first, __m256i lane,
                                     __m256 n[3]) {
  const __m256 all = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
  const __m256i identity = _mm256_set1_epi32((int)job->joint_count);
  __m256 k[9], nl[3], det, m[3], cof[9], c[4];
  __m128 rows[3][8], a[8];
  __m256i jw, w01, w23, joint[4], weight[4], total;
  int32_t index[8], joint_of[4][8];
  float weight_of[4][8];
  int i, e, r;
  if (job->normals) {
    const __m256i at = _mm256_mullo_epi32(lane, _mm256_set1_epi32(3));
    for (i = 0; i < 3; ++i) n[i] = _mm256_i32gather_ps(job->normals + 3u * first + i, at, 4);
    normalize_or_zero(n, all);
    return;
  }
  _mm256_storeu_si256((__m256i*)(void*)index, lane);
  /* Bytes 12..27 (normal, joints) and 20..35 (normal z, joints, weights) of each record. */
  for (i = 0; i < 8; ++i)
    a[i] = _mm_loadu_ps((const float*)(const void*)(job->skin + 36u * (first + index[i]) + 12u));
  transpose8x4(a, c);
  nl[0] = c[0], nl[1] = c[1], nl[2] = c[2];
  jw = _mm256_castps_si256(c[3]);
  for (i = 0; i < 8; ++i)
    a[i] = _mm_loadu_ps((const float*)(const void*)(job->skin + 36u * (first + index[i]) + 20u));
  transpose8x4(a, c);
  w01 = _mm256_castps_si256(c[2]);
  w23 = _mm256_castps_si256(c[3]);
  total = _mm256_setzero_si256();
  for (i = 0; i < 4; ++i) {
    const __m256i word = i < 2 ? w01 : w23;
    __m256i used;
    joint[i] = _mm256_and_si256(_mm256_srli_epi32(jw, 8 * i), _mm256_set1_epi32(0xff));
    weight[i] =
        (i & 1) ? _mm256_srli_epi32(word, 16) : _mm256_and_si256(word, _mm256_set1_epi32(0xffff));
    used = _mm256_cmpgt_epi32(identity, joint[i]);
    weight[i] = _mm256_and_si256(used, weight[i]); /* an index >= J counts as weight 0 */
    total = _mm256_add_epi32(total, weight[i]);
    /* A weight of 0 reads the identity (finite) rather than its joint, which may not be. */
    used = _mm256_andnot_si256(_mm256_cmpeq_epi32(weight[i], _mm256_setzero_si256()),
                               _mm256_set1_epi32(-1));
    joint[i] = _mm256_blendv_epi8(identity, joint[i], used);
  }
  {
    /* Integer weights and their sum are exact in float: one rounding per normalised weight. */
    const __m256 totalf = _mm256_cvtepi32_ps(total);
    const __m256 none = _mm256_cmp_ps(totalf, _mm256_setzero_ps(), _CMP_EQ_OQ);
    const __m256 divisor = _mm256_blendv_ps(totalf, _mm256_set1_ps(1.0f), none);
    for (i = 0; i < 4; ++i) {
      __m256 w = _mm256_div_ps(_mm256_cvtepi32_ps(weight[i]), divisor);
      if (i == 0) w = _mm256_blendv_ps(w, _mm256_set1_ps(1.0f), none); /* K = the identity */
      _mm256_storeu_ps(weight_of[i], w);
      _mm256_storeu_si256((__m256i*)(void*)joint_of[i], joint[i]);
    }
  }
  /* Per vertex, K's rows as sum_k w_k rows of K_joint_k ([J + 1][12], rows padded to 4). */
  for (i = 0; i < 8; ++i) {
    __m128 row[3] = {_mm_setzero_ps(), _mm_setzero_ps(), _mm_setzero_ps()};
    int j;
    for (j = 0; j < 4; ++j) {
      const float* matrix = job->joint + 12u * (uint32_t)joint_of[j][i];
      const __m128 w = _mm_set1_ps(weight_of[j][i]);
      for (r = 0; r < 3; ++r) row[r] = _mm_fmadd_ps(w, _mm_loadu_ps(matrix + 4 * r), row[r]);
    }
    for (r = 0; r < 3; ++r) rows[r][i] = row[r];
  }
  for (r = 0; r < 3; ++r) {
    transpose8x4(rows[r], c);
    for (e = 0; e < 3; ++e) k[3 * r + e] = c[e];
  }
  /* cof[r][c] = K[r1][c1] K[r2][c2] - K[r1][c2] K[r2][c1] (r1 = r + 1, r2 = r + 2 mod 3). */
  for (i = 0; i < 3; ++i)
    for (e = 0; e < 3; ++e) {
      const int r1 = (i + 1) % 3, r2 = (i + 2) % 3, c1 = (e + 1) % 3, c2 = (e + 2) % 3;
      cof[3 * i + e] = _mm256_fmsub_ps(k[3 * r1 + c1], k[3 * r2 + c2],
                                       _mm256_mul_ps(k[3 * r1 + c2], k[3 * r2 + c1]));
    }
  det = _mm256_fmadd_ps(k[0], cof[0], _mm256_fmadd_ps(k[1], cof[1], _mm256_mul_ps(k[2], cof[2])));
  {
    const __m256 sign = _mm256_and_ps(det, _mm256_set1_ps(-0.0f));
    for (i = 0; i < 3; ++i)
      m[i] = _mm256_xor_ps(
          sign, _mm256_fmadd_ps(
                    cof[3 * i], nl[0],
                    _mm256_fmadd_ps(cof[3 * i + 1], nl[1], _mm256_mul_ps(cof[3 * i + 2], nl[2]))));
  }
  normalize_or_zero(m, _mm256_cmp_ps(det, _mm256_setzero_ps(), _CMP_NEQ_OQ));
  for (i = 0; i < 3; ++i) n[i] = m[i];
}

/* y[c] for c < order^2 at the unit normals n (model frame; SH frame x = X, y = -Z, z = Y) into
 * y, or, with `fold`, each y[c] of a band whose factor is not 0 times light[c][ch] added to
 * acc[ch] (the basis is then never stored). Inlined with constants, the loops unroll and the
 * branches go. */
PRT_KERNEL_INLINE void exact_basis(uint32_t order, const __m256 n[3], int fold, const float* light,
                                   __m256* y, __m256 acc[3]) {
  const __m256 x = n[0], yy = _mm256_xor_ps(n[2], _mm256_set1_ps(-0.0f)), z = n[1];
  const __m256 sqrt2 = _mm256_set1_ps(1.41421356f);
  __m256 cos_m = _mm256_set1_ps(1.0f), sin_m = _mm256_setzero_ps();
  uint32_t m, l;
/* Bands l >= 3 of odd l have A_l = 0 (prt_sh_cosine_band_factor): folded, they are skipped. */
#define EXACT_EMIT(c, value)                                                            \
  do {                                                                                  \
    const uint32_t c_ = (c);                                                            \
    int ch_;                                                                            \
    if (!fold) {                                                                        \
      y[c_] = (value);                                                                  \
    } else if (l < 3u || l % 2u == 0u) {                                                \
      const __m256 v_ = (value);                                                        \
      for (ch_ = 0; ch_ < 3; ++ch_)                                                     \
        acc[ch_] = _mm256_fmadd_ps(v_, _mm256_set1_ps(light[3u * c_ + ch_]), acc[ch_]); \
    }                                                                                   \
  } while (0)
  for (m = 0; m < order; ++m) {
    __m256 q_prev2 = _mm256_set1_ps(kExactDiag[m]);
    __m256 q_prev = _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(kExactSub[m]), z), q_prev2);
    __m256 scale_cos, scale_sin;
    if (m > 0) {
      const __m256 c = _mm256_fmsub_ps(cos_m, x, _mm256_mul_ps(sin_m, yy));
      sin_m = _mm256_fmadd_ps(sin_m, x, _mm256_mul_ps(cos_m, yy));
      cos_m = c;
    }
    scale_cos = m == 0 ? _mm256_set1_ps(1.0f) : _mm256_mul_ps(sqrt2, cos_m);
    scale_sin = _mm256_mul_ps(sqrt2, sin_m);
    for (l = m; l < order; ++l) {
      __m256 q;
      if (l == m) {
        q = q_prev2;
      } else if (l == m + 1) {
        q = q_prev;
      } else {
        const uint32_t i = l * (l + 1) / 2 + m;
        q = _mm256_mul_ps(
            _mm256_set1_ps(kExactA[i]),
            _mm256_fnmadd_ps(_mm256_set1_ps(kExactB[i]), q_prev2, _mm256_mul_ps(z, q_prev)));
        q_prev2 = q_prev;
        q_prev = q;
      }
      EXACT_EMIT(l * (l + 1) + m, _mm256_mul_ps(q, scale_cos));
      if (m > 0) EXACT_EMIT(l * (l + 1) - m, _mm256_mul_ps(q, scale_sin));
    }
  }
#undef EXACT_EMIT
}

/* Lane i of the batch at v: i, or the range's last vertex past its end (computed, never
 * written). Small offsets from the batch, so that no index overflows whatever the range. */
PRT_KERNEL_INLINE __m256i batch_lanes(uint32_t v, uint32_t count) {
  const uint32_t last = count - v - 1u;
  return _mm256_min_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7),
                          _mm256_set1_epi32((int)(last < 7u ? last : 7u)));
}

/* The shading loop for one order; a constant `order` unrolls the basis. */
PRT_KERNEL_INLINE void exact_shade(const prt_pose_exact_job* job, uint32_t order, uint32_t count,
                                   float* out_rgb) {
  __m256 n[3];
  uint32_t v, i;
  for (v = 0; v < count; v += 8) {
    const uint32_t lanes = count - v < 8u ? count - v : 8u;
    __m256 acc[3] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
    float rgb[3][8];
    int ch;
    exact_normals(job, v, batch_lanes(v, count), n);
    exact_basis(order, n, 1, job->light, NULL, acc);
    for (ch = 0; ch < 3; ++ch) _mm256_storeu_ps(rgb[ch], acc[ch]);
    for (i = 0; i < lanes; ++i)
      for (ch = 0; ch < 3; ++ch) out_rgb[3u * ((size_t)v + i) + ch] += rgb[ch][i];
  }
}

void prt_pose_exact_shade_avx2(const prt_pose_exact_job* job, uint32_t count, float* out_rgb) {
  if (job->order == 6) /* the baker's default, unrolled; the other orders share one loop */
    exact_shade(job, 6, count, out_rgb);
  else
    exact_shade(job, job->order, count, out_rgb);
}

void prt_pose_exact_transfer_avx2(const prt_pose_exact_job* job, uint32_t count, float* out,
                                  size_t out_stride) {
  const uint32_t n2 = job->order * job->order;
  __m256 y[EXACT_MAX_C], n[3];
  float terms[EXACT_MAX_C][8];
  uint32_t v, c, i;
  for (v = 0; v < count; v += 8) {
    const uint32_t lanes = count - v < 8u ? count - v : 8u;
    exact_normals(job, v, batch_lanes(v, count), n);
    exact_basis(job->order, n, 0, NULL, y, NULL);
    for (c = 0; c < n2; ++c)
      _mm256_storeu_ps(terms[c], _mm256_mul_ps(y[c], _mm256_set1_ps(job->factor[c])));
    for (i = 0; i < lanes; ++i)
      for (c = 0; c < n2; ++c) out[((size_t)v + i) * out_stride + c] += terms[c][i];
  }
}
