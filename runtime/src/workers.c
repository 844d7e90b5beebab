/* SPDX-License-Identifier: MIT */
/* Runtime-owned worker threads: a persistent pthreads pool. The only file with thread code, so
 * that another platform's threads replace this file alone. */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <unistd.h>

#include "workers_internal.h"

#define PRT_WORKERS_DESC_SIZE_1_0 PRT_SIZE_THROUGH(prt_workers_desc, thread_count)

/* A bound on "one per core", so that a misreported core count cannot exhaust memory. */
#define PRT_WORKERS_MAX_DEFAULT_THREADS 256u

typedef struct prt_worker {
  prt_workers* pool;
  uint32_t index; /* its chunk */
  pthread_t thread;
} prt_worker;

struct prt_workers {
  prt_context* context;
  prt_allocator allocator;
  uint32_t thread_count;
  prt_worker* workers; /* thread_count - 1 of them: chunks 1.. */
  prt_result* results; /* per chunk */
  pthread_mutex_t mutex;
  pthread_cond_t work_ready;
  pthread_cond_t work_done;
  /* The job, guarded by mutex: a new generation wakes the threads. */
  unsigned long generation;
  uint32_t pending; /* threads still running the job */
  int stopping;
  prt_workers_chunk_fn fn;
  void* user;
  uint32_t count;
};

static void chunk_range(const prt_workers* pool, uint32_t index, uint32_t* first, uint32_t* count) {
  uint64_t begin = (uint64_t)pool->count * index / pool->thread_count;
  uint64_t end = (uint64_t)pool->count * (index + 1u) / pool->thread_count;
  *first = (uint32_t)begin;
  *count = (uint32_t)(end - begin);
}

static void* worker_main(void* arg) {
  prt_worker* self = (prt_worker*)arg;
  prt_workers* pool = self->pool;
  unsigned long seen = 0;
  pthread_mutex_lock(&pool->mutex);
  for (;;) {
    uint32_t first, count;
    while (!pool->stopping && pool->generation == seen)
      pthread_cond_wait(&pool->work_ready, &pool->mutex);
    if (pool->stopping) break;
    seen = pool->generation;
    chunk_range(pool, self->index, &first, &count);
    pthread_mutex_unlock(&pool->mutex);
    pool->results[self->index] = pool->fn(pool->user, first, count);
    pthread_mutex_lock(&pool->mutex);
    if (--pool->pending == 0) pthread_cond_signal(&pool->work_done);
  }
  pthread_mutex_unlock(&pool->mutex);
  return NULL;
}

static uint32_t core_count(void) {
  long cores = sysconf(_SC_NPROCESSORS_ONLN);
  if (cores < 1) return 1;
  if ((unsigned long)cores > PRT_WORKERS_MAX_DEFAULT_THREADS)
    return PRT_WORKERS_MAX_DEFAULT_THREADS;
  return (uint32_t)cores;
}

/* Stops and joins the first `started` threads, then frees everything. */
static void release(prt_workers* pool, uint32_t started) {
  uint32_t i;
  size_t threads = pool->thread_count - 1u;
  pthread_mutex_lock(&pool->mutex);
  pool->stopping = 1;
  pthread_cond_broadcast(&pool->work_ready);
  pthread_mutex_unlock(&pool->mutex);
  for (i = 0; i < started; ++i) pthread_join(pool->workers[i].thread, NULL);
  pthread_cond_destroy(&pool->work_done);
  pthread_cond_destroy(&pool->work_ready);
  pthread_mutex_destroy(&pool->mutex);
  prt_internal_free(&pool->allocator, pool->workers, threads * sizeof *pool->workers);
  prt_internal_free(&pool->allocator, pool->results, pool->thread_count * sizeof *pool->results);
  prt_internal_free(&pool->allocator, pool, sizeof *pool);
}

prt_result prt_workers_create(prt_context* context, const prt_workers_desc* desc,
                              prt_workers** out_workers) {
  prt_workers* pool;
  uint32_t threads, i;
  if (out_workers) *out_workers = NULL;
  if (!context) return PRT_ERROR_INVALID_ARGUMENT;
  if (!out_workers)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_workers_create: out_workers is NULL");
  if (desc && !prt_internal_struct_size_ok(desc, PRT_WORKERS_DESC_SIZE_1_0))
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_workers_create: desc->struct_size %zu is below %zu",
                             desc->struct_size, (size_t)PRT_WORKERS_DESC_SIZE_1_0);
  threads = desc && desc->thread_count ? desc->thread_count : core_count();

  pool = (prt_workers*)prt_internal_alloc(&context->allocator, sizeof *pool, sizeof(void*));
  if (!pool)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "prt_workers_create: out of memory");
  memset(pool, 0, sizeof *pool);
  pool->context = context;
  pool->allocator = context->allocator;
  pool->thread_count = threads;
  pool->results = (prt_result*)prt_internal_alloc(&pool->allocator, threads * sizeof *pool->results,
                                                  sizeof(prt_result));
  pool->workers = (prt_worker*)prt_internal_alloc(
      &pool->allocator, (threads - 1u) * sizeof *pool->workers, sizeof(void*));
  if (!pool->results || !pool->workers) {
    prt_internal_free(&pool->allocator, pool->workers, (threads - 1u) * sizeof *pool->workers);
    prt_internal_free(&pool->allocator, pool->results, threads * sizeof *pool->results);
    prt_internal_free(&pool->allocator, pool, sizeof *pool);
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "prt_workers_create: out of memory");
  }
  /* Default attributes: these allocate nothing on the platforms built for and do not fail. */
  pthread_mutex_init(&pool->mutex, NULL);
  pthread_cond_init(&pool->work_ready, NULL);
  pthread_cond_init(&pool->work_done, NULL);
  for (i = 0; i + 1u < threads; ++i) {
    pool->workers[i].pool = pool;
    pool->workers[i].index = i + 1u;
    if (pthread_create(&pool->workers[i].thread, NULL, worker_main, &pool->workers[i]) != 0) {
      release(pool, i);
      return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY,
                               "prt_workers_create: could not start thread %u of %u", i + 2u,
                               threads);
    }
  }
  *out_workers = pool;
  return PRT_OK;
}

void prt_workers_destroy(prt_workers* workers) {
  if (workers) release(workers, workers->thread_count - 1u);
}

uint32_t prt_workers_thread_count(const prt_workers* workers) {
  return workers ? workers->thread_count : 0u;
}

prt_result prt_workers_run(prt_workers* workers, uint32_t count, prt_workers_chunk_fn fn,
                           void* user) {
  uint32_t first, chunk, i;
  if (!workers || !fn) return PRT_ERROR_INVALID_ARGUMENT;
  pthread_mutex_lock(&workers->mutex);
  workers->fn = fn;
  workers->user = user;
  workers->count = count;
  workers->pending = workers->thread_count - 1u;
  ++workers->generation;
  pthread_cond_broadcast(&workers->work_ready);
  pthread_mutex_unlock(&workers->mutex);

  chunk_range(workers, 0, &first, &chunk);
  workers->results[0] = fn(user, first, chunk);

  pthread_mutex_lock(&workers->mutex);
  while (workers->pending) pthread_cond_wait(&workers->work_done, &workers->mutex);
  pthread_mutex_unlock(&workers->mutex);
  for (i = 0; i < workers->thread_count; ++i)
    if (workers->results[i] != PRT_OK) return workers->results[i];
  return PRT_OK;
}
