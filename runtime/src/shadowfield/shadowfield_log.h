/* SPDX-License-Identifier: MIT */
/* Private to the runtime: technique `shadowfield`'s log-space product, the option for many
 * blockers (docs/shadowfield/design.md, "Many blockers"; after Ren et al. 2006). Each object's
 * occlusion field is kept a second time as the SH projection of the log of its visibility; a
 * receiver sums its blockers' logs (a rotation and an addition each, no triple product) and takes
 * one exponential. The exponential is taken in direction space: the summed log evaluated at a
 * quadrature's directions, exponentiated there and projected back, which costs about two triple
 * products and, unlike a series of truncated SH products, has no error that grows with the log's
 * size. */
#ifndef PRT_RUNTIME_SHADOWFIELD_LOG_H
#define PRT_RUNTIME_SHADOWFIELD_LOG_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include <prt/prt_types.h>

/* Visibility below this is read as this before its log: a blocker that hides a direction
 * entirely leaves this much of it, and the log stays finite. Above it nothing is clamped, not
 * even the SH's ringing above 1: cutting that would darken every small blocker. Measured on a
 * half-space blocker at order 4 (docs/shadowfield/design.md, "Many blockers"), a lower floor
 * leaves a large blocker brighter and a higher one lets more through a small one. */
#define PRT_SF_LOG_FLOOR 0.03f

/* A product quadrature on the sphere for order n: Gauss-Legendre nodes in cos(theta) times
 * uniform nodes in phi, with y_i at every direction and its weight. */
typedef struct prt_sf_sphere_rule {
  uint32_t order, directions;
  float* eval;    /* directions x n^2: y_i(d) at [d n^2 + i] */
  float* project; /* n^2 x directions: weight_d y_i(d) at [i directions + d] */
} prt_sf_sphere_rule;

/* The rule of z_nodes x phi_nodes directions for `order` (1..6). PRT_ERROR_INVALID_ARGUMENT,
 * PRT_ERROR_OUT_OF_MEMORY; on failure *out is empty (safe to free). */
prt_result prt_sf_sphere_rule_build(const prt_allocator* allocator, uint32_t order,
                                    uint32_t z_nodes, uint32_t phi_nodes, prt_sf_sphere_rule* out);
void prt_sf_sphere_rule_free(const prt_allocator* allocator, prt_sf_sphere_rule* rule);

/* The rule the run-time exponential uses: exact for the product of two order-n functions and a
 * little more, so that the projection of exp(f) aliases little. */
prt_result prt_sf_exp_rule_build(const prt_allocator* allocator, uint32_t order,
                                 prt_sf_sphere_rule* out);

/* out[p n^2 + i] = the SH projection of log(max(V_p, floor_value)) with V_p the visibility of
 * field[p n^2 + .], for `points` points, on a rule finer than the exponential's (`fine`, from
 * prt_sf_log_rule_build). */
void prt_sf_log_of_field(const prt_sf_sphere_rule* fine, const float* field, uint64_t points,
                         float floor_value, float* out);
prt_result prt_sf_log_rule_build(const prt_allocator* allocator, uint32_t order,
                                 prt_sf_sphere_rule* out);

/* exp(x) to about one float ulp for x in [-87, 88], by range reduction and a polynomial; the
 * SIMD kernels evaluate the same steps in lanes. x is clamped to that range first, NaN to -87
 * (as the SIMD max does), so the exponent's conversion to an integer is always defined. */
static inline float prt_sf_exp(float x) {
  x = x > -87.0f ? x : -87.0f;
  x = x < 88.0f ? x : 88.0f;
  const float k = nearbyintf(x * 1.44269504088896341f);
  const float r = (x - k * 0.693145751953125f) - k * 1.428606765330187045e-06f;
  float p = 1.0f / 5040.0f;
  p = p * r + 1.0f / 720.0f;
  p = p * r + 1.0f / 120.0f;
  p = p * r + 1.0f / 24.0f;
  p = p * r + 1.0f / 6.0f;
  p = p * r + 0.5f;
  p = p * r + 1.0f;
  p = p * r + 1.0f;
  const uint32_t bits = (uint32_t)((int32_t)k + 127) << 23;
  float scale;
  memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

#endif /* PRT_RUNTIME_SHADOWFIELD_LOG_H */
