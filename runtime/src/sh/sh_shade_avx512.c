/* SPDX-License-Identifier: MIT */
/* `sh` shading kernel for 8-bit RGB values with AVX-512 VNNI (this file is compiled with AVX-512
 * F/BW/VL/VNNI flags and only called when the CPU and the OS have them): the weights in fixed
 * point (prt_sh_fixed_weights, sh_shade_simd.h), each limb's dot product an exact int32 sum by
 * vpdpbusd, four u8 values times four s8 digits per lane at a time. Eight vertices go through
 * the lanes of one set of accumulators: each block of four dwords of their runs is transposed
 * so that a lane holds one vertex, which leaves no horizontal sum to do. Only 256-bit registers
 * are used (the EVEX forms), since some CPUs run 512-bit operations as two halves.
 *
 * A vertex's integer sums are exact and its limbs combine in its own lane by the same float
 * operations whatever the other lanes hold, so its result does not depend on where a call's
 * range starts. */
#include <immintrin.h>
#include <string.h>

#include "sh_shade_simd.h"

#define GROUP 8 /* vertices shaded together, one per 32-bit lane */
#define LIMBS PRT_SH_FIXED_LIMBS

#if defined(__GNUC__)
#define PRT_KERNEL_INLINE static inline __attribute__((always_inline))
#define PRT_KERNEL_OUTLINE static __attribute__((noinline))
#else
#define PRT_KERNEL_INLINE static inline
#define PRT_KERNEL_OUTLINE static
#endif

/* Eight rows `stride` bytes apart from `base`: row v at base + v * stride. */
typedef struct rows {
  const uint8_t* base;
  size_t stride;
} rows;

/* Rows v and v + 4, 16 bytes of each at `offset` (or the bytes `mask` selects, zeros above: a
 * masked load reads nothing else): row v in the low half, row v + 4 in the high one. */
PRT_KERNEL_INLINE __m256i load_row_pair(rows r, size_t v, size_t offset, int masked,
                                        __mmask16 mask) {
  const uint8_t* low = r.base + offset + v * r.stride;
  const uint8_t* high = low + 4u * r.stride;
  if (masked)
    return _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_maskz_loadu_epi8(mask, low)),
                                   _mm_maskz_loadu_epi8(mask, high), 1);
  return _mm256_inserti128_si256(
      _mm256_castsi128_si256(_mm_loadu_si128((const __m128i*)(const void*)low)),
      _mm_loadu_si128((const __m128i*)(const void*)high), 1);
}

/* t[i] = dword i (i < 4) of the 16 bytes at `offset` of the eight rows, lane j from row j: a 4x4
 * transpose in each 128-bit half of the row pairs. */
PRT_KERNEL_INLINE void transpose4(rows r, size_t offset, int masked, __mmask16 mask, __m256i t[4]) {
  const __m256i a0 = load_row_pair(r, 0, offset, masked, mask);
  const __m256i a1 = load_row_pair(r, 1, offset, masked, mask);
  const __m256i a2 = load_row_pair(r, 2, offset, masked, mask);
  const __m256i a3 = load_row_pair(r, 3, offset, masked, mask);
  const __m256i lo01 = _mm256_unpacklo_epi32(a0, a1), lo23 = _mm256_unpacklo_epi32(a2, a3);
  const __m256i hi01 = _mm256_unpackhi_epi32(a0, a1), hi23 = _mm256_unpackhi_epi32(a2, a3);
  t[0] = _mm256_unpacklo_epi64(lo01, lo23);
  t[1] = _mm256_unpackhi_epi64(lo01, lo23);
  t[2] = _mm256_unpacklo_epi64(hi01, hi23);
  t[3] = _mm256_unpackhi_epi64(hi01, hi23);
}

/* acc[l] += the limb-l products of one dword of the eight runs (t) with `digits` (the LIMBS
 * digit words of the matching four weights). */
PRT_KERNEL_INLINE void add_dword(const int32_t* digits, __m256i t, __m256i acc[LIMBS]) {
  int l;
  for (l = 0; l < LIMBS; ++l) acc[l] = _mm256_dpbusd_epi32(acc[l], t, _mm256_set1_epi32(digits[l]));
}

