/* SPDX-License-Identifier: MIT */
/* Rotation of real SH coefficients, band by band, by the recurrence of
 *   J. Ivanic and K. Ruedenberg, "Rotation Matrices for Real Spherical Harmonics. Direct
 *   Determination by Recursion", J. Phys. Chem. 100(15), 6342-6347 (1996), with the corrections
 *   of the erratum, J. Phys. Chem. A 102(45), 9099-9100 (1998) (Table 2: the sqrt(1 + delta)
 *   and (1 - delta) factors of V for m = +-1).
 * The band-l matrix M^l is built from the band-1 matrix (the rotation itself, in SH-frame
 * order y, z, x) and M^(l-1); the recurrence is valid for the no-Condon-Shortley real basis of
 * prt_sh.h. Coefficients transform as out_l = M^l in_l. */
#include <math.h>
#include <string.h>

#include "sh_internal.h"
#include "sphere_internal.h"

#define PRT_SH_BAND_DIM (2 * PRT_SH_MAX_ORDER - 1)

/* A band matrix indexed by m, n in [-l, l]. */
typedef struct band_matrix {
  int l;
  double v[PRT_SH_BAND_DIM * PRT_SH_BAND_DIM];
} band_matrix;

static double band_at(const band_matrix* b, int m, int n) {
  return b->v[(m + b->l) * (2 * b->l + 1) + (n + b->l)];
}

static void band_set(band_matrix* b, int m, int n, double value) {
  b->v[(m + b->l) * (2 * b->l + 1) + (n + b->l)] = value;
}

/* Ivanic-Ruedenberg's P function: i in {-1, 0, 1} selects a row of the band-1 matrix. */
static double ir_p(int i, int l, int a, int b, const band_matrix* r1, const band_matrix* prev) {
  const double ri1 = band_at(r1, i, 1), rim1 = band_at(r1, i, -1), ri0 = band_at(r1, i, 0);
  if (b == -l) return ri1 * band_at(prev, a, -l + 1) + rim1 * band_at(prev, a, l - 1);
  if (b == l) return ri1 * band_at(prev, a, l - 1) - rim1 * band_at(prev, a, -l + 1);
  return ri0 * band_at(prev, a, b);
}

static double ir_u(int l, int m, int n, const band_matrix* r1, const band_matrix* prev) {
  return ir_p(0, l, m, n, r1, prev);
}

static double ir_v(int l, int m, int n, const band_matrix* r1, const band_matrix* prev) {
  if (m == 0) return ir_p(1, l, 1, n, r1, prev) + ir_p(-1, l, -1, n, r1, prev);
  if (m > 0) {
    const double d = (m == 1) ? 1.0 : 0.0;
    return ir_p(1, l, m - 1, n, r1, prev) * sqrt(1.0 + d) -
           ir_p(-1, l, -m + 1, n, r1, prev) * (1.0 - d);
  } else {
    const double d = (m == -1) ? 1.0 : 0.0;
    return ir_p(1, l, m + 1, n, r1, prev) * (1.0 - d) +
           ir_p(-1, l, -m - 1, n, r1, prev) * sqrt(1.0 + d);
  }
}

static double ir_w(int l, int m, int n, const band_matrix* r1, const band_matrix* prev) {
  if (m > 0) return ir_p(1, l, m + 1, n, r1, prev) + ir_p(-1, l, -m - 1, n, r1, prev);
  return ir_p(1, l, m - 1, n, r1, prev) - ir_p(-1, l, -m + 1, n, r1, prev);
}

