/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: a prepared environment map for the `wavelet` light update, once per map
 * instead of once per frame. C99 and C++.
 *
 * prt_wavelet_resample (prt_wavelet.h) reads the map, sanitises it and computes every source
 * texel's direction and solid angle again each frame. A source does the rotation-independent part
 * once: it copies the map sanitised, with each texel's direction set-up and solid angle, and the
 * target texels' solid angles. prt_wavelet_source_resample then only turns the directions by the
 * frame's rotation and accumulates, on the context's SIMD instruction set where there is a kernel
 * for it (a lat-long map onto the cube: AVX2 or AVX512; otherwise the scalar path). Its result
 * equals prt_wavelet_resample's for the same map and rotation up to the order of the float sums:
 * every source texel lands in the same target texel (a direction whose texel a float computation
 * could get wrong is located again exactly as prt_wavelet_resample does). */
#ifndef PRT_WAVELET_SOURCE_H
#define PRT_WAVELET_SOURCE_H

#include <prt/prt_context.h>
#include <prt/prt_env.h>
#include <prt/prt_types.h>
#include <prt/prt_wavelet.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct prt_wavelet_source prt_wavelet_source;

/* Bits of prt_wavelet_source_desc.flags. */
typedef enum prt_wavelet_source_flag {
  /* Sum each 2x2 block of a lat-long map (even width and height) into one texel of a map of
   * half the width and height first: its radiance is the block's power over its solid angle,
   * so each block's power is kept but lands at the block's centre, which can move it into a
   * neighbouring target texel; and a half-size map can leave target texels empty, which take
   * their nearest texel's radiance. NOT prt_wavelet_resample's result for the map (it is that
   * for the half-size map); a quarter of the work per frame. */
  PRT_WAVELET_SOURCE_REDUCE_2X2 = 0x1
} prt_wavelet_source_flag;

/* What a source is prepared for. A zero-initialised struct with struct_size set is not valid:
 * env is required. */
typedef struct prt_wavelet_source_desc {
  size_t struct_size;      /* set by the caller: sizeof(prt_wavelet_source_desc) */
  prt_wavelet_param param; /* the target parameterisation */
  uint32_t size;           /* its face size, as prt_wavelet_resample's */
  /* The map (any layout, channels and strides prt_env_image_validate accepts); copied, so it
   * may be freed after the call. Its rotation must be NULL: the rotation is given per frame. */
  const prt_env_image* env;
  uint32_t flags; /* prt_wavelet_source_flag bits */
} prt_wavelet_source_desc;

/* Prepares a source with the context's allocator (about 12 bytes per source texel of a lat-long
 * map, 16 of a cube map, plus tables).
 * On success *out_source receives it; on failure *out_source is NULL (when out_source is not
 * NULL). PRT_ERROR_INVALID_ARGUMENT for a NULL context, desc or out_source, a struct_size below
 * 1.0's, a bad param or size, an env that prt_env_image_validate rejects or whose rotation is not
 * NULL, an unknown flag, PRT_WAVELET_SOURCE_REDUCE_2X2 on a cube map or an odd width or height;
 * PRT_ERROR_OUT_OF_MEMORY. The context must outlive the source. */
PRT_API prt_result prt_wavelet_source_create(prt_context* context,
                                             const prt_wavelet_source_desc* desc,
                                             prt_wavelet_source** out_source);

/* Resamples the source turned by `rotation` (row-major 3x3 proper rotation, as
 * prt_env_image.rotation; NULL: none) into out_rgba, prt_wavelet_coefficient_count(param, size)
 * RGBA quadruples: the texel powers prt_wavelet_resample gives (see above), the 4th floats 0.
 * Reads the source only: several threads may resample one source at once (into different
 * outputs). PRT_ERROR_INVALID_ARGUMENT for a NULL source or out_rgba, or a rotation that is not
 * finite, not orthonormal (to 1e-3) or a reflection. */
PRT_API prt_result prt_wavelet_source_resample(const prt_wavelet_source* source,
                                               const float* rotation, float* out_rgba);

/* Destroys a source. NULL is allowed. */
PRT_API void prt_wavelet_source_destroy(prt_wavelet_source* source);

#ifdef __cplusplus
}
#endif

#endif /* PRT_WAVELET_SOURCE_H */
