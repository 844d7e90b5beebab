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

/* The AVX-512 VNNI kernel's form of the weights (sh_shade_avx512.c), made from the float ones per
 * call (sh_asset.c): channel ch's weight k is D * unit[ch][0] for an integer D written as
 * PRT_SH_FIXED_LIMBS signed base-256 digits, digit l (in [-128, 127]) worth unit[ch][l] =
 * unit[ch][0] * 256^l, unit[ch][0] a power of two. Each limb's dot product with the u8 values is
 * then an exact int32 sum; only the rounding of the weights to D and the final combination of the
 * limbs round. Three limbs (24 bits): a fourth costs a third more products for accuracy that
 * prt_sh_fix_weights's check against the bound does not need. */
#define PRT_SH_FIXED_LIMBS 3
#define PRT_SH_FIXED_MAX_DWORDS 64 /* order 16: 256 coefficients, four per dword */

typedef struct prt_sh_fixed_weights {
  /* digit[ch * padded / 4 + k][l]: the limb-l digits of channel ch's weights 4k..4k+3, one byte
   * each in memory order (so that an RGB vertex whose channels are contiguous reads its digits
   * in the order of its values) */
  int32_t digit[3 * PRT_SH_FIXED_MAX_DWORDS][PRT_SH_FIXED_LIMBS];
  float unit[3][PRT_SH_FIXED_LIMBS];
} prt_sh_fixed_weights;

typedef struct prt_sh_simd_job {
  const uint8_t* values;  /* the first vertex's quantised values (u8 or u16 LE), any alignment */
  size_t stride;          /* bytes per vertex */
  uint32_t bits;          /* 8 or 16 */
  uint32_t padded;        /* coefficients per channel rounded up to PRT_SH_SIMD_BLOCK */
  uint32_t segment[3];    /* first value of output channel ch's transfer within a vertex */
  const float* weight[3]; /* `padded` floats each, zero past the channel's coefficients */
  float bias[3];
  const prt_sh_fixed_weights* fixed; /* the weights in fixed point: the AVX-512 kernel only */
} prt_sh_simd_job;

/* Fills *out from job's float weights (padded, a multiple of 4, at most
 * 4 * PRT_SH_FIXED_MAX_DWORDS) and returns 1 when the rounding to fixed point stays within half
 * of the conformance bound (n2 + 8) 2^-23 M for every possible 8-bit vertex, given
 * offset_magnitude[ch] = sum_k |offset_j L_k| of each channel; returns 0 (and the float kernels
 * shade) otherwise: a weight that is not finite, a light too faint for normal-float units, or
 * weights spanning too wide a range for the offsets to cover the rounding of the small ones. */
int prt_sh_fix_weights(const prt_sh_simd_job* job, uint32_t n2, const double offset_magnitude[3],
                       prt_sh_fixed_weights* out);

/* Shades `count` vertices from job->values on into out_rgb (3 floats per vertex). Reads, for
 * each vertex and channel, values [segment, segment + padded): the caller makes sure those bytes
 * exist. Writes exactly 3 * count floats. */
typedef void (*prt_sh_simd_kernel)(const prt_sh_simd_job* job, uint32_t count, float* out_rgb);

#if defined(PRT_HAS_X86_SIMD)
void prt_sh_shade_sse41(const prt_sh_simd_job* job, uint32_t count, float* out_rgb);
void prt_sh_shade_avx2(const prt_sh_simd_job* job, uint32_t count, float* out_rgb);
/* 8-bit RGB transfer (three distinct segments) and job->fixed only. */
void prt_sh_shade_avx512(const prt_sh_simd_job* job, uint32_t count, float* out_rgb);
#endif

#endif /* PRT_SH_SHADE_SIMD_H */
