/* SPDX-License-Identifier: MIT */
/* `wavelet` shading split over a prt_workers pool: each chunk is a one-range prt_wavelet_shade. */
#include "../workers_internal.h"

typedef struct wavelet_workers_job {
  const prt_asset* asset;
  prt_backend backend;
  const float* prepared_rgba;
  const uint8_t* zero_blocks;
  uint32_t first_vertex;
  float* out_rgb;
} wavelet_workers_job;

static prt_result shade_chunk(void* user, uint32_t first, uint32_t count) {
  const wavelet_workers_job* job = (const wavelet_workers_job*)user;
  /* A NULL output stays NULL, so that the one-range call rejects it. */
  float* out = job->out_rgb ? job->out_rgb + (size_t)first * 3u : NULL;
  return prt_wavelet_shade(job->asset, job->backend, job->prepared_rgba, job->zero_blocks,
                           job->first_vertex + first, count, out);
}

prt_result prt_wavelet_shade_workers(prt_workers* workers, const prt_asset* asset,
                                     prt_backend backend, const float* prepared_rgba,
                                     const uint8_t* zero_blocks, uint32_t first_vertex,
                                     uint32_t vertex_count, float* out_rgb) {
  wavelet_workers_job job;
  if (!workers || !asset) return PRT_ERROR_INVALID_ARGUMENT;
  /* A range past the last index would wrap in the chunks' first vertex. */
  if (vertex_count > UINT32_MAX - first_vertex) return PRT_ERROR_INVALID_ARGUMENT;
  job.asset = asset;
  job.backend = backend;
  job.prepared_rgba = prepared_rgba;
  job.zero_blocks = zero_blocks;
  job.first_vertex = first_vertex;
  job.out_rgb = out_rgb;
  return prt_workers_run(workers, vertex_count, shade_chunk, &job);
}
