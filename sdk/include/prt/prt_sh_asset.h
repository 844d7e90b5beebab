/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the `sh` technique's per-vertex transfer (section SHTR, formats/SPEC.md).
 * C99 and C++.
 *
 * An `sh` asset stores, per vertex, a quantised transfer vector of order^2 coefficients per
 * channel (1 grey or 3 RGB). These functions read it from a loaded asset: they never allocate
 * and keep no state, and since an asset is immutable after loading, any of them may be called
 * on the same asset from several threads at once (e.g. disjoint vertex ranges of one frame
 * shaded by a job system). An asset loaded at PRT_VALIDATE_QUICK has not had its SHTR header
 * checked against the section size; these functions still check it before reading (returning
 * PRT_ERROR_CORRUPT), but only full validation checks offsets/scales for NaN. */
#ifndef PRT_SH_ASSET_H
#define PRT_SH_ASSET_H

#include <prt/prt_asset.h>
#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The SHTR header fields (formats/SPEC.md): kind 0 unshadowed, 1 shadowed, 2 interreflected;
 * kind and bounces are informational. */
typedef struct prt_sh_transfer_info {
  uint32_t order, vertex_count, channels, bits, kind, bounces;
} prt_sh_transfer_info;

/* PRT_ERROR_NOT_FOUND when the asset has no SHTR section. */
PRT_API prt_result prt_sh_get_transfer_info(const prt_asset* asset, prt_sh_transfer_info* out);

/* Dequantised transfer of vertices [first, first+count): count*channels*order² floats,
 * vertex-major as stored. */
PRT_API prt_result prt_sh_decode_transfer(const prt_asset* asset, uint32_t first_vertex,
                                          uint32_t vertex_count, float* out);

/* Scalar reference shading of vertices [first, first+count) under light (order² RGB
 * coefficients, coefficient-major, the asset's order): out = count*3 floats. Vertex ranges
 * may be shaded concurrently from several threads (the asset is immutable). */
PRT_API prt_result prt_sh_shade(const prt_asset* asset, const float* light_rgb,
                                uint32_t first_vertex, uint32_t vertex_count, float* out_rgb);

/* Shades vertices [first, first+count) like prt_sh_shade, on a CPU-side backend of the asset's
 * context:
 *   PRT_BACKEND_AUTO : the context's best (prt_context_backend: SIMD when usable, else CPU);
 *   PRT_BACKEND_CPU  : the scalar reference (prt_sh_shade);
 *   PRT_BACKEND_SIMD : SSE4.1 or AVX2+FMA kernels (the context's ISA, picked at run time); sums
 *                      in float, so results differ from the reference by rounding only (the
 *                      conformance test states the tolerance);
 *   PRT_BACKEND_GL   : not here (it needs the game's GL context): see prt_gl.h.
 * Returns PRT_ERROR_UNSUPPORTED_BACKEND when the backend is not usable in the asset's context
 * (compiled out, CPU without SSE4.1, or limited away), PRT_ERROR_INVALID_ARGUMENT for bad
 * pointers, ranges or backend values. Thread safety as prt_sh_shade: disjoint or overlapping
 * vertex ranges of one asset may be shaded from several threads at once. */
PRT_API prt_result prt_sh_shade_on(const prt_asset* asset, prt_backend backend,
                                   const float* light_rgb, uint32_t first_vertex,
                                   uint32_t vertex_count, float* out_rgb);

#ifdef __cplusplus
}
#endif

#endif /* PRT_SH_ASSET_H */
