/* SPDX-License-Identifier: MIT */
/* prt_sf_locate in the compact form a frame keeps per vertex and pair (shadowfield_scene.h,
 * prt_sf_cell): the same arithmetic in the same order, so the lookup it rebuilds is bitwise
 * prt_sf_locate's, with the grid's log span taken once per frame instead of once per point. */
#include <math.h>

#include "shadowfield_scene.h"

double prt_sf_log_span(const prt_sf_shells* grid) {
  return log((double)grid->outer / grid->inner);
}

/* As prt_sf_locate's: the two cells around face coordinate u in [0, 1] and the weight of the
 * second, clamped to the outermost cell centres. */
static void bracket_cells(float u, uint32_t size, uint32_t* first, float* frac) {
  float x = u * (float)size - 0.5f;
  if (!(x > 0.0f)) x = 0.0f;
  if (x > (float)(size - 1u)) x = (float)(size - 1u);
  uint32_t i = (uint32_t)x;
  if (i + 1u >= size) i = size >= 2u ? size - 2u : 0u;
  *first = i;
  *frac = size >= 2u ? x - (float)i : 0.0f;
}

/* The cell of offset d from the grid's centre (turned to +Y at the centre), rho = |d| in double;
 * *log_ratio is log(rho / (radius inner)), computed here when needed and still NAN. */
static void locate_at(const prt_sf_shells* grid, double log_span, const float d[3], double rho,
                      double* log_ratio, prt_sf_cell* out) {
  out->first = 0u;
  out->count = 0u;
  out->shell_frac = out->fi = out->fj = 0.0f;
  const double kShellSlack = 1e-6;
  const double r0 = (double)grid->radius * grid->inner;
  const double r1 = (double)grid->radius * grid->outer;
  if (!(rho <= r1 * (1.0 + kShellSlack))) return;
  uint32_t shell = 0u, inside = 0u;
  float shell_frac = 0.0f;
  if (rho < r0 || grid->shells == 1u) {
    inside = rho < r0 * (1.0 - kShellSlack) ? 1u : 0u;
  } else {
    if (isnan(*log_ratio)) *log_ratio = log(rho / r0);
    double x = (double)(grid->shells - 1u) * *log_ratio / log_span;
    if (x > (double)(grid->shells - 1u)) x = (double)(grid->shells - 1u);
    shell = (uint32_t)x;
    if (shell + 1u >= grid->shells) shell = grid->shells - 2u;
    shell_frac = (float)(x - (double)shell);
  }
  float s, t;
  const uint32_t face = prt_sf_cube_face(d, &s, &t);
  uint32_t i, j;
  bracket_cells(s, grid->face_size, &i, &out->fi);
  bracket_cells(t, grid->face_size, &j, &out->fj);
  const uint32_t f2 = grid->face_size * grid->face_size;
  const uint32_t shells_used = grid->shells >= 2u && inside == 0u ? 2u : 1u;
  out->first = (shell * 6u + face) * f2 + j * grid->face_size + i;
  out->count = 4u * shells_used;
  out->shell_frac = shell_frac;
}

/* p's offset from the centre as prt_sf_locate takes it, and its length in double. */
static double centred(const prt_sf_shells* grid, const float p[3], float d[3]) {
  d[0] = p[0] - grid->centre[0];
  d[1] = p[1] - grid->centre[1];
  d[2] = p[2] - grid->centre[2];
  const double rho = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
  if (!(rho > 0.0)) {
    d[0] = 0.0f;
    d[1] = 1.0f;
    d[2] = 0.0f;
  }
  return rho;
}

void prt_sf_cell_locate(const prt_sf_shells* grid, double log_span, const float p[3],
                        prt_sf_cell* out) {
  float d[3];
  const double rho = centred(grid, p, d);
  double log_ratio = NAN;
  locate_at(grid, log_span, d, rho, &log_ratio, out);
}

int prt_sf_shells_share_sphere(const prt_sf_shells* a, const prt_sf_shells* b) {
  return a->centre[0] == b->centre[0] && a->centre[1] == b->centre[1] &&
         a->centre[2] == b->centre[2] && a->radius == b->radius && a->inner == b->inner;
}

void prt_sf_cell_locate_two(const prt_sf_shells* a, double log_span_a, const prt_sf_shells* b,
                            double log_span_b, const float p[3], prt_sf_cell* out_a,
                            prt_sf_cell* out_b) {
  float d[3];
  const double rho = centred(a, p, d);
  double log_ratio = NAN;
  locate_at(a, log_span_a, d, rho, &log_ratio, out_a);
  locate_at(b, log_span_b, d, rho, &log_ratio, out_b);
}

void prt_sf_cell_lookup(const prt_sf_shells* grid, const prt_sf_cell* cell, prt_sf_lookup* out) {
  const uint32_t size = grid->face_size, di = size >= 2u ? 1u : 0u;
  const uint32_t shell_step = 6u * size * size, shells_used = cell->count / 4u;
  const float fi = cell->fi, fj = cell->fj;
  uint32_t n = 0u;
  for (uint32_t k = 0; k < shells_used; ++k) {
    const float ws =
        shells_used == 2u ? (k == 0u ? 1.0f - cell->shell_frac : cell->shell_frac) : 1.0f;
    const uint32_t base = cell->first + k * shell_step;
    for (uint32_t c = 0; c < 4u; ++c) {
      const uint32_t ci = (c & 1u) ? di : 0u, cj = (c & 2u) ? di : 0u;
      const float wi = (c & 1u) ? fi : 1.0f - fi, wj = (c & 2u) ? fj : 1.0f - fj;
      out->index[n] = base + cj * size + ci;
      out->weight[n] = ws * wi * wj;
      ++n;
    }
  }
  out->count = n;
  out->inside = 0u;
}
