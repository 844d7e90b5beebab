/* SPDX-License-Identifier: MIT */
/* Private to the wavelet light (wavelet_light.c, wavelet_source*.c): the steps of
 * prt_wavelet_resample that a prepared source (prt_wavelet_source.h) shares with it, so that
 * both give the same texels. */
#ifndef PRT_RUNTIME_WAVELET_LIGHT_INTERNAL_H
#define PRT_RUNTIME_WAVELET_LIGHT_INTERNAL_H

#include <stdint.h>

#include "env_internal.h"
#include "sphere_internal.h"
#include "wavelet_internal.h"

/* The largest source texel's solid angle of a lat-long map and of a cube map's faces. */
double prt_wavelet_latlong_largest_texel(uint32_t width, uint32_t height);
double prt_wavelet_cube_largest_texel(uint32_t face_size);

/* A lat-long map in bands of PRT_WAVELET_BAND_ROWS rows, as a prepared source keeps it so that
 * a SIMD lane can take each row of a band: band b, column x, channel c (RGB) and row j of the
 * band at ((b W + x) 3 + c) ROWS + j; the rows past the map's last are 0. */
#define PRT_WAVELET_BAND_ROWS 16u

/* Where texel (x, y)'s red is in a banded map of `width` columns (green and blue follow, each
 * PRT_WAVELET_BAND_ROWS floats on). */
static inline size_t prt_wavelet_banded_at(uint32_t width, uint32_t x, uint32_t y) {
  return ((size_t)(y / PRT_WAVELET_BAND_ROWS) * width + x) * 3u * PRT_WAVELET_BAND_ROWS +
         y % PRT_WAVELET_BAND_ROWS;
}

/* The end of a resampling (SPEC §14): turns what landed in every target texel (sum of L dw in
 * RGB, sum of dw in the 4th float) into its power, fills the texels nothing landed in from the
 * map's nearest texel in direction R^T c, and zeroes the 4th floats. The map: env's layout and
 * size, its texels in env or, for a lat-long map, in `banded` (NULL: env's). solid_angles: the
 * target texels' solid angles by y * size + x (shared by every face), or NULL to compute them. */
void prt_wavelet_finish_resample(uint32_t param, uint32_t size, const double r[9],
                                 const prt_env_view* env, const float* banded, double largest_texel,
                                 const double* solid_angles, float* out_rgba);

/* The target texel of a cube map's texel: face f, face coordinates (sc, tc), its direction scaled
 * by inv_length (1 / its length) and turned by R. One expression for both resamplings, so that
 * both send a texel to the same target. */
static inline uint32_t prt_wavelet_locate_cube_texel(uint32_t param, uint32_t size,
                                                     const double r[9], uint32_t f, double sc,
                                                     double tc, double inv_length) {
  double d[3];
  prt_cube_direction(f, sc, tc, d);
  d[0] *= inv_length;
  d[1] *= inv_length;
  d[2] *= inv_length;
  return prt_wavelet_locate_unit(param, size, r[0] * d[0] + r[1] * d[1] + r[2] * d[2],
                                 r[3] * d[0] + r[4] * d[1] + r[5] * d[2],
                                 r[6] * d[0] + r[7] * d[1] + r[8] * d[2]);
}

#endif /* PRT_RUNTIME_WAVELET_LIGHT_INTERNAL_H */
