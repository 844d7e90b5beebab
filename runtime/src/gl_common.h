/* SPDX-License-Identifier: MIT */
/* Private to the runtime: what every GL backend (<t>_gl.c: sh, wavelet and pose's compute shaders,
 * cloth's full-screen draw) does the same way — checking the create call's arguments, loading the
 * entry points, checking the context, compiling the program, uploading little-endian words and
 * checking the upload. Only compiled with PRT_HAS_GL. Every function that can fail records the
 * failure in `context` with `function` (the public entry point, e.g. "prt_gl_sh_create") at the
 * start of the message. */
#ifndef PRT_RUNTIME_GL_COMMON_H
#define PRT_RUNTIME_GL_COMMON_H

#include "gl_functions.h"
#include "internal.h"

/* Fills every entry point of prt_gl_functions through the loader; returns the first missing
 * name, or NULL when all are there. */
const char* prt_gl_load_functions(prt_gl_loader_fn loader, void* user, prt_gl_functions* gl);

/* Loads the entry points and checks the version (4.3+): UNSUPPORTED_BACKEND naming the missing
 * entry point or the context's version. */
prt_result prt_gl_open(prt_context* context, const char* function, prt_gl_loader_fn loader,
                       void* user, prt_gl_functions* gl);

/* GL is allowed when the context's backend limit is AUTO (none) or GL. */
int prt_gl_allowed(const prt_context* context);

/* The checks every prt_gl_<t>_create starts with: a context, non-NULL asset, loader and
 * out_shader, GL allowed by the context, and the technique's section present (`tag` names it in
 * the message). PRT_OK with the technique's view in *out_view, or the failure recorded. */
prt_result prt_gl_check_create(prt_context* context, const char* function, const prt_asset* asset,
                               const void* loader, const void* out_shader, prt_technique technique,
                               const char* tag, const void** out_view);

/* Reads RGB floats of vertices [first, first+count) from the radiance SSBO `buffer` into out_rgb
 * after the writes that made them (prt_gl_<t>_read). */
void prt_gl_read_radiance(const prt_gl_functions* gl, prt_GLuint buffer, uint32_t first,
                          uint32_t count, float* out_rgb);

/* Every SSBO must fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE and stay below 4 GiB (the shaders index
 * with uint). `names` describes the buffers in the message. UNSUPPORTED_BACKEND otherwise. */
prt_result prt_gl_check_block_sizes(prt_context* context, const prt_gl_functions* gl,
                                    const char* function, const uint64_t* bytes,
                                    const char* const* names, int count);

/* Compiles sources (the #version line first) into a compute program; UNSUPPORTED_BACKEND
 * quoting the log when it does not compile or link. *out_program is set (possibly to a program
 * that failed to link, for the caller to delete) or 0. */
prt_result prt_gl_compile_compute(prt_context* context, const prt_gl_functions* gl,
                                  const char* function, const prt_GLchar* const* sources,
                                  int source_count, prt_GLuint* out_program);

/* Compiles a vertex and a fragment stage (each from its sources, the #version line first) into
 * a program, as prt_gl_compile_compute does: UNSUPPORTED_BACKEND quoting the log of the stage
 * that does not compile, or of the link. */
prt_result prt_gl_compile_draw(prt_context* context, const prt_gl_functions* gl,
                               const char* function, const prt_GLchar* const* vertex_sources,
                               int vertex_count, const prt_GLchar* const* fragment_sources,
                               int fragment_count, prt_GLuint* out_program);

/* Discards GL errors the application left pending, so that the next check is about our calls. */
void prt_gl_drain_errors(const prt_gl_functions* gl);

/* After buffer creation: OUT_OF_MEMORY for GL_OUT_OF_MEMORY, UNSUPPORTED_BACKEND for another
 * error, PRT_OK when GL reports none. */
prt_result prt_gl_check_upload(prt_context* context, const prt_gl_functions* gl,
                               const char* function, uint64_t bytes);

/* glBufferData of `bytes` (a multiple of 4) little-endian words into the buffer bound to
 * `target`, at `offset` when `sub` (glBufferSubData) — as they are on a little-endian host,
 * through a temporary word-by-word copy otherwise. */
prt_result prt_gl_upload_le_words(prt_context* context, const prt_allocator* allocator,
                                  const prt_gl_functions* gl, const char* function,
                                  prt_GLenum target, int sub, size_t offset, const uint8_t* data,
                                  size_t bytes);

#endif /* PRT_RUNTIME_GL_COMMON_H */
