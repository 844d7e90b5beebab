/* SPDX-License-Identifier: MIT */
/* The pose maths of formats/SPEC.md §7.3 in double: features of the joint rotations, pose
 * coordinates and model coefficients, the skeleton's transforms, the model frame and the skin.
 * Reads only the section through the view (pose_internal.h); no allocation. */
#include <math.h>

#include "../sh/sh_internal.h"
#include "pose_internal.h"

static const uint8_t* joint_record(const prt_pose_view* view, uint32_t j) {
  return view->data + view->layout.joints + (uint64_t)PRT_BLOB_PSTR_JOINT_SIZE * j;
}

static double record_f32(const uint8_t* record, uint32_t offset) {
  return (double)prt_blob_pstr_load_f32(record + offset);
}

/* Joint j's rotation, normalised; 0 when it is zero or not finite. */
static int unit_rotation(const prt_pose_input* pose, uint32_t j, double q[4]) {
  const float* in = pose->joint_rotations + 4u * (size_t)j;
  double len2 = 0.0;
  int i;
  for (i = 0; i < 4; ++i) {
    q[i] = in[i];
    len2 += q[i] * q[i];
  }
  if (!(len2 > 0.0) || !isfinite(len2)) return 0;
  for (i = 0; i < 4; ++i) q[i] /= sqrt(len2);
  return 1;
}

prt_result prt_pose_check_input(const prt_pose_view* view, const prt_pose_input* pose) {
  double q[4];
  uint32_t j;
  if (!pose || !prt_internal_struct_size_ok(pose, PRT_POSE_INPUT_SIZE_1_0) ||
      !pose->joint_rotations)
    return PRT_ERROR_INVALID_ARGUMENT;
  for (j = 0; j < view->info.joint_count; ++j)
    if (!unit_rotation(pose, j, q)) return PRT_ERROR_INVALID_ARGUMENT;
  return PRT_OK;
}

void prt_pose_features_d(const prt_pose_view* view, const prt_pose_input* pose, double* features) {
  uint32_t j;
  for (j = 0; j < view->info.joint_count; ++j) {
    const uint8_t* record = joint_record(view, j);
    double q[4], b[4], r[4], len;
    int i;
    features[3u * j] = features[3u * j + 1u] = features[3u * j + 2u] = 0.0;
    if (j == view->info.model_joint || !unit_rotation(pose, j, q)) continue;
    for (i = 0; i < 4; ++i)
      b[i] = record_f32(record, PRT_BLOB_PSTR_JOINT_OFF_BIND_ROTATION + 4u * i);
    /* r = conj(b) (x) q, Hamilton: w = bw qw + b.q, v = bw qv - qw bv - bv x qv. */
    r[3] = b[3] * q[3] + b[0] * q[0] + b[1] * q[1] + b[2] * q[2];
    r[0] = b[3] * q[0] - q[3] * b[0] - (b[1] * q[2] - b[2] * q[1]);
    r[1] = b[3] * q[1] - q[3] * b[1] - (b[2] * q[0] - b[0] * q[2]);
    r[2] = b[3] * q[2] - q[3] * b[2] - (b[0] * q[1] - b[1] * q[0]);
    if (r[3] < 0.0)
      for (i = 0; i < 4; ++i) r[i] = -r[i];
    len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (i = 0; i < 3; ++i)
      features[3u * j + i] = len > 0.0 ? 2.0 * atan2(len, r[3]) * r[i] / len : 2.0 * r[i];
  }
}

void prt_pose_coordinates_d(const prt_pose_view* view, const double* features, double* z) {
  const prt_blob_pstr_layout* l = &view->layout;
  const uint32_t p = view->info.pose_dims;
  uint32_t i, f;
  for (i = 0; i < p; ++i) z[i] = 0.0;
  for (f = 0; f < l->features; ++f) {
    const double centred = features[f] - prt_pose_f32(view, l->pose_mean + 4u * f);
    const uint64_t row = l->pose_basis + 4u * (uint64_t)f * p;
    for (i = 0; i < p; ++i) z[i] += prt_pose_f32(view, row + 4u * i) * centred;
  }
  if (!view->info.clamps_pose) return;
  for (i = 0; i < p; ++i) {
    const double lo = prt_pose_f32(view, l->pose_range + 8u * i);
    const double hi = prt_pose_f32(view, l->pose_range + 8u * i + 4u);
    if (z[i] < lo) z[i] = lo;
    if (z[i] > hi) z[i] = hi;
  }
}

