/* SPDX-License-Identifier: MIT */
/* Reading a fabric table (formats/SPEC.md §7.4) at a lobe and a view in double: the thread's
 * canonical frame and its mirrors, the octahedral lobe grid, the sharpness levels and the view
 * grid, bilinear (and linear across levels) on the dequantised factors. */
#include <math.h>
#include <string.h>

#include "cloth_shade_internal.h"

#define HALF_PI 1.57079632679489661923
#define PI 3.14159265358979323846

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void prt_cloth_canonical(const prt_cloth_frame* frame, int thread, int mirror, const double w[3],
                         double out[3]) {
  /* thread 1: (u, v, n); thread 2: (v, -u, n) */
  const double x = thread == 0 ? dot3(w, frame->u) : dot3(w, frame->v);
  const double y = thread == 0 ? dot3(w, frame->v) : -dot3(w, frame->u);
  out[0] = mirror ? -x : x;
  out[1] = y;
  out[2] = dot3(w, frame->n);
}

static double stored(const prt_cloth_factor* f, const void* values, uint64_t row, uint32_t r) {
  if (f->bits == 16) {
    const uint8_t* p = (const uint8_t*)values + 2u * (row * f->rank + r);
    return (double)(int16_t)(uint16_t)(p[0] | (p[1] << 8));
  }
  return (double)((const int8_t*)values)[row * f->rank + r];
}

static double scale_of(const uint8_t* scales, uint32_t r) {
  return (double)prt_blob_clth_load_f32(scales + 4u * r);
}

void prt_cloth_grid_cell(double x, uint32_t n, uint32_t* lower, double* frac) {
  double g = x * (double)(n - 1);
  uint32_t i;
  if (!(g > 0.0)) g = 0.0;
  if (g > (double)(n - 1)) g = (double)(n - 1);
  i = (uint32_t)g;
  if (i >= n - 1) i = n - 2;
  *lower = i;
  *frac = g - (double)i;
}

/* Accumulates weight x row `row` of `values` into out[rank]. */
static void add_row(const prt_cloth_factor* f, const void* values, uint64_t row, double weight,
                    double* out) {
  uint32_t r;
  if (weight == 0.0) return;
  for (r = 0; r < f->rank; ++r) out[r] += weight * stored(f, values, row, r);
}

void prt_cloth_view_factor(const prt_cloth_view* view, const prt_cloth_factor* factor,
                           const double canonical_view[3], double* out) {
  const uint32_t nt = view->header.view_theta, np = view->header.view_phi;
  const double z = fmin(1.0, fmax(0.0, canonical_view[2]));
  const double theta = acos(z);
  const double phi = atan2(fabs(canonical_view[1]), canonical_view[0]); /* y mirrored to >= 0 */
  uint32_t a, b, r;
  double fa, fb;
  prt_cloth_grid_cell(theta / HALF_PI, nt, &a, &fa);
  prt_cloth_grid_cell(phi / PI, np, &b, &fb);
  memset(out, 0, sizeof(double) * factor->rank);
  add_row(factor, factor->v_values, (uint64_t)a * np + b, (1 - fa) * (1 - fb), out);
  add_row(factor, factor->v_values, (uint64_t)a * np + b + 1, (1 - fa) * fb, out);
  add_row(factor, factor->v_values, (uint64_t)(a + 1) * np + b, fa * (1 - fb), out);
  add_row(factor, factor->v_values, (uint64_t)(a + 1) * np + b + 1, fa * fb, out);
  for (r = 0; r < factor->rank; ++r) out[r] *= scale_of(factor->v_scale, r);
}

/* The octahedral map of a unit direction onto [-1, 1]^2 (formats/SPEC.md §7.4). */
static void octahedral(const double d[3], double p[2]) {
  const double l1 = fabs(d[0]) + fabs(d[1]) + fabs(d[2]);
  double x = d[0] / l1, y = d[1] / l1;
  if (d[2] < 0.0) {
    const double sx = x >= 0.0 ? 1.0 : -1.0, sy = y >= 0.0 ? 1.0 : -1.0;
    const double ax = fabs(x), ay = fabs(y);
    x = (1.0 - ay) * sx;
    y = (1.0 - ax) * sy;
  }
  p[0] = x;
  p[1] = y;
}

void prt_cloth_lobe_factor(const prt_cloth_view* view, const prt_cloth_factor* factor,
                           const double canonical_lobe[3], double level, double* out) {
  const uint32_t n = view->header.xi_size, levels = view->header.levels;
  const uint64_t plane = (uint64_t)n * n;
  double p[2], fi, fj, fl = 0.0;
  uint32_t i, j, l = 0, r, k;
  octahedral(canonical_lobe, p);
  prt_cloth_grid_cell(0.5 * (p[0] + 1.0), n, &i, &fi);
  prt_cloth_grid_cell(0.5 * (p[1] + 1.0), n, &j, &fj);
  if (levels > 1) prt_cloth_grid_cell(level / (double)(levels - 1), levels, &l, &fl);
  memset(out, 0, sizeof(double) * factor->rank);
  for (k = 0; k < (levels > 1 ? 2u : 1u); ++k) {
    const double wl = levels > 1 ? (k ? fl : 1.0 - fl) : 1.0;
    const uint64_t base = (uint64_t)(l + k) * plane;
    add_row(factor, factor->u_values, base + (uint64_t)j * n + i, wl * (1 - fi) * (1 - fj), out);
    add_row(factor, factor->u_values, base + (uint64_t)j * n + i + 1, wl * fi * (1 - fj), out);
    add_row(factor, factor->u_values, base + (uint64_t)(j + 1) * n + i, wl * (1 - fi) * fj, out);
    add_row(factor, factor->u_values, base + (uint64_t)(j + 1) * n + i + 1, wl * fi * fj, out);
  }
  for (r = 0; r < factor->rank; ++r) out[r] *= scale_of(factor->u_scale, r);
}
