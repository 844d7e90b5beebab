/* SPDX-License-Identifier: MIT */
/* De-ringing of SH light by Sloan's Laplacian-minimising window (Sloan 2008, "Stupid Spherical
 * Harmonics (SH) Tricks", section on windowing): band l is scaled by h_l = 1/(1 + lambda l^2
 * (l+1)^2), lambda = strength * the order's lambda at which a delta light's irradiance stops
 * going negative (table below). */
#include <math.h>
#include <string.h>

#include "sh_internal.h"

/* The smallest lambda for which the windowed irradiance of a delta light,
 * E(t) = sum_l h_l A_l (2l+1)/(4 pi) P_l(t), is >= 0 for every t = cos(angle) in [-1, 1], by
 * bisection on the closed form in double, rounded up in the 7th digit. Index: order. Orders come
 * in pairs because A_l = 0 for odd l > 1; order 1 (the mean alone) cannot ring. */
static const double kNonNegativeLambda[PRT_SH_MAX_ORDER + 1] = {
    0.0,       0.0,       0.25,      0.1777319, 0.1777319, 0.1804232,
    0.1804232, 0.1800924, 0.1800924, 0.1801662, 0.1801662, 0.1801434,
    0.1801434, 0.1801521, 0.1801521, 0.1801483, 0.1801483};

static float dering_band_factor(double lambda, uint32_t l) {
  const double ll1 = (double)l * (double)(l + 1);
  return (float)(1.0 / (1.0 + lambda * ll1 * ll1));
}

prt_result prt_sh_dering_light(uint32_t order, float strength, const float* light_rgb,
                               float* out_rgb) {
  uint32_t l, i;
  double lambda;
  if (!light_rgb || !out_rgb || order == 0 || order > PRT_SH_MAX_ORDER || !isfinite(strength) ||
      strength < 0.0f)
    return PRT_ERROR_INVALID_ARGUMENT;
  if (strength == 0.0f) {
    if (out_rgb != light_rgb) memmove(out_rgb, light_rgb, sizeof(float) * 3u * order * order);
    return PRT_OK;
  }
  lambda = (double)strength * kNonNegativeLambda[order];
  for (l = 0; l < order; ++l) {
    const float factor = dering_band_factor(lambda, l);
    for (i = 3u * l * l; i < 3u * (l + 1) * (l + 1); ++i) out_rgb[i] = light_rgb[i] * factor;
  }
  return PRT_OK;
}
