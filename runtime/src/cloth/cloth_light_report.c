/* SPDX-License-Identifier: MIT */
/* The SG light fit's report (prt_cloth_fit_report): the RMS over the grid's cells of the lobes'
 * mean radiance minus the map's, solid-angle weighted, over the map's RMS radiance; and the
 * power error. A lobe's mean over a cell is its centre value corrected to second order in the
 * cell's size (cell_mean), on the cell itself when the lobe is broad for it, else on n x n
 * sub-cells at most half the lobe's width (1 / sqrt(sharpness)) across; cells where the lobe is
 * below exp(-CUTOFF) of its peak are left out. */
#include "cloth_light_internal.h"

#define CUTOFF 30.0
#define SAMPLES PRT_CLOTH_LIGHT_CELL_SAMPLES
/* Each row's and column's entries in sub_rows and sub_cols: SAMPLES sub-cells, then the centre. */
#define SLOTS (SAMPLES + 1u)

/* The largest cell of the grid: its angular radius (a bound: half its polar extent plus half
 * its widest azimuthal arc) and its size (the larger of its extents). */
static void largest_cell(const light_fit* fit, double* radius, double* size) {
  double widest_phi = 0.0, widest_theta = 0.0;
  uint32_t i;
  for (i = 0; i < fit->cols; ++i) widest_phi = fmax(widest_phi, fit->phi[i + 1u] - fit->phi[i]);
  for (i = 0; i < fit->rows; ++i)
    widest_theta = fmax(widest_theta, fit->theta[i + 1u] - fit->theta[i]);
  *radius = 0.5 * widest_theta + 0.5 * widest_phi;
  *size = fmax(widest_theta, widest_phi);
}

/* The mean of exp(l (a . w - 1)) over a cell (polar extent dt, azimuthal extent dp) centred at
 * polar angle t and azimuth p (st = sin t, ...): f + (dt^2 / 12) cot t f_t + (dt^2 / 24) f_tt +
 * (dp^2 / 24) f_pp, the first-order term from the sin t weight of the solid angle. With
 * g = f / l: f_t = l f (a . e_t), f_tt = f (l^2 (a . e_t)^2 - l a . w) (meridians are great
 * circles) and f_pp = f (l^2 sin^2 t (a . e_p)^2 - l sin t (a_x sin p - a_z cos p)). */
static double cell_mean(const fit_lobe* lobe, const double row[3], const double col[2], double dt,
                        double dp, int single) {
  const double* a = lobe->axis;
  const double l = lobe->sharpness, st = row[0], ct = row[1], sp = col[0], cp = col[1];
  const double across = a[0] * sp - a[2] * cp;
  const double t = st * across + ct * a[1];
  const double polar = ct * across - st * a[1];   /* a . e_t */
  const double azimuthal = a[0] * cp + a[2] * sp; /* a . e_p */
  const double correction =
      1.0 + dt * dt / 12.0 * (ct / st) * l * polar +
      dt * dt / 24.0 * (l * l * polar * polar - l * t) +
      dp * dp / 24.0 * (l * l * st * st * azimuthal * azimuthal - l * st * across);
  /* Single precision is plenty for a broad lobe's one sample per cell, and much faster. */
  const double value = single ? expf((float)(l * (t - 1.0))) : exp(l * (t - 1.0));
  return correction > 0.0 ? value * correction : 0.0;
}

/* The trigonometry of every row's and column's centre (their last slot). */
static void fill_centres(light_fit* fit) {
  uint32_t i;
  for (i = 0; i < fit->rows; ++i) {
    const double t0 = fit->theta[i], t1 = fit->theta[i + 1u], t = 0.5 * (t0 + t1);
    double* s = fit->sub_rows + 3u * ((size_t)i * SLOTS + SAMPLES);
    s[0] = sin(t), s[1] = cos(t), s[2] = cos(t0) - cos(t1);
  }
  for (i = 0; i < fit->cols; ++i) {
    const double p = 0.5 * (fit->phi[i] + fit->phi[i + 1u]);
    double* s = fit->sub_cols + 2u * ((size_t)i * SLOTS + SAMPLES);
    s[0] = sin(p), s[1] = cos(p);
  }
}

static const double* row_centre(const light_fit* fit, uint32_t row) {
  return fit->sub_rows + 3u * ((size_t)row * SLOTS + SAMPLES);
}

static const double* col_centre(const light_fit* fit, uint32_t col) {
  return fit->sub_cols + 2u * ((size_t)col * SLOTS + SAMPLES);
}

/* A broad lobe: one corrected sample per cell. */
static void add_broad_lobe(light_fit* fit, const fit_lobe* lobe) {
  uint32_t row, col, c;
  for (row = 0; row < fit->rows; ++row) {
    const double dt = fit->theta[row + 1u] - fit->theta[row];
    for (col = 0; col < fit->cols; ++col) {
      const double value = cell_mean(lobe, row_centre(fit, row), col_centre(fit, col), dt,
                                     fit->phi[col + 1u] - fit->phi[col], 1);
      double* model = fit->model + 3u * ((size_t)row * fit->cols + col);
      for (c = 0; c < 3u; ++c) model[c] += lobe->rgb[c] * value;
    }
  }
}