void prt_pose_coefficients_d(const prt_pose_view* view, const double* z, uint32_t k, uint32_t first,
                             uint32_t count, double* out) {
  const prt_blob_pstr_layout* l = &view->layout;
  const uint64_t row_bytes = 4u * (uint64_t)view->info.basis_dims * l->coefficients;
  const uint64_t base = l->regression + 4u * ((uint64_t)k * l->coefficients + first);
  uint32_t i, c;
  for (c = 0; c < count; ++c) out[c] = prt_pose_f32(view, base + 4u * c);
  for (i = 0; i < view->info.pose_dims; ++i) {
    const uint64_t row = base + row_bytes * (i + 1u);
    for (c = 0; c < count; ++c) out[c] += z[i] * prt_pose_f32(view, row + 4u * c);
  }
}

/* a * b of affine transforms (out may not alias either). */
static void affine_mul(const prt_pose_affine* a, const prt_pose_affine* b, prt_pose_affine* out) {
  int r, c;
  for (r = 0; r < 3; ++r)
    for (c = 0; c < 4; ++c)
      out->m[r][c] = a->m[r][0] * b->m[0][c] + a->m[r][1] * b->m[1][c] + a->m[r][2] * b->m[2][c] +
                     (c == 3 ? a->m[r][3] : 0.0);
}

static void load_affine(const uint8_t* record, uint32_t offset, prt_pose_affine* out) {
  int r, c;
  for (r = 0; r < 3; ++r)
    for (c = 0; c < 4; ++c) out->m[r][c] = record_f32(record, offset + 4u * (4u * r + c));
}

/* L_j = T(t) R(q) S(s), with the caller's translation and scale or the rest values. */
static void local_transform(const prt_pose_input* pose, const uint8_t* record, uint32_t j,
                            prt_pose_affine* out) {
  double q[4] = {0.0, 0.0, 0.0, 1.0}, t[3], s[3], rot[3][3];
  int i, c;
  unit_rotation(pose, j, q); /* checked by the caller; the identity stays otherwise */
  for (i = 0; i < 3; ++i) {
    t[i] = pose->joint_translations
               ? pose->joint_translations[3u * (size_t)j + i]
               : record_f32(record, PRT_BLOB_PSTR_JOINT_OFF_TRANSLATION + 4u * i);
    s[i] = pose->joint_scales ? pose->joint_scales[3u * (size_t)j + i]
                              : record_f32(record, PRT_BLOB_PSTR_JOINT_OFF_SCALE + 4u * i);
  }
  rot[0][0] = 1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]);
  rot[0][1] = 2.0 * (q[0] * q[1] - q[2] * q[3]);
  rot[0][2] = 2.0 * (q[0] * q[2] + q[1] * q[3]);
  rot[1][0] = 2.0 * (q[0] * q[1] + q[2] * q[3]);
  rot[1][1] = 1.0 - 2.0 * (q[0] * q[0] + q[2] * q[2]);
  rot[1][2] = 2.0 * (q[1] * q[2] - q[0] * q[3]);
  rot[2][0] = 2.0 * (q[0] * q[2] - q[1] * q[3]);
  rot[2][1] = 2.0 * (q[1] * q[2] + q[0] * q[3]);
  rot[2][2] = 1.0 - 2.0 * (q[0] * q[0] + q[1] * q[1]);
  for (i = 0; i < 3; ++i) {
    for (c = 0; c < 3; ++c) out->m[i][c] = rot[i][c] * s[c];
    out->m[i][3] = t[i];
  }
}

static double norm3(const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* M = [R_m | o_m]: R_m the Gram-Schmidt rotation of G_m's 3x3 part (x = first column, y = the
 * second made orthogonal, z = x cross y). A degenerate part keeps the identity's axes. */
