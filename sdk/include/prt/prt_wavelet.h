/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: 2-D Haar wavelets on square images (cube-map faces), the basis of the
 * `wavelet` technique (all-frequency shadows, Ng, Ramamoorthi, Hanrahan 2003). C99 and C++.
 * Pure functions: no context, no heap allocation (at most 16 KiB of stack), no global state; any
 * thread at any time.
 *
 * Convention (normative; formats/SPEC.md will carry it with the `wavelet` section):
 * - A face is size x size texels (size a power of two, 1..PRT_HAAR_MAX_SIZE), rows from the top,
 *   each texel `channels` consecutive floats (1..PRT_HAAR_MAX_CHANNELS), tightly packed.
 * - The transform is the orthonormal Haar basis in the NON-STANDARD decomposition: one level
 *   transforms every row of the current n x n top-left block (pairs (a, b) -> (a+b)/sqrt 2 in
 *   the left half, (a-b)/sqrt 2 in the right half), then every column of it the same way (sums
 *   on top, differences below), and the next level repeats on the n/2 x n/2 top-left block, down
 *   to 1 x 1. So each 2x2 block [a b; c d] gives
 *       scaling (a+b+c+d)/2  -> top-left quadrant        difference along x (a-b+c-d)/2 ->
 * top-right difference along y (a+b-c-d)/2 -> bottom-left    diagonal (a-b-c+d)/2 -> bottom-right
 *   ("Mallat" placement). After the last level, texel (0, 0) holds the face's single scaling
 *   coefficient, sum / size; the coefficient at (x, y) with max(x, y) in [2^j, 2^(j+1)) belongs
 *   to level j (support size / 2^j texels wide), level 0 being the coarsest detail.
 * - Orthonormal: the sum of squares is preserved (Parseval) and the inverse is the transpose, so
 *   a dot product of two functions equals the dot product of their coefficients. */
#ifndef PRT_WAVELET_H
#define PRT_WAVELET_H

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

#ifdef __cplusplus
}
#endif

#endif /* PRT_WAVELET_H */
