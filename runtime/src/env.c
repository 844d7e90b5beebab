/* SPDX-License-Identifier: MIT */
/* The environment image every projection and resampling takes (prt_env.h): one check, used by
 * all of them. */
#include "env_internal.h"
#include "sphere_internal.h"

/* a * b for b > 0, or 0 when it does not fit size_t. */
static size_t product(size_t a, size_t b) {
  return a > SIZE_MAX / b ? 0u : a * b;
}

prt_result prt_internal_env_open(const prt_env_image* caller_env, prt_env_view* out) {
  prt_env_image env;
  size_t texel_row, face_floats;
  if (!caller_env || !prt_internal_struct_size_ok(caller_env, PRT_ENV_IMAGE_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  memset(&env, 0, sizeof env);
  memcpy(&env, caller_env,
         caller_env->struct_size < sizeof env ? caller_env->struct_size : sizeof env);
  if ((env.layout != PRT_ENV_LATLONG && env.layout != PRT_ENV_CUBE) || !env.texels ||
      env.width == 0 || env.height == 0 || (env.channels != 3 && env.channels != 4))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (env.layout == PRT_ENV_CUBE && (env.width != env.height || env.width > PRT_ENV_MAX_FACE_SIZE))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (env.rotation && !prt_is_rotation(env.rotation)) return PRT_ERROR_INVALID_ARGUMENT;
  /* Strides and their defaults; the image's extent (6 faces at most) must fit size_t. */
  texel_row = product(env.width, env.channels);
  if (texel_row == 0) return PRT_ERROR_INVALID_ARGUMENT;
  out->row_stride = env.row_stride ? env.row_stride : texel_row;
  if (out->row_stride < texel_row) return PRT_ERROR_INVALID_ARGUMENT;
  face_floats = product(out->row_stride, env.height);
  if (face_floats == 0) return PRT_ERROR_INVALID_ARGUMENT;
  out->faces = env.layout == PRT_ENV_CUBE ? 6u : 1u;
  out->face_stride = 0;
  if (env.layout == PRT_ENV_CUBE) {
    out->face_stride = env.face_stride ? env.face_stride : face_floats;
    if (out->face_stride < face_floats || product(out->face_stride, 6u) == 0)
      return PRT_ERROR_INVALID_ARGUMENT;
  }
  out->layout = env.layout;
  out->width = env.width;
  out->height = env.height;
  out->channels = env.channels;
  out->texels = env.texels;
  out->rotation = env.rotation;
  return PRT_OK;
}

prt_result prt_env_image_validate(const prt_env_image* env) {
  prt_env_view view;
  return prt_internal_env_open(env, &view);
}
