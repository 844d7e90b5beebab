/* SPDX-License-Identifier: MIT */
/* The SG light fit's grid (prt_cloth_fit_light): the map averaged onto a lat-long grid of
 * rows x cols cells in the image's frame (per cell its power, the power-weighted sum of its
 * texel directions and its solid angle), and the walk over its brightest texels that finds
 * compact sources. A lat-long image's cells are whole blocks of texels; a cube's texels are
 * binned into the cells by their centres. */
#include "cloth_light_internal.h"

/* atan2 in single precision without a libm call (Cephes' atanf reduction and polynomial): it
 * only bins directions of cube texels into grid cells. */
static float fast_atan2(float y, float x) {
  const float ax = fabsf(x), ay = fabsf(y);
  const float hi = ax > ay ? ax : ay, lo = ax > ay ? ay : ax;
  float t = hi > 0.0f ? lo / hi : 0.0f, base = 0.0f, z, angle;
  if (t > 0.414213562f) {
    base = 0.785398163f;
    t = (t - 1.0f) / (t + 1.0f);
  }
  z = t * t;
  angle = ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
            3.33329491539e-1f) *
               z * t +
           t) +
          base;
  if (ay > ax) angle = 1.570796327f - angle;
  if (x < 0.0f) angle = 3.141592654f - angle;
  return y < 0.0f ? -angle : angle;
}

/* The first of n source indices that lands in each of m bins when index i lands in bin
 * floor((2 i + 1) m / (2 n)) (its centre's bin); first[m] = n. */
static void bin_starts(uint32_t n, uint32_t m, uint32_t* first) {
  uint32_t i, bin = 0u;
  first[0] = 0u;
  for (i = 0; i < n; ++i) {
    const uint32_t b = (uint32_t)(((2u * (uint64_t)i + 1u) * m) / (2u * (uint64_t)n));
    while (bin < b) first[++bin] = i;
  }
  while (bin < m) first[++bin] = n;
}

/* Grid bounds: a lat-long source's cells are whole texels (their bounds are texel edges); a
 * cube's cells are the nominal lat-long cells its texel centres are binned into. */
static void setup_grid(light_fit* fit) {
  const prt_env_view* env = &fit->env;
  uint32_t i;
  if (env->layout == PRT_ENV_LATLONG) {
    bin_starts(env->height, fit->rows, fit->row_first);
    bin_starts(env->width, fit->cols, fit->col_first);
    for (i = 0; i <= fit->rows; ++i)
      fit->theta[i] = PRT_SPHERE_PI * (double)fit->row_first[i] / (double)env->height;
    for (i = 0; i <= fit->cols; ++i)
      fit->phi[i] =
          2.0 * PRT_SPHERE_PI * (double)fit->col_first[i] / (double)env->width - PRT_SPHERE_PI;
    for (i = 0; i < env->width; ++i) {
      const double phi = 2.0 * PRT_SPHERE_PI * (((double)i + 0.5) / (double)env->width - 0.5);
      fit->sin_phi[i] = sin(phi);
      fit->cos_phi[i] = cos(phi);
    }
  } else {
    for (i = 0; i <= fit->rows; ++i) fit->theta[i] = PRT_SPHERE_PI * (double)i / (double)fit->rows;
    for (i = 0; i <= fit->cols; ++i)
      fit->phi[i] = 2.0 * PRT_SPHERE_PI * (double)i / (double)fit->cols - PRT_SPHERE_PI;
  }
}

/* Adds one lat-long image row (n floats) to the sums; returns its largest value (kept as bits:
 * positive floats order as their bit patterns, and an integer maximum vectorises). */
static float sum_row(const float* restrict row, size_t n, float solid_angle, float sin_theta,
                     float cos_theta, float* restrict power, float* restrict along_sin,
                     float* restrict along_cos) {
  const float weight_sin = solid_angle * sin_theta, weight_cos = solid_angle * cos_theta;
  int32_t largest = 0;
  float row_max;
  size_t j;
  for (j = 0; j < n; ++j) {
    const float value = prt_cloth_light_sanitised(row[j]);
    int32_t bits;
    power[j] += solid_angle * value;
    along_sin[j] += weight_sin * value;
    along_cos[j] += weight_cos * value;
    memcpy(&bits, &value, sizeof bits);
    largest = bits > largest ? bits : largest;
  }
  memcpy(&row_max, &largest, sizeof row_max);
  return row_max;
}

