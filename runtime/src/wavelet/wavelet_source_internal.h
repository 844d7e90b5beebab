/* SPDX-License-Identifier: MIT */
/* Private to the prepared wavelet source (wavelet_source.c and its SIMD kernels): the source's
 * tables, built once per map with the same expressions prt_wavelet_resample evaluates per frame,
 * so that a direction computed from them has the same bits as there. */
#ifndef PRT_RUNTIME_WAVELET_SOURCE_INTERNAL_H
#define PRT_RUNTIME_WAVELET_SOURCE_INTERNAL_H

#include <stdint.h>

#include "env_internal.h"
#include "internal.h"
#include "wavelet_light_internal.h"

/* Lat-long columns whose turned azimuth vectors a kernel tabulates at once (on the stack). */
#define PRT_WAVELET_SOURCE_COLUMN_BLOCK 512u

struct prt_wavelet_source {
  prt_allocator allocator;
  size_t bytes;     /* of the allocation holding the struct and its tables */
  prt_simd_isa isa; /* the context's SIMD instruction set at creation */
  int avx512;       /* the context's SIMD ISA is AVX512 (F, BW, DQ, VL, VNNI) */
  uint32_t param, size;
  /* The map's layout and size (env.texels: the cube map's copy; NULL for a lat-long map). */
  prt_env_view env;
  /* A cube map sanitised: 4 floats per texel (RGB, then 1 so that RGBA x dw gives (L dw, dw)),
   * rows of env.width texels, faces of env.height rows. A lat-long map sanitised and banded
   * (PRT_WAVELET_BAND_ROWS, zero rows after the last): one 64-byte load gives a channel of a
   * column's rows. Both 64-byte aligned; the other is NULL. */
  float* radiance;
  float* banded;
  double largest_texel; /* the largest source texel's solid angle */
  /* Lat-long: per column sin and cos of its azimuth, per row sin and cos of its polar angle
   * and its texels' solid angle. Cube: per column s_c, per row t_c, per texel (shared by the
   * faces) 1 / |(1, s_c, t_c)| and the solid angle. */
  double* column_sin;         /* lat-long: width */
  double* column_cos;         /* lat-long: width; cube: s_c, width */
  double* row_sin;            /* lat-long: height */
  double* row_cos;            /* lat-long: height; cube: t_c, height */
  double* inv_length;         /* cube: width * height */
  float* texel_solid_angle;   /* lat-long: height (per row); cube: width * height */
  double* target_solid_angle; /* size * size, shared by the target faces */
};

/* The target texel of lat-long texel (x, y) turned by r, exactly as prt_wavelet_resample
 * locates it (double precision, the same expressions). */
uint32_t prt_wavelet_source_locate_latlong(const prt_wavelet_source* source, const double r[9],
                                           uint32_t x, uint32_t y);

#if defined(PRT_HAS_X86_SIMD)
/* Accumulate (L dw, dw) of every texel of a lat-long source into its cube target texel, each
 * texel where the scalar path puts it (AVX2 + FMA, AVX-512 F + DQ; the caller checked the CPU). */
void prt_wavelet_source_splat_cube_avx2(const prt_wavelet_source* source, const double r[9],
                                        float* out_rgba);
void prt_wavelet_source_splat_cube_avx512(const prt_wavelet_source* source, const double r[9],
                                          float* out_rgba);
#endif

#endif /* PRT_RUNTIME_WAVELET_SOURCE_INTERNAL_H */
