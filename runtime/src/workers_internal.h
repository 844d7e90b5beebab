/* SPDX-License-Identifier: MIT */
/* Private to the runtime: how a technique's shade call runs on a prt_workers pool. */
#ifndef PRT_RUNTIME_WORKERS_INTERNAL_H
#define PRT_RUNTIME_WORKERS_INTERNAL_H

#include "internal.h"

/* One chunk of a split call: elements [first, first+count). */
typedef prt_result (*prt_workers_chunk_fn)(void* user, uint32_t first, uint32_t count);

/* Splits [0, count) into contiguous chunks, one per thread (the calling thread runs the first),
 * calls fn on every chunk, empty ones included (so argument checks fail as in a one-range call),
 * waits for all, and returns the failing result of the lowest chunk, else PRT_OK.
 * PRT_ERROR_INVALID_ARGUMENT for NULL workers or fn. */
prt_result prt_workers_run(prt_workers* workers, uint32_t count, prt_workers_chunk_fn fn,
                           void* user);

#endif /* PRT_RUNTIME_WORKERS_INTERNAL_H */
