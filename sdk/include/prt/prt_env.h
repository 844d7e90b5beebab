/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: one description of an environment image, taken by every technique's
 * projection or resampling of the light (prt_sh_project, prt_wavelet_resample, ...), so a game
 * describes its map once, in the layout it already has. C99 and C++. Pure functions: any thread.
 *
 * Layouts (formats/SPEC.md §12 and §13, world frame of glTF: right-handed, +Y up, front -Z):
 * - PRT_ENV_LATLONG: equirectangular, `height` rows from the top (+Y), `width` texels each;
 *   the image centre is world -Z and three quarters across is +X. Texel (x, y) covers
 *   u in [x, x+1)/width, v in [y, y+1)/height with direction
 *   (sin t sin f, cos t, -sin t cos f), f = 2 pi (u - 1/2), t = pi v.
 *   width = 2 height is the usual shape; any width, height >= 1 is accepted.
 * - PRT_ENV_CUBE: six square faces of `width` = `height` texels in the order +X, -X, +Y, -Y, +Z,
 *   -Z, oriented as OpenGL cube maps (row 0 = GL t = 0): with s_c = 2 (i + 0.5)/F - 1 (column i)
 *   and t_c = 2 (j + 0.5)/F - 1 (row j), the texel's direction is the normalised
 *       +X: ( 1, -t_c, -s_c)   -X: (-1, -t_c,  s_c)   +Y: ( s_c,  1,  t_c)
 *       -Y: ( s_c, -1, -t_c)   +Z: ( s_c, -t_c,  1)   -Z: (-s_c, -t_c, -1).
 * Texel (x, y) of face f starts at texels[f * face_stride + y * row_stride + x * channels]:
 * RGB, then the 4th float when channels is 4 (ignored, e.g. an alpha or padding). A channel
 * value that is NaN, infinite or negative counts as 0. */
#ifndef PRT_ENV_H
#define PRT_ENV_H

#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum prt_env_layout {
  PRT_ENV_LATLONG = 0, /* equirectangular, one image */
  PRT_ENV_CUBE = 1     /* six faces */
} prt_env_layout;

/* The largest cube face (texels per side) an environment image may have. */
#define PRT_ENV_MAX_FACE_SIZE 65536u

typedef struct prt_env_image {
  size_t struct_size; /* set by the caller: sizeof(prt_env_image) */
  prt_env_layout layout;
  uint32_t width;      /* lat-long: texels per row; cube: the face size */
  uint32_t height;     /* lat-long: rows; cube: the face size again (width == height) */
  uint32_t channels;   /* 3 (RGB) or 4 (RGBA, the 4th float ignored) */
  const float* texels; /* the first face's (or the image's) top-left texel */
  size_t row_stride;   /* floats from one row's start to the next; 0: width * channels */
  size_t face_stride;  /* cube: floats from one face's start to the next; 0: height * rows */
  /* Row-major 3x3 proper rotation R turning the light: light that comes from direction d in the
   * image then comes from R d. Finite, orthonormal to 1e-3 and with determinant +1. NULL: none. */
  const float* rotation;
} prt_env_image;

/* PRT_OK when every projection and resampling accepts `env`; PRT_ERROR_INVALID_ARGUMENT for a NULL
 * env or texels, a struct_size below 1.0's, an unknown layout, a zero width or height, a cube
 * whose width and height differ or exceed PRT_ENV_MAX_FACE_SIZE, channels other than 3 or 4, a
 * row_stride below width * channels, a face_stride below height * row_stride, strides whose
 * extent does not fit size_t, or a rotation that is not finite, not orthonormal (to 1e-3) or has
 * determinant -1 (a reflection). */
PRT_API prt_result prt_env_image_validate(const prt_env_image* env);

#ifdef __cplusplus
}
#endif

#endif /* PRT_ENV_H */
