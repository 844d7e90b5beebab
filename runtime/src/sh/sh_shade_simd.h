/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the SIMD shading kernels of technique `sh` (one file per instruction
 * set, compiled with that ISA's flags) and the job they run. Only sh_asset.c calls them, and only
 * when the context's SIMD ISA allows it.
 *
 * The light is folded into the quantisation once per call (sh_asset.c): for output channel ch,
 *   radiance = bias[ch] + sum_k q[segment[ch] + k] * weight[ch][k],
 *   bias = sum_k offset_j L_k,  weight[ch][k] = scale_j L_k  (j = segment[ch] + k),
 * so a kernel only converts the stored integers to float and takes dot products. */
#ifndef PRT_SH_SHADE_SIMD_H
#define PRT_SH_SHADE_SIMD_H

#include <stddef.h>
#include <stdint.h>

/* Every kernel works on blocks of at least this many coefficients: weights are zero-padded to a
 * multiple of it, and a kernel reads up to PRT_SH_SIMD_BLOCK - 1 values past a channel's end. */
#define PRT_SH_SIMD_BLOCK 4u

typedef struct prt_sh_simd_job {
  const uint8_t* values;  /* the first vertex's quantised values (u8 or u16 LE), any alignment */
  size_t stride;          /* bytes per vertex */
  uint32_t bits;          /* 8 or 16 */
  uint32_t padded;        /* coefficients per channel rounded up to PRT_SH_SIMD_BLOCK */
  uint32_t segment[3];    /* first value of output channel ch's transfer within a vertex */
  const float* weight[3]; /* `padded` floats each, zero past the channel's coefficients */
  float bias[3];
} prt_sh_simd_job;

/* Shades `count` vertices from job->values on into out_rgb (3 floats per vertex). Reads, for
 * each vertex and channel, values [segment, segment + padded): the caller makes sure those bytes
 * exist. Writes exactly 3 * count floats. */
typedef void (*prt_sh_simd_kernel)(const prt_sh_simd_job* job, uint32_t count, float* out_rgb);

#if defined(PRT_HAS_X86_SIMD)
void prt_sh_shade_sse41(const prt_sh_simd_job* job, uint32_t count, float* out_rgb);
void prt_sh_shade_avx2(const prt_sh_simd_job* job, uint32_t count, float* out_rgb);
#endif

#endif /* PRT_SH_SHADE_SIMD_H */
