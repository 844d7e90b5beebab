/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the `wavelet` technique's sparse per-vertex transfer (section WVLT,
 * formats/SPEC.md §7.2 and §14) and its shading on the CPU, SIMD and GL backends. C99 and C++.
 *
 * A `wavelet` asset stores, per vertex, the Haar coefficients of its shadowed diffuse transfer
 * over a cube (or dual paraboloid), truncated and quantised to 8 bits. Per frame the game turns
 * its environment into a light (prt/prt_wavelet.h: resample -> transform -> select), folds the
 * asset's band scales into it once with prt_wavelet_prepare_light, and shades vertex ranges as
 * sparse dot products. The WVLT header is decoded and checked against the section's size once,
 * when the asset is loaded (a header that does not fit fails the load). Like the `sh` functions
 * the CPU-side ones never allocate and keep no state: an asset is immutable after loading, so
 * any of them may be called on the same asset from several threads at once (e.g. disjoint vertex
 * ranges of one frame shaded by a job system). At PRT_VALIDATE_QUICK the rows have not been
 * checked (counts, indices, values); the shading functions still never read outside the section,
 * but may return PRT_ERROR_CORRUPT part-way. Load at PRT_VALIDATE_FULL to have every rule of
 * §7.2 checked once. */
#ifndef PRT_WAVELET_ASSET_H
#define PRT_WAVELET_ASSET_H

#include <prt/prt_asset.h>
#include <prt/prt_gl.h>
#include <prt/prt_types.h>
#include <prt/prt_wavelet.h>
#include <prt/prt_workers.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The `wavelet` transfer section (technique PRT_TECHNIQUE_WAVELET, element = vertex). */
#define PRT_SECTION_WVLT PRT_TAG('W', 'V', 'L', 'T')

/* How the baker quantised the rows (informational: shading is the same for both). */
typedef enum prt_wavelet_quantizer {
  PRT_WAVELET_QUANTIZER_VERTEX = 0, /* one scale per vertex */
  PRT_WAVELET_QUANTIZER_BAND = 1    /* one scale per face and level */
} prt_wavelet_quantizer;

/* The WVLT header fields (formats/SPEC.md §7.2) and derived sizes. quantizer, keep and bounces
 * are informational. */
typedef struct prt_wavelet_info {
  size_t struct_size; /* set by the caller: sizeof(prt_wavelet_info) */
  prt_wavelet_param param;
  uint32_t size;              /* face size S */
  uint32_t faces;             /* 6 or 2 */
  uint32_t coefficient_count; /* faces * S^2: the light's length in RGBA quadruples */
  uint32_t block_count;       /* 256-coefficient blocks per row: the zero-block mask's length */
  uint32_t vertex_count;
  prt_wavelet_quantizer quantizer;
  uint32_t keep; /* most non-zeros kept per vertex */
  uint32_t bounces;
  uint32_t pair_count; /* stored non-zeros, all vertices */
} prt_wavelet_info;

/* PRT_ERROR_NOT_FOUND when the asset has no WVLT section; PRT_ERROR_INVALID_ARGUMENT for NULL
 * pointers or a struct_size below 1.0's. */
PRT_API prt_result prt_wavelet_get_info(const prt_asset* asset, prt_wavelet_info* out_info);

/* Dequantised transfer of vertices [first, first+count) as dense rows: per vertex,
 * coefficient_count RGB triples (coefficient-major, t[j][c] of §7.2), zeros where nothing is
 * stored; count * coefficient_count * 3 floats. For tools and tests. */
PRT_API prt_result prt_wavelet_decode_transfer(const prt_asset* asset, uint32_t first_vertex,
                                               uint32_t vertex_count, float* out_rgb);

/* Folds the asset's band scales into a selected light (prt_wavelet_select_light's output, the
 * asset's param and size): out_rgba[j] = light_rgba[j] * bs[band(j)], the 4th float written 0
 * (plain padding, never read). out_zero_blocks (may be NULL) receives block_count bytes, 1 where
 * the block's 256 prepared coefficients are all zero in RGB, else 0: handed to the shading, it
 * lets the shading skip those blocks' stored pairs (they would add exactly 0), so the time
 * follows the blocks the M selected coefficients touch. light_rgba and out_rgba may be the same
 * array. */
PRT_API prt_result prt_wavelet_prepare_light(const prt_asset* asset, const float* light_rgba,
                                             float* out_rgba, uint8_t* out_zero_blocks);

