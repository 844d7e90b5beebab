/* SPDX-License-Identifier: MIT */
/* Private to the runtime: technique `shadowfield`'s scene (prt/prt_shadowfield.h) and the
 * evaluation of docs/shadowfield/design.md, "At run time" (shadowfield_eval.c). */
#ifndef PRT_RUNTIME_SHADOWFIELD_SCENE_H
#define PRT_RUNTIME_SHADOWFIELD_SCENE_H

#include <stddef.h>

#include <prt/prt.h>

#include "shadowfield_gaunt.h"
#include "shadowfield_kernels.h"
#include "shadowfield_log.h"
#include "shadowfield_object.h"

#define PRT_SF_MAX_COEFFS (PRT_SF_GAUNT_MAX_ORDER * PRT_SF_GAUNT_MAX_ORDER)
/* An SH rotation up to order 6 as its band blocks: sum over l < 6 of (2l + 1)^2. */
#define PRT_SF_ROTATION_FLOATS 286u
/* The same with each block's columns padded with zeros to a multiple of 8 floats: sum over
 * l < 6 of (2l + 1) x 8 ceil((2l + 1) / 8). */
#define PRT_SF_PADDED_ROTATION_FLOATS 448u
#define PRT_SF_PASSES (PRT_SHADOWFIELD_MAX_BOUNCES + 1u)
/* prt_shadowfield_settings as 1.0 had it, and as far as bounce_probe_spacing reaches. */
#define PRT_SF_SETTINGS_1_0_SIZE offsetof(prt_shadowfield_settings, bounce_probe_spacing)
#define PRT_SF_SETTINGS_PROBES_SIZE \
  (offsetof(prt_shadowfield_settings, bounce_probe_spacing) + sizeof(float))
/* The most BRDF terms an object may have (the baker's default is 4). */
#define PRT_SF_MAX_TERMS 64u

/* A lookup of prt_sf_locate in compact form: the corner of the first of its 4 or 8 grid points
 * and the fractions its weights are made of. */
typedef struct prt_sf_cell {
  uint32_t first; /* grid point of (shell, face, i, j) */
  uint32_t count; /* 0, 4 or 8, as prt_sf_lookup::count */
  float shell_frac, fi, fj;
} prt_sf_cell;

/* log(outer / inner) of a grid, as prt_sf_locate takes it. */
double prt_sf_log_span(const prt_sf_shells* grid);
/* prt_sf_locate(grid, p) in compact form (log_span from prt_sf_log_span); prt_sf_cell_lookup
 * rebuilds its lookup bitwise (but for `inside`, which it leaves 0). Grids of fewer than 2^32
 * points (the format's limits keep them far below). */
void prt_sf_cell_locate(const prt_sf_shells* grid, double log_span, const float p[3],
                        prt_sf_cell* out);
void prt_sf_cell_lookup(const prt_sf_shells* grid, const prt_sf_cell* cell, prt_sf_lookup* out);
/* Whether two grids have one centre, radius and inner shell (an object's OOF and SRF usually
 * do), so that a point's distance and log radius serve both. */
int prt_sf_shells_share_sphere(const prt_sf_shells* a, const prt_sf_shells* b);
/* prt_sf_cell_locate in grids a and b that share their sphere, with one square root and at most
 * one logarithm. */
void prt_sf_cell_locate_two(const prt_sf_shells* a, double log_span_a, const prt_sf_shells* b,
                            double log_span_b, const float p[3], prt_sf_cell* out_a,
                            prt_sf_cell* out_b);

/* Receiver instance i and another instance j that affects it. */
typedef struct prt_sf_pair {
  uint32_t other;
  uint32_t occludes; /* within j's OOF: j shadows i */
  uint32_t lights;   /* within j's SRF and j has a basis: j lights i */
  /* prt_sf_log_span of j's OOF and SRF grids, and whether they share their sphere
   * (prt_sf_shells_share_sphere) when both are read. */
  double oof_log_span, srf_log_span;
  uint32_t fields_share_sphere;
  float to_other[9]; /* row-major: i's local frame to j's, p = to_other x + offset */
  float offset[3];
  /* SH rotation from j's frame to i's (R_i^T R_j), band blocks row-major. */
  float sh_rotation[PRT_SF_ROTATION_FLOATS];
  /* The same band blocks column-major (each block's [b width + a] = row a, column b), for the
   * SIMD kernels. */
  float sh_rotation_columns[PRT_SF_ROTATION_FLOATS];
  /* For the SIMD kernels: the columns padded (column b of band l at [b pad(2l + 1) + a]) of the
   * rotation and of its inverse (the transpose), so whole vectors load without masks. */
  float padded_columns[PRT_SF_PADDED_ROTATION_FLOATS];
  float padded_columns_back[PRT_SF_PADDED_ROTATION_FLOATS];
} prt_sf_pair;

