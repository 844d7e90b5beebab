/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the PSTR view the load keeps (pose_section.c) and the pose maths of
 * formats/SPEC.md §7.3 in double (pose_model.c) that every backend of pose_asset.c shares. */
#ifndef PRT_RUNTIME_POSE_INTERNAL_H
#define PRT_RUNTIME_POSE_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include <prt/format/pose_layout.h>

#include "internal.h"

#define PRT_POSE_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_pose_info, model_bytes)
#define PRT_POSE_INPUT_SIZE_1_0 PRT_SIZE_THROUGH(prt_pose_input, joint_scales)
#define PRT_POSE_LIGHT_SIZE_1_0 PRT_SIZE_THROUGH(prt_pose_light, normals)

#define PRT_POSE_MAX_JOINTS PRT_BLOB_PSTR_MAX_JOINTS
#define PRT_POSE_MAX_FEATURES (3u * PRT_BLOB_PSTR_MAX_JOINTS)
#define PRT_POSE_MAX_BASIS_DIMS PRT_BLOB_PSTR_MAX_BASIS_DIMS
#define PRT_POSE_MAX_COEFFICIENTS (PRT_BLOB_PSTR_MAX_ORDER * PRT_BLOB_PSTR_MAX_ORDER)

/* The PSTR section of a loaded asset, its header, size, parents and evaluation order checked at
 * load (pose_section.c): every read at the layout's offsets stays inside the section, and the
 * evaluation order visits each joint once, after its parent, whatever the validation level. */
typedef struct prt_pose_view {
  prt_pose_info info;
  prt_blob_pstr_layout layout;
  const uint8_t* data; /* the section's layout.raw_size bytes */
} prt_pose_view;

/* A 3x4 affine transform [R | t], row-major. */
typedef struct prt_pose_affine {
  double m[3][4];
} prt_pose_affine;

/* Every joint's skinning matrix K_j = M^-1 G_j inverse_bind_j and the model frame M. */
typedef struct prt_pose_skeleton {
  prt_pose_affine skin[PRT_POSE_MAX_JOINTS];
  prt_pose_affine model_frame;
} prt_pose_skeleton;

/* A double as float, rounded to nearest, overflowing to an infinity rather than to the undefined
 * behaviour of a C conversion out of range (quick validation leaves floats unchecked). */
static inline float prt_pose_to_float(double x) {
  if (x >= 0x1.ffffffp127) return INFINITY;
  if (x <= -0x1.ffffffp127) return -INFINITY;
  return (float)x;
}

/* The f32 at byte `offset` of the section. */
static inline double prt_pose_f32(const prt_pose_view* view, uint64_t offset) {
  return (double)prt_blob_pstr_load_f32(view->data + offset);
}

/* PRT_OK when `pose` is a usable input of this asset: struct_size, joint rotations given, each
 * finite and of non-zero length; PRT_ERROR_INVALID_ARGUMENT otherwise. */
prt_result prt_pose_check_input(const prt_pose_view* view, const prt_pose_input* pose);

/* The pose features a (3 J) of a checked pose (SPEC §7.3 "Features"). */
void prt_pose_features_d(const prt_pose_view* view, const prt_pose_input* pose, double* features);

/* The pose coordinates z (p) of the features, clamped when the asset says so. */
void prt_pose_coordinates_d(const prt_pose_view* view, const double* features, double* z);

/* y[k][c] for c in [first, first + count) of basis column k at coordinates z. */
void prt_pose_coefficients_d(const prt_pose_view* view, const double* z, uint32_t k, uint32_t first,
                             uint32_t count, double* out);

/* The skinning matrices and the model frame of a checked pose (SPEC §7.3 "Skeleton"). */
void prt_pose_skeleton_of(const prt_pose_view* view, const prt_pose_input* pose,
                          prt_pose_skeleton* out);

/* The skinned position and normal of vertex v in the model frame (SPEC §7.3 "Skin"); either
 * output may be NULL. The normal is 0 where K's 3x3 part is singular or maps it to zero. */
void prt_pose_skin_vertex(const prt_pose_view* view, const prt_pose_skeleton* skeleton, uint32_t v,
                          double* position, double* normal);

/* The exact part's factors rho A_l / pi by coefficient (SPEC §7.3, model 1), C of them. */
void prt_pose_exact_factors(const prt_pose_view* view, double* factor);

/* The SH basis (C values) at a model-frame normal, or 0 when it is zero or not finite. */
void prt_pose_basis_at_normal(uint32_t order, const double normal[3], double* out);

/* The per-frame part of a shading call, for a backend that runs the vertex loop elsewhere
 * (pose_gl.c): the skeleton (K_j, model frame), the folded weights w_k[ch] = sum_c y[k][c]
 * L'[c][ch] and, for model 1, exact[c][ch] = factor_c L'[c][ch], with L' the light rotated into
 * the model frame. */
/* The learned part's t_00 of a pose, base + sum_k weight[k] value[v][k], and the bounds SPEC
 * §7.3 clamps it to: [0, u] for model 0, [-u, 0] for model 1 (t_00 = u + it where the normal is
 * not 0), u = albedo / (2 sqrt(pi)) the unoccluded t_00. */
typedef struct prt_pose_dc {
  double base, weight[PRT_POSE_MAX_BASIS_DIMS];
  double lo, hi;
} prt_pose_dc;

/* The learned t_00's clamp and coefficients at pose coordinates z. */
void prt_pose_dc_of(const prt_pose_view* view, const double* z, prt_pose_dc* out);

/* What clamping adds to vertex v's learned t_00 (0 inside the bounds). */
double prt_pose_dc_correction(const prt_pose_view* view, const prt_pose_dc* dc, uint32_t v);

typedef struct prt_pose_folded {
  prt_pose_skeleton skeleton;
  double weight[PRT_POSE_MAX_BASIS_DIMS][3];
  double exact[PRT_POSE_MAX_COEFFICIENTS][3];
  prt_pose_dc dc;
  double light_dc[3]; /* L_00 per channel: what a unit of t_00 adds to the radiance */
} prt_pose_folded;

/* Fills `out` for a checked pose and a light with light_rgb given (pose_asset.c, the scalar
 * backend's own code): PRT_OK, or PRT_ERROR_INVALID_ARGUMENT when the world placement is not a
 * rotation. */
prt_result prt_pose_fold_shading(const prt_pose_view* view, const prt_pose_input* pose,
                                 const prt_pose_light* light, prt_pose_folded* out);

#endif /* PRT_RUNTIME_POSE_INTERNAL_H */
