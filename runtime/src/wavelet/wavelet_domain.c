/* SPDX-License-Identifier: MIT */
/* Parameterisations of the sphere for the wavelet technique (SPEC §14): the cube of §13 and the
 * dual paraboloid; texel directions, solid angles, direction -> texel, coefficient bands. */
#include <math.h>

#include "sphere_internal.h"
#include "wavelet_internal.h"

#define NO_TEXEL 0xFFFFFFFFu

int prt_wavelet_domain_valid(uint32_t param, uint32_t size) {
  return (param == PRT_WAVELET_PARAM_CUBE || param == PRT_WAVELET_PARAM_DUAL_PARABOLOID) &&
         size >= PRT_WAVELET_MIN_SIZE && size <= PRT_WAVELET_MAX_SIZE && (size & (size - 1u)) == 0u;
}

uint32_t prt_wavelet_face_count(prt_wavelet_param param) {
  if (param == PRT_WAVELET_PARAM_CUBE) return 6u;
  if (param == PRT_WAVELET_PARAM_DUAL_PARABOLOID) return 2u;
  return 0u;
}

uint32_t prt_wavelet_coefficient_count(prt_wavelet_param param, uint32_t size) {
  if (!prt_wavelet_domain_valid(param, size)) return 0u;
  return prt_wavelet_face_count(param) * size * size;
}

/* Paraboloid disc coordinate of texel centre i: 2 (i + 1/2) / S - 1. */
static double disc_centre(uint32_t i, uint32_t size) {
  return (2.0 * (double)i + 1.0) / (double)size - 1.0;
}

/* prt_wavelet_direction once param, size and face are known to be valid. */
static inline int direction_at(prt_wavelet_param param, uint32_t size, uint32_t face, float u,
                               float v, float dir[3]) {
  const double a = 2.0 * (double)u / (double)size - 1.0;
  const double b = 2.0 * (double)v / (double)size - 1.0;
  double d[3], scale;
  if (!(u >= 0.0f && u <= (float)size && v >= 0.0f && v <= (float)size)) return 0;
  if (param == PRT_WAVELET_PARAM_CUBE) {
    prt_cube_direction(face, a, b, d);
    scale = 1.0 / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  } else {
    const double r2 = a * a + b * b;
    if (r2 > 1.0) return 0;
    d[0] = 2.0 * a;
    d[1] = face == 0u ? 1.0 - r2 : -(1.0 - r2);
    d[2] = face == 0u ? 2.0 * b : -2.0 * b;
    scale = 1.0 / (1.0 + r2);
  }
  dir[0] = (float)(d[0] * scale);
  dir[1] = (float)(d[1] * scale);
  dir[2] = (float)(d[2] * scale);
  return 1;
}

int prt_wavelet_direction(prt_wavelet_param param, uint32_t size, uint32_t face, float u, float v,
                          float dir[3]) {
  if (!prt_wavelet_domain_valid(param, size) || face >= prt_wavelet_face_count(param) || !dir)
    return 0;
  return direction_at(param, size, face, u, v, dir);
}

int prt_wavelet_directions(prt_wavelet_param param, uint32_t size, uint32_t face, uint32_t count,
                           const float* u, const float* v, float* dirs, uint8_t* has_direction) {
  uint32_t i;
  if (!prt_wavelet_domain_valid(param, size) || face >= prt_wavelet_face_count(param) ||
      (count > 0u && (!u || !v || !dirs || !has_direction)))
    return 0;
  for (i = 0; i < count; ++i)
    has_direction[i] = (uint8_t)direction_at(param, size, face, u[i], v[i], dirs + 3u * (size_t)i);
  return 1;
}

