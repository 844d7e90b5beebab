/* SPDX-License-Identifier: MIT */
/* Clamped-cosine convolution of SH coefficients (Ramamoorthi and Hanrahan 2001, eq. 8-9). */
#include "sh_internal.h"

#define PRT_SH_PI 3.14159265358979323846

float prt_sh_cosine_band_factor(uint32_t l) {
  /* binom(l, l/2) / 2^l, stepped from l = 0 by the ratio (k + 1)/(k + 2) per even step. */
  double central = 1.0;
  uint32_t k;
  if (l >= PRT_SH_MAX_ORDER) return 0.0f;
  if (l == 0) return (float)PRT_SH_PI;
  if (l == 1) return (float)(2.0 * PRT_SH_PI / 3.0);
  if (l % 2 == 1) return 0.0f;
  for (k = 0; k < l; k += 2) central *= (double)(k + 1) / (double)(k + 2);
  return (float)(2.0 * PRT_SH_PI * ((l / 2) % 2 == 1 ? 1.0 : -1.0) /
                 ((double)(l + 2) * (double)(l - 1)) * central);
}

prt_result prt_sh_convolve_cosine(uint32_t order, const float* in, float* out, uint32_t channels) {
  uint32_t l, i;
  if (!in || !out || order == 0 || order > PRT_SH_MAX_ORDER || channels == 0)
    return PRT_ERROR_INVALID_ARGUMENT;
  for (l = 0; l < order; ++l) {
    const float factor = prt_sh_cosine_band_factor(l);
    for (i = l * l * channels; i < (l + 1) * (l + 1) * channels; ++i) out[i] = in[i] * factor;
  }
  return PRT_OK;
}
