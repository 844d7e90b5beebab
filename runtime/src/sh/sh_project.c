/* SPDX-License-Identifier: MIT */
/* Projection of environment images (prt_env.h: lat-long or cube) onto SH (convention: prt_sh.h).
 * Each texel contributes radiance(centre) * Y(centre) * exact solid angle, accumulated in double;
 * a rotation turns the projected coefficients (prt_sh_rotate). */
#include <math.h>
#include <string.h>

#include "env_internal.h"
#include "sh_internal.h"
#include "sphere_internal.h"

#define PRT_SH_PI 3.14159265358979323846

/* A channel value as used by projection: NaN, infinities and negatives count as 0. */
static double sanitised(float value) {
  return (isfinite(value) && value > 0.0f) ? (double)value : 0.0;
}

static int order_valid(uint32_t order) {
  return order >= 1 && order <= PRT_SH_MAX_ORDER;
}

/* Lat-long. Per row, theta is constant, so the row is first reduced to its azimuthal Fourier
 * sums F_m = sum_x L(x) e^(i m psi_x) (psi the SH-frame azimuth), then combined with the
 * normalised Legendre values of the row: O(W H n + H n^2) instead of O(W H n^2).
 * SPEC §12: d = (sin t sin f, cos t, -sin t cos f), f = 2 pi (u - 1/2); in the SH frame
 * (x, y, z) = (X, -Z, Y) = (sin t sin f, sin t cos f, cos t), so psi = pi/2 - f. */
static void project_latlong(uint32_t order, const prt_env_view* env, double* sums) {
  const uint32_t width = env->width, height = env->height, channels = env->channels;
  double legendre[PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER];
  double fourier_cos[PRT_SH_MAX_ORDER * 3];
  double fourier_sin[PRT_SH_MAX_ORDER * 3];
  const double dpsi = -2.0 * PRT_SH_PI / (double)width;
  const double cos_dpsi = cos(dpsi), sin_dpsi = sin(dpsi);
  uint32_t y;
  for (y = 0; y < height; ++y) {
    const double theta0 = PRT_SH_PI * (double)y / (double)height;
    const double theta1 = PRT_SH_PI * (double)(y + 1) / (double)height;
    const double theta = 0.5 * (theta0 + theta1);
    const double sin_theta = sin(theta), cos_theta = cos(theta);
    const double solid_angle = (2.0 * PRT_SH_PI / (double)width) * (cos(theta0) - cos(theta1));
    const float* row = prt_env_texel(env, 0, 0, y);
    /* e^(i psi) at column 0's centre, f = 2 pi (0.5/W - 0.5); stepped by complex rotation. */
    const double psi0 = 0.5 * PRT_SH_PI - 2.0 * PRT_SH_PI * (0.5 / (double)width - 0.5);
    double col_cos = cos(psi0), col_sin = sin(psi0);
    uint32_t x, m, l, c;
    memset(fourier_cos, 0, sizeof fourier_cos);
    memset(fourier_sin, 0, sizeof fourier_sin);
    for (x = 0; x < width; ++x) {
      const float* texel = row + (size_t)channels * x;
      const double radiance[3] = {sanitised(texel[0]), sanitised(texel[1]), sanitised(texel[2])};
      double cm = 1.0, sm = 0.0, next;
      if (radiance[0] != 0.0 || radiance[1] != 0.0 || radiance[2] != 0.0) {
        for (m = 0; m < order; ++m) {
          for (c = 0; c < 3; ++c) {
            fourier_cos[m * 3 + c] += radiance[c] * cm;
            fourier_sin[m * 3 + c] += radiance[c] * sm;
          }
          next = cm * col_cos - sm * col_sin;
          sm = sm * col_cos + cm * col_sin;
          cm = next;
        }
      }
      next = col_cos * cos_dpsi - col_sin * sin_dpsi;
      col_sin = col_sin * cos_dpsi + col_cos * sin_dpsi;
      col_cos = next;
    }
    /* Y_lm = Q_l^|m| * sqrt2 * sin^|m| theta * cos/sin(m psi); the basis at (sin t, 0, cos t)
     * gives Q_l^m sqrt2 sin^m t in its m > 0 slots (cos 0 = 1). */
    prt_sh_eval_sh_frame_d(order, sin_theta, 0.0, cos_theta, legendre);
    for (l = 0; l < order; ++l) {
      for (c = 0; c < 3; ++c)
        sums[(l * (l + 1)) * 3 + c] += solid_angle * legendre[l * (l + 1)] * fourier_cos[c];
      for (m = 1; m <= l; ++m) {
        const double radial = solid_angle * legendre[l * (l + 1) + m];
        for (c = 0; c < 3; ++c) {
          sums[(l * (l + 1) + m) * 3 + c] += radial * fourier_cos[m * 3 + c];
          sums[(l * (l + 1) - m) * 3 + c] += radial * fourier_sin[m * 3 + c];
        }
      }
    }
  }
}

static void project_cube(uint32_t order, const prt_env_view* env, double* sums) {
  double basis[PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER];
  const uint32_t count = order * order, face_size = env->width;
  const double step = 2.0 / (double)face_size;
  uint32_t face;
  for (face = 0; face < 6; ++face) {
    uint32_t i, j;
    for (j = 0; j < face_size; ++j) {
      const double t0 = -1.0 + step * j, t1 = t0 + step;
      const double tc = 0.5 * (t0 + t1);
      for (i = 0; i < face_size; ++i) {
        const float* texel = prt_env_texel(env, face, i, j);
        const double radiance[3] = {sanitised(texel[0]), sanitised(texel[1]), sanitised(texel[2])};
        const double s0 = -1.0 + step * i, s1 = s0 + step;
        double d[3], inv, solid_angle;
        uint32_t k, c;
        if (radiance[0] == 0.0 && radiance[1] == 0.0 && radiance[2] == 0.0) continue;
        solid_angle = prt_cube_rect_solid_angle(s0, s1, t0, t1);
        prt_cube_direction(face, 0.5 * (s0 + s1), tc, d);
        inv = 1.0 / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        /* World (X, Y, Z) -> SH frame (X, -Z, Y). */
        prt_sh_eval_sh_frame_d(order, d[0] * inv, -d[2] * inv, d[1] * inv, basis);
        for (k = 0; k < count; ++k) {
          const double w = basis[k] * solid_angle;
          for (c = 0; c < 3; ++c) sums[k * 3 + c] += w * radiance[c];
        }
      }
    }
  }
}

prt_result prt_sh_project(uint32_t order, const prt_env_image* image, float* out_rgb) {
  double sums[PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER * 3];
  prt_env_view env;
  uint32_t i;
  if (!order_valid(order) || !out_rgb || prt_internal_env_open(image, &env) != PRT_OK)
    return PRT_ERROR_INVALID_ARGUMENT;
  memset(sums, 0, sizeof sums);
  if (env.layout == PRT_ENV_LATLONG)
    project_latlong(order, &env, sums);
  else
    project_cube(order, &env, sums);
  for (i = 0; i < order * order * 3u; ++i) out_rgb[i] = (float)sums[i];
  /* Exact for band-limited coefficients (prt_sh.h); the rotation was checked with the image. */
  if (env.rotation) return prt_sh_rotate(order, env.rotation, out_rgb, out_rgb, 3u);
  return PRT_OK;
}