PRT_KERNEL_INLINE void clear(__m256i acc[LIMBS]) {
  int l;
  for (l = 0; l < LIMBS; ++l) acc[l] = _mm256_setzero_si256();
}

/* The limbs of channel ch in float, most significant first, plus the bias. */
PRT_KERNEL_INLINE __m256 combine(const prt_sh_simd_job* job, int ch, const __m256i acc[LIMBS]) {
  const float* unit = job->fixed->unit[ch];
  __m256 sum = _mm256_mul_ps(_mm256_cvtepi32_ps(acc[LIMBS - 1]), _mm256_set1_ps(unit[LIMBS - 1]));
  int l;
  for (l = LIMBS - 2; l >= 0; --l)
    sum = _mm256_fmadd_ps(_mm256_cvtepi32_ps(acc[l]), _mm256_set1_ps(unit[l]), sum);
  return _mm256_add_ps(sum, _mm256_set1_ps(job->bias[ch]));
}

/* Channel ch of an RGB transfer for `sets` (1 or 2) sets of eight rows, the second set eight
 * rows after the first: four dwords of the run at a time, then the rest in one masked block
 * whose size is a constant in each case. A weight's digits, broadcast once, serve both sets. */
PRT_KERNEL_INLINE void rgb_channel(const prt_sh_simd_job* job, rows r, int ch, int sets,
                                   __m256 out[2]) {
  const uint32_t dwords = job->padded / 4u;
  const int32_t(*digit)[LIMBS] = job->fixed->digit + (uint32_t)ch * dwords;
  const size_t start = job->segment[ch];
  rows second = r;
  uint32_t p;
  int i, l, set;
  __m256i acc[2][LIMBS], t[2][4];
  second.base = r.base + GROUP * r.stride;
  for (set = 0; set < sets; ++set) clear(acc[set]);
#define ADD_DWORDS(n)                                                 \
  for (i = 0; i < (n); ++i)                                           \
    for (l = 0; l < LIMBS; ++l) {                                     \
      const __m256i w = _mm256_set1_epi32(digit[p + (uint32_t)i][l]); \
      for (set = 0; set < sets; ++set)                                \
        acc[set][l] = _mm256_dpbusd_epi32(acc[set][l], t[set][i], w); \
    }
#define BLOCK(n, masked, mask)                                          \
  transpose4(r, start + 4u * p, masked, mask, t[0]);                    \
  if (sets > 1) transpose4(second, start + 4u * p, masked, mask, t[1]); \
  ADD_DWORDS(n)
  for (p = 0; dwords - p >= 4u; p += 4u) {
    BLOCK(4, 0, 0)
  }
  switch (dwords - p) {
    case 3:
      BLOCK(3, 1, 0x0FFF)
      break;
    case 2:
      BLOCK(2, 1, 0x00FF)
      break;
    case 1:
      BLOCK(1, 1, 0x000F)
      break;
    default:
      break;
  }
#undef BLOCK
#undef ADD_DWORDS
  for (set = 0; set < sets; ++set) out[set] = combine(job, ch, acc[set]);
}

PRT_KERNEL_OUTLINE void rgb_channel_8(const prt_sh_simd_job* job, rows r, int ch, __m256 out[2]) {
  rgb_channel(job, r, ch, 1, out);
}

PRT_KERNEL_OUTLINE void rgb_channel_16(const prt_sh_simd_job* job, rows r, int ch, __m256 out[2]) {
  rgb_channel(job, r, ch, 2, out);
}

/* The three channels of an RGB vertex stored contiguously as one run of 3 * `per_channel`
 * dwords (a constant at each call site, at most 16), unrolled so that every dword's channel, and
 * so its accumulators, is a constant: four dwords of the eight rows transposed at a time, a block
 * spanning two channels transposed once for both. */
