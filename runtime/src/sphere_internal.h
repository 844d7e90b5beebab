/* SPDX-License-Identifier: MIT */
/* Sphere helpers shared by the SH projection and the wavelet parameterisations (not public):
 * the runtime cube faces of SPEC §13 and their exact texel solid angle. */
#ifndef PRT_RUNTIME_SPHERE_INTERNAL_H
#define PRT_RUNTIME_SPHERE_INTERNAL_H

#include <math.h>
#include <stdint.h>

#define PRT_SPHERE_PI 3.14159265358979323846

/* 1 when the row-major 3x3 matrix r is a proper rotation: finite, orthonormal to 1e-3 and with
 * det > 0 (what prt_sh_rotate and prt_env_image.rotation accept). */
static inline int prt_is_rotation(const float r[9]) {
  int i, j, k;
  double det;
  for (i = 0; i < 9; ++i)
    if (!isfinite(r[i])) return 0;
  for (i = 0; i < 3; ++i)
    for (j = 0; j < 3; ++j) {
      double dot = 0.0;
      for (k = 0; k < 3; ++k) dot += (double)r[i * 3 + k] * r[j * 3 + k];
      if (fabs(dot - (i == j ? 1.0 : 0.0)) > 1e-3) return 0;
    }
  det = r[0] * ((double)r[4] * r[8] - (double)r[5] * r[7]) -
        r[1] * ((double)r[3] * r[8] - (double)r[5] * r[6]) +
        r[2] * ((double)r[3] * r[7] - (double)r[4] * r[6]);
  return det > 0.0;
}

/* Solid angle subtended by the rectangle [0, a] x [0, b] of the plane at unit distance, as seen
 * from the origin: atan(a b / sqrt(a^2 + b^2 + 1)); a texel is the signed sum over its corners. */
static inline double prt_cube_corner_solid_angle(double a, double b) {
  return atan2(a * b, sqrt(a * a + b * b + 1.0));
}

/* Exact solid angle of the face rectangle [s0, s1] x [t0, t1] (face coordinates in [-1, 1]). */
static inline double prt_cube_rect_solid_angle(double s0, double s1, double t0, double t1) {
  return fabs(prt_cube_corner_solid_angle(s1, t1) - prt_cube_corner_solid_angle(s0, t1) -
              prt_cube_corner_solid_angle(s1, t0) + prt_cube_corner_solid_angle(s0, t0));
}

/* World direction (unnormalised) of face coordinates (sc, tc) on a GL cube face, faces in the
 * order +X, -X, +Y, -Y, +Z, -Z (SPEC §13). */
static inline void prt_cube_direction(uint32_t face, double sc, double tc, double d[3]) {
  switch (face) {
    case 0:
      d[0] = 1.0, d[1] = -tc, d[2] = -sc;
      break;
    case 1:
      d[0] = -1.0, d[1] = -tc, d[2] = sc;
      break;
    case 2:
      d[0] = sc, d[1] = 1.0, d[2] = tc;
      break;
    case 3:
      d[0] = sc, d[1] = -1.0, d[2] = -tc;
      break;
    case 4:
      d[0] = sc, d[1] = -tc, d[2] = 1.0;
      break;
    default:
      d[0] = -sc, d[1] = -tc, d[2] = -1.0;
      break;
  }
}

/* The inverse: the face of a nonzero direction's largest |component| (ties: the earlier face)
 * and its face coordinates (sc, tc) in [-1, 1] (one division: it runs per source texel). */
static inline uint32_t prt_cube_face_coords(double x, double y, double z, double* sc, double* tc) {
  const double ax = fabs(x), ay = fabs(y), az = fabs(z);
  double inv;
  if (ax >= ay && ax >= az) {
    inv = 1.0 / ax;
    *tc = -y * inv;
    *sc = (x > 0.0 ? -z : z) * inv;
    return x > 0.0 ? 0u : 1u;
  }
  if (ay >= az) {
    inv = 1.0 / ay;
    *sc = x * inv;
    *tc = (y > 0.0 ? z : -z) * inv;
    return y > 0.0 ? 2u : 3u;
  }
  inv = 1.0 / az;
  *tc = -y * inv;
  *sc = (z > 0.0 ? x : -x) * inv;
  return z > 0.0 ? 4u : 5u;
}

/* The texel column (or row) of face coordinate c in [-1, 1] on a face of n texels: floor of
 * (c + 1) n / 2, clamped to 0..n-1 (NaN gives 0). Truncation is the floor for t > 0, and avoids
 * a libm call in per-frame loops. */
static inline uint32_t prt_face_texel(double c, uint32_t n) {
  const double t = (c + 1.0) * 0.5 * (double)n;
  if (!(t > 0.0)) return 0u;
  return t >= (double)n ? n - 1u : (uint32_t)t;
}

#endif /* PRT_RUNTIME_SPHERE_INTERNAL_H */
