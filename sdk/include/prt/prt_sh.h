/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: real spherical harmonics (SH), shared by the runtime and the baker.
 * C99 and C++. All functions are pure (no context, no allocation, no global state) and may be
 * called from any thread.
 *
 * Conventions (normative; also in formats/SPEC.md "Spherical harmonics"):
 * - Order n means bands l = 0..n-1 and n*n coefficients; coefficient (l, m), -l <= m <= l, is
 *   at index l*(l+1) + m. PRT_SH_MAX_ORDER is the largest order every function accepts.
 * - Real, orthonormal SH over the unit sphere (integral of Y_lm * Y_l'm' = delta), built from the
 *   associated Legendre functions by a stable recurrence. Sign convention and SH frame: see the
 *   implementation's header comment and formats/SPEC.md, which state them exactly.
 * - Directions are world directions (glTF frame, +Y up) as unit vectors {x, y, z}.
 * - "Radiance" coefficients are the projection L_lm = integral of L(w) Y_lm(w) dw.
 */
#ifndef PRT_SH_H
#define PRT_SH_H

#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRT_SH_MAX_ORDER 16u

/* Number of coefficients of an order: order*order. */
#define PRT_SH_COEFF_COUNT(order) ((order) * (order))

/* Evaluates all order*order basis functions at the unit direction dir into out.
 * Returns PRT_ERROR_INVALID_ARGUMENT when order is 0 or above PRT_SH_MAX_ORDER or a pointer is
 * NULL. dir need not be exactly unit length; it is normalised (a zero vector is invalid). */
PRT_API prt_result prt_sh_eval(uint32_t order, const float dir[3], float* out);

#ifdef __cplusplus
}
#endif

#endif /* PRT_SH_H */
