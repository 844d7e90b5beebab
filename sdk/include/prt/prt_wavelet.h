/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: 2-D Haar wavelets on square images (cube-map faces), the basis of the
 * `wavelet` technique (all-frequency shadows, Ng, Ramamoorthi, Hanrahan 2003). C99 and C++.
 * Pure functions: no context, no heap allocation (at most 16 KiB of stack), no global state; any
 * thread at any time.
 *
 * Convention (normative; formats/SPEC.md §14 carries it with the `wavelet` section):
 * - A face is size x size texels (size a power of two, 1..PRT_HAAR_MAX_SIZE), rows from the top,
 *   each texel `channels` consecutive floats (1..PRT_HAAR_MAX_CHANNELS), tightly packed.
 * - The transform is the orthonormal Haar basis in the NON-STANDARD decomposition: one level
 *   transforms every row of the current n x n top-left block (pairs (a, b) -> (a+b)/sqrt 2 in
 *   the left half, (a-b)/sqrt 2 in the right half), then every column of it the same way (sums
 *   on top, differences below), and the next level repeats on the n/2 x n/2 top-left block, down
 *   to 1 x 1. So each 2x2 block [a b; c d] gives
 *       scaling              (a+b+c+d)/2  -> top-left quadrant
 *       difference along x   (a-b+c-d)/2  -> top-right
 *       difference along y   (a+b-c-d)/2  -> bottom-left
 *       diagonal             (a-b-c+d)/2  -> bottom-right
 *   ("Mallat" placement). After the last level, texel (0, 0) holds the face's single scaling
 *   coefficient, sum / size; the coefficient at (x, y) with max(x, y) in [2^j, 2^(j+1)) belongs
 *   to level j (support size / 2^j texels wide), level 0 being the coarsest detail.
 * - Orthonormal: the sum of squares is preserved (Parseval) and the inverse is the transpose, so
 *   a dot product of two functions equals the dot product of their coefficients. */
#ifndef PRT_WAVELET_H
#define PRT_WAVELET_H

#include <prt/prt_env.h>
#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRT_HAAR_MAX_SIZE 1024u
#define PRT_HAAR_MAX_CHANNELS 4u

/* Forward transform of one face in place (see the convention above). Returns
 * PRT_ERROR_INVALID_ARGUMENT for a NULL face, a size that is 0, not a power of two or above
 * PRT_HAAR_MAX_SIZE, or channels outside 1..PRT_HAAR_MAX_CHANNELS. Non-finite values propagate
 * (the caller sanitises its input). */
PRT_API prt_result prt_haar_forward(uint32_t size, uint32_t channels, float* face);

/* Inverse transform of one face in place: prt_haar_inverse(prt_haar_forward(f)) = f up to float
 * rounding. Errors as prt_haar_forward. */
PRT_API prt_result prt_haar_inverse(uint32_t size, uint32_t channels, float* face);

/* The level of the coefficient at (x, y) of a transformed face of this size: -1 for the scaling
 * coefficient (0, 0), else j with max(x, y) in [2^j, 2^(j+1)); its basis function's support is
 * (size >> j) texels wide, i.e. covers (size >> j)^2 texels. -2 for coordinates outside the face
 * or a bad size. */
PRT_API int prt_haar_level(uint32_t size, uint32_t x, uint32_t y);

/* ---- Parameterisations of the sphere (formats/SPEC.md §14) --------------------------------- */

/* The parameterisations: the cube of six S x S faces (§13's face order and orientation), or the
 * dual paraboloid of two S x S faces (upper hemisphere y >= 0 first). The values are the WVLT
 * header's `param`. */
typedef enum prt_wavelet_param {
  PRT_WAVELET_PARAM_CUBE = 0,
  PRT_WAVELET_PARAM_DUAL_PARABOLOID = 1
} prt_wavelet_param;

#define PRT_WAVELET_MIN_SIZE 16u
#define PRT_WAVELET_MAX_SIZE 128u

/* Faces of a parameterisation (6 or 2); 0 for an unknown param. */
PRT_API uint32_t prt_wavelet_face_count(prt_wavelet_param param);

/* Coefficients (= texels) of a parameterisation: faces * size^2; 0 for an unknown param or a
 * size that is not a power of two in PRT_WAVELET_MIN_SIZE..PRT_WAVELET_MAX_SIZE. */
