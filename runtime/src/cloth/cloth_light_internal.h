/* SPDX-License-Identifier: MIT */
/* Private to the SG light fit (prt_cloth_fit_light): the state its three files share. The fit
 * (cloth_light_fit.c) plans the scratch and runs the steps; the grid (cloth_light_grid.c) averages
 * the map onto a lat-long grid and walks its brightest texels; the report (cloth_light_report.c)
 * measures the lobes against the grid. Everything is in the image's frame. */
#ifndef PRT_RUNTIME_CLOTH_LIGHT_INTERNAL_H
#define PRT_RUNTIME_CLOTH_LIGHT_INTERNAL_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "cloth_internal.h"
#include "env_internal.h"
#include "sphere_internal.h"

/* At most this many midpoint samples per axis when the report integrates a sharp lobe. */
#define PRT_CLOTH_LIGHT_CELL_SAMPLES 16u

typedef struct grid_cell {
  double power[3];     /* sum of radiance x solid angle, RGB */
  double weight;       /* the sum of power's channels: what directions are weighted by */
  double resultant[3]; /* sum of weight x direction over the cell's texels */
  double solid_angle;  /* of the texels that landed in the cell */
  double removed[3];   /* power taken out for compact sources (the map's is power + removed) */
} grid_cell;

/* A histogram bin of texel levels: the solid angle and count of its texels. */
typedef struct level_bin {
  double solid_angle;
  uint32_t texels;
} level_bin;

/* A texel of a compact-source candidate. */
typedef struct bright_texel {
  float level;  /* r + g + b radiance */
  size_t order; /* its place in the walk: ties of level are broken by it */
  uint32_t cell;
  uint32_t group; /* its compact-source group, or the group cap: none */
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
#define PRT_CLOTH_LIGHT_POINT_ARRAYS 8u /* x, y, z, weight, best, cell, nearest, assignment */

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
  level_bin* levels;      /* PRT_CLOTH_LIGHT_LEVEL_COUNT */
  cluster_points points;  /* up to rows x cols */
  power_group* groups;    /* lobes: the compact sources, then the clusters */
  fit_lobe* fitted;       /* lobes */
  double* model;          /* report: rows x cols x 3, the lobes' mean radiance per cell */
  double* sub_rows;       /* report: rows x (CELL_SAMPLES + 1) x 3: each sub-row's (then the
                             row's) sin and cos of its centre and cos t0 - cos t1 */
  double* sub_cols;       /* report: cols x (CELL_SAMPLES + 1) x 2: sin and cos of each
                             sub-column's (then the column's) centre */
  double total_weight;
  double total_solid_angle;
} light_fit;

/* A channel value as the fit uses it: NaN, infinities and negatives count as 0 (NaN fails both
 * compares; in the grid loop they become masks, not branches). */
static inline float prt_cloth_light_sanitised(float value) {
  return ((value > 0.0f) & (value <= FLT_MAX)) ? value : 0.0f;
}

static inline double prt_cloth_light_dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The integral of exp(l (w . axis - 1)) over the sphere. */
static inline double prt_cloth_light_integral(double l) {
  return 2.0 * PRT_SPHERE_PI / l * (1.0 - exp(-2.0 * l));
}

/* cloth_light_grid.c: the grid of fit->env (cells, row_max, totals), its bounds set up first. */
void prt_cloth_light_build_grid(light_fit* fit);

/* Visits every texel whose level (r + g + b) is at least `floor`, skipping image rows that
 * cannot hold one. Without out, counts it in fit->levels[prt_cloth_light_level_bin(level)]
 * (with a rough solid angle); with out, appends it there (up to capacity) with its power,
 * direction and grid cell as the grid has them. Returns the texels visited. */
uint32_t prt_cloth_light_visit_bright(light_fit* fit, float floor, bright_texel* out,
                                      uint32_t capacity);

/* Histogram bins of texel levels: a positive float's bits >> 20 (exponent and 3 mantissa bits:
 * eighths of an octave), so the histogram needs no logarithm. */
#define PRT_CLOTH_LIGHT_LEVEL_SHIFT 20u
#define PRT_CLOTH_LIGHT_LEVEL_COUNT 2048u
static inline uint32_t prt_cloth_light_level_bin(float level) {
  uint32_t bits;
  if (!(level <= FLT_MAX)) return PRT_CLOTH_LIGHT_LEVEL_COUNT - 1u;
  memcpy(&bits, &level, sizeof bits);
  return bits >> PRT_CLOTH_LIGHT_LEVEL_SHIFT;
}

/* cloth_light_report.c: the report's relative error (prt_cloth_fit_report) of `count` lobes and
 * the power error of the written lobes. */
double prt_cloth_light_relative_error(light_fit* fit, const fit_lobe* lobes, uint32_t count);
double prt_cloth_light_power_error(const light_fit* fit, const prt_cloth_lobe* lobes,
                                   uint32_t count);

#endif /* PRT_RUNTIME_CLOTH_LIGHT_INTERNAL_H */