/* The sub-rows' and sub-columns' trigonometry of n x n sub-cells, for rows [first, last]. */
static void fill_sub_cells(light_fit* fit, uint32_t n, uint32_t first, uint32_t last) {
  uint32_t row, col, j;
  for (row = first; row <= last; ++row)
    for (j = 0; j < n; ++j) {
      const double t0 = fit->theta[row], height = fit->theta[row + 1u] - t0;
      const double ta = t0 + height * (double)j / (double)n;
      const double tb = t0 + height * (double)(j + 1u) / (double)n;
      double* s = fit->sub_rows + 3u * ((size_t)row * SLOTS + j);
      s[0] = sin(0.5 * (ta + tb)), s[1] = cos(0.5 * (ta + tb)), s[2] = cos(ta) - cos(tb);
    }
  for (col = 0; col < fit->cols; ++col)
    for (j = 0; j < n; ++j) {
      const double p =
          fit->phi[col] + (fit->phi[col + 1u] - fit->phi[col]) * ((double)j + 0.5) / (double)n;
      double* s = fit->sub_cols + 2u * ((size_t)col * SLOTS + j);
      s[0] = sin(p), s[1] = cos(p);
    }
}

/* The mean of a sharp lobe (per unit amplitude) over cell (row, col): the solid-angle weighted
 * mean of its corrected means over n x n sub-cells. */
static double sharp_cell_mean(const light_fit* fit, const fit_lobe* lobe, uint32_t n, uint32_t row,
                              uint32_t col) {
  const double dt = (fit->theta[row + 1u] - fit->theta[row]) / (double)n;
  const double dp = (fit->phi[col + 1u] - fit->phi[col]) / (double)n;
  double sum = 0.0;
  uint32_t i, j;
  for (j = 0; j < n; ++j) {
    const double* r = fit->sub_rows + 3u * ((size_t)row * SLOTS + j);
    double row_sum = 0.0;
    for (i = 0; i < n; ++i)
      row_sum += cell_mean(lobe, r, fit->sub_cols + 2u * ((size_t)col * SLOTS + i), dt, dp, 0);
    sum += r[2] * row_sum;
  }
  return sum / (double)n / row_centre(fit, row)[2];
}

/* A sharp lobe: its mean over the cells of the rows within its reach (the cells themselves
 * tested against the cutoff by the angle to their nearest point). */
static void add_sharp_lobe(light_fit* fit, const fit_lobe* lobe, uint32_t n, double radius) {
  const double reach = acos(fmax(-1.0, 1.0 - CUTOFF / lobe->sharpness)) + radius;
  const double polar = acos(fmax(-1.0, fmin(1.0, lobe->axis[1])));
  const double cos_radius = cos(radius), sin_radius = sin(radius);
  uint32_t first = 0u, last = fit->rows - 1u, row, col, c;
  while (first < last && fit->theta[first + 1u] < polar - reach) ++first;
  while (last > first && fit->theta[last] > polar + reach) --last;
  fill_sub_cells(fit, n, first, last);
  for (row = first; row <= last; ++row)
    for (col = 0; col < fit->cols; ++col) {
      const double *r = row_centre(fit, row), *s = col_centre(fit, col);
      const double centre[3] = {r[0] * s[0], r[1], -r[0] * s[1]};
      const double d = prt_cloth_light_dot(lobe->axis, centre);
      double nearest, value;
      double* model = fit->model + 3u * ((size_t)row * fit->cols + col);
      nearest = d >= cos_radius ? 1.0 : d * cos_radius + sqrt(fmax(0.0, 1.0 - d * d)) * sin_radius;
      if (lobe->sharpness * (1.0 - nearest) > CUTOFF) continue;
      value = sharp_cell_mean(fit, lobe, n, row, col);
      for (c = 0; c < 3u; ++c) model[c] += lobe->rgb[c] * value;
    }
}

double prt_cloth_light_relative_error(light_fit* fit, const fit_lobe* lobes, uint32_t count) {
  double radius, size, error = 0.0, norm = 0.0;
  size_t k;
  uint32_t c;
  largest_cell(fit, &radius, &size);
  fill_centres(fit);
  memset(fit->model, 0, 3u * sizeof(double) * fit->rows * fit->cols);
  for (k = 0; k < count; ++k) {
    /* Sub-cells at most half the lobe's width (1 / sqrt(sharpness)) across. */
    const double wanted = ceil(2.0 * sqrt(lobes[k].sharpness) * size);
    if (wanted <= 1.0)
      add_broad_lobe(fit, &lobes[k]);
    else
      add_sharp_lobe(fit, &lobes[k], wanted < SAMPLES ? (uint32_t)wanted : SAMPLES, radius);
  }
  for (k = 0; k < (size_t)fit->rows * fit->cols; ++k) {
    const grid_cell* cell = &fit->cells[k];
    if (!(cell->solid_angle > 0.0)) continue;
    for (c = 0; c < 3u; ++c) {
      const double map = (cell->power[c] + cell->removed[c]) / cell->solid_angle;
      const double diff = fit->model[3u * k + c] - map;
      error += cell->solid_angle * diff * diff;
      norm += cell->solid_angle * map * map;
    }
  }
  return norm > 0.0 ? sqrt(error / norm) : 0.0;
}

double prt_cloth_light_power_error(const light_fit* fit, const prt_cloth_lobe* lobes,
                                   uint32_t count) {
  double map = 0.0, fitted = 0.0;
  size_t k;
  uint32_t c;
  for (k = 0; k < (size_t)fit->rows * fit->cols; ++k)
    for (c = 0; c < 3u; ++c) map += fit->cells[k].power[c] + fit->cells[k].removed[c];
  for (k = 0; k < count; ++k)
    for (c = 0; c < 3u; ++c)
      fitted += (double)lobes[k].rgb[c] * prt_cloth_light_integral(lobes[k].sharpness);
  return map > 0.0 ? fabs(fitted - map) / map : 0.0;
}
