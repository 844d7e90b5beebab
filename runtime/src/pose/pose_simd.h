/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the AVX2 + FMA kernels of technique `pose` (pose_kernels_avx2.c,
 * compiled with those flags) and the jobs they run. Only pose_asset.c calls them, and only when
 * the context's SIMD ISA is AVX2 or above.
 *
 * Both fold the basis quantisation U[v][k] = offset_k + scale_k value[v][k] into what the values
 * multiply, so that a kernel converts the stored integers to float and takes dot products:
 *   shade:    radiance[v][ch] = bias[ch] + sum_k value[v][k] weight[ch][k],
 *             weight[ch][k] = scale_k w_k[ch], bias[ch] = sum_k offset_k w_k[ch];
 *   transfer: t[v][c] = bias[c] + sum_k value[v][k] column[k][c] for a block of 8 c,
 *             column[k][c] = scale_k y[k][c], bias[c] = sum_k offset_k y[k][c].
 * Each vertex's arithmetic is the same wherever a call's range starts, so split ranges give the
 * one-range call's bits. */
#ifndef PRT_POSE_SIMD_H
#define PRT_POSE_SIMD_H

#include <stddef.h>
#include <stdint.h>

/* Coefficients of one transfer block: one AVX register. */
#define PRT_POSE_SIMD_BLOCK 8u

typedef struct prt_pose_shade_job {
  const uint8_t* values;  /* the first vertex's q values (u8 or u16 LE), any alignment */
  size_t stride;          /* bytes per vertex: q * bits / 8 */
  uint32_t bits;          /* 8 or 16 */
  uint32_t basis_dims;    /* q */
  const float* weight[3]; /* q rounded up to 8 floats each, zero past q */
  float bias[3];
} prt_pose_shade_job;

typedef struct prt_pose_transfer_job {
  const uint8_t* values; /* as in prt_pose_shade_job */
  size_t stride;
  uint32_t bits;
  uint32_t basis_dims;
  const float* column; /* [q][8]: the block's 8 columns of scale_k y[k][c] (zero past C) */
  float bias[PRT_POSE_SIMD_BLOCK];
  size_t out_stride; /* floats between two vertices' outputs (C) */
  uint32_t width;    /* coefficients of the block written, 1..8 */
} prt_pose_transfer_job;

#if defined(PRT_HAS_X86_SIMD)
/* Writes 3 * count floats; reads exactly the count rows of values. */
void prt_pose_shade_avx2(const prt_pose_shade_job* job, uint32_t count, float* out_rgb);
/* Writes job->width floats at out + v * out_stride for each of the count vertices. */
void prt_pose_transfer_avx2(const prt_pose_transfer_job* job, uint32_t count, float* out);
#endif

#endif /* PRT_POSE_SIMD_H */
