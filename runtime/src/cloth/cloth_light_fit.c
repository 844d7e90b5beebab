/* SPDX-License-Identifier: MIT */
/* The spherical-Gaussian light fitted to an environment image every frame (prt_cloth_fit_light).
 *
 * A least-squares fit of radiance is not robust to a small very bright source (it spends lobes on
 * it and overflows their sharpness), so the fit keeps power instead:
 * 1. the map is averaged onto a lat-long grid: per cell its power (radiance x solid angle), the
 *    power-weighted sum of its texel directions (the resultant) and its solid angle;
 * 2. compact very bright sources (a sun) are found among the original texels: the brightest
 *    texels within a tiny solid angle, grouped by direction; a group that holds a large share of
 *    the power and stands out from its surroundings becomes a lobe of its own and leaves the grid;
 * 3. the rest of the grid is clustered by direction (power-weighted spherical k-means, seeded by
 *    k-means++ from a fixed-seed generator);
 * 4. every group or cluster becomes the lobe with its power, its mean direction and a sharpness
 *    from its spread: the mean resultant length r of a von Mises-Fisher lobe of sharpness l is
 *    coth(l) - 1/l, and its integral is (2 pi / l)(1 - exp(-2 l)) x rgb, so power is exact.
 * Everything runs in the image's frame and the axes are turned by the env's rotation at the end.
 * All scratch comes from the context's allocator and is freed before return. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "cloth_internal.h"
#include "env_internal.h"
#include "sphere_internal.h"

#define DEFAULT_LOBES 10u
#define DEFAULT_RESOLUTION 64u
#define DEFAULT_ITERATIONS 8u

/* Compact sources: texels at least this many times the mean radiance, ... */
#define COMPACT_CONTRAST 16.0
/* ... the brightest of them within this fraction of the sphere, ... */
#define COMPACT_SPHERE_FRACTION 1.0e-4
/* ... grouped by direction within this angle of each group's brightest texel (radians). */
#define COMPACT_GROUP_RADIUS (2.0 * PRT_SPHERE_PI / 180.0)
/* A group becomes a lobe when it holds at least half a lobe's fair share of the power (1 / 2K)
 * and this many times the power of the rest of the map within COMPACT_SURROUND_RADIUS. */
#define COMPACT_DOMINANCE 3.0
#define COMPACT_SURROUND_RADIUS (6.0 * PRT_SPHERE_PI / 180.0)
#define MAX_COMPACT_GROUPS 32u

/* Texel levels: a positive float's bits >> 20 (exponent and 3 mantissa bits: eighths of an
 * octave), so the histogram needs no logarithm. */
#define LEVEL_SHIFT 20u
#define LEVEL_COUNT 2048u

/* A lobe's value below exp(-CUTOFF) of its peak is left out of the error's cell integrals. */
#define LOBE_CUTOFF 30.0
/* At most this many midpoint samples per axis when a lobe is sharp for a cell. */
#define MAX_CELL_SAMPLES 16u

typedef struct grid_cell {
  double power[3];     /* sum of radiance x solid angle, RGB */
  double weight;       /* the sum of power's channels: what directions are weighted by */
  double resultant[3]; /* sum of weight x direction over the cell's texels */
  double solid_angle;  /* of the texels that landed in the cell */
  double removed[3];   /* power taken out for compact sources (the map's is power + removed) */
} grid_cell;

typedef struct level_bin {
  double solid_angle, weight;
  uint32_t texels;
} level_bin;

/* A texel of a compact-source candidate. */
typedef struct bright_texel {
  float level;  /* r + g + b radiance */
  size_t order; /* its place in the walk: ties of level are broken by it */
  uint32_t cell;
  uint32_t group; /* MAX_COMPACT_GROUPS: none */
  double power[3], weight, direction[3];
} bright_texel;

/* A group of bright texels, and later any group of power that becomes a lobe. */
typedef struct power_group {
  double power[3], weight, resultant[3];
  double seed[3]; /* its brightest texel's direction, or a cluster's centre */
} power_group;

/* The points of the clustering, one per lit cell, as arrays. */
typedef struct cluster_points {
  float *x, *y, *z;     /* the cell's mean direction */
  float* weight;        /* the cell's weight */
  float* best;          /* the best dot product with a centre so far */
  uint32_t* cell;       /* the cell's index */
  uint32_t* nearest;    /* the nearest centre in this pass */
  uint32_t* assignment; /* the centre it belongs to */
} cluster_points;
#define POINT_ARRAYS 8u

/* The grid's geometry for the error's cell integrals: per row its polar bounds, centre and a
 * bound of its cells' angular radius and size; per column its azimuth bounds and centre. */
typedef struct row_shape {
  double theta0, theta1, cos0, cos1, sin_centre, cos_centre, cos_radius, sin_radius, size;
} row_shape;

typedef struct col_shape {
  double phi0, phi1, sin_centre, cos_centre;
} col_shape;

/* A lat-long image's sums over the image rows of one grid row, per float of a row (texel x's
 * channel c at channels x + c): its value times the texel's solid angle, and that times sin theta
 * and cos theta. Per float rather than per texel, so the loop is the same for RGB and RGBA. */
enum { SUM_POWER, SUM_SIN, SUM_COS, SUM_COUNT };

/* A lobe in double while the fit works on it. */
typedef struct fit_lobe {
  double axis[3], sharpness, rgb[3];
} fit_lobe;

