/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: what every technique's OpenGL backend shares. C99 and C++.
 *
 * The runtime neither links an OpenGL library nor creates a GL context: the game hands over a
 * loader (e.g. a wrapper of eglGetProcAddress, glfwGetProcAddress or SDL_GL_GetProcAddress) and
 * calls a technique's GL functions (prt_gl_<t>_*, declared in prt_<t>_asset.h) on a thread where
 * its GL 4.3+ core context is current (sh, wavelet and pose use compute shaders + SSBOs, cloth a
 * fragment shader). Every such function issues GL calls and must be called with that context
 * current; none is thread-safe with respect to the same GL context. The GL state a call changes is listed by its technique and left unbound (0)
 * afterwards; nothing else is touched.
 *
 * Contexts: prt_gl_<t>_create takes the prt_context of the calling thread (one thread at a time
 * per context, prt_context.h) and records its failures there. The per-frame calls (shade, read,
 * output buffer, destroy) write no prt_context at all and report through their result only, so
 * they may run on the render thread while other threads use the asset's context.
 *
 * Available when the library was built with PRT_ENABLE_GL=ON; otherwise every create function
 * returns PRT_ERROR_UNSUPPORTED_BACKEND. */
#ifndef PRT_GL_H
#define PRT_GL_H

#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Returns the address of the GL entry point `name` (e.g. "glDispatchCompute"), or NULL. */
typedef void* (*prt_gl_loader_fn)(void* user, const char* name);

#ifdef __cplusplus
}
#endif

#endif /* PRT_GL_H */
