/* SPDX-License-Identifier: MIT */
/* `pose` shading split over a prt_workers pool: each chunk is a one-range prt_pose_shade, with
 * the caller's normals (if any) offset to the chunk. */
#include "../workers_internal.h"
#include "pose_internal.h"

typedef struct pose_workers_job {
  const prt_asset* asset;
  prt_backend backend;
  const prt_pose_input* pose;
  const prt_pose_light* light;
  uint32_t first_vertex;
  float* out_rgb;
} pose_workers_job;

static prt_result shade_chunk(void* user, uint32_t first, uint32_t count) {
  const pose_workers_job* job = (const pose_workers_job*)user;
  /* A NULL output or light stays NULL, so that the one-range call rejects it. */
  float* out = job->out_rgb ? job->out_rgb + (size_t)first * 3u : NULL;
  prt_pose_light light;
  if (!job->light || !prt_internal_struct_size_ok(job->light, PRT_POSE_LIGHT_SIZE_1_0) ||
      !job->light->normals)
    return prt_pose_shade(job->asset, job->backend, job->pose, job->light,
                          job->first_vertex + first, count, out);
  light = *job->light; /* struct_size reaches the 1.0 size, which is the whole struct */
  light.normals = job->light->normals + (size_t)first * 3u;
  return prt_pose_shade(job->asset, job->backend, job->pose, &light, job->first_vertex + first,
                        count, out);
}

prt_result prt_pose_shade_workers(prt_workers* workers, const prt_asset* asset, prt_backend backend,
                                  const prt_pose_input* pose, const prt_pose_light* light,
                                  uint32_t first_vertex, uint32_t vertex_count, float* out_rgb) {
  pose_workers_job job;
  if (!workers || !asset) return PRT_ERROR_INVALID_ARGUMENT;
  /* A range past the last index would wrap in the chunks' first vertex. */
  if (vertex_count > UINT32_MAX - first_vertex) return PRT_ERROR_INVALID_ARGUMENT;
  job.asset = asset;
  job.backend = backend;
  job.pose = pose;
  job.light = light;
  job.first_vertex = first_vertex;
  job.out_rgb = out_rgb;
  return prt_workers_run(workers, vertex_count, shade_chunk, &job);
}