PRT_KERNEL_INLINE void rgb_unrolled(const prt_sh_simd_job* job, rows r, const uint32_t per_channel,
                                    __m256 rgb[3]) {
  const uint32_t dwords = 3u * per_channel;
  const int32_t(*digit)[LIMBS] = job->fixed->digit;
  const size_t start = job->segment[0];
  __m256i acc[3][LIMBS], t[4];
  int c;
  for (c = 0; c < 3; ++c) clear(acc[c]);
#define DWORD(q, i) \
  if ((q) < dwords) add_dword(digit[q], t[i], acc[(q) / per_channel])
#define BLOCK(b)                                                                                  \
  do {                                                                                            \
    const uint32_t first = 4u * (b);                                                              \
    if (first >= dwords) break;                                                                   \
    if (first + 4u <= dwords)                                                                     \
      transpose4(r, start + 4u * first, 0, 0, t);                                                 \
    else                                                                                          \
      transpose4(r, start + 4u * first, 1, (__mmask16)((1u << (4u * (dwords - first))) - 1u), t); \
    DWORD(first, 0);                                                                              \
    DWORD(first + 1u, 1);                                                                         \
    DWORD(first + 2u, 2);                                                                         \
    DWORD(first + 3u, 3);                                                                         \
  } while (0)
  BLOCK(0);
  BLOCK(1);
  BLOCK(2);
  BLOCK(3);
  BLOCK(4);
  BLOCK(5);
  BLOCK(6);
  BLOCK(7);
  BLOCK(8);
  BLOCK(9);
  BLOCK(10);
  BLOCK(11);
#undef BLOCK
#undef DWORD
  for (c = 0; c < 3; ++c) rgb[c] = combine(job, c, acc[c]);
}

/* The unrolled shapes: orders 2, 4, 6 and 8 (per_channel 1, 4, 9, 16). */
#define PRT_SH_UNROLLED(d)                                                                      \
  PRT_KERNEL_OUTLINE void rgb_unrolled_##d(const prt_sh_simd_job* job, rows r, __m256 rgb[3]) { \
    rgb_unrolled(job, r, d, rgb);                                                               \
  }
PRT_SH_UNROLLED(1)
PRT_SH_UNROLLED(4)
PRT_SH_UNROLLED(9)
PRT_SH_UNROLLED(16)
#undef PRT_SH_UNROLLED

/* An RGB transfer of one of the unrolled shapes, or NULL. */
typedef void (*rgb_shape)(const prt_sh_simd_job* job, rows r, __m256 rgb[3]);
static rgb_shape unrolled_shape(const prt_sh_simd_job* job) {
  const uint32_t* segment = job->segment;
  if (segment[1] != segment[0] + job->padded || segment[2] != segment[1] + job->padded) return NULL;
  switch (job->padded / 4u) {
    case 1:
      return rgb_unrolled_1;
    case 4:
      return rgb_unrolled_4;
    case 9:
      return rgb_unrolled_9;
    case 16:
      return rgb_unrolled_16;
    default:
      return NULL;
  }
}

/* Writes the first n (1..8) vertices' r, g, b, interleaved, from the per-channel lanes. */
PRT_KERNEL_INLINE void store_rgb8(float* out, __m256 r, __m256 g, __m256 b, int n) {
  const __m256i rg0 = _mm256_setr_epi32(0, 8, 0, 1, 9, 0, 2, 10);
  const __m256i rg1 = _mm256_setr_epi32(0, 3, 11, 0, 4, 12, 0, 5);
  const __m256i rg2 = _mm256_setr_epi32(13, 0, 6, 14, 0, 7, 15, 0);
  const __m256i b0 = _mm256_setr_epi32(0, 0, 0, 0, 0, 1, 0, 0);
  const __m256i b1 = _mm256_setr_epi32(2, 0, 0, 3, 0, 0, 4, 0);
  const __m256i b2 = _mm256_setr_epi32(0, 5, 0, 0, 6, 0, 0, 7);
  const __m256 v0 = _mm256_mask_permutexvar_ps(_mm256_permutex2var_ps(r, rg0, g), 0x24, b0, b);
  const __m256 v1 = _mm256_mask_permutexvar_ps(_mm256_permutex2var_ps(r, rg1, g), 0x49, b1, b);
  const __m256 v2 = _mm256_mask_permutexvar_ps(_mm256_permutex2var_ps(r, rg2, g), 0x92, b2, b);
  if (n == GROUP) {
    _mm256_storeu_ps(out, v0);
    _mm256_storeu_ps(out + 8, v1);
    _mm256_storeu_ps(out + 16, v2);
  } else {
    /* Exactly 3n floats: lanes below 3n, 3n - 8 and 3n - 16 of the three vectors. */
    const unsigned floats = 3u * (unsigned)n;
    _mm256_mask_storeu_ps(out, (__mmask8)((1u << (floats < 8u ? floats : 8u)) - 1u), v0);
    if (floats > 8u)
      _mm256_mask_storeu_ps(out + 8, (__mmask8)((1u << (floats < 16u ? floats - 8u : 8u)) - 1u),
                            v1);
    if (floats > 16u) _mm256_mask_storeu_ps(out + 16, (__mmask8)((1u << (floats - 16u)) - 1u), v2);
  }
}

