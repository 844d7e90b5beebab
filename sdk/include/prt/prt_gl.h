/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the OpenGL backend. C99 and C++.
 *
 * The runtime neither links an OpenGL library nor creates a context: the game hands over a loader
 * (e.g. a wrapper of eglGetProcAddress, glfwGetProcAddress or SDL_GL_GetProcAddress) and calls
 * these functions on a thread where its GL 4.3+ core context (compute shaders + SSBOs) is
 * current. Every function below issues GL calls and must be called with that context current;
 * none is thread-safe with respect to the same GL context. GL state changed by a call (program,
 * SSBO bindings 0..3) is left unbound afterwards.
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
 * outlive the shader. PRT_ERROR_NOT_FOUND without an SHTR section; PRT_ERROR_UNSUPPORTED_BACKEND
 * when GL is compiled out, limited away by the context, a required entry point is missing or the
 * context is older than 4.3; PRT_ERROR_OUT_OF_MEMORY when the allocator or GL fails. */
PRT_API prt_result prt_gl_sh_create(const prt_asset* asset, prt_gl_loader_fn loader,
                                    void* loader_user, prt_gl_sh_shader** out_shader);

/* Deletes the GL objects and frees the shader; NULL is ignored. Needs the GL context current. */
PRT_API void prt_gl_sh_destroy(prt_gl_sh_shader* shader);

/* Shades vertices [first, first+count) under light (order² RGB coefficients, coefficient-major,
 * as prt_sh_shade) into the output buffer. Returns once the work is queued (no CPU wait). */
PRT_API prt_result prt_gl_sh_shade(prt_gl_sh_shader* shader, const float* light_rgb,
                                   uint32_t first_vertex, uint32_t vertex_count);

/* The GL name of the output buffer: vertex_count tightly packed RGB float triples (12-byte
 * stride, vertex v at byte 12 v), usable directly as a vertex attribute buffer. Owned by the
 * shader. */
PRT_API uint32_t prt_gl_sh_output_buffer(const prt_gl_sh_shader* shader);

/* Reads shaded RGB of vertices [first, first+count) back to the CPU (waits for the GPU):
 * count*3 floats. For tools and tests; a game normally renders from the output buffer. */
PRT_API prt_result prt_gl_sh_read(prt_gl_sh_shader* shader, uint32_t first_vertex,
                                  uint32_t vertex_count, float* out_rgb);

#ifdef __cplusplus
}
#endif

#endif /* PRT_GL_H */
