/* SPDX-License-Identifier: MIT */
/* The `pose` section PSTR, layout version 1 (formats/SPEC.md §7.3): a learned SH transfer of a
 * skinned character as a function of its joint rotations (James and Fatahalian's linear model,
 * paper 002), with the skeleton and per-vertex skin the runtime needs to form the pose features
 * and the skinned normals. A 64-byte header, then the joint table, the pose PCA, the regression,
 * the quantised vertex basis and the per-vertex skin. Element = vertex; the size follows from
 * the header (prt_blob_pstr_layout_of). Plain C99, pure functions. */
#ifndef PRT_FORMAT_POSE_LAYOUT_H
#define PRT_FORMAT_POSE_LAYOUT_H

#include <prt/format/blob_layout.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRT_BLOB_TAG_PSTR PRT_BLOB_TAG('P', 'S', 'T', 'R')

#define PRT_BLOB_PSTR_HEADER_SIZE 64u
#define PRT_BLOB_PSTR_MAX_ORDER 8u        /* SH order n: n^2 coefficients C */
#define PRT_BLOB_PSTR_MAX_JOINTS 256u     /* joint indices are stored as u8 */
#define PRT_BLOB_PSTR_MAX_BASIS_DIMS 256u /* q */

#define PRT_BLOB_PSTR_OFF_ORDER 0u        /* u32: n, 1..8 */
#define PRT_BLOB_PSTR_OFF_VERTICES 4u     /* u32: V = VPOS element count */
#define PRT_BLOB_PSTR_OFF_JOINTS 8u       /* u32: J, 1..256; features F = 3 J */
#define PRT_BLOB_PSTR_OFF_POSE_DIMS 12u   /* u32: p, 0..F (0: the model is one constant) */
#define PRT_BLOB_PSTR_OFF_BASIS_DIMS 16u  /* u32: q, 1..256 */
#define PRT_BLOB_PSTR_OFF_MODEL 20u       /* u32: PRT_BLOB_PSTR_MODEL_* */
#define PRT_BLOB_PSTR_OFF_BITS 24u        /* u32: bits per basis value, 8 or 16 */
#define PRT_BLOB_PSTR_OFF_MODEL_JOINT 28u /* u32: the joint whose frame is the model frame, < J */
#define PRT_BLOB_PSTR_OFF_KIND 32u        /* u32, informational: PRT_BLOB_SHTR_KIND_* values */
#define PRT_BLOB_PSTR_OFF_BOUNCES 36u     /* u32, informational */
#define PRT_BLOB_PSTR_OFF_ALBEDO 40u      /* f32: grey albedo of the exact part, finite, >= 0 */
#define PRT_BLOB_PSTR_OFF_FLAGS 44u       /* u32: PRT_BLOB_PSTR_FLAG_* */
#define PRT_BLOB_PSTR_OFF_RESERVED 48u    /* u32[4], zero */
#define PRT_BLOB_PSTR_RESERVED_SIZE 16u

/* The learned part is the whole transfer (the paper's model). */
#define PRT_BLOB_PSTR_MODEL_DIRECT 0u
/* The learned part is the residual over the exact unshadowed transfer of the skinned normal,
 * albedo * (A_l / pi) * y_lm(n) (A_l: the clamped-cosine band factors, SPEC §13). */
#define PRT_BLOB_PSTR_MODEL_RESIDUAL 1u
/* Pose coordinates are clamped to the [min, max] range stored with the pose basis. */
#define PRT_BLOB_PSTR_FLAG_CLAMP 1u
#define PRT_BLOB_PSTR_KNOWN_FLAGS 1u

/* A joint record, 140 bytes: i32 parent (-1: none; else < J and not the joint itself),
 * f32 bind_rotation[4] (x, y, z, w, unit), f32 rest_translation[3], f32 rest_scale[3],
 * f32 pre[12] and f32 inverse_bind[12] (3x4 affine, row-major: rows x, y, z of [R | t]). */
#define PRT_BLOB_PSTR_JOINT_SIZE 140u
#define PRT_BLOB_PSTR_JOINT_OFF_PARENT 0u
#define PRT_BLOB_PSTR_JOINT_OFF_BIND_ROTATION 4u
#define PRT_BLOB_PSTR_JOINT_OFF_TRANSLATION 20u
#define PRT_BLOB_PSTR_JOINT_OFF_SCALE 32u
#define PRT_BLOB_PSTR_JOINT_OFF_PRE 44u
#define PRT_BLOB_PSTR_JOINT_OFF_INVERSE_BIND 92u

/* A vertex's skin, 36 bytes: f32 local_position[3], f32 local_normal[3] (the mesh's own
 * attributes, before skinning), u8 joints[4], u16 weights[4] (w / 65535). */
#define PRT_BLOB_PSTR_SKIN_SIZE 36u
#define PRT_BLOB_PSTR_SKIN_OFF_POSITION 0u
#define PRT_BLOB_PSTR_SKIN_OFF_NORMAL 12u
#define PRT_BLOB_PSTR_SKIN_OFF_JOINTS 24u
#define PRT_BLOB_PSTR_SKIN_OFF_WEIGHTS 28u

