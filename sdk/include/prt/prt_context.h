/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: version query and the context (allocator, messages, last error,
 * backend limits). C99 and C++.
 *
 * Thread safety: prt_get_version*() and prt_result_string() may be called from any thread.
 * A context may be used by one thread at a time: every function that takes a non-const
 * prt_context* (including loading and validation) records its failure in the context. Functions
 * taking a const prt_context* only read it and may run concurrently with each other. Distinct
 * contexts are independent; the runtime has no global mutable state. */
#ifndef PRT_CONTEXT_H
#define PRT_CONTEXT_H

#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The library's version, PRT_VERSION of the headers it was built with (prt_version.h). */
PRT_API uint32_t prt_get_version(void);
/* The library's PRT_VERSION_STRING, e.g. "0.1.0". */
PRT_API const char* prt_get_version_string(void);

/* Bits of prt_context_desc.flags. */
typedef enum prt_context_flag {
  /* Let the environment variables PRT_BACKEND=cpu|simd|gl and
   * PRT_SIMD_ISA=none|sse4.1|avx2|avx512 lower the backend limits below. Off by default, so
   * that a shipping game's backend does not depend on its players' environment; tools and
   * samples set it, so that a user can force a lower backend without a rebuild. An unknown value
   * is reported as a warning and ignored. */
  PRT_CONTEXT_READ_ENVIRONMENT = 0x1
} prt_context_flag;

/* How to create a context. A zero-initialised struct with struct_size set gives the defaults. */
typedef struct prt_context_desc {
  size_t struct_size; /* set by the caller: sizeof(prt_context_desc) */
  /* Allocator for everything the context and its assets allocate; copied. NULL: malloc/free.
   * Its alloc and free must both be set. */
  const prt_allocator* allocator;
  /* Message callback and its user pointer; NULL: messages are only recorded, never printed. */
  prt_message_fn message;
  void* message_user;
  /* Highest backend this context may use (tests use this to force a lower one). AUTO: no limit.
   * With PRT_CONTEXT_READ_ENVIRONMENT, PRT_BACKEND lowers it further. */
  prt_backend backend_limit;
  /* Highest SIMD instruction set the SIMD backend may use. AUTO: no limit.
   * With PRT_CONTEXT_READ_ENVIRONMENT, PRT_SIMD_ISA lowers it further. */
  prt_simd_isa simd_isa_limit;
  uint32_t flags; /* prt_context_flag bits */
} prt_context_desc;

/* Creates a context. desc may be NULL (defaults). On success *out_context receives it; on
 * failure *out_context is NULL.
 * Returns PRT_ERROR_INVALID_ARGUMENT (out_context NULL, a struct_size below 1.0's, an allocator
 * with a NULL function, an unknown limit value or flag) or PRT_ERROR_OUT_OF_MEMORY. */
PRT_API prt_result prt_context_create(const prt_context_desc* desc, prt_context** out_context);

/* Destroys a context. NULL is allowed. Every asset created with it must be destroyed first. */
PRT_API void prt_context_destroy(prt_context* context);

/* The result of the last failed call on this context (PRT_OK if none since creation or the last
 * prt_context_clear_error()). Successful calls do not reset it. */
PRT_API prt_result prt_context_last_result(const prt_context* context);

/* The message of that failure, "" if none. Valid until the next call on this context. */
PRT_API const char* prt_context_last_message(const prt_context* context);

/* Forgets the last failure. */
PRT_API void prt_context_clear_error(prt_context* context);

#ifdef __cplusplus
}
#endif

#endif /* PRT_CONTEXT_H */
