/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: optional worker threads the runtime starts and owns, for a game without
 * a job system of its own. C99 and C++.
 *
 * A prt_workers pool splits one shade call's vertex range into contiguous chunks, one per
 * thread, the calling thread taking one of them; the results are bitwise those of the one-range
 * call. A game with its own job system should keep calling the one-range shade calls over its
 * own vertex ranges instead. A pool may be used by one thread at a time (its calls block until
 * every chunk is done); the assets it shades may be shaded elsewhere at the same time. */
#ifndef PRT_WORKERS_H
#define PRT_WORKERS_H

#include <prt/prt_context.h>
#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct prt_workers prt_workers;

/* How to create a pool. A zero-initialised struct with struct_size set gives the defaults. */
typedef struct prt_workers_desc {
  size_t struct_size;    /* set by the caller: sizeof(prt_workers_desc) */
  uint32_t thread_count; /* threads sharing a call, the caller's included; 0: one per core */
} prt_workers_desc;

/* Starts thread_count - 1 threads (the calling thread is the last one) waiting for work. The
 * pool is allocated with the context's allocator, and failures are recorded in the context,
 * which must outlive the pool. desc may be NULL (defaults). On failure *out_workers is NULL.
 * PRT_ERROR_INVALID_ARGUMENT (NULL context or out_workers, a struct_size below 1.0's),
 * PRT_ERROR_OUT_OF_MEMORY (the allocator, or a thread could not be started). */
PRT_API prt_result prt_workers_create(prt_context* context, const prt_workers_desc* desc,
                                      prt_workers** out_workers);

/* Stops and joins the threads and frees the pool; NULL is ignored. */
PRT_API void prt_workers_destroy(prt_workers* workers);

/* Threads sharing a call, the caller's included; 0 for NULL. */
PRT_API uint32_t prt_workers_thread_count(const prt_workers* workers);

#ifdef __cplusplus
}
#endif

#endif /* PRT_WORKERS_H */
