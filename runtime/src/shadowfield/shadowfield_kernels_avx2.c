/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield`'s inner loops for AVX2 + FMA (this file is compiled with -mavx2 -mfma
 * and only called when the CPU has both; shadowfield_kernels.h): eight coefficients a lane (eight
 * vertices for the triple product), a masked load for a row's last partial group, dot products
 * summed by one tree for eight rows. */
#include <immintrin.h>
#include <math.h>
#include <string.h>

#include "shadowfield_kernels.h"
#include "shadowfield_scene.h"

/* Lanes [0, count) set, count in 0..8. */
static __m256i lane_mask(uint32_t count) {
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  return _mm256_cmpgt_epi32(_mm256_set1_epi32((int)count), lanes);
}

/* Eight floats from p on, or the first `left` of them (zeros above) when left < 8. */
static __m256 load_part(const float* p, uint32_t left) {
  return left >= 8u ? _mm256_loadu_ps(p) : _mm256_maskload_ps(p, lane_mask(left));
}

static void store_part(float* p, uint32_t left, __m256 v) {
  if (left >= 8u)
    _mm256_storeu_ps(p, v);
  else
    _mm256_maskstore_ps(p, lane_mask(left), v);
}

/* All bits set in the lanes whose bit of `mask` is clear: the lanes a masked kernel keeps. */
static __m256 kept_lanes(uint32_t mask) {
  return _mm256_castsi256_ps(
      _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)mask),
                                          _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128)),
                         _mm256_setzero_si256()));
}

/* The eight accumulators' lane sums, in order. */
static __m256 sum8(const __m256 a[8]) {
  const __m256 t0 = _mm256_hadd_ps(a[0], a[1]), t1 = _mm256_hadd_ps(a[2], a[3]);
  const __m256 t2 = _mm256_hadd_ps(a[4], a[5]), t3 = _mm256_hadd_ps(a[6], a[7]);
  const __m256 u0 = _mm256_hadd_ps(t0, t1), u1 = _mm256_hadd_ps(t2, t3);
  return _mm256_add_ps(_mm256_permute2f128_ps(u0, u1, 0x20), _mm256_permute2f128_ps(u0, u1, 0x31));
}

/* The lanes of a . b over n floats, a and b read up to n only. */
static __m256 dot_lanes(const float* a, const float* b, uint32_t n) {
  __m256 acc = _mm256_setzero_ps();
  for (uint32_t i = 0; i < n; i += 8u)
    acc = _mm256_fmadd_ps(load_part(a + i, n - i), load_part(b + i, n - i), acc);
  return acc;
}

static void read_rows_avx2(const float* field, uint64_t plane, uint32_t planes, uint32_t width,
                           const prt_sf_lookup* lookup, float* out) {
  for (uint32_t c = 0; c < planes; ++c)
    for (uint32_t i = 0; i < width; i += 8u) {
      const uint32_t left = width - i;
      __m256 acc = _mm256_setzero_ps();
      for (uint32_t e = 0; e < lookup->count; ++e) {
        const float* row = field + c * plane + lookup->index[e] * width + i;
        acc = _mm256_fmadd_ps(_mm256_set1_ps(lookup->weight[e]), load_part(row, left), acc);
      }
      store_part(out + c * width + i, left, acc);
    }
}

/* Each group of 8 coefficients of a plane is read into a register and multiplied into the
 * terms' lane sums there, so neither the read values nor a dot's horizontal sum go through
 * memory per source. */
static void read_dot_avx2(const float* field, uint64_t plane, uint32_t width,
                          const prt_sf_lookup* lookup, const float* transfer, uint32_t terms,
                          float* partial) {
  for (uint32_t c = 0; c < 3u; ++c) {
    __m256 sums[2] = {_mm256_setzero_ps(), _mm256_setzero_ps()};
    for (uint32_t i = 0; i < width; i += 8u) {
      const uint32_t left = width - i;
      __m256 acc = _mm256_setzero_ps();
      for (uint32_t e = 0; e < lookup->count; ++e) {
        const float* row = field + c * plane + lookup->index[e] * width + i;
        acc = _mm256_fmadd_ps(_mm256_set1_ps(lookup->weight[e]), load_part(row, left), acc);
      }
      for (uint32_t k = 0; k < terms && k < 2u; ++k)
        sums[k] = _mm256_fmadd_ps(load_part(transfer + k * width + i, left), acc, sums[k]);
    }
    for (uint32_t k = 0; k < terms && k < 2u; ++k) {
      float* at = partial + (3u * k + c) * PRT_SF_LANES;
      _mm256_storeu_ps(at, _mm256_add_ps(_mm256_loadu_ps(at), sums[k]));
    }
  }
}

static void reduce_lanes_avx2(const float* partial, uint32_t count, float* out) {
  for (uint32_t r = 0; r < count; r += 8u) {
    __m256 acc[8];
    for (uint32_t q = 0; q < 8u; ++q)
      acc[q] =
          r + q < count ? _mm256_loadu_ps(partial + (r + q) * PRT_SF_LANES) : _mm256_setzero_ps();
    store_part(out + r, count - r, sum8(acc));
  }
}

/* Band by band with the columns padded to whole vectors: out_band = sum_b in_b column_b, the
 * planes' sums side by side so that their multiply-adds overlap; only the stores are masked. */
static void rotate_padded(const float* block, uint32_t order, const float* in, float* out,
                          uint32_t planes) {
  const uint32_t n2 = order * order;
  for (uint32_t l = 0; l < order; ++l) {
    const uint32_t width = 2u * l + 1u, base = l * l, pad = (width + 7u) / 8u * 8u;
    for (uint32_t a = 0; a < width; a += 8u) {
      __m256 acc[3] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
      for (uint32_t b = 0; b < width; ++b) {
        const __m256 column = _mm256_loadu_ps(block + b * pad + a);
        for (uint32_t c = 0; c < planes && c < 3u; ++c)
          acc[c] = _mm256_fmadd_ps(_mm256_set1_ps(in[c * n2 + base + b]), column, acc[c]);
      }
      for (uint32_t c = 0; c < planes && c < 3u; ++c)
        store_part(out + c * n2 + base + a, width - a, acc[c]);
    }
    block += width * pad;
  }
}

static void rotate_avx2(const prt_sf_pair* pair, uint32_t order, const float* in, float* out,
                        uint32_t planes) {
  rotate_padded(pair->padded_columns, order, in, out, planes);
}

static void rotate_back_avx2(const prt_sf_pair* pair, uint32_t order, const float* in, float* out,
                             uint32_t planes) {
  rotate_padded(pair->padded_columns_back, order, in, out, planes);
}

/* One output coefficient for all eight lanes per register: out_a = sum_b column_b[a] in_b, the
 * same multiply-adds in the same order as rotate_padded's lane a, so each lane's bits are
 * rotate's; a blend keeps the lanes outside the mask. */
static void rotate_lanes_avx2(const prt_sf_pair* pair, uint32_t order, const float* in, float* out,
                              uint32_t mask) {
  const __m256 keep = kept_lanes(mask);
  const float* block = pair->padded_columns;
  for (uint32_t l = 0; l < order; ++l) {
    const uint32_t width = 2u * l + 1u, base = l * l, pad = (width + 7u) / 8u * 8u;
    for (uint32_t a = 0; a < width; ++a) {
      __m256 acc = _mm256_setzero_ps();
      for (uint32_t b = 0; b < width; ++b)
        acc = _mm256_fmadd_ps(_mm256_loadu_ps(in + (base + b) * PRT_SF_LANES),
                              _mm256_broadcast_ss(block + b * pad + a), acc);
      float* at = out + (base + a) * PRT_SF_LANES;
      _mm256_storeu_ps(at, _mm256_blendv_ps(acc, _mm256_loadu_ps(at), keep));
    }
    block += width * pad;
  }
}

/* out[r] = rows_at[r] . vectors_at[r] (n floats each) for r < count, eight dots per tree,
 * stored straight into out. */
static void dots(const float* const* rows_at, const float* const* vectors_at, uint32_t count,
                 uint32_t n, float* out) {
  for (uint32_t r = 0; r < count; r += 8u) {
    __m256 acc[8];
    for (uint32_t q = 0; q < 8u; ++q)
      acc[q] =
          r + q < count ? dot_lanes(rows_at[r + q], vectors_at[r + q], n) : _mm256_setzero_ps();
    store_part(out + r, count - r, sum8(acc));
  }
}

static void light_times_avx2(const float* matrix, uint32_t n2, const float* visibility,
                             float* light) {
  const float* rows[3u * PRT_SF_MAX_COEFFS];
  const float* vectors[3u * PRT_SF_MAX_COEFFS];
  for (uint32_t r = 0; r < 3u * n2; ++r) {
    rows[r] = matrix + (size_t)r * n2;
    vectors[r] = visibility;
  }
  dots(rows, vectors, 3u * n2, n2, light);
}

/* One lane a vertex: each non-zero Gaunt coefficient is one multiply and one multiply-add for
 * all eight, against the scalar form's per-vertex sparse loop. */
static void multiply_lanes_avx2(const prt_sf_gaunt* gaunt, float* a, const float* b,
                                uint32_t mask) {
  const uint32_t n2 = gaunt->order * gaunt->order;
  __m256 product[PRT_SF_MAX_COEFFS];
  for (uint32_t k = 0; k < n2; ++k) {
    __m256 acc = _mm256_setzero_ps();
    for (uint32_t e = gaunt->k_start[k]; e < gaunt->k_start[k + 1u]; ++e) {
      const __m256 ca = _mm256_mul_ps(_mm256_set1_ps(gaunt->value[e]),
                                      _mm256_loadu_ps(a + gaunt->i[e] * PRT_SF_LANES));
      acc = _mm256_fmadd_ps(ca, _mm256_loadu_ps(b + gaunt->j[e] * PRT_SF_LANES), acc);
    }
    product[k] = acc;
  }
  const __m256 keep = kept_lanes(mask);
  for (uint32_t k = 0; k < n2; ++k) {
    float* at = a + k * PRT_SF_LANES;
    _mm256_storeu_ps(at, _mm256_blendv_ps(product[k], _mm256_loadu_ps(at), keep));
  }
}

static void transfer_dot_avx2(const float* transfer, uint32_t n2, uint32_t terms,
                              const float* light, float* out) {
  const float* rows[3u * PRT_SF_MAX_TERMS];
  const float* vectors[3u * PRT_SF_MAX_TERMS];
  for (uint32_t k = 0; k < terms; ++k)
    for (uint32_t c = 0; c < 3u; ++c) {
      rows[3u * k + c] = transfer + (size_t)k * n2;
      vectors[3u * k + c] = light + c * n2;
    }
  dots(rows, vectors, 3u * terms, n2, out);
}

/* Thirty-two values (two cache lines of each SRF row) of all three planes at a time in
 * registers while every SRF row adds to them, so each plane is written once and each SRF row
 * read once, a whole line per row visited. */
static void cast_field_avx2(const prt_sf_object* object, const float* weights, float* field,
                            uint64_t first, uint64_t count) {
  const uint32_t n2 = object->order * object->order, rows = object->basis_size * object->terms;
  const uint64_t points = prt_sf_point_count(&object->srf_shells);
  const size_t plane = (size_t)points * n2, begin = (size_t)first * n2;
  const size_t end = begin + (size_t)count * n2;
  const float* srf = object->srf;
  for (size_t e = begin; e < end; e += 32u) {
    uint32_t left[4];
    for (uint32_t q = 0; q < 4u; ++q) {
      const size_t at = e + 8u * q;
      left[q] = at >= end ? 0u : end - at < 8u ? (uint32_t)(end - at) : 8u;
    }
    __m256 acc[3][4];
    for (uint32_t c = 0; c < 3u; ++c)
      for (uint32_t q = 0; q < 4u; ++q) acc[c][q] = _mm256_setzero_ps();
    for (uint32_t r = 0; r < rows; ++r) {
      const float* row = srf + r * plane + e;
      /* Each row is its own stream: ask for its next lines ahead of the hardware prefetcher. */
      _mm_prefetch((const char*)(row + 64), _MM_HINT_T0);
      _mm_prefetch((const char*)(row + 80), _MM_HINT_T0);
      __m256 s[4];
      for (uint32_t q = 0; q < 4u; ++q)
        s[q] = left[q] ? load_part(row + 8u * q, left[q]) : _mm256_setzero_ps();
      for (uint32_t c = 0; c < 3u; ++c) {
        const __m256 w = _mm256_broadcast_ss(weights + 3u * r + c);
        for (uint32_t q = 0; q < 4u; ++q) acc[c][q] = _mm256_fmadd_ps(w, s[q], acc[c][q]);
      }
    }
    for (uint32_t c = 0; c < 3u; ++c)
      for (uint32_t q = 0; q < 4u; ++q)
        if (left[q]) store_part(field + c * plane + e + 8u * q, left[q], acc[c][q]);
  }
}

/* prt_sf_exp's steps in eight lanes. */
static __m256 exp8(__m256 x) {
  x = _mm256_min_ps(_mm256_max_ps(x, _mm256_set1_ps(-87.0f)), _mm256_set1_ps(88.0f));
  const __m256 k = _mm256_round_ps(_mm256_mul_ps(x, _mm256_set1_ps(1.44269504088896341f)),
                                   _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  __m256 r = _mm256_fnmadd_ps(k, _mm256_set1_ps(0.693145751953125f), x);
  r = _mm256_fnmadd_ps(k, _mm256_set1_ps(1.428606765330187045e-06f), r);
  static const float kCoefficients[8] = {1.0f / 5040.0f, 1.0f / 720.0f, 1.0f / 120.0f, 1.0f / 24.0f,
                                         1.0f / 6.0f,    0.5f,          1.0f,          1.0f};
  __m256 p = _mm256_set1_ps(kCoefficients[0]);
  for (int c = 1; c < 8; ++c) p = _mm256_fmadd_ps(p, r, _mm256_set1_ps(kCoefficients[c]));
  const __m256i bits =
      _mm256_slli_epi32(_mm256_add_epi32(_mm256_cvtps_epi32(k), _mm256_set1_epi32(127)), 23);
  return _mm256_mul_ps(p, _mm256_castsi256_ps(bits));
}

static void exp_lanes_avx2(const prt_sf_sphere_rule* rule, float* lanes, uint32_t mask) {
  const uint32_t n2 = rule->order * rule->order, directions = rule->directions;
  __m256 in[PRT_SF_MAX_COEFFS], out[PRT_SF_MAX_COEFFS];
  for (uint32_t i = 0; i < n2; ++i) {
    in[i] = _mm256_loadu_ps(lanes + i * PRT_SF_LANES);
    out[i] = _mm256_setzero_ps();
  }
  for (uint32_t d = 0; d < directions; ++d) {
    const float* y = rule->eval + (size_t)d * n2;
    __m256 value = _mm256_setzero_ps();
    for (uint32_t i = 0; i < n2; ++i) value = _mm256_fmadd_ps(_mm256_set1_ps(y[i]), in[i], value);
    const __m256 e = exp8(value);
    for (uint32_t i = 0; i < n2; ++i)
      out[i] =
          _mm256_fmadd_ps(_mm256_set1_ps(rule->project[(size_t)i * directions + d]), e, out[i]);
  }
  const __m256 keep = kept_lanes(mask);
  for (uint32_t i = 0; i < n2; ++i)
    _mm256_storeu_ps(lanes + i * PRT_SF_LANES, _mm256_blendv_ps(out[i], in[i], keep));
}

const prt_sf_kernels prt_sf_kernels_avx2 = {
    read_rows_avx2,    rotate_avx2,         rotate_back_avx2, rotate_lanes_avx2,
    light_times_avx2,  multiply_lanes_avx2, read_dot_avx2,    reduce_lanes_avx2,
    transfer_dot_avx2, cast_field_avx2,     exp_lanes_avx2};