/* Shades vertices [first, first+count) under a prepared light into out_rgb (count*3 floats):
 * out_rgb[v] = vs[v] * sum over stored pairs of q * prepared[j] (§7.2). zero_blocks: NULL, or
 * block_count bytes of which every non-zero one skips its block's pairs (prepare_light's mask;
 * a block marked although its light is not zero drops out of the sum). Backends as prt_sh_shade:
 *   PRT_BACKEND_AUTO : the asset's context's best CPU-side backend (SIMD when usable, else CPU);
 *   PRT_BACKEND_CPU  : the scalar reference (float sums in stored order);
 *   PRT_BACKEND_SIMD : SSE4.1 or AVX2 kernels (float sums in another order: rounding only);
 *   PRT_BACKEND_GL   : PRT_ERROR_UNSUPPORTED_BACKEND: use a prt_gl_wavelet_shader (below).
 * Returns PRT_ERROR_UNSUPPORTED_BACKEND when the backend is not usable in the context,
 * PRT_ERROR_NOT_FOUND without a WVLT section, PRT_ERROR_INVALID_ARGUMENT for bad pointers,
 * ranges or backend values, PRT_ERROR_CORRUPT at a malformed row (quick validation only). */
PRT_API prt_result prt_wavelet_shade(const prt_asset* asset, prt_backend backend,
                                     const float* prepared_rgba, const uint8_t* zero_blocks,
                                     uint32_t first_vertex, uint32_t vertex_count, float* out_rgb);

/* prt_wavelet_shade split over the pool's threads, as prt_sh_shade_workers (prt_sh_asset.h). */
PRT_API prt_result prt_wavelet_shade_workers(prt_workers* workers, const prt_asset* asset,
                                             prt_backend backend, const float* prepared_rgba,
                                             const uint8_t* zero_blocks, uint32_t first_vertex,
                                             uint32_t vertex_count, float* out_rgb);

/* ---- GL (prt_gl.h: loader, thread and GL state contract) --------------------------------------
 *
 * GPU-side `wavelet` shading of one asset: the sparse rows (WVLT, as stored) uploaded once, a
 * prepared light uploaded and shaded per frame by one work group per vertex. The GL shader walks
 * every stored pair: it takes no zero-block mask (the pairs of a zero block add exactly 0).
 * Results match the scalar reference up to float rounding (the conformance test's bound,
 * gamma_(pairs+4) * sum_j |q bs vs L|, doubled). GL state touched: the current program, the
 * generic GL_SHADER_STORAGE_BUFFER binding and the indexed GL_SHADER_STORAGE_BUFFER bindings 0
 * and 2, all left 0 afterwards. Every read of the shader is clamped to its array, so the rows of
 * a quick-validated asset give wrong sums at worst, never reads outside the buffer. */

typedef struct prt_gl_wavelet_shader prt_gl_wavelet_shader;

/* As prt_gl_sh_create (prt_sh_asset.h), with PRT_ERROR_NOT_FOUND when the asset has no WVLT
 * section. */
PRT_API prt_result prt_gl_wavelet_create(prt_context* context, const prt_asset* asset,
                                         prt_gl_loader_fn loader, void* loader_user,
                                         prt_gl_wavelet_shader** out_shader);
PRT_API void prt_gl_wavelet_destroy(prt_gl_wavelet_shader* shader);

/* prepared_rgba: the asset's coefficient_count RGBA quadruples (prt_wavelet_prepare_light).
 * Writes no context: PRT_OK, or PRT_ERROR_INVALID_ARGUMENT for a NULL shader or light or a range
 * outside the asset (nothing is issued to GL then). */
PRT_API prt_result prt_gl_wavelet_shade(prt_gl_wavelet_shader* shader, const float* prepared_rgba,
                                        uint32_t first_vertex, uint32_t vertex_count);

/* The output buffer, as prt_gl_sh_output_buffer. */
PRT_API uint32_t prt_gl_wavelet_output_buffer(const prt_gl_wavelet_shader* shader);

/* As prt_gl_sh_read: PRT_OK, or PRT_ERROR_INVALID_ARGUMENT; writes no context. */
PRT_API prt_result prt_gl_wavelet_read(prt_gl_wavelet_shader* shader, uint32_t first_vertex,
                                       uint32_t vertex_count, float* out_rgb);

#ifdef __cplusplus
}
#endif

#endif /* PRT_WAVELET_ASSET_H */
