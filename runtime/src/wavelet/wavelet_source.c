/* SPDX-License-Identifier: MIT */
/* The prepared wavelet source (prt_wavelet_source.h): the map copied sanitised, with the
 * direction and solid-angle tables prt_wavelet_resample (wavelet_light.c) computes per frame,
 * built here with the same expressions; the scalar resampling, which runs the same loops as
 * prt_wavelet_resample, and the dispatch to the SIMD kernels. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "env_internal.h"
#include "sphere_internal.h"
#include "wavelet_internal.h"
#include "wavelet_light_internal.h"
#include "wavelet_source_internal.h"

#define PRT_WAVELET_SOURCE_DESC_SIZE_1_0 PRT_SIZE_THROUGH(prt_wavelet_source_desc, flags)

/* A channel value as the light uses it: NaN, infinities and negatives count as 0. */
static float sanitised(float value) {
  return (value > 0.0f && value <= FLT_MAX) ? value : 0.0f; /* NaN fails both */
}

/* ---- The single allocation: the texels first (64-byte aligned), then the tables. ---- */

typedef struct source_layout {
  size_t texel_bytes;          /* of the cube map's RGBA or the lat-long map's bands */
  size_t columns, rows, plane; /* plane: texels of one cube face, or 0 */
  size_t total;                /* bytes after the struct */
} source_layout;

static size_t round_up(size_t n, size_t to) {
  return (n + to - 1u) / to * to;
}

/* 0 when the sizes do not fit size_t. */
static int plan_layout(const prt_env_view* env, uint32_t size, source_layout* out) {
  const size_t w = env->width, h = env->height;
  const size_t limit = SIZE_MAX / 64u;
  /* The bands' rows: h rounded up to whole bands (h < 2^32, so this cannot wrap). */
  const size_t band_rows = round_up(h, PRT_WAVELET_BAND_ROWS);
  out->columns = w;
  out->rows = h;
  if (w > limit / band_rows || w * band_rows > limit / env->faces) return 0;
  out->plane = env->layout == PRT_ENV_CUBE ? w * h : 0u;
  out->texel_bytes = env->layout == PRT_ENV_CUBE ? 16u * w * h * env->faces : 12u * w * band_rows;
  out->total = round_up(out->texel_bytes, 64u) + 8u * (2u * w + 2u * h + out->plane) +
               8u * (size_t)size * size + 4u * (env->layout == PRT_ENV_CUBE ? out->plane : h);
  return 1;
}

static void fill_latlong_tables(prt_wavelet_source* s) {
  const uint32_t width = s->env.width, height = s->env.height;
  const double column_step = 2.0 * PRT_SPHERE_PI / (double)width;
  uint32_t x, y;
  for (x = 0; x < width; ++x) {
    /* Column centre: f = 2 pi ((x + 1/2) / W - 1/2) (SPEC §12). */
    const double phi = column_step * ((double)x + 0.5) - PRT_SPHERE_PI;
    s->column_sin[x] = sin(phi);
    s->column_cos[x] = cos(phi);
  }
  for (y = 0; y < height; ++y) {
    const double theta = PRT_SPHERE_PI * ((double)y + 0.5) / (double)height;
    const double cos_top = cos(PRT_SPHERE_PI * (double)y / (double)height);
    const double cos_bottom = cos(PRT_SPHERE_PI * (double)(y + 1u) / (double)height);
    s->row_sin[y] = sin(theta);
    s->row_cos[y] = cos(theta);
    s->texel_solid_angle[y] = (float)(2.0 * PRT_SPHERE_PI / (double)width * (cos_top - cos_bottom));
  }
  s->largest_texel = prt_wavelet_latlong_largest_texel(width, height);
}

/* The face coordinates, lengths and exact solid angles of wavelet_light.c's cube loop. */
static void fill_cube_tables(prt_wavelet_source* s) {
  const uint32_t face_size = s->env.width;
  const double step = 2.0 / (double)face_size;
  uint32_t i, j;
  for (j = 0; j < face_size; ++j) {
    const double t0 = step * (double)j - 1.0, t1 = t0 + step, tc = 0.5 * (t0 + t1);
    double corner_top = prt_cube_corner_solid_angle(-1.0, t0);
    double corner_bottom = prt_cube_corner_solid_angle(-1.0, t1);
    s->row_cos[j] = tc;
    for (i = 0; i < face_size; ++i) {
      const double s1 = step * (double)(i + 1u) - 1.0, sc = s1 - 0.5 * step;
      const double next_top = prt_cube_corner_solid_angle(s1, t0);
      const double next_bottom = prt_cube_corner_solid_angle(s1, t1);
      const size_t at = (size_t)j * face_size + i;
      s->texel_solid_angle[at] = (float)fabs(next_bottom - corner_bottom - next_top + corner_top);
      s->inv_length[at] = 1.0 / sqrt(1.0 + sc * sc + tc * tc);
      if (j == 0u) s->column_cos[i] = sc;
      corner_top = next_top;
      corner_bottom = next_bottom;
    }
  }
  s->largest_texel = prt_wavelet_cube_largest_texel(face_size);
}

