/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield`'s frame split over a prt_workers pool: each stage's items (every
 * instance's probes, its vertices, then every source's field points) numbered one after another
 * across the instances and cut into contiguous chunks, with the pool's barrier between stages. Each
 * item is computed as in the one-thread frame, so the result is bitwise prt_shadowfield_shade's. */
#include "../workers_internal.h"
#include "shadowfield_scene.h"

typedef struct sf_workers_job {
  const prt_shadowfield_scene* scene;
  uint32_t pass;
  float* const* out_rgb;
} sf_workers_job;

typedef uint64_t (*sf_items_fn)(const prt_shadowfield_scene* scene, uint32_t instance);
typedef void (*sf_span_fn)(const sf_workers_job* job, uint32_t instance, uint64_t first,
                           uint64_t count);

static uint64_t vertex_items(const prt_shadowfield_scene* scene, uint32_t instance) {
  return prt_shadowfield_instance_vertex_count(scene, instance);
}

static uint64_t probe_items(const prt_shadowfield_scene* scene, uint32_t instance) {
  return scene->instances[instance].probe_count;
}

static uint64_t total_items(const prt_shadowfield_scene* scene, sf_items_fn items) {
  uint64_t total = 0;
  for (uint32_t i = 0; i < scene->instance_count; ++i) total += items(scene, i);
  return total;
}

/* Calls span on each instance's share of the items [first, first + count). */
static void for_spans(const sf_workers_job* job, sf_items_fn items, sf_span_fn span, uint64_t first,
                      uint64_t count) {
  const uint64_t end = first + count;
  uint64_t start = 0;
  for (uint32_t i = 0; i < job->scene->instance_count && start < end; ++i) {
    const uint64_t size = items(job->scene, i);
    const uint64_t a = first > start ? first : start;
    const uint64_t b = end < start + size ? end : start + size;
    if (a < b) span(job, i, a - start, b - a);
    start += size;
  }
}

static void gather_span(const sf_workers_job* job, uint32_t instance, uint64_t first,
                        uint64_t count) {
  prt_sf_gather_range(job->scene, job->pass, instance, (uint32_t)first, (uint32_t)count);
}

static void probe_span(const sf_workers_job* job, uint32_t instance, uint64_t first,
                       uint64_t count) {
  prt_sf_gather_probes_range(job->scene, job->pass, instance, (uint32_t)first, (uint32_t)count);
}

static void field_span(const sf_workers_job* job, uint32_t instance, uint64_t first,
                       uint64_t count) {
  prt_sf_cast_field(job->scene, instance, first, count);
}

static void output_span(const sf_workers_job* job, uint32_t instance, uint64_t first,
                        uint64_t count) {
  float* out = job->out_rgb[instance];
  if (out)
    prt_sf_output_range(job->scene, instance, job->scene->bounces, (uint32_t)first, (uint32_t)count,
                        out + first * 3u);
}

static prt_result gather_chunk(void* user, uint32_t first, uint32_t count) {
  for_spans((const sf_workers_job*)user, vertex_items, gather_span, first, count);
  return PRT_OK;
}

static prt_result probe_chunk(void* user, uint32_t first, uint32_t count) {
  for_spans((const sf_workers_job*)user, probe_items, probe_span, first, count);
  return PRT_OK;
}

static prt_result weights_chunk(void* user, uint32_t first, uint32_t count) {
  const sf_workers_job* job = (const sf_workers_job*)user;
  for (uint32_t i = first; i < first + count; ++i) prt_sf_project_weights(job->scene, job->pass, i);
  return PRT_OK;
}

static prt_result field_chunk(void* user, uint32_t first, uint32_t count) {
  for_spans((const sf_workers_job*)user, prt_sf_field_points, field_span, first, count);
  return PRT_OK;
}

static prt_result output_chunk(void* user, uint32_t first, uint32_t count) {
  for_spans((const sf_workers_job*)user, vertex_items, output_span, first, count);
  return PRT_OK;
}

static prt_result run_passes(prt_workers* workers, sf_workers_job* job, uint32_t vertices,
                             uint32_t probes, uint32_t points) {
  const prt_shadowfield_scene* scene = job->scene;
  prt_result result = PRT_OK;
  for (uint32_t pass = 0; pass <= scene->bounces && result == PRT_OK; ++pass) {
    job->pass = pass;
    if (probes > 0u) result = prt_workers_run(workers, probes, probe_chunk, job);
    if (result == PRT_OK) result = prt_workers_run(workers, vertices, gather_chunk, job);
    if (pass == scene->bounces || result != PRT_OK) continue;
    result = prt_workers_run(workers, scene->instance_count, weights_chunk, job);
    if (result == PRT_OK) result = prt_workers_run(workers, points, field_chunk, job);
  }
  if (result == PRT_OK) result = prt_workers_run(workers, vertices, output_chunk, job);
  return result;
}

prt_result prt_shadowfield_shade_workers(prt_workers* workers, prt_shadowfield_scene* scene,
                                         const float* light_sh_rgb, const float eye[3],
                                         const prt_shadowfield_settings* settings,
                                         float* const* out_rgb) {
  if (!workers || !scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (!out_rgb)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_shadowfield_shade_workers: NULL out_rgb");
  const prt_result prepared = prt_shadowfield_prepare(scene, light_sh_rgb, eye, settings);
  if (prepared != PRT_OK) return prepared;
  const uint64_t vertices = total_items(scene, vertex_items);
  const uint64_t probes = total_items(scene, probe_items);
  const uint64_t points = total_items(scene, prt_sf_field_points);
  if (vertices > UINT32_MAX || probes > UINT32_MAX || points > UINT32_MAX)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_shadowfield_shade_workers: more than 2^32 vertices or points");
  sf_workers_job job;
  job.scene = scene;
  job.pass = 0u;
  job.out_rgb = out_rgb;
  return run_passes(workers, &job, (uint32_t)vertices, (uint32_t)probes, (uint32_t)points);
}
