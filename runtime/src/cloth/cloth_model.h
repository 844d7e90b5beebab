/* SPDX-License-Identifier: MIT */
/* Private to cloth's exact model (cloth_model.c) and the files that evaluate it many times for
 * one view (cloth_params.c, cloth_reference.c): everything of the kernel that depends on the
 * frame and the view alone, computed once, then the kernel or the weights for any light. The
 * kernel of cloth_internal.h goes through the same path, so the reference's one texel and the
 * kernel agree bitwise. */
#ifndef PRT_RUNTIME_CLOTH_MODEL_H
#define PRT_RUNTIME_CLOTH_MODEL_H

#include <float.h>

#include "cloth_internal.h"

/* One thread's live parameters in double, with its Gaussians written as
 * g(x; gamma) = norm exp(-x^2 scale). */
typedef struct prt_cloth_material {
  double coverage, eta, kd, albedo[3];
  double surface_scale, surface_norm;
  double volume_scale, volume_norm;
} prt_cloth_material;

void prt_cloth_material_of(const prt_cloth_thread* thread, prt_cloth_material* out);

/* A direction's angles in one fibre frame (docs/cloth/model.md, Angles), with the terms that
 * depend on it alone. A direction along t has no azimuth (phi = 0, m = 1), one along b no psi
 * (psi = 0, p = 1): the projections they are measured in vanish there. */
typedef struct prt_cloth_angles {
  double theta, cos_theta; /* elevation from the normal plane; cos_theta >= 0 */
  double phi, m;           /* azimuth about t from n'; m = max(cos phi, 0) */
  double psi, p;           /* angle from n' in the plane normal to b; p = max(cos psi, 0) */
} prt_cloth_angles;

/* One distinct offset of a thread, with the view's angles in its fibre frame. */
typedef struct prt_cloth_tangent_out {
  double cos_tau, sin_tau, multiplicity;
  prt_cloth_angles view;
} prt_cloth_tangent_out;

typedef struct prt_cloth_thread_out {
  double x[3], y[3]; /* the thread's canonical frame (x_j, y_j, n) */
  uint32_t count;
  prt_cloth_tangent_out tangents[PRT_CLOTH_MAX_THREAD_TANGENTS];
} prt_cloth_thread_out;

/* What the kernel needs of the frame, the weave and the view wo. */
typedef struct prt_cloth_outgoing {
  double n[3];
  int above; /* wo . n > 0; else the kernel is 0 for every light */
  prt_cloth_thread_out threads[2];
} prt_cloth_outgoing;

void prt_cloth_outgoing_of(const prt_cloth_weave* weave, const prt_cloth_frame* frame,
                           const double wo[3], prt_cloth_outgoing* out);

/* k(wi, wo) for a unit wi (RGB), 0 below the surface. */
void prt_cloth_outgoing_kernel(const prt_cloth_material materials[2],
                               const prt_cloth_outgoing* outgoing, const double wi[3],
                               double out_rgb[3]);

/* W of each distinct offset of thread j for a unit wi, all 0 below the surface. */
void prt_cloth_outgoing_weights(const prt_cloth_outgoing* outgoing, int thread, const double wi[3],
                                double* out_weights);

/* The unit vector along `in`; 0 for a zero or non-finite vector. */
int prt_cloth_unit_direction(const float in[3], double out[3]);

/* A kernel value as a float: one above FLT_MAX (a lobe far narrower than a float can resolve)
 * saturates instead of becoming infinite. */
static inline float prt_cloth_to_float(double value) {
  return value > (double)FLT_MAX ? FLT_MAX : (float)value;
}

#endif /* PRT_RUNTIME_CLOTH_MODEL_H */
