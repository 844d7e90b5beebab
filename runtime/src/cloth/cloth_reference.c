/* SPDX-License-Identifier: MIT */
/* The brute-force reference of prt_cloth.h: for each sample, everything that depends on its frame
 * and view is computed once (prt_cloth_outgoing_of), then the kernel is summed over the texels
 * above its surface in double. One range, or split over a prt_workers pool. */
#include <math.h>

#include "../workers_internal.h"
#include "cloth_model.h"

/* How far from unit length a texel's direction may be. */
#define CLOTH_TEXEL_LENGTH_SLACK 1e-3

static int texels_ok(const prt_cloth_env_texels* env) {
  uint32_t i;
  if (!env || !prt_internal_struct_size_ok(env, PRT_CLOTH_ENV_TEXELS_SIZE_1_0)) return 0;
  if (env->count == 0u) return 1;
  if (!env->directions || !env->power) return 0;
  for (i = 0; i < env->count; ++i) {
    const float* d = env->directions + 3u * (size_t)i;
    const float* p = env->power + 3u * (size_t)i;
    double length2 = 0.0;
    int c;
    for (c = 0; c < 3; ++c) {
      if (!isfinite(d[c]) || !isfinite(p[c]) || p[c] < 0.0f) return 0;
      length2 += (double)d[c] * d[c];
    }
    if (fabs(sqrt(length2) - 1.0) > CLOTH_TEXEL_LENGTH_SLACK) return 0;
  }
  return 1;
}

static int pixels_ok(const prt_cloth_pixels* pixels) {
  return pixels && prt_internal_struct_size_ok(pixels, PRT_CLOTH_PIXELS_SIZE_1_0) &&
         pixels->normals && pixels->warps && pixels->views;
}

/* The sum over texels of power x k for sample `index`, 0 when its vectors are degenerate. */
static void shade_sample(const prt_cloth_material materials[2], const prt_cloth_weave* weave,
                         const prt_cloth_env_texels* env, const prt_cloth_pixels* pixels,
                         size_t index, double out[3]) {
  prt_cloth_frame frame;
  prt_cloth_outgoing outgoing;
  double wo[3];
  uint32_t i;
  out[0] = out[1] = out[2] = 0.0;
  if (!prt_cloth_make_frame(pixels->normals + 3u * index, pixels->warps + 3u * index, &frame) ||
      !prt_cloth_unit_direction(pixels->views + 3u * index, wo))
    return;
  prt_cloth_outgoing_of(weave, &frame, wo, &outgoing);
  if (!outgoing.above) return;
  for (i = 0; i < env->count; ++i) {
    const float* d = env->directions + 3u * (size_t)i;
    const float* p = env->power + 3u * (size_t)i;
    double wi[3], k[3], length;
    int c;
    /* The texels below this surface, and black ones, add nothing. */
    if (!((double)d[0] * frame.n[0] + (double)d[1] * frame.n[1] + (double)d[2] * frame.n[2] >
          0.0) ||
        (p[0] == 0.0f && p[1] == 0.0f && p[2] == 0.0f))
      continue;
    for (c = 0; c < 3; ++c) wi[c] = d[c];
    length = sqrt(wi[0] * wi[0] + wi[1] * wi[1] + wi[2] * wi[2]);
    for (c = 0; c < 3; ++c) wi[c] /= length;
    prt_cloth_outgoing_kernel(materials, &outgoing, wi, k);
    for (c = 0; c < 3; ++c) out[c] += (double)p[c] * k[c];
  }
}

prt_result prt_cloth_reference(const prt_cloth_params* params, const prt_cloth_weave* weave,
                               const prt_cloth_env_texels* env, const prt_cloth_pixels* pixels,
                               uint32_t first, uint32_t count, float* out_rgb) {
  prt_cloth_material materials[2];
  uint32_t s;
  if (!out_rgb || prt_cloth_params_validate(params) != PRT_OK ||
      prt_cloth_weave_validate(weave) != PRT_OK || !texels_ok(env) || !pixels_ok(pixels) ||
      count > UINT32_MAX - first)
    return PRT_ERROR_INVALID_ARGUMENT;
  prt_cloth_material_of(&params->threads[0], &materials[0]);
  prt_cloth_material_of(&params->threads[1], &materials[1]);
  for (s = 0; s < count; ++s) {
    double rgb[3];
    int c;
    shade_sample(materials, weave, env, pixels, (size_t)first + s, rgb);
    for (c = 0; c < 3; ++c) out_rgb[3u * (size_t)s + c] = prt_cloth_to_float(rgb[c]);
  }
  return PRT_OK;
}

typedef struct cloth_reference_job {
  const prt_cloth_params* params;
  const prt_cloth_weave* weave;
  const prt_cloth_env_texels* env;
  const prt_cloth_pixels* pixels;
  uint32_t first;
  float* out_rgb;
} cloth_reference_job;

static prt_result reference_chunk(void* user, uint32_t first, uint32_t count) {
  const cloth_reference_job* job = (const cloth_reference_job*)user;
  /* A NULL output stays NULL, so that the one-range call rejects it. */
  float* out = job->out_rgb ? job->out_rgb + (size_t)first * 3u : NULL;
  return prt_cloth_reference(job->params, job->weave, job->env, job->pixels, job->first + first,
                             count, out);
}

prt_result prt_cloth_reference_workers(prt_workers* workers, const prt_cloth_params* params,
                                       const prt_cloth_weave* weave,
                                       const prt_cloth_env_texels* env,
                                       const prt_cloth_pixels* pixels, uint32_t first,
                                       uint32_t count, float* out_rgb) {
  cloth_reference_job job;
  if (!workers) return PRT_ERROR_INVALID_ARGUMENT;
  /* A range past the last index would wrap in the chunks' first sample. */
  if (count > UINT32_MAX - first) return PRT_ERROR_INVALID_ARGUMENT;
  job.params = params;
  job.weave = weave;
  job.env = env;
  job.pixels = pixels;
  job.first = first;
  job.out_rgb = out_rgb;
  return prt_workers_run(workers, count, reference_chunk, &job);
}