static void model_frame_of(const prt_pose_affine* g, prt_pose_affine* out) {
  double x[3], y[3], z[3], len, dot;
  int i;
  for (i = 0; i < 3; ++i) {
    x[i] = g->m[i][0];
    y[i] = g->m[i][1];
  }
  len = norm3(x);
  if (!(len > 0.0) || !isfinite(len)) {
    x[0] = 1.0, x[1] = 0.0, x[2] = 0.0;
  } else {
    for (i = 0; i < 3; ++i) x[i] /= len;
  }
  dot = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  for (i = 0; i < 3; ++i) y[i] -= dot * x[i];
  len = norm3(y);
  if (!(len > 0.0) || !isfinite(len)) { /* any unit vector orthogonal to x */
    const int a = fabs(x[0]) < 0.9 ? 0 : 1;
    double e[3] = {0.0, 0.0, 0.0};
    e[a] = 1.0;
    dot = x[a];
    for (i = 0; i < 3; ++i) y[i] = e[i] - dot * x[i];
    len = norm3(y);
  }
  for (i = 0; i < 3; ++i) y[i] /= len;
  z[0] = x[1] * y[2] - x[2] * y[1];
  z[1] = x[2] * y[0] - x[0] * y[2];
  z[2] = x[0] * y[1] - x[1] * y[0];
  for (i = 0; i < 3; ++i) {
    out->m[i][0] = x[i];
    out->m[i][1] = y[i];
    out->m[i][2] = z[i];
    out->m[i][3] = g->m[i][3];
  }
}

/* [R^T | -R^T t] of a rigid transform. */
static void rigid_inverse(const prt_pose_affine* a, prt_pose_affine* out) {
  int r, c;
  for (r = 0; r < 3; ++r) {
    for (c = 0; c < 3; ++c) out->m[r][c] = a->m[c][r];
    out->m[r][3] = -(a->m[0][r] * a->m[0][3] + a->m[1][r] * a->m[1][3] + a->m[2][r] * a->m[2][3]);
  }
}

void prt_pose_skeleton_of(const prt_pose_view* view, const prt_pose_input* pose,
                          prt_pose_skeleton* out) {
  const uint32_t joints = view->info.joint_count;
  prt_pose_affine local, pre_local, model_inverse, global_bind;
  uint32_t i;
  /* First the joints' transforms G_j in out->skin, in the evaluation order checked at load. */
  for (i = 0; i < joints; ++i) {
    const uint32_t j = prt_le_load_u32(view->data + view->layout.eval_order + 4u * i);
    const uint8_t* record = joint_record(view, j);
    const int32_t parent = (int32_t)prt_le_load_u32(record + PRT_BLOB_PSTR_JOINT_OFF_PARENT);
    prt_pose_affine pre;
    load_affine(record, PRT_BLOB_PSTR_JOINT_OFF_PRE, &pre);
    local_transform(pose, record, j, &local);
    if (parent < 0) {
      affine_mul(&pre, &local, &out->skin[j]);
    } else {
      affine_mul(&pre, &local, &pre_local);
      affine_mul(&out->skin[parent], &pre_local, &out->skin[j]);
    }
  }
  model_frame_of(&out->skin[view->info.model_joint], &out->model_frame);
  rigid_inverse(&out->model_frame, &model_inverse);
  /* Then K_j = M^-1 G_j inverse_bind_j. */
  for (i = 0; i < joints; ++i) {
    prt_pose_affine inverse_bind;
    load_affine(joint_record(view, i), PRT_BLOB_PSTR_JOINT_OFF_INVERSE_BIND, &inverse_bind);
    affine_mul(&out->skin[i], &inverse_bind, &global_bind);
    affine_mul(&model_inverse, &global_bind, &out->skin[i]);
  }
}

/* K = sum_k (w_k / sum w) K_joint_k over the weights > 0 of joints below J (an index >= J, only
 * possible at quick validation, counts as weight 0); the identity when no weight is left. */