static void copy_cube_radiance(const prt_env_view* env, float* radiance) {
  uint32_t f, x, y, c;
  for (f = 0; f < env->faces; ++f)
    for (y = 0; y < env->height; ++y)
      for (x = 0; x < env->width; ++x) {
        const float* texel = prt_env_texel(env, f, x, y);
        float* to = radiance + 4u * (((size_t)f * env->height + y) * env->width + x);
        for (c = 0; c < 3u; ++c) to[c] = sanitised(texel[c]);
        to[3] = 1.0f;
      }
}

/* The lat-long map into its bands (the rows past the last stay 0: the allocation is zeroed). */
static void copy_banded_radiance(const prt_env_view* env, float* banded) {
  uint32_t x, y, c;
  for (y = 0; y < env->height; ++y)
    for (x = 0; x < env->width; ++x) {
      const float* texel = prt_env_texel(env, 0u, x, y);
      float* to = banded + prt_wavelet_banded_at(env->width, x, y);
      for (c = 0; c < 3u; ++c) to[c * PRT_WAVELET_BAND_ROWS] = sanitised(texel[c]);
    }
}

/* The lat-long solid angle of row y of `height` rows, `width` columns (SPEC §12). */
static double latlong_row_solid_angle(uint32_t width, uint32_t height, uint32_t y) {
  return 2.0 * PRT_SPHERE_PI / (double)width *
         (cos(PRT_SPHERE_PI * (double)y / (double)height) -
          cos(PRT_SPHERE_PI * (double)(y + 1u) / (double)height));
}

/* PRT_WAVELET_SOURCE_REDUCE_2X2: texel (x, y) of the half-size map gets the power of the full
 * map's 2x2 block over the block's solid angle (the half-size texel's, as lat-long rows add). */
static void copy_reduced_radiance(const prt_env_view* env, float* banded) {
  const uint32_t width = env->width / 2u, height = env->height / 2u;
  uint32_t x, y, c, i;
  for (y = 0; y < height; ++y) {
    const double dw[2] = {latlong_row_solid_angle(env->width, env->height, 2u * y),
                          latlong_row_solid_angle(env->width, env->height, 2u * y + 1u)};
    const double block = 2.0 * (dw[0] + dw[1]);
    for (x = 0; x < width; ++x) {
      double power[3] = {0.0, 0.0, 0.0};
      float* to = banded + prt_wavelet_banded_at(width, x, y);
      for (i = 0; i < 4u; ++i) {
        const float* texel = prt_env_texel(env, 0u, 2u * x + (i & 1u), 2u * y + (i >> 1));
        for (c = 0; c < 3u; ++c) power[c] += (double)sanitised(texel[c]) * dw[i >> 1];
      }
      for (c = 0; c < 3u; ++c) to[c * PRT_WAVELET_BAND_ROWS] = (float)(power[c] / block);
    }
  }
}

