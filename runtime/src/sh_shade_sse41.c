/* SPDX-License-Identifier: MIT */
/* `sh` shading kernel for SSE4.1 (this file is compiled with -msse4.1 and only called when the
 * CPU has it): per vertex and channel, a dot product of the quantised values with the light
 * folded into the scale (sh_shade_simd.h), four coefficients at a time. */
#include <smmintrin.h>
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

/* Four stored values (u8 or u16 little-endian, any alignment) as floats. */
PRT_KERNEL_INLINE __m128 load4(const uint8_t* p, int bits) {
  if (bits == 8) {
    int32_t packed;
    memcpy(&packed, p, sizeof packed);
    return _mm_cvtepi32_ps(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(packed)));
  } else {
    return _mm_cvtepi32_ps(_mm_cvtepu16_epi32(load_low8(p)));
  }
}

/* (sum r, sum g, sum b, sum b) of three accumulators. */
PRT_KERNEL_INLINE __m128 horizontal_sums(__m128 r, __m128 g, __m128 b) {
  return _mm_hadd_ps(_mm_hadd_ps(r, g), _mm_hadd_ps(b, b));
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
  __m128 r = _mm_setzero_ps(), g = _mm_setzero_ps(), b = _mm_setzero_ps();
  uint32_t k;
  for (k = 0; k < job->padded; k += 4) {
    r = _mm_add_ps(r, _mm_mul_ps(load4(pr + size * k, bits), _mm_loadu_ps(job->weight[0] + k)));
    g = _mm_add_ps(g, _mm_mul_ps(load4(pg + size * k, bits), _mm_loadu_ps(job->weight[1] + k)));
    b = _mm_add_ps(b, _mm_mul_ps(load4(pb + size * k, bits), _mm_loadu_ps(job->weight[2] + k)));
  }
  return horizontal_sums(r, g, b);
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

void prt_sh_shade_sse41(const prt_sh_simd_job* job, uint32_t count, float* out_rgb) {
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