/* An object's bounce probes at one spacing (shadowfield_probes.c): the corners of the grid cells
 * its vertices fall in (those some vertex weighs above 0), and each vertex's trilinear lookup of
 * them. */
typedef struct prt_sf_probes {
  float spacing;          /* what the layout was made for; 0: none */
  uint32_t count;         /* probes; 0 when the object gathers per vertex at this spacing */
  float* positions;       /* count x 3, in the object's frame */
  prt_sf_lookup* lookups; /* one per vertex (count 1..8, the probes' indices and weights) */
  uint32_t lookup_count;  /* the object's vertices, kept so that freeing reads no object */
} prt_sf_probes;

typedef struct prt_sf_instance {
  uint32_t object;
  float rotation[9]; /* row-major, orthonormalised */
  float translation[3];
  float scale;
  /* L_k,c per pass: incident[((pass V + v) K + k) 3 + c]. */
  float* incident;
  size_t incident_floats;
  /* Basis weights w_ikc of the last projected pass ([(i K + k) 3 + c]), then as much scratch. */
  float* weights;
  size_t weights_floats;
  /* The source field of the last projected pass, sum_ik w_ikc SRF_ik(p), one plane per colour:
   * [(c points + p) n^2 + coef]; NULL when the object has no basis. */
  float* field;
  size_t field_floats;
  /* Per SRF point, 1 when some receiver's cell reads it this frame (needed_frame): the field is
   * cast at those points only. NULL when the object has no basis. */
  uint8_t* needed;
  size_t needed_bytes; /* kept so that destroying the scene reads no object */
  uint32_t needed_frame;

  /* The triple product with the frame's light as a matrix, one plane per colour:
   * [(c n^2 + k) n^2 + j] = sum_i C_ijk light_i,c, so that light x V = this . V. */
  float* light_product;
  size_t light_product_floats;

  /* The frame stamp of each vertex's row of cells (scene->cells), set by its direct pass: a row
   * is read by the bounces only when its stamp is the prepared frame's. */
  uint32_t* located;
  size_t located_bytes;

  /* Per frame (prepare). */
  float light[PRT_SF_MAX_COEFFS * 3u]; /* the environment in this instance's frame */
  uint32_t pair_first, pair_count;
  uint32_t is_source; /* some pair reads its field */
  /* Where this receiver's cells start in scene->cells: vertex v's row of pair_count cells (the
   * SRF lookup of each of its pairs) begins at cell_first + v pair_count. */
  size_t cell_first;
  /* A receiver of fewer terms than colours: where its transfer turned into each source's frame
   * starts in scene->turned (vertex v, pair q: turned_first + (v pair_count + q) terms n^2). */
  size_t turned_first;

  /* Bounce probes this frame (prt_sf_prepare_probes): their count (0: none), where their row
   * of cells starts in scene->probe_cells (probe p, pair q: probe_cell_first + p pair_count +
   * q), the frame stamp of each probe's row, and the light of the pass being gathered, one plane
   * per colour: [(c probe_count + p) n^2 + k]. */
  uint32_t probe_count;
  size_t probe_cell_first;
  uint32_t* probe_located;
  size_t probe_located_capacity; /* stamps */
  float* probe_light;
  size_t probe_light_capacity; /* floats */
} prt_sf_instance;

/* An object's log occlusion field (shadowfield_log.h), its size kept so that freeing it reads no
 * object. */
typedef struct prt_sf_log_field {
  float* values; /* OOF points x n^2, NULL when not computed */
  size_t floats;
} prt_sf_log_field;

struct prt_shadowfield_scene {
  prt_context* context;
  prt_allocator allocator;
  uint32_t max_instances;
  uint32_t order; /* 0 until the first object */
  uint32_t object_count, instance_count;
  const prt_sf_object** objects;
  prt_sf_instance* instances;
  prt_sf_gaunt gaunt;
  prt_sf_pair* pairs;
  uint32_t pair_count, pair_capacity;
  /* Each receiver vertex's SRF lookups in its pairs' sources, located once per frame by the
   * direct pass (they depend only on the placements) and read by every bounce. */
  prt_sf_cell* cells;
  size_t cell_capacity;
  /* Diffuse receivers' transfer turned into each source's frame (R^T T), by the direct pass
   * with the cells and read by every bounce. */
  float* turned;
  size_t turned_capacity;
  uint32_t frame; /* the prepared frame's stamp, never 0 */
  /* Each object's bounce probes (one per object slot), and the probes' rows of cells as
   * receivers (prt_sf_instance::probe_cell_first). */
  prt_sf_probes* probes;
  prt_sf_cell* probe_cells;
  size_t probe_cell_capacity;
  /* How blockers combine; with PRT_SHADOWFIELD_PRODUCT_LOG every object's log field (one per
   * object slot) and the exponential's rule (once the scene has an order). */
  prt_shadowfield_product product;
  prt_sf_log_field* log_fields;
  prt_sf_sphere_rule exp_rule;