prt_result prt_wavelet_source_create(prt_context* context, const prt_wavelet_source_desc* desc,
                                     prt_wavelet_source** out_source) {
  prt_wavelet_source_desc d;
  prt_env_view env, reduced;
  source_layout layout;
  prt_wavelet_source* s;
  unsigned char* at;
  size_t bytes;
  uint32_t x, y;
  if (out_source) *out_source = NULL;
  if (!context) return PRT_ERROR_INVALID_ARGUMENT;
  if (!desc || !out_source || !prt_internal_struct_size_ok(desc, PRT_WAVELET_SOURCE_DESC_SIZE_1_0))
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_wavelet_source_create: NULL desc or out_source, or a "
                             "struct_size below 1.0's");
  memset(&d, 0, sizeof d);
  memcpy(&d, desc, desc->struct_size < sizeof d ? desc->struct_size : sizeof d);
  if (!prt_wavelet_domain_valid(d.param, d.size))
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_wavelet_source_create: bad param or size");
  if (prt_internal_env_open(d.env, &env) != PRT_OK || env.rotation)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_wavelet_source_create: env rejected by prt_env_image_validate "
                             "or with a rotation (give it per frame)");
  if ((d.flags & ~(uint32_t)PRT_WAVELET_SOURCE_REDUCE_2X2) != 0u ||
      ((d.flags & PRT_WAVELET_SOURCE_REDUCE_2X2) &&
       (env.layout != PRT_ENV_LATLONG || env.width % 2u != 0u || env.height % 2u != 0u)))
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_wavelet_source_create: unknown flag, or REDUCE_2X2 on a cube "
                             "map or an odd width or height");
  reduced = env;
  if (d.flags & PRT_WAVELET_SOURCE_REDUCE_2X2) reduced.width /= 2u, reduced.height /= 2u;
  if (!plan_layout(&reduced, d.size, &layout))
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY,
                             "prt_wavelet_source_create: the map is too large");
  bytes = round_up(sizeof *s, 64u) + layout.total;
  s = (prt_wavelet_source*)prt_internal_alloc(&context->allocator, bytes, 64u);
  if (!s)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY,
                             "prt_wavelet_source_create: out of memory");
  memset(s, 0, bytes);
  s->allocator = context->allocator;
  s->bytes = bytes;
  s->isa = prt_internal_simd_isa(context);
  s->avx512 = prt_internal_simd_isa(context) >= PRT_SIMD_ISA_AVX512;
  s->param = d.param;
  s->size = d.size;
  at = (unsigned char*)s + round_up(sizeof *s, 64u);
  if (env.layout == PRT_ENV_CUBE)
    s->radiance = (float*)(void*)at;
  else
    s->banded = (float*)(void*)at;
  at += round_up(layout.texel_bytes, 64u);
  s->column_sin = (double*)(void*)at;
  s->column_cos = s->column_sin + layout.columns;
  s->row_sin = s->column_cos + layout.columns;
  s->row_cos = s->row_sin + layout.rows;
  s->inv_length = s->row_cos + layout.rows;
  s->target_solid_angle = s->inv_length + layout.plane;
  s->texel_solid_angle = (float*)(void*)(s->target_solid_angle + (size_t)d.size * d.size);
  s->env = reduced;
  s->env.channels = 4u;
  s->env.texels = s->radiance;
  s->env.row_stride = 4u * (size_t)reduced.width;
  s->env.face_stride = s->env.row_stride * reduced.height;
  if (d.flags & PRT_WAVELET_SOURCE_REDUCE_2X2)
    copy_reduced_radiance(&env, s->banded);
  else if (env.layout == PRT_ENV_CUBE)
    copy_cube_radiance(&env, s->radiance);
  else
    copy_banded_radiance(&env, s->banded);
  if (env.layout == PRT_ENV_LATLONG)
    fill_latlong_tables(s);
  else
    fill_cube_tables(s);
  for (y = 0; y < d.size; ++y)
    for (x = 0; x < d.size; ++x)
      s->target_solid_angle[(size_t)y * d.size + x] =
          prt_wavelet_texel_solid_angle(d.param, d.size, 0u, x, y);
  *out_source = s;
  return PRT_OK;
}

void prt_wavelet_source_destroy(prt_wavelet_source* source) {
  if (source) {
    const prt_allocator allocator = source->allocator;
    prt_internal_free(&allocator, source, source->bytes);
  }
}

/* ---- Scalar resampling: wavelet_light.c's loops over the tables. ---- */

/* out[target] += (L dw, dw), L's channels `step` floats apart. */
static inline void accumulate(float* out_rgba, uint32_t target, const float* radiance, size_t step,
                              float solid_angle) {
  float* to = out_rgba + 4u * (size_t)target;
  to[0] += radiance[0] * solid_angle;
  to[1] += radiance[step] * solid_angle;
  to[2] += radiance[2u * step] * solid_angle;
  to[3] += solid_angle;
}

/* g(f) = R (sin f, 0, -cos f) of column x (wavelet_light.c's turned azimuth). */
static inline void turned_azimuth(const prt_wavelet_source* s, const double r[9], uint32_t x,
                                  double g[3]) {
  const double sin_phi = s->column_sin[x], cos_phi = s->column_cos[x];
  g[0] = r[0] * sin_phi - r[2] * cos_phi;
  g[1] = r[3] * sin_phi - r[5] * cos_phi;
  g[2] = r[6] * sin_phi - r[8] * cos_phi;
}

