/* SPDX-License-Identifier: MIT */
/* `pose` kernels for AVX2 + FMA (compiled with -mavx2 -mfma, called only when the CPU has both;
 * pose_simd.h). Shading: per vertex three dot products of its q values with the folded light
 * weights, eight at a time, the last partial block from a zero-padded copy so that nothing past
 * the vertex's row is read. Transfer: per vertex one FMA chain over k of its value broadcast
 * against a block of eight coefficients, four vertices interleaved to hide the FMA latency. */
#include <immintrin.h>
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

/* The eight lanes summed by a fixed tree. */
PRT_KERNEL_INLINE float sum8(__m256 v) {
  __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  s = _mm_add_ps(s, _mm_movehl_ps(s, s));
  s = _mm_add_ss(s, _mm_shuffle_ps(s, s, 1));
  return _mm_cvtss_f32(s);
}

void prt_pose_shade_avx2(const prt_pose_shade_job* job, uint32_t count, float* out_rgb) {
  const size_t size = job->bits / 8u;
  const uint32_t full = job->basis_dims / 8u * 8u;
  const uint8_t* row = job->values;
  uint32_t v, k;
  for (v = 0; v < count; ++v, row += job->stride) {
    __m256 acc[3] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
    int ch;
    for (k = 0; k < full; k += 8) {
      const __m256 values = load8(row + size * k, job->bits);
      for (ch = 0; ch < 3; ++ch)
        acc[ch] = _mm256_fmadd_ps(values, _mm256_loadu_ps(job->weight[ch] + k), acc[ch]);
    }
    if (full < job->basis_dims) {
      uint8_t tail[16] = {0};
      __m256 values;
      memcpy(tail, row + size * full, size * (job->basis_dims - full));
      values = load8(tail, job->bits);
      for (ch = 0; ch < 3; ++ch)
        acc[ch] = _mm256_fmadd_ps(values, _mm256_loadu_ps(job->weight[ch] + full), acc[ch]);
    }
    for (ch = 0; ch < 3; ++ch) out_rgb[3u * v + ch] = job->bias[ch] + sum8(acc[ch]);
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
