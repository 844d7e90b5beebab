/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: which evaluation backends exist and which one a context uses.
 * C99 and C++.
 *
 * cpu  : the scalar reference, always compiled and usable.
 * simd : compiled unless the library was built with PRT_ENABLE_SIMD=OFF; usable when the CPU
 *        has SSE4.1 (AVX2 + FMA preferred, then AVX-512 F/BW/VL/VNNI where the OS saves its
 *        state), detected at run time.
 * gl   : compiled when built with PRT_ENABLE_GL=ON; then reported usable unless the context's
 *        backend limit excludes it, meaning "usable with the application's GL 4.3+ context":
 *        the runtime owns no GL context, so whether one exists is only known when the game creates
 *        a technique's GL shader (prt_gl_<t>_create, in prt_<t>_asset.h) with its loader. Never
 *        picked by AUTO.
 * A context's limits (prt_context_desc.backend_limit / simd_isa_limit, and with
 * PRT_CONTEXT_READ_ENVIRONMENT the environment variables PRT_BACKEND and PRT_SIMD_ISA) can force a
 * lower backend or instruction set.
 *
 * Thread safety: these functions only read the context and may be called concurrently. */
#ifndef PRT_BACKEND_H
#define PRT_BACKEND_H

#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct prt_backend_info {
  size_t struct_size; /* set by the caller: sizeof(prt_backend_info) */
  prt_backend backend;
  uint32_t compiled; /* 1 if built into this library */
  uint32_t usable;   /* 1 if compiled, supported here, and within the context's limits */
  prt_simd_isa isa;  /* SIMD: the instruction set the context would use; otherwise NONE */
  const char* name;  /* "cpu", "simd" or "gl" (static string) */
  const char* note;  /* why it is not usable, or which ISA it uses (static string) */
} prt_backend_info;

/* Describes `backend` (CPU, SIMD or GL) as seen by this context.
 * Returns PRT_ERROR_INVALID_ARGUMENT for a NULL pointer, a struct_size below 1.0's, or
 * PRT_BACKEND_AUTO / unknown values. */
PRT_API prt_result prt_backend_get_info(const prt_context* context, prt_backend backend,
                                        prt_backend_info* out_info);

/* The best usable backend of this context: SIMD if usable, else CPU. (GL is never picked
 * automatically: it needs the game's GL context.) */
PRT_API prt_backend prt_context_backend(const prt_context* context);

/* Name of a backend ("auto", "cpu", "simd", "gl"; "unknown" otherwise), static string. */
PRT_API const char* prt_backend_name(prt_backend backend);

/* Name of an instruction set ("auto", "none", "sse4.1", "avx2", "avx512"; "unknown"), static
 * string. */
PRT_API const char* prt_simd_isa_name(prt_simd_isa isa);

#ifdef __cplusplus
}
#endif

#endif /* PRT_BACKEND_H */
