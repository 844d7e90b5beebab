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

/* Model 1's exact part (SPEC §7.3) eight vertices at a time, in float: each vertex's model-frame
 * normal, skinned as normalize(sign(det K3) cof(K3) n_local) with K3 the weight blend of the
 * joints' 3x3 parts (or the caller's normal normalised), 0 where the scalar path gives 0; the SH
 * basis at it by sh_eval.c's recurrence; then either factor_c y_c(n) (factor_c = rho A_l / pi)
 * added to the transfer, or y_c(n) times the light folded with the factors added to the
 * radiance, skipping the odd bands above 1 (A_l = 0), so that shading keeps no C-vector per
 * vertex. Lanes do not mix: a vertex gets the same bits wherever its range starts. */
typedef struct prt_pose_exact_job {
  uint32_t order;
  const uint8_t* skin;  /* the range's first skin record (36 bytes each); read without normals */
  const float* normals; /* the caller's normals of the range (3 floats per vertex), or NULL */
  const float* joint;   /* [J + 1][12]: K_j's 3x3 part, rows padded to 4 floats, then the
                         * identity; read without normals */
  uint32_t joint_count; /* J: a stored joint index >= J counts as weight 0 */
  const float* factor;  /* [C] factor_c */
  const float* light;   /* [C][3] factor_c L'[c][ch]: shading only */
} prt_pose_exact_job;

#if defined(PRT_HAS_X86_SIMD)
/* Adds the exact radiance to the 3 * count floats of out_rgb. */
void prt_pose_exact_shade_avx2(const prt_pose_exact_job* job, uint32_t count, float* out_rgb);
/* Adds factor_c y_c(n) to out[v * out_stride + c] for each of the count vertices and every c. */
void prt_pose_exact_transfer_avx2(const prt_pose_exact_job* job, uint32_t count, float* out,
                                  size_t out_stride);
/* Writes 3 * count floats; reads exactly the count rows of values. */
void prt_pose_shade_avx2(const prt_pose_shade_job* job, uint32_t count, float* out_rgb);
/* Writes job->width floats at out + v * out_stride for each of the count vertices. */
void prt_pose_transfer_avx2(const prt_pose_transfer_job* job, uint32_t count, float* out);
#endif

#endif /* PRT_POSE_SIMD_H */
