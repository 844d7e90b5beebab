/* SPDX-License-Identifier: MIT */
/* Private to the SIMD kernels of the prepared wavelet source (wavelet_source_avx2.c,
 * wavelet_source_avx512.c): what they share about locating lat-long texels on the cube in float.
 *
 * Each lane is a row of a band of the banded copy; a column's direction is
 * R d = sin t g(f) + cos t R e_y, from a float table of g per column block and sin t, cos t R e_y
 * per lane, and its cube face and texel are found in float. A float texel can differ from the
 * double one of prt_wavelet_resample only for a direction near a texel edge or near a face
 * boundary: such lanes (EDGE_MARGIN around every texel edge, far wider than the float error) are
 * located again by the scalar path's exact function, so every source texel lands where it does
 * there. Runs of a row's texels with one target are summed in the lane's registers and only a
 * finished run is added to its target. */
#ifndef PRT_RUNTIME_WAVELET_SOURCE_SIMD_H
#define PRT_RUNTIME_WAVELET_SOURCE_SIMD_H

#include <stdint.h>

#include "wavelet_light_internal.h"
#include "wavelet_source_internal.h"

/* The kernels' per-column helpers are large; without inlining, each column pays a call and
 * passes its vectors through memory. */
#if defined(__GNUC__)
#define PRT_SOURCE_INLINE static inline __attribute__((always_inline))
#else
#define PRT_SOURCE_INLINE static inline
#endif

/* The margin, in texels, around a texel edge within which a float texel coordinate is taken
 * from the exact path; the float error is orders of magnitude smaller. It also covers the face
 * choice: float and double can only pick different faces where two |components| are nearly
 * equal, and there the face coordinate is nearly +-1, a texel edge. */
#define EDGE_MARGIN (1.0f / 2048.0f)

/* g(f) = R (sin f, 0, -cos f) in float for columns first .. first + count - 1. */
typedef struct prt_wavelet_column_block {
  uint32_t first, count;
  float gx[PRT_WAVELET_SOURCE_COLUMN_BLOCK], gy[PRT_WAVELET_SOURCE_COLUMN_BLOCK],
      gz[PRT_WAVELET_SOURCE_COLUMN_BLOCK];
} prt_wavelet_column_block;

static inline void prt_wavelet_source_column_block(const prt_wavelet_source* s, const double r[9],
                                                   uint32_t first, prt_wavelet_column_block* out) {
  const uint32_t width = s->env.width;
  uint32_t x;
  out->first = first;
  out->count = width - first < PRT_WAVELET_SOURCE_COLUMN_BLOCK ? width - first
                                                               : PRT_WAVELET_SOURCE_COLUMN_BLOCK;
  for (x = 0; x < out->count; ++x) {
    const double sin_phi = s->column_sin[first + x], cos_phi = s->column_cos[first + x];
    out->gx[x] = (float)(r[0] * sin_phi - r[2] * cos_phi);
    out->gy[x] = (float)(r[3] * sin_phi - r[5] * cos_phi);
    out->gz[x] = (float)(r[6] * sin_phi - r[8] * cos_phi);
  }
}

/* Per row of the band from first_row: sin t, cos t R e_y and the solid angle in float; mask: bit j
 * set when row first_row + j is a row of the map (the others repeat the last row's direction and
 * are never added). */
typedef struct prt_wavelet_band_rows {
  float sin_theta[PRT_WAVELET_BAND_ROWS], up[3][PRT_WAVELET_BAND_ROWS];
  float solid_angle[PRT_WAVELET_BAND_ROWS];
  uint32_t mask;
} prt_wavelet_band_rows;

static inline void prt_wavelet_source_band_rows(const prt_wavelet_source* s, const double r[9],
                                                uint32_t first_row, prt_wavelet_band_rows* out) {
  const uint32_t height = s->env.height;
  uint32_t j;
  out->mask = 0u;
  for (j = 0; j < PRT_WAVELET_BAND_ROWS; ++j) {
    const uint32_t y = first_row + j < height ? first_row + j : height - 1u;
    const double cos_theta = s->row_cos[y];
    out->sin_theta[j] = (float)s->row_sin[y];
    out->up[0][j] = (float)(cos_theta * r[1]);
    out->up[1][j] = (float)(cos_theta * r[4]);
    out->up[2][j] = (float)(cos_theta * r[7]);
    out->solid_angle[j] = s->texel_solid_angle[y];
    if (first_row + j < height) out->mask |= 1u << j;
  }
}

#endif /* PRT_RUNTIME_WAVELET_SOURCE_SIMD_H */
