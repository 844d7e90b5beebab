/* SPDX-License-Identifier: MIT */
/* A windowless OpenGL 4.3+ core context through EGL, for tests, benchmarks and headless samples
 * (Mesa llvmpipe on CI). C99 and C++. Not part of the runtime, which never links GL.
 *
 * Tried in order: the EGL_MESA_platform_surfaceless display, each EGL device
 * (EGL_EXT_platform_device), then the default display with a small pbuffer (without X this last
 * one needs EGL_PLATFORM=surfaceless); the environment variable HEADLESS_GL_PATH=surfaceless,
 * device or pbuffer restricts creation to that one way (for debugging). The context is made
 * current on the calling thread. Destroying one terminates its EGL display, so keep at most one
 * alive per display (normally one per process) and use it from one thread. */
#ifndef PRT_HEADLESS_GL_H
#define PRT_HEADLESS_GL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct headless_gl headless_gl;

/* Creates the context and makes it current. On failure returns NULL and, if error is not NULL,
 * writes a NUL-terminated reason (what each attempt gave) of at most error_capacity bytes. */
headless_gl* headless_gl_create(char* error, size_t error_capacity);

/* Releases and destroys the context; NULL is ignored. */
void headless_gl_destroy(headless_gl* gl);

/* A prt_gl_loader_fn (prt_gl.h): the address of a GL entry point, or NULL. `user` is unused
 * (pass the headless_gl* or NULL). */
void* headless_gl_get_proc(void* user, const char* name);

/* The GL_RENDERER string, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"; "" for NULL. */
const char* headless_gl_renderer(const headless_gl* gl);

#ifdef __cplusplus
}
#endif

#endif /* PRT_HEADLESS_GL_H */
