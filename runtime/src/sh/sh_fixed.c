/* SPDX-License-Identifier: MIT */
/* The light-folded `sh` weights in fixed point for the AVX-512 VNNI kernel (prt_sh_fixed_weights,
 * sh_shade_simd.h), and the check that decides whether that kernel may shade a call. Plain C:
 * it runs once per call, before any kernel. */
#include <math.h>

#include "sh_shade_simd.h"

#if defined(PRT_HAS_X86_SIMD)

/* The largest integer PRT_SH_FIXED_LIMBS digits in [-128, 127] can write: 127 * (1 + 256 + ...);
 * its negative is writable too. */
static double largest_fixed(void) {
  double largest = 0.0;
  int l;
  for (l = 0; l < PRT_SH_FIXED_LIMBS; ++l) largest = largest * 256.0 + 127.0;
  return largest;
}

/* Writes D as balanced base-256 digits, least significant first, into byte k % 4 (memory order,
 * as vpdpbusd reads it) of out->digit[ch * dwords + k / 4][l]. |D| <= largest_fixed(), so the
 * top digit is in [-128, 127] too. */
static void write_digits(long long d, prt_sh_fixed_weights* out, uint32_t ch, uint32_t dwords,
                         uint32_t k) {
  int l;
  for (l = 0; l < PRT_SH_FIXED_LIMBS; ++l) {
    long long digit = d % 256; /* in (-256, 256), of d's sign */
    if (digit > 127) digit -= 256;
    if (digit < -128) digit += 256;
    d = (d - digit) / 256;
    ((unsigned char*)&out->digit[ch * dwords + k / 4u][l])[k % 4u] = (unsigned char)(digit & 0xFF);
  }
}

int prt_sh_fix_weights(const prt_sh_simd_job* job, uint32_t n2, const double offset_magnitude[3],
                       prt_sh_fixed_weights* out) {
  /* The part of the conformance bound (n2 + 8) 2^-23 M the rounding of the weights may take:
   * half, the float weight, limb combination and bias roundings staying within the other. */
  const double tolerance = ldexp((double)n2 + 8.0, -24);
  const double largest = largest_fixed();
  uint32_t ch, k;
  if (job->padded > 4u * PRT_SH_FIXED_MAX_DWORDS) return 0;
  for (ch = 0; ch < 3; ++ch) {
    const float* w = job->weight[ch];
    double top = 0.0, excess = 0.0, unit;
    int exponent, l;
    for (k = 0; k < job->padded; ++k) {
      if (!isfinite(w[k])) return 0;
      if (fabs(w[k]) > top) top = fabs(w[k]);
    }
    /* The unit: the smallest power of two at least top / largest, so that every weight's D fits
     * (an all-zero channel takes 1). */
    if (top > 0.0) {
      (void)frexp(top / largest, &exponent);
      unit = ldexp(1.0, exponent);
    } else {
      unit = 1.0;
    }
    /* The limbs' units must be normal floats: below that the light is too faint to matter. */
    if (unit < ldexp(1.0, -126)) return 0;
    for (k = 0; k < job->padded; ++k) {
      const double d = nearbyint((double)w[k] / unit); /* exact quotient: unit is 2^exponent */
      const double error = fabs((double)w[k] - d * unit);
      if (error > tolerance * fabs((double)w[k])) excess += error - tolerance * fabs((double)w[k]);
      write_digits((long long)d, out, ch, job->padded / 4u, k);
    }
    /* Error <= sum_k q_k e_k, q_k <= 255. It is within tolerance * M for every vertex (M = the
     * offset magnitude plus sum_k q_k |w_k|) when the part of the e_k above tolerance * |w_k|,
     * taken at q = 255, stays within tolerance times the offset magnitude. */
    if (255.0 * excess > tolerance * offset_magnitude[ch]) return 0;
    for (l = 0; l < PRT_SH_FIXED_LIMBS; ++l) out->unit[ch][l] = (float)ldexp(unit, 8 * l);
  }
  return 1;
}

#endif /* PRT_HAS_X86_SIMD */