typedef struct light_fit {
  prt_env_view env;
  uint32_t lobes, iterations;
  uint32_t rows, cols;
  double* theta;       /* rows + 1 bounds of the grid rows (polar angle from +Y) */
  double* phi;         /* cols + 1 bounds of the grid columns (azimuth, from -pi) */
  uint32_t* row_first; /* lat-long source: first image row / column of each grid row / */
  uint32_t* col_first; /* column, rows + 1 / cols + 1 entries */
  double* sin_phi;     /* lat-long source: env.width column azimuths' sin and cos */
  double* cos_phi;
  float* column_sums;     /* lat-long source: SUM_COUNT x env.width x env.channels */
  double* cos_bounds;     /* cube source: cos of the rows' polar bounds, rows + 1 */
  uint32_t* side_columns; /* cube source: 4 x face size (+X, -X, +Z, -Z) */
  double* edge_terms;     /* cube source: 2 x (face size + 1) */
  float* row_max;         /* largest channel value per image row (cube: per face row) */
  uint32_t image_rows;    /* entries of row_max */
  grid_cell* cells;       /* rows x cols */
  level_bin* levels;      /* LEVEL_COUNT */
  cluster_points points;  /* up to rows x cols */
  row_shape* rows_shape;  /* rows */
  col_shape* cols_shape;  /* cols */
  power_group* groups;    /* lobes + MAX_COMPACT_GROUPS */
  fit_lobe* fitted;       /* lobes */
  double total_weight;
  double total_solid_angle;
} light_fit;

/* ---- Small maths --------------------------------------------------------------------------- */

/* A channel value as the fit uses it: NaN, infinities and negatives count as 0 (NaN fails both
 * compares; in the grid loop they become masks, not branches). */
static float sanitised(float value) {
  return ((value > 0.0f) & (value <= FLT_MAX)) ? value : 0.0f;
}

static uint32_t level_of(float level) {
  uint32_t bits;
  if (!(level <= FLT_MAX)) return LEVEL_COUNT - 1u;
  memcpy(&bits, &level, sizeof bits);
  return bits >> LEVEL_SHIFT;
}

