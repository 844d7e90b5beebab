/* SPDX-License-Identifier: MIT */
/* The checks of prt_cloth.h's parameters, weave and light, and the exact kernel and thread
 * weights as the public API gives them (float in and out, double inside, cloth_model.c). */
#include <math.h>

#include "cloth_model.h"

/* Limits compared in float, so that a caller's (float)M_PI or (float)(M_PI / 2) passes. */
#define CLOTH_PI_F 3.14159265358979323846f
#define CLOTH_HALF_PI_F 1.57079632679489661923f
/* Coverages are decimal fractions rounded to float: their sum may pass 1 by a rounding. */
#define CLOTH_AXIS_LENGTH_SLACK 1e-3

static int within(float value, float low, float high) {
  return isfinite(value) && value >= low && value <= high;
}

static int thread_ok(const prt_cloth_thread* t) {
  int c;
  for (c = 0; c < 3; ++c)
    if (!within(t->albedo[c], 0.0f, 1.0f)) return 0;
  return within(t->eta, 1.0f, 4.0f) && within(t->kd, 0.0f, 1.0f) &&
         within(t->gamma_s, 0.0f, CLOTH_PI_F) && t->gamma_s > 0.0f &&
         within(t->gamma_v, 0.0f, CLOTH_PI_F) && t->gamma_v > 0.0f &&
         within(t->coverage, 0.0f, 1.0f);
}

prt_result prt_cloth_params_validate(const prt_cloth_params* params) {
  if (!params || !prt_internal_struct_size_ok(params, PRT_CLOTH_PARAMS_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (!thread_ok(&params->threads[0]) || !thread_ok(&params->threads[1]))
    return PRT_ERROR_INVALID_ARGUMENT;
  if ((double)params->threads[0].coverage + (double)params->threads[1].coverage >
      1.0 + PRT_BLOB_CLTH_COVERAGE_SLACK)
    return PRT_ERROR_INVALID_ARGUMENT;
  return PRT_OK;
}

/* 1..16 distinct finite offsets within [-pi/2, pi/2], each repeated 1..64 times. */
static int thread_weave_ok(const prt_cloth_weave* weave, int j) {
  const uint32_t count = weave->tangent_count[j];
  uint32_t k, l;
  if (count < 1u || count > PRT_CLOTH_MAX_THREAD_TANGENTS) return 0;
  for (k = 0; k < count; ++k) {
    if (!within(weave->offsets[j][k], -CLOTH_HALF_PI_F, CLOTH_HALF_PI_F)) return 0;
    if (weave->multiplicity[j][k] < 1u || weave->multiplicity[j][k] > PRT_CLOTH_MAX_MULTIPLICITY)
      return 0;
    for (l = 0; l < k; ++l)
      if (weave->offsets[j][l] == weave->offsets[j][k]) return 0;
  }
  return 1;
}

prt_result prt_cloth_weave_validate(const prt_cloth_weave* weave) {
  if (!weave || !prt_internal_struct_size_ok(weave, PRT_CLOTH_WEAVE_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  return thread_weave_ok(weave, 0) && thread_weave_ok(weave, 1) ? PRT_OK
                                                                : PRT_ERROR_INVALID_ARGUMENT;
}

static int lobe_ok(const prt_cloth_lobe* lobe) {
  double length2 = 0.0;
  int i;
  for (i = 0; i < 3; ++i) {
    if (!isfinite(lobe->axis[i]) || !within(lobe->rgb[i], 0.0f, FLT_MAX)) return 0;
    length2 += (double)lobe->axis[i] * lobe->axis[i];
  }
  return fabs(sqrt(length2) - 1.0) <= CLOTH_AXIS_LENGTH_SLACK &&
         within(lobe->sharpness, PRT_CLOTH_MIN_SHARPNESS, PRT_CLOTH_MAX_SHARPNESS);
}

prt_result prt_cloth_light_validate(const prt_cloth_light* light) {
  uint32_t k;
  if (!light || !prt_internal_struct_size_ok(light, PRT_CLOTH_LIGHT_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (light->lobe_count > PRT_CLOTH_MAX_LOBES || (light->lobe_count > 0u && !light->lobes))
    return PRT_ERROR_INVALID_ARGUMENT;
  for (k = 0; k < light->lobe_count; ++k)
    if (!lobe_ok(&light->lobes[k])) return PRT_ERROR_INVALID_ARGUMENT;
  return PRT_OK;
}

/* The frame and unit directions of a kernel or weights call, or 0 for a degenerate one. */
static int directions_of(const float normal[3], const float warp[3], const float light_dir[3],
                         const float view_dir[3], prt_cloth_frame* frame, double wi[3],
                         double wo[3]) {
  if (!normal || !warp || !light_dir || !view_dir) return 0;
  return prt_cloth_make_frame(normal, warp, frame) && prt_cloth_unit_direction(light_dir, wi) &&
         prt_cloth_unit_direction(view_dir, wo);
}

prt_result prt_cloth_kernel(const prt_cloth_params* params, const prt_cloth_weave* weave,
                            const float normal[3], const float warp[3], const float light_dir[3],
                            const float view_dir[3], float out_rgb[3]) {
  prt_cloth_frame frame;
  double wi[3], wo[3], rgb[3];
  int c;
  if (!out_rgb || prt_cloth_params_validate(params) != PRT_OK ||
      prt_cloth_weave_validate(weave) != PRT_OK ||
      !directions_of(normal, warp, light_dir, view_dir, &frame, wi, wo))
    return PRT_ERROR_INVALID_ARGUMENT;
  prt_cloth_kernel_d(params, weave, &frame, wi, wo, rgb);
  for (c = 0; c < 3; ++c) out_rgb[c] = prt_cloth_to_float(rgb[c]);
  return PRT_OK;
}

prt_result prt_cloth_thread_weights(const prt_cloth_weave* weave, uint32_t thread,
                                    const float normal[3], const float warp[3],
                                    const float light_dir[3], const float view_dir[3],
                                    float* out_weights) {
  prt_cloth_frame frame;
  prt_cloth_outgoing outgoing;
  double wi[3], wo[3], weights[PRT_CLOTH_MAX_THREAD_TANGENTS];
  uint32_t k;
  if (!out_weights || thread > 1u || prt_cloth_weave_validate(weave) != PRT_OK ||
      !directions_of(normal, warp, light_dir, view_dir, &frame, wi, wo))
    return PRT_ERROR_INVALID_ARGUMENT;
  prt_cloth_outgoing_of(weave, &frame, wo, &outgoing);
  prt_cloth_outgoing_weights(&outgoing, (int)thread, wi, weights);
  for (k = 0; k < weave->tangent_count[thread]; ++k) out_weights[k] = (float)weights[k];
  return PRT_OK;
}
