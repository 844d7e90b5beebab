/* SPDX-License-Identifier: MIT */
/* `sh` shading kernel for AVX2 + FMA (this file is compiled with -mavx2 -mfma and only called
 * when the CPU has both): per vertex and channel, a dot product of the quantised values with the
 * light folded into the scale (sh_shade_simd.h), eight coefficients at a time and a block of
 * four when the padded count is not a multiple of eight. */
#include <immintrin.h>
#include <string.h>

#include "sh_shade_simd.h"

#if defined(__GNUC__)
#define PRT_KERNEL_INLINE static inline __attribute__((always_inline))
#else
#define PRT_KERNEL_INLINE static inline
#endif

/* Eight bytes at p (any alignment) in the low half of a vector; movq, also on 32-bit x86. */
PRT_KERNEL_INLINE __m128i load_low8(const uint8_t* p) {
  return _mm_loadl_epi64((const __m128i*)(const void*)p);
}

/* Eight stored values (u8 or u16 little-endian, any alignment) as floats. */
PRT_KERNEL_INLINE __m256 load8(const uint8_t* p, int bits) {
  if (bits == 8) {
    return _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(load_low8(p)));
  }
  return _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_loadu_si128((const __m128i*)(const void*)p)));
}

/* Four stored values as floats. */
PRT_KERNEL_INLINE __m128 load4(const uint8_t* p, int bits) {
  if (bits == 8) {
    int32_t packed;
    memcpy(&packed, p, sizeof packed);
    return _mm_cvtepi32_ps(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(packed)));
  } else {
    return _mm_cvtepi32_ps(_mm_cvtepu16_epi32(load_low8(p)));
  }
}

PRT_KERNEL_INLINE __m128 fold_halves(__m256 x) {
  return _mm_add_ps(_mm256_castps256_ps128(x), _mm256_extractf128_ps(x, 1));
}

/* Writes R, G, B; the last vertex of a call must not touch the float after it. */
PRT_KERNEL_INLINE void store_rgb(float* out, __m128 rgb, int last) {
  if (!last) {
    _mm_storeu_ps(out, rgb); /* the 4th float is the next vertex's red, written next */
  } else {
    float lanes[4];
    _mm_storeu_ps(lanes, rgb);
    memcpy(out, lanes, 3 * sizeof(float));
  }
}

/* (sum r, sum g, sum b, sum b) of the channels' runs starting at pr, pg, pb (equal for grey
 * transfer, where the compiler shares the loads). */
PRT_KERNEL_INLINE __m128 shade_runs(const prt_sh_simd_job* job, const uint8_t* pr,
                                    const uint8_t* pg, const uint8_t* pb, int bits) {
  const size_t size = (size_t)bits / 8u;
  const float* wr = job->weight[0];
  const float* wg = job->weight[1];
  const float* wb = job->weight[2];
  const uint32_t blocks8 = job->padded / 8u * 8u; /* the rest, if any, is one block of 4 */
  __m128 r, g, b;
  uint32_t k;
  if (blocks8 < job->padded) {
    r = _mm_mul_ps(load4(pr + size * blocks8, bits), _mm_loadu_ps(wr + blocks8));
    g = _mm_mul_ps(load4(pg + size * blocks8, bits), _mm_loadu_ps(wg + blocks8));
    b = _mm_mul_ps(load4(pb + size * blocks8, bits), _mm_loadu_ps(wb + blocks8));
  } else {
    r = g = b = _mm_setzero_ps();
  }
  if (blocks8 > 0) { /* skipped for orders 1 and 2, where folding 8 lanes would be wasted */
    __m256 r8 = _mm256_setzero_ps(), g8 = _mm256_setzero_ps(), b8 = _mm256_setzero_ps();
    for (k = 0; k < blocks8; k += 8) {
      r8 = _mm256_fmadd_ps(load8(pr + size * k, bits), _mm256_loadu_ps(wr + k), r8);
      g8 = _mm256_fmadd_ps(load8(pg + size * k, bits), _mm256_loadu_ps(wg + k), g8);
      b8 = _mm256_fmadd_ps(load8(pb + size * k, bits), _mm256_loadu_ps(wb + k), b8);
    }
    r = _mm_add_ps(r, fold_halves(r8));
    g = _mm_add_ps(g, fold_halves(g8));
    b = _mm_add_ps(b, fold_halves(b8));
  }
  return _mm_hadd_ps(_mm_hadd_ps(r, g), _mm_hadd_ps(b, b));
}

/* The vertex loop, specialised by the constant `bits` and `grey` of each call site. */
PRT_KERNEL_INLINE void shade_vertices(const prt_sh_simd_job* shared, uint32_t count, float* out_rgb,
                                      int bits, int grey) {
  const prt_sh_simd_job local = *shared; /* a copy the stores to out_rgb cannot alias */
  const prt_sh_simd_job* job = &local;
  const size_t size = (size_t)bits / 8u;
  const __m128 bias = _mm_setr_ps(job->bias[0], job->bias[1], job->bias[2], 0.0f);
  const uint8_t* vertex = job->values;
  uint32_t v;
  for (v = 0; v < count; ++v, vertex += job->stride) {
    const uint8_t* pr = vertex + size * job->segment[0];
    const uint8_t* pg = grey ? pr : vertex + size * job->segment[1];
    const uint8_t* pb = grey ? pr : vertex + size * job->segment[2];
    const __m128 sums = shade_runs(job, pr, pg, pb, bits);
    store_rgb(out_rgb + 3u * (size_t)v, _mm_add_ps(sums, bias), v + 1 == count);
  }
}

void prt_sh_shade_avx2(const prt_sh_simd_job* job, uint32_t count, float* out_rgb) {
  const int grey = job->segment[0] == job->segment[1] && job->segment[1] == job->segment[2];
  if (job->bits == 8) {
    if (grey)
      shade_vertices(job, count, out_rgb, 8, 1);
    else
      shade_vertices(job, count, out_rgb, 8, 0);
  } else {
    if (grey)
      shade_vertices(job, count, out_rgb, 16, 1);
    else
      shade_vertices(job, count, out_rgb, 16, 0);
  }
}
