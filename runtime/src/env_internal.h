/* SPDX-License-Identifier: MIT */
/* Private to the runtime: an environment image (prt_env.h) checked once and with its defaults
 * resolved, as every projection and resampling reads it. */
#ifndef PRT_RUNTIME_ENV_INTERNAL_H
#define PRT_RUNTIME_ENV_INTERNAL_H

#include "internal.h"

typedef struct prt_env_view {
  prt_env_layout layout;
  uint32_t width, height, channels;
  uint32_t faces; /* 1 lat-long, 6 cube */
  const float* texels;
  size_t row_stride, face_stride; /* in floats, defaults applied */
  const float* rotation;          /* NULL: none */
} prt_env_view;

/* Checks env as prt_env_image_validate does and fills *out; PRT_ERROR_INVALID_ARGUMENT when it
 * is rejected. */
prt_result prt_internal_env_open(const prt_env_image* env, prt_env_view* out);

/* The first channel of texel (x, y) of face f (0 for lat-long). */
static inline const float* prt_env_texel(const prt_env_view* env, uint32_t face, uint32_t x,
                                         uint32_t y) {
  return env->texels + (size_t)face * env->face_stride + (size_t)y * env->row_stride +
         (size_t)x * env->channels;
}

#endif /* PRT_RUNTIME_ENV_INTERNAL_H */