PRT_API uint32_t prt_wavelet_coefficient_count(prt_wavelet_param param, uint32_t size);

/* The unit direction at continuous coordinates (u, v) in [0, size]^2 of a face (texel (x, y)
 * covers [x, x+1) x [y, y+1)). Returns 1 and writes dir, or 0 when (u, v) has no direction
 * (outside the paraboloid's disc) or an argument is bad. */
PRT_API int prt_wavelet_direction(prt_wavelet_param param, uint32_t size, uint32_t face, float u,
                                  float v, float dir[3]);

/* prt_wavelet_direction at `count` points (u[i], v[i]) of one face, with the same bits: writes
 * dirs[3i..3i+2] and has_direction[i] = 1 where the point has a direction, has_direction[i] = 0
 * (dirs[3i..] untouched) where it has none. Returns 0 and writes nothing for a bad param, size or
 * face or a NULL array with count > 0, else 1. For bakes that place many samples at a time. */
PRT_API int prt_wavelet_directions(prt_wavelet_param param, uint32_t size, uint32_t face,
                                   uint32_t count, const float* u, const float* v, float* dirs,
                                   uint8_t* has_direction);

/* The solid angle of texel (x, y) of a face (§14; 0 for a paraboloid texel outside the disc or a
 * bad argument). Sums to 4 pi over a cube. */
PRT_API double prt_wavelet_texel_solid_angle(prt_wavelet_param param, uint32_t size, uint32_t face,
                                             uint32_t x, uint32_t y);

/* The global index f*size^2 + y*size + x of the texel holding direction dir (need not be unit
 * length). Always an inside texel (§14 for the paraboloid's rim). The zero vector and
 * non-finite components have no direction: the cube gives texel 0, the paraboloid the texel of
 * direction (-sqrt 1/2, 0, -sqrt 1/2) (§14). 0xFFFFFFFF for a bad param or size. */
PRT_API uint32_t prt_wavelet_locate(prt_wavelet_param param, uint32_t size, const float dir[3]);

/* The band of coefficient j (§7.2): face * (log2 size + 1) + (level + 1), level from
 * prt_haar_level; bands per face = log2 size + 1. 0xFFFFFFFF for a bad argument. */
PRT_API uint32_t prt_wavelet_band(prt_wavelet_param param, uint32_t size, uint32_t j);

/* ---- Light, once per frame ----------------------------------------------------------------- */

/* A light is prt_wavelet_coefficient_count(param, size) RGBA float quadruples, indexed by the
 * global texel/coefficient index; the 4th float of each is padding and written as 0. The steps
 * are: resample (texel values) -> transform (Haar coefficients) -> select (keep M) ->
 * prt_wavelet_prepare_light (prt_wavelet_asset.h). Each step is a pure function of its
 * arguments; a game may run them on any thread, e.g. the light for frame n+1 while frame n
 * shades. */

/* Resamples an environment image (prt_env.h: lat-long or cube, RGB or RGBA, any strides, turned
 * by env->rotation) onto the texels of a parameterisation: out_rgba = the power per texel, i.e.
 * its mean radiance times its solid angle (§14; a vertex's radiance is then sum_j T_j P_j with
 * T_j its transfer's mean over texel j; a source finer than the texels keeps its power exactly).
 * Non-finite and negative channels count as 0. PRT_ERROR_INVALID_ARGUMENT for a NULL out_rgba, a
 * bad param or size, or an env that prt_env_image_validate rejects. */
PRT_API prt_result prt_wavelet_resample(prt_wavelet_param param, uint32_t size,
                                        const prt_env_image* env, float* out_rgba);

/* Haar-transforms every face of a light in place (texel powers -> coefficients, §14). A game
 * that builds its own texel light writes radiance x prt_wavelet_texel_solid_angle per texel. */
PRT_API prt_result prt_wavelet_transform_light(prt_wavelet_param param, uint32_t size, float* rgba);

/* Keeps every face's scaling coefficient and the m detail coefficients of largest area-weighted
 * magnitude (§14, Ng et al. 2003), setting the others to 0; m >= the detail count keeps all.
 * Deterministic (ties keep the lower index); no heap. */
PRT_API prt_result prt_wavelet_select_light(prt_wavelet_param param, uint32_t size, uint32_t m,
                                            float* rgba);

#ifdef __cplusplus
}
#endif

#endif /* PRT_WAVELET_H */