/* Builds M^l into next from r1 = M^1 and prev = M^(l-1). */
static void build_band(int l, const band_matrix* r1, const band_matrix* prev, band_matrix* next) {
  int m, n;
  next->l = l;
  for (m = -l; m <= l; ++m) {
    const int abs_m = m < 0 ? -m : m;
    const double d = (m == 0) ? 1.0 : 0.0;
    for (n = -l; n <= l; ++n) {
      const int abs_n = n < 0 ? -n : n;
      const double denom =
          (abs_n == l) ? (2.0 * l) * (2.0 * l - 1.0) : (double)(l + n) * (double)(l - n);
      const double u = sqrt((double)(l + m) * (double)(l - m) / denom);
      const double v = 0.5 *
                       sqrt((1.0 + d) * (double)(l + abs_m - 1) * (double)(l + abs_m) / denom) *
                       (1.0 - 2.0 * d);
      const double w =
          -0.5 * sqrt((double)(l - abs_m - 1) * (double)(l - abs_m) / denom) * (1.0 - d);
      double value = 0.0;
      if (u != 0.0) value += u * ir_u(l, m, n, r1, prev);
      if (v != 0.0) value += v * ir_v(l, m, n, r1, prev);
      if (w != 0.0) value += w * ir_w(l, m, n, r1, prev);
      band_set(next, m, n, value);
    }
  }
}

/* The band-1 matrix: R expressed in the SH frame (S R S^T with S mapping world (X, Y, Z) to
 * (X, -Z, Y)), rows and columns ordered m = -1, 0, 1 <-> y, z, x. */
static void band1_from_world(const float r[9], band_matrix* r1) {
  /* SH axis k as a world axis and sign: x = +X, y = -Z, z = +Y. */
  static const int world_axis[3] = {0, 2, 1};
  static const double axis_sign[3] = {1.0, -1.0, 1.0};
  /* m = -1, 0, 1 -> SH axis y, z, x. */
  static const int sh_axis_of_m[3] = {1, 2, 0};
  int a, b;
  r1->l = 1;
  for (a = 0; a < 3; ++a)
    for (b = 0; b < 3; ++b) {
      const int ka = sh_axis_of_m[a], kb = sh_axis_of_m[b];
      const double value =
          axis_sign[ka] * axis_sign[kb] * (double)r[world_axis[ka] * 3 + world_axis[kb]];
      band_set(r1, a - 1, b - 1, value);
    }
}

/* out_l = M^l in_l for one band, per channel; reads the band into scratch first (in == out). */
static void apply_band(const band_matrix* mat, const float* in, float* out, uint32_t channels) {
  const int l = mat->l;
  const int dim = 2 * l + 1;
  const size_t first = (size_t)l * (size_t)l * channels;
  double band_in[PRT_SH_BAND_DIM];
  uint32_t c;
  int i, j;
  for (c = 0; c < channels; ++c) {
    for (j = 0; j < dim; ++j) band_in[j] = in[first + (size_t)j * channels + c];
    for (i = 0; i < dim; ++i) {
      double sum = 0.0;
      for (j = 0; j < dim; ++j) sum += mat->v[i * dim + j] * band_in[j];
      out[first + (size_t)i * channels + c] = (float)sum;
    }
  }
}

prt_result prt_sh_rotate(uint32_t order, const float rotation[9], const float* in, float* out,
                         uint32_t channels) {
  band_matrix r1, bands[2];
  uint32_t c;
  int l;
  if (!rotation || !in || !out || order == 0 || order > PRT_SH_MAX_ORDER || channels == 0)
    return PRT_ERROR_INVALID_ARGUMENT;
  if (!prt_is_rotation(rotation)) return PRT_ERROR_INVALID_ARGUMENT;
  for (c = 0; c < channels; ++c) out[c] = in[c]; /* band 0 is invariant */
  if (order == 1) return PRT_OK;
  band1_from_world(rotation, &r1);
  apply_band(&r1, in, out, channels);
  memcpy(&bands[1], &r1, sizeof r1);
  for (l = 2; l < (int)order; ++l) {
    const band_matrix* prev = &bands[(l - 1) % 2];
    band_matrix* next = &bands[l % 2];
    build_band(l, &r1, prev, next);
    apply_band(next, in, out, channels);
  }
  return PRT_OK;
}