/* The header fields, as stored. */
typedef struct prt_blob_pstr_header {
  uint32_t order;
  uint32_t vertices;
  uint32_t joints;
  uint32_t pose_dims;
  uint32_t basis_dims;
  uint32_t model;
  uint32_t bits;
  uint32_t model_joint;
  uint32_t kind;
  uint32_t bounces;
  float albedo;
  uint32_t flags;
} prt_blob_pstr_header;

/* A little-endian f32 (the bits of prt_le_load_u32). */
static inline float prt_blob_pstr_load_f32(const uint8_t* p) {
  union {
    uint32_t u;
    float f;
  } v;
  v.u = prt_le_load_u32(p);
  return v.f;
}

/* Reads the header from the section's first PRT_BLOB_PSTR_HEADER_SIZE bytes (the caller checks
 * that they are there). The reserved words are not part of it. */
static inline void prt_blob_pstr_read_header(const uint8_t* p, prt_blob_pstr_header* out) {
  out->order = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_ORDER);
  out->vertices = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_VERTICES);
  out->joints = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_JOINTS);
  out->pose_dims = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_POSE_DIMS);
  out->basis_dims = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_BASIS_DIMS);
  out->model = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_MODEL);
  out->bits = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_BITS);
  out->model_joint = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_MODEL_JOINT);
  out->kind = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_KIND);
  out->bounces = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_BOUNCES);
  out->albedo = prt_blob_pstr_load_f32(p + PRT_BLOB_PSTR_OFF_ALBEDO);
  out->flags = prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_FLAGS);
}

/* Where the parts of a PSTR section lie; offsets in bytes from the section's first byte, each a
 * multiple of 4 (C = n^2 coefficients, F = 3 J features):
 *   joints      J records of PRT_BLOB_PSTR_JOINT_SIZE
 *   eval_order  u32[J]: every joint once, each after its parent
 *   pose_mean   f32[F]
 *   pose_basis  f32[F][p]: pose coordinate i = sum_f basis[f][i] (feature_f - mean_f)
 *   pose_range  f32[p][2]: min, max of each coordinate over the training poses
 *   regression  f32[p + 1][q][C]: row 0 the bias, row i + 1 coordinate i's weights
 *   basis_params f32[q][2]: offset, scale of basis column k
 *   basis_values u8 or u16 [V][q]: U[v][k] = offset_k + scale_k value[v][k]
 *   skin        V records of PRT_BLOB_PSTR_SKIN_SIZE (after padding the values to 4 bytes) */
typedef struct prt_blob_pstr_layout {
  uint32_t coefficients; /* C = n^2 */
  uint32_t features;     /* F = 3 J */
  uint32_t value_size;   /* bytes per basis value: bits / 8 */
  uint64_t joints;
  uint64_t eval_order;
  uint64_t pose_mean;
  uint64_t pose_basis;
  uint64_t pose_range;
  uint64_t regression;
  uint64_t basis_params;
  uint64_t basis_values;
  uint64_t skin;
  uint64_t payload_end; /* skin + 36 V */
  uint64_t raw_size;    /* = payload_end (a multiple of 4) */
} prt_blob_pstr_layout;

/* Fills *out for an order in 1..8, 1..256 joints, p <= 3 J, q in 1..256 and 8 or 16 bits and
 * returns 1; returns 0 (out untouched) otherwise. Nothing overflows 64 bits for V < 2^32. */
static inline int prt_blob_pstr_layout_of(uint32_t order, uint32_t vertices, uint32_t joints,
                                          uint32_t pose_dims, uint32_t basis_dims, uint32_t bits,
                                          prt_blob_pstr_layout* out) {
  uint64_t at, values_bytes;
  if (order < 1u || order > PRT_BLOB_PSTR_MAX_ORDER) return 0;
  if (joints < 1u || joints > PRT_BLOB_PSTR_MAX_JOINTS) return 0;
  if (pose_dims > 3u * joints) return 0;
  if (basis_dims < 1u || basis_dims > PRT_BLOB_PSTR_MAX_BASIS_DIMS) return 0;
  if (bits != 8u && bits != 16u) return 0;
  out->coefficients = order * order;
  out->features = 3u * joints;
  out->value_size = bits / 8u;
  at = PRT_BLOB_PSTR_HEADER_SIZE;
  out->joints = at;
  at += (uint64_t)PRT_BLOB_PSTR_JOINT_SIZE * joints;
  out->eval_order = at;
  at += 4u * (uint64_t)joints;
  out->pose_mean = at;
  at += 4u * (uint64_t)out->features;
  out->pose_basis = at;
  at += 4u * (uint64_t)out->features * pose_dims;
  out->pose_range = at;
  at += 8u * (uint64_t)pose_dims;
  out->regression = at;
  at += 4u * ((uint64_t)pose_dims + 1u) * basis_dims * out->coefficients;
  out->basis_params = at;
  at += 8u * (uint64_t)basis_dims;
  out->basis_values = at;
  values_bytes = (uint64_t)vertices * basis_dims * out->value_size;
  at += (values_bytes + 3u) & ~(uint64_t)3u;
  out->skin = at;
  out->payload_end = at + (uint64_t)PRT_BLOB_PSTR_SKIN_SIZE * vertices;
  out->raw_size = out->payload_end;
  return 1;
}

#ifdef __cplusplus
}
#endif

#endif /* PRT_FORMAT_POSE_LAYOUT_H */