static void sum_latlong_row(light_fit* fit, uint32_t y) {
  const prt_env_view* env = &fit->env;
  const size_t n = (size_t)env->width * env->channels;
  const double theta = PRT_SPHERE_PI * ((double)y + 0.5) / (double)env->height;
  const float solid_angle = (float)(2.0 * PRT_SPHERE_PI / (double)env->width *
                                    (cos(PRT_SPHERE_PI * (double)y / (double)env->height) -
                                     cos(PRT_SPHERE_PI * (double)(y + 1u) / (double)env->height)));
  float* sums = fit->column_sums;
  fit->row_max[y] =
      sum_row(prt_env_texel(env, 0u, 0u, y), n, solid_angle, (float)sin(theta), (float)cos(theta),
              sums + SUM_POWER * n, sums + SUM_SIN * n, sums + SUM_COS * n);
}

/* Moves the sums into grid row `grid_row`'s cells (in double) and clears them. A direction is
 * d = (sin t sin f, cos t, -sin t cos f) (prt_env.h). */
static void flush_column_sums(light_fit* fit, uint32_t grid_row) {
  const uint32_t width = fit->env.width;
  const size_t channels = fit->env.channels, n = (size_t)width * channels;
  const double solid_angle = 2.0 * PRT_SPHERE_PI / (double)width *
                             (cos(fit->theta[grid_row]) - cos(fit->theta[grid_row + 1u]));
  const float* power = fit->column_sums + SUM_POWER * n;
  const float* along_sin = fit->column_sums + SUM_SIN * n;
  const float* along_cos = fit->column_sums + SUM_COS * n;
  uint32_t c, x, k;
  for (c = 0; c < fit->cols; ++c) {
    grid_cell* cell = &fit->cells[(size_t)grid_row * fit->cols + c];
    const uint32_t first = fit->col_first[c], last = fit->col_first[c + 1u];
    cell->solid_angle = solid_angle * (double)(last - first);
    for (x = first; x < last; ++x) {
      const size_t at = channels * x;
      const double level_sin = (double)along_sin[at] + along_sin[at + 1u] + along_sin[at + 2u];
      for (k = 0; k < 3u; ++k) cell->power[k] += power[at + k];
      cell->resultant[0] += level_sin * fit->sin_phi[x];
      cell->resultant[1] += (double)along_cos[at] + along_cos[at + 1u] + along_cos[at + 2u];
      cell->resultant[2] -= level_sin * fit->cos_phi[x];
    }
    cell->weight = cell->power[0] + cell->power[1] + cell->power[2];
  }
  memset(fit->column_sums, 0, SUM_COUNT * sizeof(float) * n);
}

/* ---- Cube sources: binning by symmetry ------------------------------------------------------
 *
 * A direction's grid row follows from its y = cos(theta), its column from its azimuth
 * atan2(x, -z). The four side faces share a texel's y, and their azimuths are base - atan(sc)
 * (+X: pi/2, -X: -pi/2, +Z: pi, -Z: 0): columns per face and texel column, tabulated once. The
 * two polar faces take one atan2 each per texel. */

/* The grid row holding y = cos(theta): rows r has cos in (cos theta_{r+1}, cos theta_r]. */
static uint32_t polar_row(const light_fit* fit, double y) {
  uint32_t lo = 0u, hi = fit->rows - 1u;
  while (lo < hi) {
    const uint32_t mid = (lo + hi + 1u) / 2u;
    if (fit->cos_bounds[mid] >= y)
      lo = mid;
    else
      hi = mid - 1u;
  }
  return lo;
}

/* The grid column of azimuth a (radians, any turn). */
static uint32_t azimuth_column(const light_fit* fit, double a) {
  double u = (a + PRT_SPHERE_PI) * (0.5 / PRT_SPHERE_PI);
  uint32_t col;
  u -= floor(u);
  col = (uint32_t)(u * (double)fit->cols);
  return col < fit->cols ? col : fit->cols - 1u;
}

/* Face coordinates of texel (i, j) of a face of n: the centre's (sc, tc) and 1 / |(1, sc, tc)|. */
typedef struct cube_texel {
  double sc, tc, inv_length;
} cube_texel;

static void cube_texel_at(uint32_t n, uint32_t i, uint32_t j, cube_texel* t) {
  t->sc = 2.0 * ((double)i + 0.5) / (double)n - 1.0;
  t->tc = 2.0 * ((double)j + 0.5) / (double)n - 1.0;
  t->inv_length = 1.0 / sqrt(1.0 + t->sc * t->sc + t->tc * t->tc);
}

static void cube_texel_direction(uint32_t face, const cube_texel* t, double d[3]) {
  prt_cube_direction(face, t->sc, t->tc, d);
  d[0] *= t->inv_length, d[1] *= t->inv_length, d[2] *= t->inv_length;
}