/* The eight vertices from r.base on into out (the first n of them stored), or sixteen when
 * `sets` is 2 (all stored), by the unrolled `shape` or, without one, channel by channel. */
PRT_KERNEL_INLINE void shade_group(const prt_sh_simd_job* job, rows r, float* out, int n,
                                   rgb_shape shape, int sets) {
  __m256 rgb[3][2];
  int c;
  if (shape) {
    __m256 one[3];
    shape(job, r, one);
    for (c = 0; c < 3; ++c) rgb[c][0] = one[c];
    if (sets > 1) {
      rows second = r;
      second.base += GROUP * r.stride;
      shape(job, second, one);
      for (c = 0; c < 3; ++c) rgb[c][1] = one[c];
    }
  } else {
    for (c = 0; c < 3; ++c) {
      if (sets > 1)
        rgb_channel_16(job, r, c, rgb[c]);
      else
        rgb_channel_8(job, r, c, rgb[c]);
    }
  }
  store_rgb8(out, rgb[0][0], rgb[1][0], rgb[2][0], n);
  if (sets > 1) store_rgb8(out + 3 * GROUP, rgb[0][1], rgb[1][1], rgb[2][1], GROUP);
}

/* Fewer than eight vertices in all: shaded from a copy padded with zero rows, so that every
 * lane reads memory. */
static void shade_few(const prt_sh_simd_job* job, uint32_t count, float* out, rgb_shape shape) {
  /* The bytes a vertex's runs reach: at most three runs of 256 values. */
  uint8_t copy[GROUP * 3u * 4u * PRT_SH_FIXED_MAX_DWORDS];
  const size_t reach = job->segment[2] + job->padded;
  rows r;
  uint32_t v;
  memset(copy, 0, GROUP * reach);
  for (v = 0; v < count; ++v) memcpy(copy + v * reach, job->values + v * job->stride, reach);
  r.base = copy;
  r.stride = reach;
  shade_group(job, r, out, (int)count, shape, 1);
}

/* Sixteen vertices at a time, then eight; the last vertices of the range shaded as the last
 * eight of it (the overlap gets the same bits a second time). */
static void shade_vertices(const prt_sh_simd_job* job, uint32_t count, float* out,
                           rgb_shape shape) {
  rows r;
  uint32_t v;
  r.stride = job->stride;
  for (v = 0; count - v >= 2u * GROUP; v += 2u * GROUP) {
    r.base = job->values + (size_t)v * job->stride;
    shade_group(job, r, out + 3u * (size_t)v, GROUP, shape, 2);
  }
  for (; v < count; v += GROUP) {
    if (count - v < GROUP) v = count - GROUP;
    r.base = job->values + (size_t)v * job->stride;
    shade_group(job, r, out + 3u * (size_t)v, GROUP, shape, 1);
  }
}

void prt_sh_shade_avx512(const prt_sh_simd_job* shared, uint32_t count, float* out_rgb) {
  const prt_sh_simd_job job = *shared; /* a copy the stores to out_rgb cannot alias */
  const rgb_shape shape = unrolled_shape(&job);
  if (count < GROUP)
    shade_few(&job, count, out_rgb, shape);
  else
    shade_vertices(&job, count, out_rgb, shape);
}