double prt_wavelet_texel_solid_angle(prt_wavelet_param param, uint32_t size, uint32_t face,
                                     uint32_t x, uint32_t y) {
  const double step = 2.0 / (double)size;
  if (!prt_wavelet_domain_valid(param, size) || face >= prt_wavelet_face_count(param) ||
      x >= size || y >= size)
    return 0.0;
  if (param == PRT_WAVELET_PARAM_CUBE) {
    const double s0 = step * (double)x - 1.0, t0 = step * (double)y - 1.0;
    return prt_cube_rect_solid_angle(s0, s0 + step, t0, t0 + step);
  } else {
    const double a = disc_centre(x, size), b = disc_centre(y, size);
    const double r2 = a * a + b * b;
    if (r2 > 1.0) return 0.0;
    return 4.0 / ((1.0 + r2) * (1.0 + r2)) * step * step;
  }
}

/* Rim rule (SPEC §14): the inside texel of the face whose centre is nearest to the disc point
 * (a, b), ties to the lower index. The nearest inside centre is at most 2.2 texels from a point
 * of the closed disc (S >= 16), so the 7 x 7 texels around (tx, ty) hold it. */
static uint32_t nearest_inside(uint32_t size, double a, double b, uint32_t tx, uint32_t ty) {
  const uint32_t x0 = tx >= 3u ? tx - 3u : 0u, y0 = ty >= 3u ? ty - 3u : 0u;
  const uint32_t x1 = tx + 3u < size ? tx + 3u : size - 1u;
  const uint32_t y1 = ty + 3u < size ? ty + 3u : size - 1u;
  uint32_t x, y, best = 0u;
  double best_distance = HUGE_VAL;
  for (y = y0; y <= y1; ++y) {
    for (x = x0; x <= x1; ++x) {
      const double ca = disc_centre(x, size), cb = disc_centre(y, size);
      const double distance = (ca - a) * (ca - a) + (cb - b) * (cb - b);
      if (prt_paraboloid_texel_inside(size, x, y) && distance < best_distance) {
        best_distance = distance;
        best = y * size + x;
      }
    }
  }
  return best;
}

uint32_t prt_wavelet_paraboloid_rim_texel(uint32_t size, double a, double b) {
  uint32_t tx, ty;
  if (a * a + b * b > 1.0) { /* rounding, or a direction that was not quite unit length */
    const double scale = 1.0 / sqrt(a * a + b * b);
    a *= scale;
    b *= scale;
  }
  tx = prt_face_texel(a, size);
  ty = prt_face_texel(b, size);
  if (prt_paraboloid_texel_inside(size, tx, ty)) return ty * size + tx;
  return nearest_inside(size, a, b, tx, ty);
}

uint32_t prt_wavelet_locate(prt_wavelet_param param, uint32_t size, const float dir[3]) {
  double x, y, z, length;
  if (!prt_wavelet_domain_valid(param, size)) return NO_TEXEL;
  if (dir) {
    x = dir[0], y = dir[1], z = dir[2];
    length = sqrt(x * x + y * y + z * z);
    if (isfinite(length) && length > 0.0)
      return prt_wavelet_locate_unit(param, size, x / length, y / length, z / length);
  }
  /* No direction: face 0's texel 0 on the cube; on the paraboloid (whose texel 0 is outside)
   * the texel the rim rule gives for the disc point nearest that corner, direction
   * (-1/sqrt 2, 0, -1/sqrt 2). */
  if (param == PRT_WAVELET_PARAM_CUBE) return 0u;
  return prt_wavelet_locate_unit(param, size, -sqrt(0.5), 0.0, -sqrt(0.5));
}

uint32_t prt_wavelet_band(prt_wavelet_param param, uint32_t size, uint32_t j) {
  const uint32_t count = prt_wavelet_coefficient_count(param, size);
  uint32_t face, within, log2_size = 0u;
  if (count == 0u || j >= count) return NO_TEXEL;
  while ((1u << log2_size) < size) ++log2_size;
  face = j / (size * size);
  within = j % (size * size);
  return face * (log2_size + 1u) +
         (uint32_t)(prt_haar_level(size, within % size, within / size) + 1);
}