/* The grid cells of texel t (column i) on the six faces. */
static void cube_texel_cells(const light_fit* fit, uint32_t i, const cube_texel* t,
                             uint32_t cells[6]) {
  static const uint32_t side_faces[4] = {0u, 1u, 4u, 5u};
  const uint32_t n = fit->env.width, cols = fit->cols;
  const uint32_t side = polar_row(fit, -t->tc * t->inv_length) * cols;
  const uint32_t pole = polar_row(fit, t->inv_length);
  uint32_t k;
  for (k = 0; k < 4u; ++k) cells[side_faces[k]] = side + fit->side_columns[k * n + i];
  /* -Y mirrors +Y's row (the grid is symmetric about the equator). */
  cells[2] = pole * cols + azimuth_column(fit, fast_atan2((float)t->sc, (float)-t->tc));
  cells[3] =
      (fit->rows - 1u - pole) * cols + azimuth_column(fit, fast_atan2((float)t->sc, (float)t->tc));
}

static void setup_cube_bins(light_fit* fit) {
  static const double bases[4] = {0.5 * PRT_SPHERE_PI, -0.5 * PRT_SPHERE_PI, PRT_SPHERE_PI, 0.0};
  const uint32_t n = fit->env.width;
  uint32_t i, k;
  for (i = 0; i <= fit->rows; ++i) fit->cos_bounds[i] = cos(fit->theta[i]);
  for (i = 0; i < n; ++i) {
    const double slope = atan(2.0 * ((double)i + 0.5) / (double)n - 1.0);
    for (k = 0; k < 4u; ++k) fit->side_columns[k * n + i] = azimuth_column(fit, bases[k] - slope);
  }
}

/* The corner terms atan(s t / sqrt(s^2 + t^2 + 1)) along the face edge t = t_j at every column
 * edge s_k (k = 0..n); the term is odd in s, so half the edges are mirrored. A texel's exact
 * solid angle is the signed sum of its four corners' terms (sphere_internal.h). */
static void cube_edge_terms(uint32_t n, uint32_t j, double* out) {
  const double step = 2.0 / (double)n, t = step * (double)j - 1.0;
  uint32_t k;
  for (k = 0; 2u * k <= n; ++k) {
    out[k] = prt_cube_corner_solid_angle(step * (double)k - 1.0, t);
    out[n - k] = -out[k];
  }
}

static double cube_texel_solid_angle(const double* top, const double* bottom, uint32_t i) {
  return fabs(bottom[i + 1u] - bottom[i] - top[i + 1u] + top[i]);
}

/* Adds texel rgb (solid angle w, direction d) to its cell; returns its largest channel. */
static float add_cube_texel(grid_cell* cell, const float* texel, double w, const double d[3]) {
  const float rgb[3] = {prt_cloth_light_sanitised(texel[0]), prt_cloth_light_sanitised(texel[1]),
                        prt_cloth_light_sanitised(texel[2])};
  const double p = ((double)rgb[0] + rgb[1] + rgb[2]) * w;
  uint32_t c;
  cell->solid_angle += w;
  if (p == 0.0) return 0.0f;
  for (c = 0; c < 3u; ++c) {
    cell->power[c] += (double)rgb[c] * w;
    cell->resultant[c] += p * d[c];
  }
  cell->weight += p;
  return rgb[0] > rgb[1] ? (rgb[0] > rgb[2] ? rgb[0] : rgb[2])
                         : (rgb[1] > rgb[2] ? rgb[1] : rgb[2]);
}

static void grid_cube(light_fit* fit) {
  const prt_env_view* env = &fit->env;
  const uint32_t n = env->width;
  double* top = fit->edge_terms;
  double* bottom = fit->edge_terms + n + 1u;
  uint32_t i, j, f, cells[6];
  cube_texel t;
  setup_cube_bins(fit);
  cube_edge_terms(n, 0u, bottom);
  for (j = 0; j < n; ++j) {
    double* swap = top;
    top = bottom, bottom = swap;
    cube_edge_terms(n, j + 1u, bottom);
    for (i = 0; i < n; ++i) {
      const double w = cube_texel_solid_angle(top, bottom, i);
      cube_texel_at(n, i, j, &t);
      cube_texel_cells(fit, i, &t, cells);
      for (f = 0; f < 6u; ++f) {
        double d[3];
        float largest;
        cube_texel_direction(f, &t, d);
        largest = add_cube_texel(&fit->cells[cells[f]], prt_env_texel(env, f, i, j), w, d);
        if (largest > fit->row_max[f * n + j]) fit->row_max[f * n + j] = largest;
      }
    }
  }
}

void prt_cloth_light_build_grid(light_fit* fit) {
  size_t k;
  uint32_t y;
  setup_grid(fit);
  if (fit->env.layout == PRT_ENV_LATLONG) {
    uint32_t grid_row;
    for (grid_row = 0; grid_row < fit->rows; ++grid_row) {
      for (y = fit->row_first[grid_row]; y < fit->row_first[grid_row + 1u]; ++y)
        sum_latlong_row(fit, y);
      flush_column_sums(fit, grid_row);
    }
  } else {
    grid_cube(fit);
  }
  fit->total_weight = 0.0;
  fit->total_solid_angle = 0.0;
  for (k = 0; k < (size_t)fit->rows * fit->cols; ++k) {
    fit->total_weight += fit->cells[k].weight;
    fit->total_solid_angle += fit->cells[k].solid_angle;
  }
}

