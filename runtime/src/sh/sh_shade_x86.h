/* SPDX-License-Identifier: MIT */
/* Private to the x86 `sh` kernels (sh_shade_sse41.c, sh_shade_avx2.c): the helpers and the vertex
 * loop both share. Included by each kernel file, so it is compiled with that file's ISA flags
 * (SSE4.1 at least). The includer defines PRT_SH_KERNEL_NAME (the entry point) and
 *   PRT_KERNEL_INLINE void shade_runs(const prt_sh_simd_job* job,
 *                                     const uint8_t* const run[][3], int n, int bits,
 *                                     __m128 sums[]);
 * (sums[j] = (sum r, sum g, sum b, any) of vertex j's channel runs starting at run[j][0..2], for
 * j < n, n being the constant 1 or PRT_SH_X86_GROUP) before including this file a second time
 * with PRT_SH_X86_LOOP defined. shade_runs must do the same arithmetic for each vertex whatever
 * n is, so that a vertex's result does not depend on where a call's range starts. */
#if !defined(PRT_SH_X86_LOOP)
#ifndef PRT_SH_SHADE_X86_H
#define PRT_SH_SHADE_X86_H

#include <smmintrin.h>
#include <string.h>

#include "sh_shade_simd.h"

/* Vertices shaded together: their independent accumulator chains hide the add latency, and
 * each light weight loaded serves all of them. */
#define PRT_SH_X86_GROUP 4

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

#endif /* PRT_SH_SHADE_X86_H */
#else  /* PRT_SH_X86_LOOP: the vertex loop and the entry point */

/* The channel runs of the vertex at `vertex`; one pointer for all three with grey transfer, so
 * that the compiler shares their loads. */
PRT_KERNEL_INLINE void vertex_runs(const prt_sh_simd_job* job, const uint8_t* vertex, size_t size,
                                   int grey, const uint8_t* run[3]) {
  run[0] = vertex + size * job->segment[0];
  run[1] = grey ? run[0] : vertex + size * job->segment[1];
  run[2] = grey ? run[0] : vertex + size * job->segment[2];
}

/* The vertex loop, specialised by the constant `bits` and `grey` of each call site: groups of
 * PRT_SH_X86_GROUP vertices, then the rest one by one. */
PRT_KERNEL_INLINE void shade_vertices(const prt_sh_simd_job* shared, uint32_t count, float* out_rgb,
                                      int bits, int grey) {
  const prt_sh_simd_job local = *shared; /* a copy the stores to out_rgb cannot alias */
  const prt_sh_simd_job* job = &local;
  const size_t size = (size_t)bits / 8u;
  const __m128 bias = _mm_setr_ps(job->bias[0], job->bias[1], job->bias[2], 0.0f);
  const uint8_t* vertex = job->values;
  const uint8_t* run[PRT_SH_X86_GROUP][3];
  __m128 sums[PRT_SH_X86_GROUP];
  uint32_t v = 0;
  int j;
  for (; count - v >= PRT_SH_X86_GROUP; v += PRT_SH_X86_GROUP) {
    for (j = 0; j < PRT_SH_X86_GROUP; ++j, vertex += job->stride)
      vertex_runs(job, vertex, size, grey, run[j]);
    shade_runs(job, (const uint8_t* const(*)[3])run, PRT_SH_X86_GROUP, bits, sums);
    for (j = 0; j < PRT_SH_X86_GROUP; ++j)
      store_rgb(out_rgb + 3u * ((size_t)v + (size_t)j), _mm_add_ps(sums[j], bias),
                v + (uint32_t)j + 1u == count);
  }
  for (; v < count; ++v, vertex += job->stride) {
    vertex_runs(job, vertex, size, grey, run[0]);
    shade_runs(job, (const uint8_t* const(*)[3])run, 1, bits, sums);
    store_rgb(out_rgb + 3u * (size_t)v, _mm_add_ps(sums[0], bias), v + 1 == count);
  }
}

void PRT_SH_KERNEL_NAME(const prt_sh_simd_job* job, uint32_t count, float* out_rgb) {
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

#endif /* PRT_SH_X86_LOOP */