static void vertex_matrix(const prt_pose_view* view, const prt_pose_skeleton* skeleton,
                          const uint8_t* skin, prt_pose_affine* out) {
  double weight[4], total = 0.0;
  int k, r, c;
  for (k = 0; k < 4; ++k) {
    const uint32_t joint = skin[PRT_BLOB_PSTR_SKIN_OFF_JOINTS + k];
    const uint32_t w = prt_le_load_u16(skin + PRT_BLOB_PSTR_SKIN_OFF_WEIGHTS + 2u * k);
    weight[k] = joint < view->info.joint_count ? w / 65535.0 : 0.0;
    total += weight[k];
  }
  for (r = 0; r < 3; ++r)
    for (c = 0; c < 4; ++c) out->m[r][c] = total > 0.0 ? 0.0 : (r == c ? 1.0 : 0.0);
  if (!(total > 0.0)) return;
  for (k = 0; k < 4; ++k) {
    const prt_pose_affine* joint = &skeleton->skin[skin[PRT_BLOB_PSTR_SKIN_OFF_JOINTS + k]];
    if (weight[k] == 0.0) continue;
    for (r = 0; r < 3; ++r)
      for (c = 0; c < 4; ++c) out->m[r][c] += weight[k] / total * joint->m[r][c];
  }
}

/* normalize(K3^-T n) = normalize(cof(K3) n / det K3): the cofactors keep the sign of det. */
static void skin_normal(const prt_pose_affine* k, const double n[3], double out[3]) {
  double cof[3][3], det, len;
  int r, c;
  for (r = 0; r < 3; ++r)
    for (c = 0; c < 3; ++c) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      cof[r][c] = k->m[r1][c1] * k->m[r2][c2] - k->m[r1][c2] * k->m[r2][c1];
    }
  det = k->m[0][0] * cof[0][0] + k->m[0][1] * cof[0][1] + k->m[0][2] * cof[0][2];
  for (r = 0; r < 3; ++r)
    out[r] = (cof[r][0] * n[0] + cof[r][1] * n[1] + cof[r][2] * n[2]) * (det < 0.0 ? -1.0 : 1.0);
  len = norm3(out);
  if (det == 0.0 || !(len > 0.0) || !isfinite(len)) {
    out[0] = out[1] = out[2] = 0.0;
    return;
  }
  for (r = 0; r < 3; ++r) out[r] /= len;
}

void prt_pose_skin_vertex(const prt_pose_view* view, const prt_pose_skeleton* skeleton, uint32_t v,
                          double* position, double* normal) {
  const uint8_t* skin = view->data + view->layout.skin + (uint64_t)PRT_BLOB_PSTR_SKIN_SIZE * v;
  prt_pose_affine k;
  double p[3], n[3];
  int i;
  vertex_matrix(view, skeleton, skin, &k);
  for (i = 0; i < 3; ++i) {
    p[i] = record_f32(skin, PRT_BLOB_PSTR_SKIN_OFF_POSITION + 4u * i);
    n[i] = record_f32(skin, PRT_BLOB_PSTR_SKIN_OFF_NORMAL + 4u * i);
  }
  if (position)
    for (i = 0; i < 3; ++i)
      position[i] = k.m[i][0] * p[0] + k.m[i][1] * p[1] + k.m[i][2] * p[2] + k.m[i][3];
  if (normal) skin_normal(&k, n, normal);
}

void prt_pose_exact_factors(const prt_pose_view* view, double* factor) {
  const double pi = 3.14159265358979323846;
  uint32_t l, m;
  for (l = 0; l < view->info.order; ++l)
    for (m = 0; m <= 2u * l; ++m)
      factor[l * l + m] = (double)view->info.albedo * (double)prt_sh_cosine_band_factor(l) / pi;
}

void prt_pose_basis_at_normal(uint32_t order, const double normal[3], double* out) {
  const double len = norm3(normal);
  uint32_t c;
  if (!(len > 0.0) || !isfinite(len)) {
    for (c = 0; c < order * order; ++c) out[c] = 0.0;
    return;
  }
  /* SH frame (SPEC §13): x = X, y = -Z, z = Y. */
  prt_sh_eval_sh_frame_d(order, normal[0] / len, -normal[2] / len, normal[1] / len, out);
}
