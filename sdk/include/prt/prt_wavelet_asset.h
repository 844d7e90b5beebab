/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the `wavelet` technique's sparse per-vertex transfer (section WVLT,
 * formats/SPEC.md §7.2 and §14). C99 and C++.
 *
 * A `wavelet` asset stores, per vertex, the Haar coefficients of its shadowed diffuse transfer
 * over a cube (or dual paraboloid), truncated and quantised to 8 bits. Per frame the game turns
 * its environment into a light (prt/prt_wavelet.h: resample -> transform -> select), folds the
 * asset's band scales into it once with prt_wavelet_prepare_light, and shades vertex ranges as
 * sparse dot products. Like the `sh` functions these never allocate and keep no state: an asset
 * is immutable after loading, so any of them may be called on the same asset from several
 * threads at once (e.g. disjoint vertex ranges of one frame shaded by a job system). At
 * PRT_VALIDATE_QUICK the rows have not been checked (counts, indices, values); the shading
 * functions still never read outside the section, but may return PRT_ERROR_CORRUPT part-way.
 * Load at PRT_VALIDATE_FULL to have every rule of §7.2 checked once. */
#ifndef PRT_WAVELET_ASSET_H
#define PRT_WAVELET_ASSET_H

#include <prt/prt_asset.h>
#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The WVLT header fields (formats/SPEC.md §7.2) and derived sizes. quantizer, keep and bounces
 * are informational. */
typedef struct prt_wavelet_info {
  uint32_t param;             /* PRT_WAVELET_PARAM_CUBE or PRT_WAVELET_PARAM_DUAL_PARABOLOID */
  uint32_t size;              /* face size S */
  uint32_t faces;             /* 6 or 2 */
  uint32_t coefficient_count; /* faces * S^2: the light's length in RGBA quadruples */
  uint32_t block_count;       /* 256-entry blocks per row */
  uint32_t vertex_count;
  uint32_t quantizer; /* 0 one scale per vertex, 1 one scale per face and level */
  uint32_t keep;      /* most non-zeros kept per vertex */
  uint32_t bounces;
  uint32_t pair_count; /* stored non-zeros, all vertices */
} prt_wavelet_info;

/* PRT_ERROR_NOT_FOUND when the asset has no WVLT section, PRT_ERROR_CORRUPT for a bad header. */
PRT_API prt_result prt_wavelet_get_info(const prt_asset* asset, prt_wavelet_info* out);

/* Dequantised transfer of one vertex as a dense row: coefficient_count RGB triples
 * (coefficient-major, t[j][c] of §7.2), zeros where nothing is stored. For tools and tests. */
PRT_API prt_result prt_wavelet_decode_row(const prt_asset* asset, uint32_t vertex, float* out_rgb);

/* Folds the asset's band scales into a selected light (prt_wavelet_select_light's output, the
 * asset's param and size): out_rgba[j] = light_rgba[j] * bs[band(j)]. The 4th float is 0, except
 * that of each 256-coefficient block's first coefficient when the block's RGB is all zero: there
 * it is a marker (a NaN with a fixed payload), and shading skips the block's stored pairs (they
 * would add exactly 0), so the time follows the blocks the M selected coefficients touch. A light
 * prepared otherwise (any other 4th float) shades the same, only without skipping. light_rgba and
 * out_rgba may be the same array. */
PRT_API prt_result prt_wavelet_prepare_light(const prt_asset* asset, const float* light_rgba,
                                             float* out_rgba);

/* Scalar reference shading of vertices [first, first+count) under a prepared light:
 * out_rgb[v] = vs[v] * sum over stored pairs of q * prepared[j] (§7.2), count*3 floats. */
PRT_API prt_result prt_wavelet_shade(const prt_asset* asset, const float* prepared_rgba,
                                     uint32_t first_vertex, uint32_t vertex_count, float* out_rgb);

/* prt_wavelet_shade on a CPU-side backend of the asset's context, exactly as prt_sh_shade_on:
 * AUTO = the context's best, CPU = the scalar reference, SIMD = SSE4.1 or AVX2 kernels (float
 * sums in another order: rounding differences only), GL = not here (prt_gl.h). Returns
 * PRT_ERROR_UNSUPPORTED_BACKEND when the backend is not usable in the context. */
PRT_API prt_result prt_wavelet_shade_on(const prt_asset* asset, prt_backend backend,
                                        const float* prepared_rgba, uint32_t first_vertex,
                                        uint32_t vertex_count, float* out_rgb);

#ifdef __cplusplus
}
#endif

#endif /* PRT_WAVELET_ASSET_H */