  /* The prepared frame. */
  uint32_t prepared;
  uint32_t bounces;
  float eye[3];
  const prt_sf_kernels* kernels; /* the prepared backend's inner loops */
};

/* The test entry and what prt_shadowfield_scene_add_object calls: adds an object read in place
 * (it must outlive the scene). Records failures in the scene's context. */
prt_result prt_internal_sf_scene_add_object(prt_shadowfield_scene* scene,
                                            const prt_sf_object* object, uint32_t* out_object);

/* The log-space product's state for objects [0, objects) (shadowfield_scene_product.c): the
 * exponential's rule and each object's log field, built where missing. Records failures in the
 * scene's context. */
prt_result prt_sf_scene_build_log_fields(prt_shadowfield_scene* scene, uint32_t objects);
/* Frees every log field and the exponential's rule. */
void prt_sf_scene_free_log_fields(prt_shadowfield_scene* scene);

/* The frame's bounce probes (shadowfield_probes.c), after the pairs: each object's layout at
 * `spacing` (laid out again when it changed; freed at 0), and for every instance that has
 * probes this frame (bounces > 0 and some pair lights it) their count, buffers and cells.
 * Records failures in the scene's context. */
prt_result prt_sf_prepare_probes(prt_shadowfield_scene* scene, float spacing, uint32_t bounces);
/* Frees every layout and the probes' buffers and cells. */
void prt_sf_free_probes(prt_shadowfield_scene* scene);
/* Pass 0: locates probes [first, first + count) of `instance` in its sources' SRF grids;
 * a bounce: gathers their light from the sources' fields. */
void prt_sf_gather_probes_range(const prt_shadowfield_scene* scene, uint32_t pass,
                                uint32_t instance, uint32_t first, uint32_t count);
/* Vertex v's bounce light L_k (out[3 k + c]) interpolated from its instance's probes. */
void prt_sf_probed_light(const prt_shadowfield_scene* scene, const prt_sf_instance* receiver,
                         uint32_t v, const float* transfer, uint32_t terms, float* out);

/* Receiver point x in the other instance's frame of the pair. */
void prt_sf_point_in_other(const prt_sf_pair* pair, const float x[3], float p[3]);

/* Rotates `in` (order^2 coefficients x channels, coefficient-major) by band blocks. */
void prt_sf_rotate_apply(uint32_t order, const float* blocks, const float* in, float* out,
                         uint32_t channels);

/* The evaluation's steps on valid arguments (shadowfield_eval.c). */
void prt_sf_gather_range(const prt_shadowfield_scene* scene, uint32_t pass, uint32_t instance,
                         uint32_t first_vertex, uint32_t vertex_count);
void prt_sf_project_instance(const prt_shadowfield_scene* scene, uint32_t pass, uint32_t instance);
/* prt_sf_project_instance in two steps, the second split by SRF points: the basis weights, then
 * the field at points [first, first + count) of prt_sf_field_points (0 unless a source). */
void prt_sf_project_weights(const prt_shadowfield_scene* scene, uint32_t pass, uint32_t instance);
uint64_t prt_sf_field_points(const prt_shadowfield_scene* scene, uint32_t instance);
void prt_sf_cast_field(const prt_shadowfield_scene* scene, uint32_t instance, uint64_t first,
                       uint64_t count);
void prt_sf_output_range(const prt_shadowfield_scene* scene, uint32_t instance,
                         uint32_t through_pass, uint32_t first_vertex, uint32_t vertex_count,
                         float* out_rgb);

/* The concentric map of a direction (z >= 0 used; below is read at the horizon) to the square
 * [-1, 1]^2, as the baker's square_from_hemisphere. */
void prt_sf_square_from_hemisphere(const double direction[3], double* a, double* b);
/* Term k of the object's g table read bilinearly between cell centres at local direction wo,
 * as the baker's SeparableBrdf::outgoing_at. */
float prt_sf_outgoing_at(const prt_sf_object* object, uint32_t term, const double wo[3]);
/* The tangent frame of a unit normal (Duff et al. 2017, as the baker's Frame). */
void prt_sf_tangent_frame(const float n[3], float t[3], float b[3]);

#endif /* PRT_RUNTIME_SHADOWFIELD_SCENE_H */
