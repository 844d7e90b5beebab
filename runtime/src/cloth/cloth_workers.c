/* SPDX-License-Identifier: MIT */
/* `cloth` shading split over a prt_workers pool: each chunk is a one-range prt_cloth_shade of the
 * same samples (the range indexes the caller's arrays), its output offset to the chunk. */
#include "../workers_internal.h"
#include "cloth_internal.h"

typedef struct cloth_workers_job {
  const prt_asset* asset;
  prt_backend backend;
  uint32_t fabric;
  const prt_cloth_params* params;
  const prt_cloth_light* light;
  const prt_cloth_settings* settings;
  const prt_cloth_pixels* pixels;
  uint32_t first;
  float* out_rgb;
} cloth_workers_job;

static prt_result shade_chunk(void* user, uint32_t first, uint32_t count) {
  const cloth_workers_job* job = (const cloth_workers_job*)user;
  /* A NULL output stays NULL, so that the one-range call rejects it. */
  float* out = job->out_rgb ? job->out_rgb + (size_t)first * 3u : NULL;
  return prt_cloth_shade(job->asset, job->backend, job->fabric, job->params, job->light,
                         job->settings, job->pixels, job->first + first, count, out);
}

prt_result prt_cloth_shade_workers(prt_workers* workers, const prt_asset* asset,
                                   prt_backend backend, uint32_t fabric,
                                   const prt_cloth_params* params, const prt_cloth_light* light,
                                   const prt_cloth_settings* settings,
                                   const prt_cloth_pixels* pixels, uint32_t first, uint32_t count,
                                   float* out_rgb) {
  cloth_workers_job job;
  if (!workers || !asset) return PRT_ERROR_INVALID_ARGUMENT;
  /* A range past the last index would wrap in the chunks' first sample. */
  if (count > UINT32_MAX - first) return PRT_ERROR_INVALID_ARGUMENT;
  job.asset = asset;
  job.backend = backend;
  job.fabric = fabric;
  job.params = params;
  job.light = light;
  job.settings = settings;
  job.pixels = pixels;
  job.first = first;
  job.out_rgb = out_rgb;
  return prt_workers_run(workers, count, shade_chunk, &job);
}