/* The smallest level (texel brightness) in bin b. */
static float level_floor(uint32_t bin) {
  const uint32_t bits = bin << LEVEL_SHIFT;
  float value;
  memcpy(&value, &bits, sizeof value);
  return value;
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

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

/* The mean resultant length of a von Mises-Fisher lobe of sharpness l: coth(l) - 1/l. */
static double resultant_of_sharpness(double l) {
  return 1.0 / tanh(l) - 1.0 / l;
}

/* The sharpness whose lobe has mean resultant length r, within the light's bounds (Newton from
 * Banerjee et al.'s approximation r (3 - r^2) / (1 - r^2); the function is increasing). */
static double sharpness_of_resultant(double r) {
  const double lo = PRT_CLOTH_MIN_SHARPNESS, hi = PRT_CLOTH_MAX_SHARPNESS;
  double l;
  int i;
  if (!(r > resultant_of_sharpness(lo))) return lo;
  if (r >= resultant_of_sharpness(hi)) return hi;
  l = r * (3.0 - r * r) / (1.0 - r * r);
  if (l < lo) l = lo;
  if (l > hi) l = hi;
  for (i = 0; i < 16; ++i) {
    const double s = sinh(l);
    const double slope = 1.0 / (l * l) - (s > 1e150 ? 0.0 : 1.0 / (s * s));
    double next = l - (resultant_of_sharpness(l) - r) / slope;
    if (next < lo) next = lo;
    if (next > hi) next = hi;
    if (fabs(next - l) <= 1e-12 * l) return next;
    l = next;
  }
  return l;
}

/* The integral of exp(l (w . axis - 1)) over the sphere. */
static double lobe_integral(double l) {
  return 2.0 * PRT_SPHERE_PI / l * (1.0 - exp(-2.0 * l));
}

/* ---- Scratch ------------------------------------------------------------------------------- */

typedef struct scratch_plan {
  size_t total;
  size_t theta, phi, row_first, col_first, sin_phi, cos_phi, column_sums, cos_bounds, side_columns,
      edge_terms, row_max, cells, levels, points, rows_shape, cols_shape, groups, fitted;
} scratch_plan;

/* Reserves n elements of size each at the plan's end (64-byte aligned); 0 on overflow. */
static int reserve(scratch_plan* plan, size_t* offset, size_t n, size_t size) {
  const size_t start = (plan->total + 63u) & ~(size_t)63u;
  if (start < plan->total || (n && size > (SIZE_MAX - start) / n)) return 0;
  *offset = start;
  plan->total = start + n * size;
  return 1;
}

/* Grid rows: the resolution asked for, at most the image's own (a lat-long image's rows, a cube
 * face's texels), so every cell holds texels. */
static void choose_grid(light_fit* fit, uint32_t resolution) {
  const prt_env_view* env = &fit->env;
  if (env->layout == PRT_ENV_LATLONG) {
    fit->rows = resolution < env->height ? resolution : env->height;
    fit->cols = 2u * (uint64_t)resolution < env->width ? 2u * resolution : env->width;
    fit->image_rows = env->height;
  } else {
    fit->rows = resolution < env->width ? resolution : env->width;
    fit->cols = 2u * fit->rows;
    fit->image_rows = 6u * env->width;
  }
}

static int plan_scratch(const light_fit* fit, scratch_plan* plan) {
  const size_t cells = (size_t)fit->rows * fit->cols;
  const int latlong = fit->env.layout == PRT_ENV_LATLONG;
  const size_t columns = latlong ? fit->env.width : 0u;
  const size_t face = latlong ? 0u : fit->env.width;
  memset(plan, 0, sizeof *plan);
  return reserve(plan, &plan->theta, fit->rows + 1u, sizeof(double)) &&
         reserve(plan, &plan->phi, fit->cols + 1u, sizeof(double)) &&
         reserve(plan, &plan->row_first, fit->rows + 1u, sizeof(uint32_t)) &&
         reserve(plan, &plan->col_first, fit->cols + 1u, sizeof(uint32_t)) &&
         reserve(plan, &plan->sin_phi, columns, sizeof(double)) &&
         reserve(plan, &plan->cos_phi, columns, sizeof(double)) &&
         reserve(plan, &plan->column_sums, columns * fit->env.channels,
                 SUM_COUNT * sizeof(float)) &&
         reserve(plan, &plan->cos_bounds, latlong ? 0u : fit->rows + 1u, sizeof(double)) &&
         reserve(plan, &plan->side_columns, 4u * face, sizeof(uint32_t)) &&
         reserve(plan, &plan->edge_terms, latlong ? 0u : 2u * (face + 1u), sizeof(double)) &&
         reserve(plan, &plan->row_max, fit->image_rows, sizeof(float)) &&
         reserve(plan, &plan->cells, cells, sizeof(grid_cell)) &&
         reserve(plan, &plan->levels, LEVEL_COUNT, sizeof(level_bin)) &&
         reserve(plan, &plan->points, cells, POINT_ARRAYS * sizeof(float)) &&
         reserve(plan, &plan->rows_shape, fit->rows, sizeof(row_shape)) &&
         reserve(plan, &plan->cols_shape, fit->cols, sizeof(col_shape)) &&
         reserve(plan, &plan->groups, fit->lobes + MAX_COMPACT_GROUPS, sizeof(power_group)) &&
         reserve(plan, &plan->fitted, fit->lobes, sizeof(fit_lobe));
}

static void place_scratch(light_fit* fit, const scratch_plan* plan, unsigned char* base) {
  fit->theta = (double*)(void*)(base + plan->theta);
  fit->phi = (double*)(void*)(base + plan->phi);
  fit->row_first = (uint32_t*)(void*)(base + plan->row_first);
  fit->col_first = (uint32_t*)(void*)(base + plan->col_first);
  fit->sin_phi = (double*)(void*)(base + plan->sin_phi);
  fit->cos_phi = (double*)(void*)(base + plan->cos_phi);
  fit->column_sums = (float*)(void*)(base + plan->column_sums);
  fit->cos_bounds = (double*)(void*)(base + plan->cos_bounds);
  fit->side_columns = (uint32_t*)(void*)(base + plan->side_columns);
  fit->edge_terms = (double*)(void*)(base + plan->edge_terms);
  fit->row_max = (float*)(void*)(base + plan->row_max);
  fit->cells = (grid_cell*)(void*)(base + plan->cells);
  fit->levels = (level_bin*)(void*)(base + plan->levels);
  {
    const size_t cells = (size_t)fit->rows * fit->cols;
    float* f = (float*)(void*)(base + plan->points);
    uint32_t* u = (uint32_t*)(void*)(f + 5u * cells);
    fit->points.x = f, fit->points.y = f + cells, fit->points.z = f + 2u * cells;
    fit->points.weight = f + 3u * cells, fit->points.best = f + 4u * cells;
    fit->points.cell = u, fit->points.nearest = u + cells, fit->points.assignment = u + 2u * cells;
  }
  fit->rows_shape = (row_shape*)(void*)(base + plan->rows_shape);
  fit->cols_shape = (col_shape*)(void*)(base + plan->cols_shape);
  fit->groups = (power_group*)(void*)(base + plan->groups);
  fit->fitted = (fit_lobe*)(void*)(base + plan->fitted);
  memset(base, 0, plan->total);
}

/* ---- The grid ------------------------------------------------------------------------------ */

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
    const float value = sanitised(row[j]);
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
  const float rgb[3] = {sanitised(texel[0]), sanitised(texel[1]), sanitised(texel[2])};
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

static void build_grid(light_fit* fit) {
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

/* ---- Compact sources ----------------------------------------------------------------------- */

/* Visits every texel of level >= floor (rows that cannot hold one are skipped):
 * without out, adds it to fit->levels; with out, appends it there (up to capacity). Returns the
 * texels visited (listed). */
static uint32_t visit_bright(light_fit* fit, float floor, bright_texel* out, uint32_t capacity) {
  const prt_env_view* env = &fit->env;
  uint32_t count = 0u, x, y;
  for (y = 0; y < fit->image_rows; ++y) {
    if (3.0f * fit->row_max[y] < floor) continue; /* a level is at most 3 channels' largest */
    for (x = 0; x < env->width; ++x) {
      const uint32_t face = env->layout == PRT_ENV_LATLONG ? 0u : y / env->width;
      const uint32_t row = env->layout == PRT_ENV_LATLONG ? y : y % env->width;
      const float* texel = prt_env_texel(env, face, x, row);
      const float rgb[3] = {sanitised(texel[0]), sanitised(texel[1]), sanitised(texel[2])};
      const float level = rgb[0] + rgb[1] + rgb[2];
      double d[3], solid_angle;
      cube_texel cube;
      if (!(level >= floor)) continue;
      if (out && count == capacity) return count;
      if (env->layout == PRT_ENV_LATLONG) {
        const double theta = PRT_SPHERE_PI * ((double)row + 0.5) / (double)env->height;
        const double phi = 2.0 * PRT_SPHERE_PI * (((double)x + 0.5) / (double)env->width - 0.5);
        d[0] = sin(theta) * sin(phi), d[1] = cos(theta), d[2] = -sin(theta) * cos(phi);
        solid_angle = 2.0 * PRT_SPHERE_PI / (double)env->width *
                      (cos(PRT_SPHERE_PI * (double)row / (double)env->height) -
                       cos(PRT_SPHERE_PI * (double)(row + 1u) / (double)env->height));
      } else {
        const double step = 2.0 / (double)env->width;
        const double s0 = step * (double)x - 1.0, t0 = step * (double)row - 1.0;
        cube_texel_at(env->width, x, row, &cube);
        cube_texel_direction(face, &cube, d);
        solid_angle = prt_cube_rect_solid_angle(s0, s0 + step, t0, t0 + step);
      }
      if (out) {
        bright_texel* t = &out[count];
        uint32_t c;
        t->level = level;
        t->order = (size_t)y * env->width + x;
        t->group = MAX_COMPACT_GROUPS;
        t->weight = (double)level * solid_angle;
        for (c = 0; c < 3u; ++c) {
          t->power[c] = (double)rgb[c] * solid_angle;
          t->direction[c] = d[c];
        }
        if (env->layout == PRT_ENV_LATLONG) {
          /* The grid cell it was added to (build_grid bins texels by index). */
          uint32_t gr = 0u, gc = 0u;
          while (row >= fit->row_first[gr + 1u]) ++gr;
          while (x >= fit->col_first[gc + 1u]) ++gc;
          t->cell = gr * fit->cols + gc;
        } else {
          uint32_t cells[6];
          cube_texel_cells(fit, x, &cube, cells);
          t->cell = cells[face];
        }
      } else {
        level_bin* bin = &fit->levels[level_of(level)];
        bin->solid_angle += solid_angle;
        bin->weight += (double)level * solid_angle;
        bin->texels += 1u;
      }
      ++count;
    }
  }
  return count;
}

/* The level above which texels are compact-source candidates: the brightest texels (at least
 * COMPACT_CONTRAST times the mean radiance) whose solid angle stays within the budget; 0 texels
 * (*texels = 0) when there are none. */
static float candidate_floor(light_fit* fit, uint32_t* texels) {
  const double mean = fit->total_weight / fit->total_solid_angle;
  const double budget = COMPACT_SPHERE_FRACTION * fit->total_solid_angle;
  const float contrast_floor = (float)(COMPACT_CONTRAST * mean);
  double solid_angle = 0.0;
  uint32_t bin, count = 0u;
  float floor = 0.0f;
  *texels = 0u;
  if (!(contrast_floor > 0.0f) || !(contrast_floor <= FLT_MAX)) return 0.0f;
  if (visit_bright(fit, contrast_floor, NULL, 0u) == 0u) return 0.0f;
  for (bin = LEVEL_COUNT; bin-- > level_of(contrast_floor);) {
    const level_bin* b = &fit->levels[bin];
    if (b->texels == 0u) continue;
    if (solid_angle + b->solid_angle > budget) break;
    solid_angle += b->solid_angle;
    count += b->texels;
    floor = level_floor(bin);
  }
  if (floor < contrast_floor) floor = contrast_floor;
  *texels = count;
  return floor;
}

static void add_to_group(power_group* g, const double power[3], double weight,
                         const double direction[3]) {
  uint32_t c;
  for (c = 0; c < 3u; ++c) {
    g->power[c] += power[c];
    g->resultant[c] += weight * direction[c];
  }
  g->weight += weight;
}

/* Greedy grouping, brightest first: a texel joins the first group whose brightest texel is
 * within COMPACT_GROUP_RADIUS, or starts a group. Returns the number of groups. */
static uint32_t group_bright(bright_texel* texels, uint32_t count, power_group* groups) {
  const double cos_radius = cos(COMPACT_GROUP_RADIUS);
  uint32_t n = 0u, t, g;
  for (t = 0; t < count; ++t) {
    bright_texel* texel = &texels[t];
    for (g = 0; g < n; ++g)
      if (dot3(texel->direction, groups[g].seed) >= cos_radius) break;
    if (g == n) {
      if (n == MAX_COMPACT_GROUPS) continue;
      memset(&groups[n], 0, sizeof groups[n]);
      memcpy(groups[n].seed, texel->direction, sizeof groups[n].seed);
      ++n;
    }
    texel->group = g;
    add_to_group(&groups[g], texel->power, texel->weight, texel->direction);
  }
  return n;
}

/* Whether a group dominates its surroundings: the grid's power within COMPACT_SURROUND_RADIUS
 * of its mean direction, less its own, is at most 1 / COMPACT_DOMINANCE of its power. */
static int group_dominates(const light_fit* fit, const power_group* g) {
  const double cos_radius = cos(COMPACT_SURROUND_RADIUS);
  const double length = sqrt(dot3(g->resultant, g->resultant));
  double around = 0.0;
  size_t k;
  if (!(length > 0.0)) return 0;
  for (k = 0; k < (size_t)fit->rows * fit->cols; ++k) {
    const grid_cell* cell = &fit->cells[k];
    if (cell->weight > 0.0 &&
        dot3(cell->resultant, g->resultant) >=
            cos_radius * length * sqrt(dot3(cell->resultant, cell->resultant)))
      around += cell->weight;
  }
  return around - g->weight <= g->weight / COMPACT_DOMINANCE;
}

/* Takes a group's texels out of the grid. */
static void remove_group(light_fit* fit, const bright_texel* texels, uint32_t count,
                         uint32_t group) {
  uint32_t t, c;
  for (t = 0; t < count; ++t) {
    grid_cell* cell;
    if (texels[t].group != group) continue;
    cell = &fit->cells[texels[t].cell];
    for (c = 0; c < 3u; ++c) {
      cell->power[c] -= texels[t].power[c];
      cell->removed[c] += texels[t].power[c];
      cell->resultant[c] -= texels[t].weight * texels[t].direction[c];
      if (cell->power[c] < 0.0) cell->power[c] = 0.0;
    }
    cell->weight -= texels[t].weight;
    if (!(cell->weight > 1e-12 * fit->total_weight)) {
      memset(cell->power, 0, sizeof cell->power);
      memset(cell->resultant, 0, sizeof cell->resultant);
      cell->weight = 0.0;
    }
  }
}

/* Orders texels by level, brightest first, then by their place in the map. */
static int brighter(const bright_texel* x, const bright_texel* y) {
  if (x->level != y->level) return x->level > y->level;
  return x->order < y->order;
}

/* Heap sort, brightest first (qsort may allocate behind the allocator's back). */
static void sift_down(bright_texel* t, uint32_t root, uint32_t count) {
  for (;;) {
    uint32_t child = 2u * root + 1u;
    bright_texel swap;
    if (child >= count) return;
    /* A min-heap on "brighter": its root is the dimmest, moved to the end each step. */
    if (child + 1u < count && brighter(&t[child], &t[child + 1u])) ++child;
    if (!brighter(&t[root], &t[child])) return;
    swap = t[root], t[root] = t[child], t[child] = swap;
    root = child;
  }
}

static void sort_brightest_first(bright_texel* t, uint32_t count) {
  uint32_t i;
  bright_texel swap;
  for (i = count / 2u; i-- > 0u;) sift_down(t, i, count);
  for (i = count; i-- > 1u;) {
    swap = t[0], t[0] = t[i], t[i] = swap;
    sift_down(t, 0u, i);
  }
}

/* Finds the compact sources among the candidates, moves them from the grid to
 * fit->groups[0..n), heaviest first, and returns n. */
static uint32_t take_groups(light_fit* fit, bright_texel* texels, uint32_t count) {
  power_group candidates[MAX_COMPACT_GROUPS];
  uint32_t order[MAX_COMPACT_GROUPS];
  const double min_weight = fit->total_weight / (2.0 * (double)fit->lobes);
  uint32_t groups, g, h, taken = 0u;
  sort_brightest_first(texels, count);
  groups = group_bright(texels, count, candidates);
  /* Heaviest first (ties: the earlier group, whose brightest texel is brighter). */
  for (g = 0; g < groups; ++g) {
    for (h = g; h > 0u && candidates[order[h - 1u]].weight < candidates[g].weight; --h)
      order[h] = order[h - 1u];
    order[h] = g;
  }
  /* Decide on the full grid, then take them out. */
  for (g = 0; g < groups && taken + 1u < fit->lobes; ++g) {
    const power_group* candidate = &candidates[order[g]];
    if (candidate->weight >= min_weight && group_dominates(fit, candidate))
      order[taken++] = order[g];
  }
  for (g = 0; g < taken; ++g) {
    fit->groups[g] = candidates[order[g]];
    remove_group(fit, texels, count, order[g]);
  }
  return taken;
}

/* The compact sources (take_groups) from the texels above candidate_floor; -1 when the
 * allocator fails. */
static int take_compact_sources(light_fit* fit, const prt_allocator* allocator) {
  uint32_t count, listed, taken;
  bright_texel* texels;
  const float floor = fit->lobes < 2u ? 0.0f : candidate_floor(fit, &count);
  if (fit->lobes < 2u || count == 0u) return 0;
  texels = (bright_texel*)prt_internal_alloc(allocator, (size_t)count * sizeof *texels, 16u);
  if (!texels) return -1;
  listed = visit_bright(fit, floor, texels, count);
  taken = take_groups(fit, texels, listed);
  prt_internal_free(allocator, texels, (size_t)count * sizeof *texels);
  return (int)taken;
}

/* ---- Clustering ---------------------------------------------------------------------------- */

/* The lit cells as points: their mean direction and weight, in arrays the loops below
 * vectorise over; returns how many. */
static uint32_t gather_points(light_fit* fit) {
  cluster_points* pts = &fit->points;
  uint32_t n = 0u, k;
  for (k = 0; k < fit->rows * fit->cols; ++k) {
    const grid_cell* cell = &fit->cells[k];
    const double length = sqrt(dot3(cell->resultant, cell->resultant));
    if (!(cell->weight > 0.0) || !(length > 0.0)) continue;
    pts->x[n] = (float)(cell->resultant[0] / length);
    pts->y[n] = (float)(cell->resultant[1] / length);
    pts->z[n] = (float)(cell->resultant[2] / length);
    pts->weight[n] = (float)cell->weight;
    pts->cell[n] = k;
    ++n;
  }
  return n;
}

/* A fixed-seed generator (xorshift64*): the seeding is the same on every call. */
static double next_uniform(uint64_t* state) {
  *state ^= *state >> 12;
  *state ^= *state << 25;
  *state ^= *state >> 27;
  return (double)((*state * 0x2545F4914F6CDD1Dull) >> 11) * (1.0 / 9007199254740992.0);
}

/* Raises each point's best dot product to its dot with centre (cx, cy, cz) and returns the new
 * seeding mass: the sum of weight x (1 - best dot), the squared chord distance over two. */
static double closer_to_centre(cluster_points* pts, uint32_t n, float cx, float cy, float cz) {
  double mass = 0.0;
  uint32_t p;
  for (p = 0; p < n; ++p) {
    const float d = pts->x[p] * cx + pts->y[p] * cy + pts->z[p] * cz;
    pts->best[p] = d > pts->best[p] ? d : pts->best[p];
  }
  for (p = 0; p < n; ++p) mass += (double)pts->weight[p] * (1.0 - (double)pts->best[p]);
  return mass;
}

/* k-means++: each centre is a point drawn with probability proportional to its weight times its
 * squared chord distance to the nearest centre so far (the first: to its weight). Returns the
 * centres placed (fewer when every point sits on a centre). */
static uint32_t seed_centres(cluster_points* pts, uint32_t n, uint32_t wanted, power_group* out) {
  uint64_t state = 0x9E3779B97F4A7C15ull;
  uint32_t placed = 0u, p;
  double mass = 0.0;
  for (p = 0; p < n; ++p) {
    pts->best[p] = -1.0f;
    mass += 2.0 * (double)pts->weight[p];
  }
  while (placed < wanted && mass > 0.0) {
    const double target = next_uniform(&state) * mass;
    double sum = 0.0;
    uint32_t chosen = n - 1u;
    for (p = 0; p < n; ++p) {
      sum += (double)pts->weight[p] * (1.0 - (double)pts->best[p]);
      if (sum > target) {
        chosen = p;
        break;
      }
    }
    memset(&out[placed], 0, sizeof out[placed]);
    out[placed].seed[0] = pts->x[chosen];
    out[placed].seed[1] = pts->y[chosen];
    out[placed].seed[2] = pts->z[chosen];
    mass = closer_to_centre(pts, n, pts->x[chosen], pts->y[chosen], pts->z[chosen]);
    ++placed;
  }
  return placed;
}

/* Assigns every point to its nearest centre (ties: the first); returns how many changed. */
static uint32_t assign_points(cluster_points* pts, uint32_t n, const power_group* centres,
                              uint32_t count) {
  const float* restrict x = pts->x;
  const float* restrict y = pts->y;
  const float* restrict z = pts->z;
  float* restrict best = pts->best;
  uint32_t* restrict nearest = pts->nearest;
  uint32_t changed = 0u, p, k;
  for (p = 0; p < n; ++p) best[p] = -2.0f;
  for (k = 0; k < count; ++k) {
    const float cx = (float)centres[k].seed[0], cy = (float)centres[k].seed[1];
    const float cz = (float)centres[k].seed[2];
    for (p = 0; p < n; ++p) {
      /* The index through a mask rather than a second select: this form vectorises. */
      const float d = x[p] * cx + y[p] * cy + z[p] * cz, b = best[p];
      const uint32_t closer = 0u - (uint32_t)(d > b);
      best[p] = d > b ? d : b;
      nearest[p] = (k & closer) | (nearest[p] & ~closer);
    }
  }
  for (p = 0; p < n; ++p) {
    changed += pts->nearest[p] != pts->assignment[p];
    pts->assignment[p] = pts->nearest[p];
  }
  return changed;
}

/* The clusters' power, weight and resultant from the assignment, and centres moved to their
 * mean directions (an empty cluster keeps its centre). */
static void gather_clusters(const light_fit* fit, uint32_t n, power_group* clusters,
                            uint32_t count) {
  uint32_t p, k;
  for (k = 0; k < count; ++k) {
    memset(clusters[k].power, 0, sizeof clusters[k].power);
    memset(clusters[k].resultant, 0, sizeof clusters[k].resultant);
    clusters[k].weight = 0.0;
  }
  for (p = 0; p < n; ++p) {
    const grid_cell* cell = &fit->cells[fit->points.cell[p]];
    power_group* g = &clusters[fit->points.assignment[p]];
    for (k = 0; k < 3u; ++k) {
      g->power[k] += cell->power[k];
      g->resultant[k] += cell->resultant[k];
    }
    g->weight += cell->weight;
  }
  for (k = 0; k < count; ++k) {
    const double length = sqrt(dot3(clusters[k].resultant, clusters[k].resultant));
    if (length > 0.0)
      for (p = 0; p < 3u; ++p) clusters[k].seed[p] = clusters[k].resultant[p] / length;
  }
}

/* Clusters the grid's lit cells into at most `wanted` groups (fit->groups from `first` on);
 * returns how many hold power. */
static uint32_t cluster_grid(light_fit* fit, uint32_t first, uint32_t wanted) {
  power_group* clusters = fit->groups + first;
  const uint32_t n = gather_points(fit);
  uint32_t count, iteration, k, kept = 0u;
  if (n == 0u || wanted == 0u) return 0u;
  count = seed_centres(&fit->points, n, wanted < n ? wanted : n, clusters);
  for (k = 0; k < n; ++k) fit->points.assignment[k] = UINT32_MAX;
  for (iteration = 0; iteration < fit->iterations; ++iteration) {
    if (assign_points(&fit->points, n, clusters, count) == 0u) break;
    gather_clusters(fit, n, clusters, count);
  }
  /* Drop empty clusters, then heaviest first (a stable insertion sort). */
  for (k = 0; k < count; ++k)
    if (clusters[k].weight > 0.0) clusters[kept++] = clusters[k];
  for (k = 1; k < kept; ++k) {
    const power_group g = clusters[k];
    uint32_t h = k;
    for (; h > 0u && clusters[h - 1u].weight < g.weight; --h) clusters[h] = clusters[h - 1u];
    clusters[h] = g;
  }
  return kept;
}

/* ---- Lobes --------------------------------------------------------------------------------- */

/* The lobe of a group of power: its mean direction, the sharpness of its spread and the
 * amplitude that gives it the group's power. */
static void lobe_of_group(const power_group* g, fit_lobe* out) {
  const double length = sqrt(dot3(g->resultant, g->resultant));
  double scale;
  uint32_t c;
  out->sharpness = sharpness_of_resultant(length / g->weight);
  scale = 1.0 / lobe_integral(out->sharpness);
  for (c = 0; c < 3u; ++c) {
    out->axis[c] = length > 0.0 ? g->resultant[c] / length : g->seed[c];
    out->rgb[c] = g->power[c] * scale;
    if (out->rgb[c] > FLT_MAX) out->rgb[c] = FLT_MAX;
  }
}

/* The report's grid geometry (shapes of rows and columns). */
static void shape_grid(light_fit* fit) {
  double widest_phi = 0.0;
  uint32_t i;
  for (i = 0; i < fit->cols; ++i) {
    col_shape* c = &fit->cols_shape[i];
    const double p = 0.5 * (fit->phi[i] + fit->phi[i + 1u]);
    c->phi0 = fit->phi[i], c->phi1 = fit->phi[i + 1u];
    c->sin_centre = sin(p), c->cos_centre = cos(p);
    widest_phi = fmax(widest_phi, c->phi1 - c->phi0);
  }
  for (i = 0; i < fit->rows; ++i) {
    row_shape* r = &fit->rows_shape[i];
    const double t0 = fit->theta[i], t1 = fit->theta[i + 1u], t = 0.5 * (t0 + t1);
    const double widest =
        (t0 < 0.5 * PRT_SPHERE_PI && t1 > 0.5 * PRT_SPHERE_PI) ? 1.0 : fmax(sin(t0), sin(t1));
    /* A bound of the angle from a cell's centre to any of its points: half its polar extent
     * plus half its widest azimuthal arc. */
    const double radius = 0.5 * (t1 - t0) + 0.5 * widest * widest_phi;
    r->theta0 = t0, r->theta1 = t1, r->cos0 = cos(t0), r->cos1 = cos(t1);
    r->sin_centre = sin(t), r->cos_centre = cos(t);
    r->cos_radius = cos(radius), r->sin_radius = sin(radius);
    r->size = fmax(t1 - t0, widest * widest_phi);
  }
}

/* The mean of a lobe's radiance (per unit amplitude) over a grid cell: a midpoint rule on n x n
 * sub-cells, n growing with the lobe's sharpness against the cell's size (one sample, at the
 * centre, for a broad lobe); 0 where the lobe is below exp(-LOBE_CUTOFF) of its peak. */
static double lobe_cell_mean(const fit_lobe* lobe, const row_shape* r, const col_shape* c) {
  const double centre[3] = {r->sin_centre * c->sin_centre, r->cos_centre,
                            -r->sin_centre * c->cos_centre};
  const double d = dot3(lobe->axis, centre);
  double sum = 0.0;
  uint32_t n, i, j;
  /* Out of reach when even the cell's point nearest the axis (at the cos computed below) is. */
  if (lobe->sharpness * (1.0 - d) > LOBE_CUTOFF && d < r->cos_radius &&
      lobe->sharpness * (1.0 - d * r->cos_radius - sqrt(fmax(0.0, 1.0 - d * d)) * r->sin_radius) >
          LOBE_CUTOFF)
    return 0.0;
  /* Samples a quarter of the lobe's width (1 / sqrt(sharpness)) apart. */
  n = (uint32_t)ceil(4.0 * sqrt(lobe->sharpness) * r->size);
  /* One sample: single precision is plenty for the report and much faster. */
  if (n <= 1u) return expf((float)(lobe->sharpness * (d - 1.0)));
  if (n > MAX_CELL_SAMPLES) n = MAX_CELL_SAMPLES;
  for (j = 0; j < n; ++j) {
    const double ta = r->theta0 + (r->theta1 - r->theta0) * (double)j / (double)n;
    const double tb = r->theta0 + (r->theta1 - r->theta0) * (double)(j + 1u) / (double)n;
    const double t = 0.5 * (ta + tb), st = sin(t), ct = cos(t);
    const double band = cos(ta) - cos(tb);
    for (i = 0; i < n; ++i) {
      const double p = c->phi0 + (c->phi1 - c->phi0) * ((double)i + 0.5) / (double)n;
      const double w[3] = {st * sin(p), ct, -st * cos(p)};
      sum += band * exp(lobe->sharpness * (dot3(lobe->axis, w) - 1.0));
    }
  }
  return sum / (double)n / (r->cos0 - r->cos1);
}

/* RMS over the grid's cells (solid-angle weighted) of the lobes' mean radiance minus the map's
 * (compact sources included), over the map's RMS radiance. */
static double relative_error(light_fit* fit, const fit_lobe* lobes, uint32_t count) {
  double error = 0.0, norm = 0.0;
  uint32_t row, col, k, c;
  shape_grid(fit);
  for (row = 0; row < fit->rows; ++row) {
    for (col = 0; col < fit->cols; ++col) {
      const size_t index = (size_t)row * fit->cols + col;
      const grid_cell* cell = &fit->cells[index];
      double model[3] = {0.0, 0.0, 0.0};
      if (!(cell->solid_angle > 0.0)) continue;
      for (k = 0; k < count; ++k) {
        const double mean = lobe_cell_mean(&lobes[k], &fit->rows_shape[row], &fit->cols_shape[col]);
        if (mean == 0.0) continue;
        for (c = 0; c < 3u; ++c) model[c] += lobes[k].rgb[c] * mean;
      }
      for (c = 0; c < 3u; ++c) {
        const double map = (cell->power[c] + cell->removed[c]) / cell->solid_angle;
        error += cell->solid_angle * (model[c] - map) * (model[c] - map);
        norm += cell->solid_angle * map * map;
      }
    }
  }
  return norm > 0.0 ? sqrt(error / norm) : 0.0;
}

/* |sum of the written lobes' power - the map's| / the map's (0 for a black map). */
static double power_error(const light_fit* fit, const prt_cloth_lobe* lobes, uint32_t count) {
  double map = 0.0, fitted = 0.0;
  size_t k;
  uint32_t c;
  for (k = 0; k < (size_t)fit->rows * fit->cols; ++k)
    for (c = 0; c < 3u; ++c) map += fit->cells[k].power[c] + fit->cells[k].removed[c];
  for (k = 0; k < count; ++k)
    for (c = 0; c < 3u; ++c) fitted += (double)lobes[k].rgb[c] * lobe_integral(lobes[k].sharpness);
  return map > 0.0 ? fabs(fitted - map) / map : 0.0;
}

/* The lobes in float, axes turned into the world by the env's rotation; the unused ones black,
 * pointing up, of the smallest sharpness. */
static void write_lobes(const light_fit* fit, uint32_t count, prt_cloth_lobe* out) {
  const float* r = fit->env.rotation;
  uint32_t k, c;
  for (k = 0; k < fit->lobes; ++k) {
    prt_cloth_lobe* lobe = &out[k];
    if (k < count) {
      const fit_lobe* f = &fit->fitted[k];
      double axis[3], length;
      for (c = 0; c < 3u; ++c)
        axis[c] =
            r ? r[3u * c] * f->axis[0] + r[3u * c + 1u] * f->axis[1] + r[3u * c + 2u] * f->axis[2]
              : f->axis[c];
      length = sqrt(dot3(axis, axis));
      for (c = 0; c < 3u; ++c) {
        lobe->axis[c] = (float)(axis[c] / length);
        lobe->rgb[c] = (float)f->rgb[c];
      }
      lobe->sharpness = (float)f->sharpness;
    } else {
      lobe->axis[0] = 0.0f, lobe->axis[1] = 1.0f, lobe->axis[2] = 0.0f;
      lobe->sharpness = PRT_CLOTH_MIN_SHARPNESS;
      lobe->rgb[0] = lobe->rgb[1] = lobe->rgb[2] = 0.0f;
    }
  }
}

/* The fit once the scratch is in place: grid, compact sources, clusters, lobes, report. */
static prt_result run_fit(light_fit* fit, const prt_allocator* allocator, prt_cloth_lobe* out_lobes,
                          prt_cloth_fit_report* report) {
  uint32_t count, k;
  int compact;
  build_grid(fit);
  compact = take_compact_sources(fit, allocator);
  if (compact < 0) return PRT_ERROR_OUT_OF_MEMORY;
  count = (uint32_t)compact + cluster_grid(fit, (uint32_t)compact, fit->lobes - (uint32_t)compact);
  for (k = 0; k < count; ++k) lobe_of_group(&fit->groups[k], &fit->fitted[k]);
  write_lobes(fit, count, out_lobes);
  if (report) {
    report->lobe_count = count;
    report->relative_error = (float)relative_error(fit, fit->fitted, count);
    report->power_error = (float)power_error(fit, out_lobes, count);
  }
  return PRT_OK;
}

prt_result prt_cloth_fit_light(prt_context* context, const prt_env_image* env,
                               const prt_cloth_fit_desc* desc, prt_cloth_lobe* out_lobes,
                               prt_cloth_fit_report* report) {
  prt_cloth_fit_desc d;
  prt_cloth_fit_report full;
  light_fit fit;
  scratch_plan plan;
  unsigned char* scratch;
  prt_result result;
  if (!context) return PRT_ERROR_INVALID_ARGUMENT;
  if (!env || !desc || !out_lobes ||
      !prt_internal_struct_size_ok(desc, PRT_CLOTH_FIT_DESC_SIZE_1_0) ||
      (report && !prt_internal_struct_size_ok(report, PRT_CLOTH_FIT_REPORT_SIZE_1_0)))
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_cloth_fit_light: NULL env, desc or out_lobes, or a struct_size "
                             "below 1.0's");
  memset(&d, 0, sizeof d);
  memcpy(&d, desc, desc->struct_size < sizeof d ? desc->struct_size : sizeof d);
  memset(&fit, 0, sizeof fit);
  fit.lobes = d.lobe_count ? d.lobe_count : DEFAULT_LOBES;
  fit.iterations = d.iterations ? d.iterations : DEFAULT_ITERATIONS;
  if (fit.lobes > PRT_CLOTH_MAX_LOBES)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_cloth_fit_light: lobe_count %u is above %u", d.lobe_count,
                             PRT_CLOTH_MAX_LOBES);
  if (prt_internal_env_open(env, &fit.env) != PRT_OK)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_cloth_fit_light: env rejected by prt_env_image_validate");
  choose_grid(&fit, d.resolution ? d.resolution : DEFAULT_RESOLUTION);
  scratch = plan_scratch(&fit, &plan)
                ? (unsigned char*)prt_internal_alloc(&context->allocator, plan.total, 64u)
                : NULL;
  if (!scratch)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY,
                             "prt_cloth_fit_light: out of memory");
  place_scratch(&fit, &plan, scratch);
  memset(&full, 0, sizeof full);
  full.struct_size = sizeof full;
  result = run_fit(&fit, &context->allocator, out_lobes, report ? &full : NULL);
  prt_internal_free(&context->allocator, scratch, plan.total);
  if (result != PRT_OK)
    return prt_internal_fail(context, result, "prt_cloth_fit_light: out of memory");
  if (report) prt_internal_write_struct(report, &full, sizeof full);
  return PRT_OK;
}
