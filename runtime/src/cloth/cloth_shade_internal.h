/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the pieces of `cloth` shading (docs/cloth/method.md) that the scalar
 * reference (cloth_shade.c), the SIMD kernels and the GL shader's set-up share: the per-call
 * preparation of the light and the fabric, the table lookups (cloth_tables.c) and the integral of
 * one lobe against one fibre's scattering (cloth_integrals.c), in double. */
#ifndef PRT_RUNTIME_CLOTH_SHADE_INTERNAL_H
#define PRT_RUNTIME_CLOTH_SHADE_INTERNAL_H

#include "cloth_internal.h"

#define PRT_CLOTH_DEFAULT_WEAK_LOBE 1e-3
#define PRT_CLOTH_DEFAULT_THETA_SEGMENTS 2u
#define PRT_CLOTH_DEFAULT_PHI_NODES 3u
#define PRT_CLOTH_MAX_THETA_SEGMENTS 16u
#define PRT_CLOTH_MAX_PHI_NODES 8u
/* A lobe whose largest value over a sample's upper hemisphere is below this fraction of its peak
 * is skipped for that sample. */
#define PRT_CLOTH_HIDDEN_LOBE 1e-4

/* The settings in force (defaults filled in). */
typedef struct prt_cloth_method {
  uint32_t flags;
  double weak_lobe;
  uint32_t theta_segments;
  uint32_t phi_nodes;
} prt_cloth_method;

/* PRT_OK and the settings with defaults, or PRT_ERROR_INVALID_ARGUMENT for a bad struct_size,
 * an unknown flag, a weak_lobe outside [0, 1) or counts above the maxima. NULL: the defaults. */
prt_result prt_cloth_method_of(const prt_cloth_settings* settings, prt_cloth_method* out);

/* One lobe of the light, ready for shading. */
typedef struct prt_cloth_lobe_prep {
  double axis[3];
  double lambda;
  double rgb[3];
  double level; /* position among the asset's sharpness levels, clamped to [0, L-1] */
} prt_cloth_lobe_prep;

/* The light kept for a call: its lobes after the weak ones are dropped. `lobes` has room for
 * PRT_CLOTH_MAX_LOBES. */
typedef struct prt_cloth_light_prep {
  uint32_t count;
  prt_cloth_lobe_prep lobes[PRT_CLOTH_MAX_LOBES];
} prt_cloth_light_prep;

/* Drops lobes below method->weak_lobe of the total power (unless the method keeps them) and
 * places the rest among the view's sharpness levels. */
void prt_cloth_prepare_light(const prt_cloth_view* view, const prt_cloth_light* light,
                             const prt_cloth_method* method, prt_cloth_light_prep* out);

/* One distinct tangent of a fabric's thread, ready for shading. */
typedef struct prt_cloth_tangent_prep {
  int thread; /* 0 warp, 1 weft */
  double tau, sin_tau, cos_tau;
  double weight;               /* coverage of the thread x multiplicity */
  prt_cloth_factor cone, full; /* the table's factorisations */
  int mirror;
} prt_cloth_tangent_prep;

typedef struct prt_cloth_fabric_prep {
  prt_cloth_params params;
  uint32_t tangent_count;
  prt_cloth_tangent_prep tangents[2 * PRT_CLOTH_MAX_THREAD_TANGENTS];
} prt_cloth_fabric_prep;

void prt_cloth_prepare_fabric(const prt_cloth_view* view, uint32_t fabric,
                              const prt_cloth_params* params, prt_cloth_fabric_prep* out);

/* ---- Tables (cloth_tables.c) ----------------------------------------------------------------- */

/* A direction in a thread's canonical frame (x_j, y_j, n), after the tangent's mirror. */
void prt_cloth_canonical(const prt_cloth_frame* frame, int thread, int mirror, const double w[3],
                         double out[3]);

/* The view part of a factorisation at a canonical view direction (z >= 0): rank values, the
 * view scales folded in. `flip_y` is set when the view was mirrored to y >= 0 (the lobe must be
 * mirrored too). */
void prt_cloth_view_factor(const prt_cloth_view* view, const prt_cloth_factor* factor,
                           const double canonical_view[3], double* out);
/* The lobe part at a canonical lobe direction (any) and sharpness level. */
void prt_cloth_lobe_factor(const prt_cloth_view* view, const prt_cloth_factor* factor,
                           const double canonical_lobe[3], double level, double* out);
/* A table grid's coordinate of x in [0, 1] over n >= 2 nodes: the lower node and the weight of
 * the upper (x outside [0, 1] clamped). Every backend reads the tables' nodes by it. */
void prt_cloth_grid_cell(double x, uint32_t n, uint32_t* lower, double* frac);

/* ---- One lobe against one fibre (cloth_integrals.c) ------------------------------------------ */

/* A lobe and a view in a fibre's angles (docs/cloth/model.md), and the fibre's tilt. */
typedef struct prt_cloth_lobe_fibre {
  double lambda;
  double theta_k, phi_k; /* the lobe's axis */
  double theta_o, phi_o; /* the view */
  double sin_tau, cos_tau;
} prt_cloth_lobe_fibre;

/* The integrals over the cloth's upper hemisphere and the fibre's front of the lobe times the
 * three parts of f_s cos(theta_i): out[0] surface (F_r cos(phi_d/2) g(theta_h; gamma_s)),
 * out[1] volume lobe (F g(theta_h; gamma_v) / (cos theta_i + cos theta_o)), out[2] isotropic
 * volume (F / (cos theta_i + cos theta_o)), each over cos^2(theta_d); without the A, 1 - k_d
 * and k_d factors. */
void prt_cloth_lobe_integrals(const prt_cloth_lobe_fibre* lf, const prt_cloth_thread* thread,
                              const prt_cloth_method* method, double out[3]);

/* Schlick's approximation of paper 003's Eq. 13, F_0 + (1 - F_0) (1 - c)^5, at incidence cosine
 * c; with `cube` its binomial sum cut at l = 3, as printed (PRT_CLOTH_PAPER_SCHLICK_CUBE). */
double prt_cloth_fresnel_schlick(double eta, double c, int cube);

#endif /* PRT_RUNTIME_CLOTH_SHADE_INTERNAL_H */
