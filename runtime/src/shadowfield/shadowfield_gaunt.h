/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the SH triple-product tensor of technique `shadowfield`
 * (docs/shadowfield/design.md, "Direct light"): the Gaunt coefficients C_ijk = integral of
 * y_i y_j y_k over the sphere, real SH of prt/prt_sh.h, so that the product of two functions of
 * order n projected back to order n is out_k = sum_ij C_ijk a_i b_j.
 *
 * Multiplying many blockers' visibilities one after another truncates after each product; the
 * log-space product (shadowfield_log.h) is the option for many blockers. */
#ifndef PRT_RUNTIME_SHADOWFIELD_GAUNT_H
#define PRT_RUNTIME_SHADOWFIELD_GAUNT_H

#include <stdint.h>

#include <prt/prt_types.h>

/* The largest order the tensor is built for (the format's largest). */
#define PRT_SF_GAUNT_MAX_ORDER 6u

/* The non-zero coefficients, grouped by k: entries [k_start[k], k_start[k + 1]) have output
 * index k, input indices i[e], j[e] and value value[e]. */
typedef struct prt_sf_gaunt {
  uint32_t order;
  uint32_t count;
  uint32_t k_start[PRT_SF_GAUNT_MAX_ORDER * PRT_SF_GAUNT_MAX_ORDER + 1u];
  uint8_t* i;
  uint8_t* j;
  float* value;
} prt_sf_gaunt;

/* Computes the tensor of `order` (1..PRT_SF_GAUNT_MAX_ORDER) by a quadrature exact for the
 * integrand's degree, keeping |C| above rounding. PRT_ERROR_INVALID_ARGUMENT for a bad order,
 * PRT_ERROR_OUT_OF_MEMORY. On failure *out is empty (safe to free). */
prt_result prt_sf_gaunt_build(const prt_allocator* allocator, uint32_t order, prt_sf_gaunt* out);
void prt_sf_gaunt_free(const prt_allocator* allocator, prt_sf_gaunt* gaunt);

/* The Gauss-Legendre nodes and weights of `count` points on [-1, 1] (Newton on P_count). */
void prt_sf_gauss_legendre(uint32_t count, double* nodes, double* weights);

/* out = the product of a and b (order^2 coefficients each) projected to the order; out may not
 * alias a or b. */
void prt_sf_sh_multiply(const prt_sf_gaunt* gaunt, const float* a, const float* b, float* out);

#endif /* PRT_RUNTIME_SHADOWFIELD_GAUNT_H */
