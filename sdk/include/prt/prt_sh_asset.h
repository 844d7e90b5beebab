/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the `sh` technique's per-vertex transfer (section SHTR, formats/SPEC.md)
 * and its shading on the CPU, SIMD and GL backends. C99 and C++.
 *
 * An `sh` asset stores, per vertex, a quantised transfer vector of order^2 coefficients per
 * channel (1 grey or 3 RGB). The SHTR header is decoded and checked against the section's size
 * once, when the asset is loaded (a header that does not fit fails the load), so these functions
 * read what the load kept. The CPU-side functions never allocate and keep no state, and since an
 * asset is immutable after loading, any of them may be called on the same asset from several
 * threads at once (e.g. disjoint vertex ranges of one frame shaded by a job system). Only full
 * validation checks the offsets and scales for NaN. */
#ifndef PRT_SH_ASSET_H
#define PRT_SH_ASSET_H

#include <prt/prt_asset.h>
#include <prt/prt_gl.h>
#include <prt/prt_types.h>
#include <prt/prt_workers.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The `sh` transfer section (technique PRT_TECHNIQUE_SH, element = vertex). */
#define PRT_SECTION_SHTR PRT_TAG('S', 'H', 'T', 'R')

/* What the baker integrated (informational: shading is the same for every kind). */
typedef enum prt_sh_transfer_kind {
  PRT_SH_TRANSFER_UNSHADOWED = 0,
  PRT_SH_TRANSFER_SHADOWED = 1,
  PRT_SH_TRANSFER_INTERREFLECTED = 2
} prt_sh_transfer_kind;

/* The SHTR header fields (formats/SPEC.md). */
typedef struct prt_sh_info {
  size_t struct_size; /* set by the caller: sizeof(prt_sh_info) */
  uint32_t order;     /* 1..PRT_SH_MAX_ORDER: order^2 coefficients per channel */
  uint32_t vertex_count;
  uint32_t channels;         /* 1 grey, 3 RGB */
  uint32_t bits;             /* 8 or 16 per stored value */
  prt_sh_transfer_kind kind; /* informational; a newer baker may write a value not listed */
  uint32_t bounces;          /* informational */
} prt_sh_info;

/* PRT_ERROR_NOT_FOUND when the asset has no SHTR section; PRT_ERROR_INVALID_ARGUMENT for NULL
 * pointers or a struct_size below 1.0's. */
PRT_API prt_result prt_sh_get_info(const prt_asset* asset, prt_sh_info* out_info);

/* Dequantised transfer of vertices [first, first+count): count*channels*order² floats,
 * vertex-major as stored. For tools and tests. */
PRT_API prt_result prt_sh_decode_transfer(const prt_asset* asset, uint32_t first_vertex,
                                          uint32_t vertex_count, float* out);

/* Shades vertices [first, first+count) under light (order² RGB coefficients, coefficient-major,
 * the asset's order; e.g. prt_sh_project's output) into out_rgb (count*3 floats):
 *   PRT_BACKEND_AUTO : the context's best CPU-side backend (prt_context_backend: SIMD when
 *                      usable, else CPU), the context being the asset's;
 *   PRT_BACKEND_CPU  : the scalar reference, summed in double;
 *   PRT_BACKEND_SIMD : SSE4.1 or AVX2+FMA kernels (the context's ISA, picked at run time); sums
 *                      in float, so results differ from the reference by rounding only (the
 *                      conformance test states the tolerance);
 *   PRT_BACKEND_GL   : PRT_ERROR_UNSUPPORTED_BACKEND: GL shading needs the game's GL context
 *                      and runs through a prt_gl_sh_shader (below).
 * Returns PRT_ERROR_UNSUPPORTED_BACKEND when the backend is not usable in the asset's context
 * (compiled out, CPU without SSE4.1, or limited away), PRT_ERROR_NOT_FOUND without an SHTR
 * section, PRT_ERROR_INVALID_ARGUMENT for bad pointers, ranges or backend values. Disjoint or
 * overlapping vertex ranges of one asset may be shaded from several threads at once. */
PRT_API prt_result prt_sh_shade(const prt_asset* asset, prt_backend backend, const float* light_rgb,
                                uint32_t first_vertex, uint32_t vertex_count, float* out_rgb);

/* prt_sh_shade of vertices [first, first+count) split over the pool's threads in contiguous
 * chunks (prt_workers.h): bitwise the one-range call's result. Returns the failing result of the
 * lowest failing chunk (an empty chunk checks its arguments as the one-range call does), or
 * PRT_ERROR_INVALID_ARGUMENT for NULL workers or asset. The pool is busy until it returns. */