/* R d = sin t g(f) + cos t R e_y, as wavelet_light.c's row loop evaluates it. */
static inline uint32_t locate_latlong(const prt_wavelet_source* s, uint32_t param,
                                      const double r[9], const double g[3], uint32_t y) {
  const double sin_theta = s->row_sin[y], cos_theta = s->row_cos[y];
  const double up0 = cos_theta * r[1], up1 = cos_theta * r[4], up2 = cos_theta * r[7];
  return prt_wavelet_locate_unit(param, s->size, sin_theta * g[0] + up0, sin_theta * g[1] + up1,
                                 sin_theta * g[2] + up2);
}

uint32_t prt_wavelet_source_locate_latlong(const prt_wavelet_source* source, const double r[9],
                                           uint32_t x, uint32_t y) {
  double g[3];
  turned_azimuth(source, r, x, g);
  return locate_latlong(source, source->param, r, g, y);
}

/* param is a literal at each call, so the inlined locate has no param branch. */
static inline void splat_latlong_for_param(const prt_wavelet_source* s, uint32_t param,
                                           const double r[9], float* out_rgba) {
  const uint32_t width = s->env.width, height = s->env.height;
  double g[3 * PRT_WAVELET_SOURCE_COLUMN_BLOCK];
  uint32_t first, x, y;
  for (first = 0; first < width; first += PRT_WAVELET_SOURCE_COLUMN_BLOCK) {
    const uint32_t count = width - first < PRT_WAVELET_SOURCE_COLUMN_BLOCK
                               ? width - first
                               : PRT_WAVELET_SOURCE_COLUMN_BLOCK;
    for (x = 0; x < count; ++x) turned_azimuth(s, r, first + x, g + 3 * x);
    for (y = 0; y < height; ++y) {
      const float* radiance = s->banded + prt_wavelet_banded_at(width, first, y);
      const float solid_angle = s->texel_solid_angle[y];
      for (x = 0; x < count; ++x)
        accumulate(out_rgba, locate_latlong(s, param, r, g + 3 * x, y),
                   radiance + 3u * PRT_WAVELET_BAND_ROWS * x, PRT_WAVELET_BAND_ROWS, solid_angle);
    }
  }
}

static void splat_cube_map(const prt_wavelet_source* s, const double r[9], float* out_rgba) {
  const uint32_t face_size = s->env.width;
  uint32_t i, j, f;
  for (j = 0; j < face_size; ++j) {
    const double tc = s->row_cos[j];
    for (i = 0; i < face_size; ++i) {
      const size_t at = (size_t)j * face_size + i;
      const double sc = s->column_cos[i], inv_length = s->inv_length[at];
      const float solid_angle = s->texel_solid_angle[at];
      for (f = 0; f < 6u; ++f)
        accumulate(out_rgba,
                   prt_wavelet_locate_cube_texel(s->param, s->size, r, f, sc, tc, inv_length),
                   s->radiance + 4u * ((size_t)f * face_size * face_size + at), 1u, solid_angle);
    }
  }
}

prt_result prt_wavelet_source_resample(const prt_wavelet_source* source, const float* rotation,
                                       float* out_rgba) {
  double r[9];
  uint32_t i;
  if (!source || !out_rgba || (rotation && !prt_is_rotation(rotation)))
    return PRT_ERROR_INVALID_ARGUMENT;
  for (i = 0; i < 9u; ++i) r[i] = rotation ? (double)rotation[i] : (i % 4u == 0u ? 1.0 : 0.0);
  memset(out_rgba, 0,
         4u * sizeof(float) * prt_wavelet_coefficient_count(source->param, source->size));
  if (source->env.layout == PRT_ENV_CUBE) {
    splat_cube_map(source, r, out_rgba);
  } else if (source->param == PRT_WAVELET_PARAM_CUBE) {
#if defined(PRT_HAS_X86_SIMD)
    if (source->avx512)
      prt_wavelet_source_splat_cube_avx512(source, r, out_rgba);
    else if (source->isa >= PRT_SIMD_ISA_AVX2)
      prt_wavelet_source_splat_cube_avx2(source, r, out_rgba);
    else
#endif
      splat_latlong_for_param(source, PRT_WAVELET_PARAM_CUBE, r, out_rgba);
  } else {
    splat_latlong_for_param(source, PRT_WAVELET_PARAM_DUAL_PARABOLOID, r, out_rgba);
  }
  prt_wavelet_finish_resample(source->param, source->size, r, &source->env, source->banded,
                              source->largest_texel, source->target_solid_angle, out_rgba);
  return PRT_OK;
}