/* A texel's solid angle: a lat-long row's exact one, a cube texel's differential one
 * (step^2 / |(1, s, t)|^3 at its centre). */
static double approximate_solid_angle(const prt_env_view* env, uint32_t x, uint32_t row) {
  if (env->layout == PRT_ENV_LATLONG)
    return 2.0 * PRT_SPHERE_PI / (double)env->width *
           (cos(PRT_SPHERE_PI * (double)row / (double)env->height) -
            cos(PRT_SPHERE_PI * (double)(row + 1u) / (double)env->height));
  {
    const double step = 2.0 / (double)env->width;
    const double s = step * ((double)x + 0.5) - 1.0, t = step * ((double)row + 0.5) - 1.0;
    const double r2 = 1.0 + s * s + t * t;
    return step * step / (r2 * sqrt(r2));
  }
}

/* Visits every texel whose level is at least floor (see cloth_light_internal.h). */
/* Texel (x, row) of face `face`: its direction, solid angle and grid cell, as the grid has it. */
static void bright_geometry(const light_fit* fit, uint32_t face, uint32_t x, uint32_t row,
                            bright_texel* t) {
  const prt_env_view* env = &fit->env;
  double solid_angle;
  uint32_t c;
  if (env->layout == PRT_ENV_LATLONG) {
    const double theta = PRT_SPHERE_PI * ((double)row + 0.5) / (double)env->height;
    const double phi = 2.0 * PRT_SPHERE_PI * (((double)x + 0.5) / (double)env->width - 0.5);
    uint32_t grid_row = 0u, grid_col = 0u;
    t->direction[0] = sin(theta) * sin(phi), t->direction[1] = cos(theta);
    t->direction[2] = -sin(theta) * cos(phi);
    solid_angle = 2.0 * PRT_SPHERE_PI / (double)env->width *
                  (cos(PRT_SPHERE_PI * (double)row / (double)env->height) -
                   cos(PRT_SPHERE_PI * (double)(row + 1u) / (double)env->height));
    /* The grid bins a lat-long image's texels by index. */
    while (row >= fit->row_first[grid_row + 1u]) ++grid_row;
    while (x >= fit->col_first[grid_col + 1u]) ++grid_col;
    t->cell = grid_row * fit->cols + grid_col;
  } else {
    const double step = 2.0 / (double)env->width;
    const double s0 = step * (double)x - 1.0, t0 = step * (double)row - 1.0;
    uint32_t cells[6];
    cube_texel cube;
    cube_texel_at(env->width, x, row, &cube);
    cube_texel_direction(face, &cube, t->direction);
    solid_angle = prt_cube_rect_solid_angle(s0, s0 + step, t0, t0 + step);
    cube_texel_cells(fit, x, &cube, cells);
    t->cell = cells[face];
  }
  t->weight = (double)t->level * solid_angle;
  for (c = 0; c < 3u; ++c) t->power[c] *= solid_angle;
}

uint32_t prt_cloth_light_visit_bright(light_fit* fit, float floor, bright_texel* out,
                                      uint32_t capacity) {
  const prt_env_view* env = &fit->env;
  uint32_t count = 0u, x, y, c;
  for (y = 0; y < fit->image_rows; ++y) {
    const uint32_t face = env->layout == PRT_ENV_LATLONG ? 0u : y / env->width;
    const uint32_t row = env->layout == PRT_ENV_LATLONG ? y : y % env->width;
    if (3.0f * fit->row_max[y] < floor) continue; /* a level is at most 3 channels' largest */
    for (x = 0; x < env->width; ++x) {
      const float* texel = prt_env_texel(env, face, x, row);
      bright_texel t;
      for (c = 0; c < 3u; ++c) t.power[c] = prt_cloth_light_sanitised(texel[c]);
      t.level = (float)t.power[0] + (float)t.power[1] + (float)t.power[2];
      if (!(t.level >= floor)) continue;
      if (out && count == capacity) return count;
      t.order = (size_t)y * env->width + x;
      t.group = UINT32_MAX;
      if (out) {
        bright_geometry(fit, face, x, row, &t);
        out[count] = t;
      } else {
        /* The histogram needs solid angles only, and only roughly (it sets a budget). */
        const double solid_angle = approximate_solid_angle(env, x, row);
        level_bin* bin = &fit->levels[prt_cloth_light_level_bin(t.level)];
        bin->solid_angle += solid_angle;
        bin->texels += 1u;
      }
      ++count;
    }
  }
  return count;
}
