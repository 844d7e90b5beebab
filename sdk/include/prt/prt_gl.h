/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the OpenGL backend. C99 and C++.
 *
 * The runtime neither links an OpenGL library nor creates a context: the game hands over a loader
 * (e.g. a wrapper of eglGetProcAddress, glfwGetProcAddress or SDL_GL_GetProcAddress) and calls
 * these functions on a thread where its GL 4.3+ core context (compute shaders + SSBOs) is
 * current. Every function below issues GL calls and must be called with that context current;
 * none is thread-safe with respect to the same GL context. GL state changed by a call (the
 * current program, the generic GL_SHADER_STORAGE_BUFFER binding, the indexed
 * GL_SHADER_STORAGE_BUFFER bindings 0 and 2 and the indexed GL_UNIFORM_BUFFER binding 0) is left
 * unbound (0) afterwards; nothing else is touched.
 *
 * How it works: the quantised transfer is uploaded as stored (8/16-bit values packed in uint
 * words); each shade call folds the dequantisation into the light on the CPU (3 order² weights
 * plus a constant, a uniform block) and one compute invocation per vertex sums in float.
 * Results match the scalar reference up to float rounding: |x - reference| <= 2 g S, with
 * g = n u / (1 - n u), n = order² + 8, u = 2^-24 and S = sum_j (|offset_j| + |scale_j q_j|) |L_j|
 * (the bound the conformance test in tests/gl/ holds every backend to).
 *
 * Available when the library was built with PRT_ENABLE_GL=ON; otherwise every function returns
 * PRT_ERROR_UNSUPPORTED_BACKEND. Failures are recorded as the last error of the asset's context
 * (prt_context_last_message) and sent to its message callback. */
#ifndef PRT_GL_H
#define PRT_GL_H

#include <prt/prt_asset.h>
#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Returns the address of the GL entry point `name` (e.g. "glDispatchCompute"), or NULL. */
typedef void* (*prt_gl_loader_fn)(void* user, const char* name);

/* GPU-side `sh` shading of one asset: the quantised transfer uploaded once, shaded per frame. */
typedef struct prt_gl_sh_shader prt_gl_sh_shader;

/* Uploads the asset's SHTR data to GL buffers and compiles the compute shader. The asset must
 * outlive the shader; the shader is allocated with the asset's allocator. GL errors the
 * application left pending are cleared (glGetError) before the upload is checked.
 * PRT_ERROR_INVALID_ARGUMENT for NULL pointers; PRT_ERROR_NOT_FOUND without an SHTR section;
 * PRT_ERROR_UNSUPPORTED_BACKEND when GL is compiled out, limited away by the context, an entry
 * point is missing (the message names it), the context is older than 4.3, the shader does not
 * compile (the message quotes the log), or the asset's buffers exceed
 * GL_MAX_SHADER_STORAGE_BLOCK_SIZE; PRT_ERROR_OUT_OF_MEMORY when the allocator or GL runs out. */
PRT_API prt_result prt_gl_sh_create(const prt_asset* asset, prt_gl_loader_fn loader,
                                    void* loader_user, prt_gl_sh_shader** out_shader);

/* Deletes the GL objects and frees the shader; NULL is ignored. Needs the GL context current. */
PRT_API void prt_gl_sh_destroy(prt_gl_sh_shader* shader);

/* Shades vertices [first, first+count) under light (order² RGB coefficients, coefficient-major,
 * as prt_sh_shade) into the same vertices of the output buffer (other vertices keep their
 * values). Returns once the work is queued (no CPU wait); a memory barrier is issued so that
 * vertex fetch, shaders and buffer reads see the result. PRT_ERROR_INVALID_ARGUMENT for NULL
 * pointers or a range outside the asset. */
PRT_API prt_result prt_gl_sh_shade(prt_gl_sh_shader* shader, const float* light_rgb,
                                   uint32_t first_vertex, uint32_t vertex_count);

/* The GL name of the output buffer: one tightly packed RGB float triple per vertex of the asset
 * (12-byte stride, vertex v at byte 12 v), usable directly as a vertex attribute buffer. Owned
 * by the shader; 0 for NULL. */
PRT_API uint32_t prt_gl_sh_output_buffer(const prt_gl_sh_shader* shader);

/* Reads shaded RGB of vertices [first, first+count) back to the CPU (waits for the GPU):
 * count*3 floats. For tools and tests; a game normally renders from the output buffer. */
PRT_API prt_result prt_gl_sh_read(prt_gl_sh_shader* shader, uint32_t first_vertex,
                                  uint32_t vertex_count, float* out_rgb);

/* GPU-side `wavelet` shading of one asset: the sparse rows (WVLT, as stored) uploaded once, a
 * prepared light (prt_wavelet_prepare_light) uploaded and shaded per frame. Same contract as the
 * prt_gl_sh_* functions above, with PRT_ERROR_NOT_FOUND when the asset has no WVLT section. */
typedef struct prt_gl_wavelet_shader prt_gl_wavelet_shader;

PRT_API prt_result prt_gl_wavelet_create(const prt_asset* asset, prt_gl_loader_fn loader,
                                         void* loader_user, prt_gl_wavelet_shader** out_shader);
PRT_API void prt_gl_wavelet_destroy(prt_gl_wavelet_shader* shader);
/* prepared_rgba: the asset's coefficient_count RGBA quadruples (prt_wavelet_asset.h). */
PRT_API prt_result prt_gl_wavelet_shade(prt_gl_wavelet_shader* shader, const float* prepared_rgba,
                                        uint32_t first_vertex, uint32_t vertex_count);
PRT_API uint32_t prt_gl_wavelet_output_buffer(const prt_gl_wavelet_shader* shader);
PRT_API prt_result prt_gl_wavelet_read(prt_gl_wavelet_shader* shader, uint32_t first_vertex,
                                       uint32_t vertex_count, float* out_rgb);

#ifdef __cplusplus
}
#endif

#endif /* PRT_GL_H */
