/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the inner loops of technique `shadowfield`'s evaluation
 * (shadowfield_eval.c), one table per backend: the scalar reference (shadowfield_kernels.c) and
 * AVX2 + FMA (shadowfield_kernels_avx2.c, compiled with those flags and picked at prepare only
 * when the context's SIMD ISA has them). The tables compute the same sums; the SIMD one fuses
 * multiply-adds and sums in another order, so it agrees with the scalar one to rounding, not
 * bitwise. */
#ifndef PRT_RUNTIME_SHADOWFIELD_KERNELS_H
#define PRT_RUNTIME_SHADOWFIELD_KERNELS_H

#include <stdint.h>

#include <prt/format/shadowfield_shells.h>

#include "shadowfield_gaunt.h"
#include "shadowfield_log.h"
#include "shadowfield_object.h"

struct prt_sf_pair;

/* The vertices the direct pass takes at once: their visibilities are lane-interleaved,
 * [coefficient * PRT_SF_LANES + lane], so one triple product serves them all. */
#define PRT_SF_LANES 8u

typedef struct prt_sf_kernels {
  /* out[c width + i] = sum_e weight_e field[c plane + index_e width + i] for the lookup's points
   * and planes c < planes (lookup->count > 0). */
  void (*read_rows)(const float* field, uint64_t plane, uint32_t planes, uint32_t width,
                    const prt_sf_lookup* lookup, float* out);
  /* `planes` (1..3) planes of order^2 coefficients turned by the pair's SH rotation (j's frame
   * to i's); out may not alias in. */
  void (*rotate)(const struct prt_sf_pair* pair, uint32_t order, const float* in, float* out,
                 uint32_t planes);
  /* The same by the inverse rotation (i's frame to j's, the transpose); out may not alias in. */
  void (*rotate_back)(const struct prt_sf_pair* pair, uint32_t order, const float* in, float* out,
                      uint32_t planes);
  /* rotate's single plane in the lanes whose bit is set in `mask`, the others of `out` left as
   * they are; in and out lane-interleaved (PRT_SF_LANES), out may not alias in. Each lane's
   * values are rotate's bits for that lane alone. */
  void (*rotate_lanes)(const struct prt_sf_pair* pair, uint32_t order, const float* in, float* out,
                       uint32_t mask);
  /* light_rgb[3 k + c] = sum_j matrix[(c n2 + k) n2 + j] visibility[j]: the environment times a
   * visibility (the instance's light_product). */
  void (*light_times)(const float* matrix, uint32_t n2, const float* visibility, float* light_rgb);
  /* a = a x b (prt_sf_sh_multiply) in the lanes whose bit is set in `mask`, the others left as
   * they are; a and b lane-interleaved (PRT_SF_LANES). */
  void (*multiply_lanes)(const prt_sf_gaunt* gaunt, float* a, const float* b, uint32_t mask);
  /* A read_rows of the 3 colour planes dotted with `terms` (1 or 2) transfer vectors (width
   * floats each), the sums kept in lanes: partial[(3 k + c) PRT_SF_LANES + lane] += a share of
   * transfer_k . (sum_e weight_e field[c plane + index_e width + .]), whose lanes add up to it. */
  void (*read_dot)(const float* field, uint64_t plane, uint32_t width, const prt_sf_lookup* lookup,
                   const float* transfer, uint32_t terms, float* partial);
  /* out[r] = the sum of partial[r PRT_SF_LANES + lane] over the lanes, for r < count. */
  void (*reduce_lanes)(const float* partial, uint32_t count, float* out);
  /* out[3 k + c] = sum_i transfer[k n2 + i] light_rgb[3 i + c] for the terms k < terms. */
  void (*transfer_dot)(const float* transfer, uint32_t n2, uint32_t terms, const float* light_rgb,
                       float* out);
  /* The source field sum_ik w_ikc SRF_ik(p) at SRF points [first, first + count) (see
   * prt_sf_instance::field). */
  void (*cast_field)(const prt_sf_object* object, const float* weights, float* field,
                     uint64_t first, uint64_t count);
  /* The log-space product's exponential in the lanes whose bit is set in `mask`, the others left
   * as they are: each lane's summed log (order^2 coefficients, lane-interleaved) becomes the
   * projection of its exponential, sum_d project[i D + d] prt_sf_exp(sum_j eval[d n2 + j] f_j). */
  void (*exp_lanes)(const prt_sf_sphere_rule* rule, float* lanes, uint32_t mask);
} prt_sf_kernels;

extern const prt_sf_kernels prt_sf_kernels_scalar;
#if defined(PRT_HAS_X86_SIMD)
extern const prt_sf_kernels prt_sf_kernels_avx2;
#endif

/* The SRF points cast_field handles at once: their three planes stay in the L1 cache while every
 * SRF row adds to them, so the SRF is read once per projection. */
#define PRT_SF_FIELD_BLOCK 64u

#endif /* PRT_RUNTIME_SHADOWFIELD_KERNELS_H */
