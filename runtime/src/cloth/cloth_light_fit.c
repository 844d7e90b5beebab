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
#include "cloth_light_internal.h"

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

/* ---- Small maths --------------------------------------------------------------------------- */

/* The smallest level (texel brightness) in bin b. */
static float level_floor(uint32_t bin) {
  const uint32_t bits = bin << PRT_CLOTH_LIGHT_LEVEL_SHIFT;
  float value;
  memcpy(&value, &bits, sizeof value);
  return value;
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

/* ---- Scratch ------------------------------------------------------------------------------- */

typedef struct scratch_plan {
  size_t total;
  size_t theta, phi, row_first, col_first, sin_phi, cos_phi, column_sums, cos_bounds, side_columns,
      edge_terms, row_max, cells, levels, points, groups, fitted, model, sub_rows, sub_cols;
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
  const size_t samples = PRT_CLOTH_LIGHT_CELL_SAMPLES;
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
         reserve(plan, &plan->levels, PRT_CLOTH_LIGHT_LEVEL_COUNT, sizeof(level_bin)) &&
         reserve(plan, &plan->points, cells, PRT_CLOTH_LIGHT_POINT_ARRAYS * sizeof(float)) &&
         reserve(plan, &plan->groups, fit->lobes, sizeof(power_group)) &&
         reserve(plan, &plan->fitted, fit->lobes, sizeof(fit_lobe)) &&
         reserve(plan, &plan->model, cells, 3u * sizeof(double)) &&
         reserve(plan, &plan->sub_rows, fit->rows, 3u * (samples + 1u) * sizeof(double)) &&
         reserve(plan, &plan->sub_cols, fit->cols, 2u * (samples + 1u) * sizeof(double));
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
  fit->groups = (power_group*)(void*)(base + plan->groups);
  fit->fitted = (fit_lobe*)(void*)(base + plan->fitted);
  fit->model = (double*)(void*)(base + plan->model);
  fit->sub_rows = (double*)(void*)(base + plan->sub_rows);
  fit->sub_cols = (double*)(void*)(base + plan->sub_cols);
  memset(base, 0, plan->total);
}

/* ---- Compact sources ----------------------------------------------------------------------- */

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
  if (prt_cloth_light_visit_bright(fit, contrast_floor, NULL, 0u) == 0u) return 0.0f;
  for (bin = PRT_CLOTH_LIGHT_LEVEL_COUNT; bin-- > prt_cloth_light_level_bin(contrast_floor);) {
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
      if (prt_cloth_light_dot(texel->direction, groups[g].seed) >= cos_radius) break;
    if (g == n) {
      if (n == MAX_COMPACT_GROUPS) continue; /* left in the grid */
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
  const double length = sqrt(prt_cloth_light_dot(g->resultant, g->resultant));
  double around = 0.0;
  size_t k;
  if (!(length > 0.0)) return 0;
  for (k = 0; k < (size_t)fit->rows * fit->cols; ++k) {
    const grid_cell* cell = &fit->cells[k];
    if (cell->weight > 0.0 &&
        prt_cloth_light_dot(cell->resultant, g->resultant) >=
            cos_radius * length * sqrt(prt_cloth_light_dot(cell->resultant, cell->resultant)))
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
  listed = prt_cloth_light_visit_bright(fit, floor, texels, count);
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
    const double length = sqrt(prt_cloth_light_dot(cell->resultant, cell->resultant));
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
    const double length = sqrt(prt_cloth_light_dot(clusters[k].resultant, clusters[k].resultant));
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
  const double length = sqrt(prt_cloth_light_dot(g->resultant, g->resultant));
  double scale;
  uint32_t c;
  out->sharpness = sharpness_of_resultant(length / g->weight);
  scale = 1.0 / prt_cloth_light_integral(out->sharpness);
  for (c = 0; c < 3u; ++c) {
    out->axis[c] = length > 0.0 ? g->resultant[c] / length : g->seed[c];
    out->rgb[c] = g->power[c] * scale;
    if (out->rgb[c] > FLT_MAX) out->rgb[c] = FLT_MAX;
  }
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
      length = sqrt(prt_cloth_light_dot(axis, axis));
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
  prt_cloth_light_build_grid(fit);
  compact = take_compact_sources(fit, allocator);
  if (compact < 0) return PRT_ERROR_OUT_OF_MEMORY;
  count = (uint32_t)compact + cluster_grid(fit, (uint32_t)compact, fit->lobes - (uint32_t)compact);
  for (k = 0; k < count; ++k) lobe_of_group(&fit->groups[k], &fit->fitted[k]);
  write_lobes(fit, count, out_lobes);
  if (report) {
    report->lobe_count = count;
    report->relative_error = (float)prt_cloth_light_relative_error(fit, fit->fitted, count);
    report->power_error = (float)prt_cloth_light_power_error(fit, out_lobes, count);
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