PRT_API prt_result prt_sh_shade_workers(prt_workers* workers, const prt_asset* asset,
                                        prt_backend backend, const float* light_rgb,
                                        uint32_t first_vertex, uint32_t vertex_count,
                                        float* out_rgb);

/* ---- GL (prt_gl.h: loader, thread and GL state contract) --------------------------------------
 *
 * The quantised transfer is uploaded as stored (8/16-bit values packed in uint words); each
 * shade call folds the dequantisation into the light on the CPU (3 order² weights plus a
 * constant, a uniform block) and one compute invocation per vertex sums in float. Results match
 * the scalar reference up to float rounding: |x - reference| <= 2 g S, with g = n u / (1 - n u),
 * n = order² + 8, u = 2^-24 and S = sum_j (|offset_j| + |scale_j q_j|) |L_j| (the bound the
 * conformance test holds every backend to). GL state touched: the current program, the generic
 * GL_SHADER_STORAGE_BUFFER binding, the indexed GL_SHADER_STORAGE_BUFFER bindings 0 and 2 and
 * the indexed GL_UNIFORM_BUFFER binding 0, all left 0 afterwards. */

/* GPU-side `sh` shading of one asset: the quantised transfer uploaded once, shaded per frame. */
typedef struct prt_gl_sh_shader prt_gl_sh_shader;

/* Uploads the asset's SHTR data to GL buffers and compiles the compute shader. `context` is the
 * calling thread's context: failures are recorded there (the asset may belong to another
 * context) and its backend limit decides whether GL may be used. The asset must outlive the
 * shader; the shader is allocated with the asset's allocator. GL errors the application left
 * pending are cleared (glGetError) before the upload is checked.
 * PRT_ERROR_INVALID_ARGUMENT for NULL pointers; PRT_ERROR_NOT_FOUND without an SHTR section;
 * PRT_ERROR_UNSUPPORTED_BACKEND when GL is compiled out, limited away by the context, an entry
 * point is missing (the message names it), the GL context is older than 4.3, the shader does
 * not compile (the message quotes the log), or the asset's buffers exceed
 * GL_MAX_SHADER_STORAGE_BLOCK_SIZE; PRT_ERROR_OUT_OF_MEMORY when the allocator or GL runs out. */
PRT_API prt_result prt_gl_sh_create(prt_context* context, const prt_asset* asset,
                                    prt_gl_loader_fn loader, void* loader_user,
                                    prt_gl_sh_shader** out_shader);

/* Deletes the GL objects and frees the shader; NULL is ignored. Needs the GL context current. */
PRT_API void prt_gl_sh_destroy(prt_gl_sh_shader* shader);

/* Shades vertices [first, first+count) under light (order² RGB coefficients, coefficient-major,
 * as prt_sh_shade) into the same vertices of the output buffer (other vertices keep their
 * values). Returns once the work is queued (no CPU wait); a memory barrier is issued so that
 * vertex fetch, shaders and buffer reads see the result. Writes no context: PRT_OK, or
 * PRT_ERROR_INVALID_ARGUMENT for a NULL shader or light or a range outside the asset (nothing
 * is issued to GL then). */
PRT_API prt_result prt_gl_sh_shade(prt_gl_sh_shader* shader, const float* light_rgb,
                                   uint32_t first_vertex, uint32_t vertex_count);

/* The GL name of the output buffer: one tightly packed RGB float triple per vertex of the asset
 * (12-byte stride, vertex v at byte 12 v), usable directly as a vertex attribute buffer. Owned
 * by the shader; 0 for NULL. */
PRT_API uint32_t prt_gl_sh_output_buffer(const prt_gl_sh_shader* shader);

/* Reads shaded RGB of vertices [first, first+count) back to the CPU (waits for the GPU):
 * count*3 floats. For tools and tests; a game normally renders from the output buffer. Writes no
 * context: PRT_OK, or PRT_ERROR_INVALID_ARGUMENT for a NULL shader, a NULL out_rgb with count > 0
 * or a range outside the asset. */
PRT_API prt_result prt_gl_sh_read(prt_gl_sh_shader* shader, uint32_t first_vertex,
                                  uint32_t vertex_count, float* out_rgb);

#ifdef __cplusplus
}
#endif

#endif /* PRT_SH_ASSET_H */
