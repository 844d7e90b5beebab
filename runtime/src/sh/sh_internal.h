/* SPDX-License-Identifier: MIT */
/* Helpers shared by the runtime's SH files (not public). */
#ifndef PRT_RUNTIME_SH_INTERNAL_H
#define PRT_RUNTIME_SH_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "internal.h"

#define PRT_SH_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_sh_info, bounces)

/* The SHTR section of a loaded asset, decoded and checked once at load (sh_section.c, with the
 * formats layer's prt_blob_shtr_layout_of): reads at the offsets below stay inside the section
 * whatever the validation level. */
typedef struct prt_sh_view {
  prt_sh_info info;
  uint32_t coefficients; /* channels * order^2 per vertex */
  const uint8_t* params; /* (offset, scale) f32 pairs, `coefficients` of them */
  const uint8_t* values; /* u8 or u16 [vertex_count][coefficients] */
  size_t value_bytes;    /* vertex_count * coefficients * bits / 8 */
} prt_sh_view;

/* All order*order basis values at a unit direction given in the SH frame (x_sh, y_sh, z_sh),
 * in double. order must be 1..PRT_SH_MAX_ORDER. */
void prt_sh_eval_sh_frame_d(uint32_t order, double x, double y, double z, double* out);

/* Normalises a world direction and maps it to the SH frame; returns 0 for a zero or
 * non-finite vector. */
int prt_sh_world_to_sh_frame(const float dir[3], double sh_dir[3]);

/* Folds a light (order² RGB coefficients, coefficient-major) into an SHTR section's
 * quantisation (params = its (offset, scale) f32 pairs), so that shading is
 *   radiance[ch] = bias[ch] + sum_k q[c(ch) order² + k] * weight[ch * weight_stride + k]
 * with weight = scale * L (float) and bias = sum_k offset * L (summed in double, rounded as the
 * hardware does, overflow to infinity); c(ch) = ch for RGB transfer, 0 for grey. Weights from k =
 * order² up to `padded` are zero. Used by the SIMD and GL backends (sh_asset.c). */
void prt_sh_fold_light(const uint8_t* params, uint32_t order, uint32_t channels,
                       const float* light_rgb, uint32_t padded, float* weight, size_t weight_stride,
                       float bias[3]);

#endif /* PRT_RUNTIME_SH_INTERNAL_H */
