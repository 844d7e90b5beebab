/* SPDX-License-Identifier: MIT */
/* 2-D orthonormal Haar transform of square faces, non-standard decomposition (prt_wavelet.h). */
#include <string.h>

#include "internal.h"

#define INV_SQRT2 0.70710678118654752440f

static int valid_face(uint32_t size, uint32_t channels, const float* face) {
  return face && size >= 1u && size <= PRT_HAAR_MAX_SIZE && (size & (size - 1u)) == 0u &&
         channels >= 1u && channels <= PRT_HAAR_MAX_CHANNELS;
}

/* One level on n values spaced `step` texels apart (a row: step 1; a column: step size), each
 * texel `channels` floats: sums to the first half, differences to the second (forward), or back
 * (inverse). `scratch` holds n * channels floats. */
#if defined(__GNUC__)
#define HAAR_INLINE static inline __attribute__((always_inline))
#else
#define HAAR_INLINE static inline
#endif

HAAR_INLINE void haar_line(float* line, uint32_t n, size_t step, uint32_t channels, int forward,
                           float* scratch) {
  uint32_t i, c, half = n / 2u;
  for (i = 0; i < n; ++i)
    memcpy(scratch + (size_t)i * channels, line + i * step * channels, channels * sizeof(float));
  for (i = 0; i < half; ++i) {
    float* even = line + (forward ? i : 2u * i) * step * channels;
    float* odd = line + (forward ? half + i : 2u * i + 1u) * step * channels;
    const float* a = scratch + (size_t)(forward ? 2u * i : i) * channels;
    const float* b = scratch + (size_t)(forward ? 2u * i + 1u : half + i) * channels;
    for (c = 0; c < channels; ++c) {
      even[c] = (a[c] + b[c]) * INV_SQRT2;
      odd[c] = (a[c] - b[c]) * INV_SQRT2;
    }
  }
}

/* The forward level of a row of n texels, haar_line's arithmetic: the even and the odd texels
 * are copied apart first (the whole row copied at once becomes a rep movs, slow for the short
 * rows of the coarse levels), then sums go to the first half and differences to the second. */
HAAR_INLINE void haar_row_forward(float* row, uint32_t n, uint32_t channels, float* scratch) {
  const uint32_t half = n / 2u;
  float* odd_texels = scratch + (size_t)half * channels;
  uint32_t i, c;
  for (i = 0; i < half; ++i)
    for (c = 0; c < channels; ++c) {
      scratch[(size_t)i * channels + c] = row[(size_t)(2u * i) * channels + c];
      odd_texels[(size_t)i * channels + c] = row[(size_t)(2u * i + 1u) * channels + c];
    }
  for (i = 0; i < half; ++i)
    for (c = 0; c < channels; ++c) {
      const float a = scratch[(size_t)i * channels + c], b = odd_texels[(size_t)i * channels + c];
      row[(size_t)i * channels + c] = (a + b) * INV_SQRT2;
      row[(size_t)(half + i) * channels + c] = (a - b) * INV_SQRT2;
    }
}

/* The forward level's columns of the n x n block, haar_line's arithmetic on every column at
 * once: a strip of columns is copied to scratch whole, then each output row is the sums (or
 * differences) of two of its rows, contiguous runs instead of a stride of a row per value. */
HAAR_INLINE void haar_columns_forward(float* face, uint32_t size, uint32_t n, uint32_t channels,
                                      float* scratch) {
  const uint32_t capacity = PRT_HAAR_MAX_SIZE * PRT_HAAR_MAX_CHANNELS; /* >= n * channels */
  const uint32_t strip = capacity / (n * channels) < n ? capacity / (n * channels) : n;
  const uint32_t half = n / 2u;
  uint32_t first, i, t;
  for (first = 0; first < n; first += strip) {
    const uint32_t width = (n - first < strip ? n - first : strip) * channels; /* floats */
    for (i = 0; i < n; ++i)
      memcpy(scratch + (size_t)i * width, face + ((size_t)i * size + first) * channels,
             width * sizeof(float));
    for (i = 0; i < half; ++i) {
      const float* a = scratch + (size_t)(2u * i) * width;
      const float* b = a + width;
      float* even = face + ((size_t)i * size + first) * channels;
      float* odd = face + ((size_t)(half + i) * size + first) * channels;
      for (t = 0; t < width; ++t) {
        even[t] = (a[t] + b[t]) * INV_SQRT2;
        odd[t] = (a[t] - b[t]) * INV_SQRT2;
      }
    }
  }
}

/* One level on the n x n top-left block: rows then columns (forward), columns then rows
 * (inverse, the transpose). */
HAAR_INLINE void haar_level_of(float* face, uint32_t size, uint32_t n, uint32_t channels,
                               int forward, float* scratch) {
  uint32_t i, pass;
  for (pass = 0; pass < 2u; ++pass) {
    const int rows = (pass == 0u) == (forward != 0);
    if (forward) {
      if (rows)
        for (i = 0; i < n; ++i)
          haar_row_forward(face + (size_t)i * size * channels, n, channels, scratch);
      else
        haar_columns_forward(face, size, n, channels, scratch);
      continue;
    }
    for (i = 0; i < n; ++i) {
      float* start = face + (size_t)(rows ? i * size : i) * channels;
      haar_line(start, n, rows ? 1u : size, channels, forward, scratch);
    }
  }
}

/* RGBA lights (the usual case) and the bake's single-channel rows get a copy with a constant
 * channel count, so that a texel's channels move and combine together instead of a call and a
 * loop per texel; same arithmetic. */
static void haar_level(float* face, uint32_t size, uint32_t n, uint32_t channels, int forward,
                       float* scratch) {
  if (channels == 4u)
    haar_level_of(face, size, n, 4u, forward, scratch);
  else if (channels == 1u)
    haar_level_of(face, size, n, 1u, forward, scratch);
  else
    haar_level_of(face, size, n, channels, forward, scratch);
}

prt_result prt_haar_forward(uint32_t size, uint32_t channels, float* face) {
  float scratch[PRT_HAAR_MAX_SIZE * PRT_HAAR_MAX_CHANNELS];
  uint32_t n;
  if (!valid_face(size, channels, face)) return PRT_ERROR_INVALID_ARGUMENT;
  for (n = size; n >= 2u; n /= 2u) haar_level(face, size, n, channels, 1, scratch);
  return PRT_OK;
}

prt_result prt_haar_inverse(uint32_t size, uint32_t channels, float* face) {
  float scratch[PRT_HAAR_MAX_SIZE * PRT_HAAR_MAX_CHANNELS];
  uint32_t n;
  if (!valid_face(size, channels, face)) return PRT_ERROR_INVALID_ARGUMENT;
  for (n = 2u; n <= size; n *= 2u) haar_level(face, size, n, channels, 0, scratch);
  return PRT_OK;
}

int prt_haar_level(uint32_t size, uint32_t x, uint32_t y) {
  uint32_t m = x > y ? x : y;
  int level = -1;
  if (size < 1u || size > PRT_HAAR_MAX_SIZE || (size & (size - 1u)) != 0u || x >= size || y >= size)
    return -2;
  while (m > 0u) {
    ++level;
    m >>= 1;
  }
  return level;
}
