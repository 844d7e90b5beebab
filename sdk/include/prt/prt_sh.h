/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: real spherical harmonics (SH), shared by the runtime and the baker.
 * C99 and C++. All functions are pure (no context, no heap allocation, no global state) and may be
 * called from any thread at once.
 *
 * Conventions (normative; also in formats/SPEC.md "Spherical harmonics"):
 * - Order n means bands l = 0..n-1 and n*n coefficients; coefficient (l, m), -l <= m <= l, is
 *   at index l*(l+1) + m. PRT_SH_MAX_ORDER is the largest order every function accepts.
 * - Directions passed in are world directions (glTF frame: right-handed, +Y up, front -Z).
 * - SH frame: the polar axis is world +Y. A world direction (X, Y, Z) has SH-frame coordinates
 *       x = X,   y = -Z,   z = Y
 *   (right-handed; z = cos(theta), x + i y = sin(theta) e^(i phi)), so a rotation of the light
 *   about the vertical axis is a rotation about the SH z axis.
 * - Real, orthonormal SH (integral over the sphere of Y_lm Y_l'm' = delta), WITHOUT the
 *   Condon-Shortley phase (-1)^m (the graphics convention of Sloan and of Ramamoorthi-Hanrahan):
 *       Y_l0    = K_l0 P_l(z)
 *       Y_lm    = sqrt(2) K_lm P_l^m(z) cos(m phi),     m > 0
 *       Y_l,-m  = sqrt(2) K_lm P_l^m(z) sin(m phi),     m > 0
 *   with K_lm = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!) and P_l^m(z) >= 0 near z = 1 (no (-1)^m), e.g.
 *       Y_00 = 0.282095,  Y_1,-1 = 0.488603 y,  Y_10 = 0.488603 z,  Y_11 = 0.488603 x,
 *       Y_2,-2 = 1.092548 x y,  Y_2,-1 = 1.092548 y z,  Y_20 = 0.315392 (3 z^2 - 1),
 *       Y_21 = 1.092548 x z,  Y_22 = 0.546274 (x^2 - y^2).
 * - Ramamoorthi-Hanrahan's published irradiance tables (and the SH9 table in the shared assets)
 *   use the same real basis and sign choice on the axes (x', y', z') = world (X, Y, -Z), i.e.
 *   x' = x, y' = z, z' = y: a reflection of our frame (swap of y and z). A function with
 *   coefficients RH[l,m] in that frame has, in ours, for l <= 2:
 *       ours[0,0] = RH[0,0]
 *       ours[1,-1] = RH[1,0]     ours[1,0] = RH[1,-1]     ours[1,1] = RH[1,1]
 *       ours[2,-2] = RH[2,1]     ours[2,-1] = RH[2,-1]    ours[2,1] = RH[2,-2]
 *       ours[2,0] = -(1/2) RH[2,0] - (sqrt(3)/2) RH[2,2]
 *       ours[2,2] = -(sqrt(3)/2) RH[2,0] + (1/2) RH[2,2]
 *   (derivation in formats/SPEC.md, section "Spherical harmonics").
 * - Irradiance: prt_sh_convolve_cosine multiplies band l by A_l (Ramamoorthi-Hanrahan A-hat),
 *   giving E_lm with sum E_lm Y_lm(n) = irradiance at normal n (pi L for a constant L).
 * - "Radiance" coefficients are the projection L_lm = integral of L(w) Y_lm(w) dw, so a constant
 *   radiance L gives L_00 = sqrt(4 pi) L and nothing else; L(w) ~ sum L_lm Y_lm(w).
 * - Colour coefficients are coefficient-major: c0.r c0.g c0.b c1.r ... ("channels" per
 *   coefficient in general).
 */
#ifndef PRT_SH_H
#define PRT_SH_H

#include <stddef.h>

#include <prt/prt_env.h>
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

/* Projects an environment image (prt_env.h: lat-long or cube, RGB or RGBA, any strides) onto
 * SH: out_rgb[3*i + c] = sum over texels of L_c(texel) Y_i(centre direction) * (exact texel
 * solid angle), i.e. midpoint quadrature per texel, accumulated in double. A channel value that
 * is NaN, infinite or negative counts as 0. With env->rotation set, the projected coefficients
 * are then rotated by prt_sh_rotate, which is exact for band-limited coefficients: the result is
 * the projection of the turned light up to float rounding (not a re-projection of turned
 * texels, which would differ by quadrature error). out_rgb receives order*order*3 floats.
 * Returns PRT_ERROR_INVALID_ARGUMENT for a bad order, a NULL out_rgb, or an env that
 * prt_env_image_validate rejects. */
PRT_API prt_result prt_sh_project(uint32_t order, const prt_env_image* env, float* out_rgb);

/* Rotates SH coefficients: rotation is a row-major 3x3 proper rotation R of the world frame, and
 * the result describes the rotated light, the light that came from direction d now coming from
 * R d (out(w) = in(R^T w)). in and out hold order*order*channels floats, coefficient-major
 * (channels consecutive per coefficient); in == out is allowed. Band by band with the
 * Ivanic-Ruedenberg recurrence; no heap (about 24 KiB of stack). Returns PRT_ERROR_INVALID_ARGUMENT
 * for NULL pointers, a bad order, channels == 0, or a matrix that is not finite, not orthonormal
 * (to 1e-3) or has determinant -1. */
PRT_API prt_result prt_sh_rotate(uint32_t order, const float rotation[9], const float* in,
                                 float* out, uint32_t channels);

/* The clamped-cosine band factor A_l (Ramamoorthi-Hanrahan 2001 "A-hat"): the irradiance of a
 * radiance with coefficients L_lm is E(n) = sum A_l L_lm Y_lm(n), for n a unit normal.
 * A_0 = pi, A_1 = 2 pi/3, A_l = 0 for odd l > 1, and for even l >= 2
 *     A_l = 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * l! / (2^l ((l/2)!)^2),
 * i.e. A_l = sqrt(4 pi/(2l+1)) k_l with k_l the zonal SH coefficient of max(0, cos theta).
 * Returns 0 for l >= PRT_SH_MAX_ORDER. */
PRT_API float prt_sh_cosine_band_factor(uint32_t l);

/* Irradiance coefficients from radiance coefficients: out[(l,m)*channels + c] = A_l *
 * in[(l,m)*channels + c] (A_l from prt_sh_cosine_band_factor), so sum out_lm Y_lm(n) is the
 * irradiance E(n) = integral L(w) max(0, n.w) dw of the band-limited radiance (for a constant
 * radiance L: pi L exactly). Divide by pi for the outgoing radiance of a white Lambertian
 * surface. in == out is allowed. Errors: NULL, bad order, channels == 0. */
PRT_API prt_result prt_sh_convolve_cosine(uint32_t order, const float* in, float* out,
                                          uint32_t channels);

/* The de-ringing strength that removes the dark far side of a point light (see
 * prt_sh_dering_light). */
#define PRT_SH_DERING_DEFAULT_STRENGTH 1.0f

/* De-rings SH light: truncating a near-delta light (a small bright sun) to order n leaves negative
 * lobes that darken surfaces facing away from it. This applies Sloan's window (Sloan 2008, "Stupid
 * Spherical Harmonics (SH) Tricks", section on windowing) that minimises the squared error plus
 * lambda times the squared Laplacian of the reconstruction: every coefficient (l, m) of band l
 * is multiplied by
 *     h_l = 1 / (1 + lambda l^2 (l+1)^2),   lambda = strength * lambda_n,
 * with lambda_n the smallest lambda at which the irradiance of a delta light at this order,
 * sum_l h_l A_l (2l+1)/(4 pi) P_l(cos angle), is non-negative at every normal (tabulated in
 * double: 0.25 at order 2, 0.178-0.181 at orders 3-16; none needed at order 1). So strength is
 * normalised: 0 leaves the light unchanged (a bit-exact copy); 1
 * (PRT_SH_DERING_DEFAULT_STRENGTH) is the weakest window under which a point light, and so by
 * linearity any non-negative light, gives no unoccluded diffuse normal a negative irradiance;
 * larger blurs more, towards the mean alone. The mean (band 0, h_0 = 1) and so the average
 * irradiance are kept, and because the window is per band it commutes with prt_sh_rotate. It
 * trades accuracy for positivity: it blurs every light, not only the sun (at strength 1 band 1
 * keeps about 58 % and band 2 about 13 %), and the light's own radiance, as opposed to its
 * irradiance, needs 1.4 to 2 times the default strength to be non-negative.
 * light_rgb and out_rgb hold order*order RGB coefficients, coefficient-major (as prt_sh_shade
 * takes them); out_rgb == light_rgb is allowed. Returns PRT_ERROR_INVALID_ARGUMENT for NULL
 * pointers, an order of 0 or above PRT_SH_MAX_ORDER, or a strength that is negative, NaN or
 * infinite. */
PRT_API prt_result prt_sh_dering_light(uint32_t order, float strength, const float* light_rgb,
                                       float* out_rgb);

#ifdef __cplusplus
}
#endif

#endif /* PRT_SH_H */
