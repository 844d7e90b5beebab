/* SPDX-License-Identifier: MIT */
/* The PSTR content check (formats/SPEC.md §7.3, full validation). */
#include "pose_section.h"

#include <inttypes.h>

#include <prt/format/pose_layout.h>

#include "../reader_internal.h"

#define FAIL_CORRUPT(...) prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'PSTR': " __VA_ARGS__)
#define FAIL_NON_FINITE(...) prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap, "'PSTR': " __VA_ARGS__)

/* The count fields, each in its range; on success *layout is filled. */
static prt_blob_status check_counts(const prt_blob_pstr_header* h, prt_blob_pstr_layout* layout,
                                    char* msg, size_t cap) {
  if (h->order < 1 || h->order > PRT_BLOB_PSTR_MAX_ORDER)
    return FAIL_CORRUPT("order %" PRIu32 " is not in 1..8", h->order);
  if (h->joints < 1 || h->joints > PRT_BLOB_PSTR_MAX_JOINTS)
    return FAIL_CORRUPT("%" PRIu32 " joints (must be 1..256)", h->joints);
  if (h->pose_dims > 3u * h->joints)
    return FAIL_CORRUPT("%" PRIu32 " pose dimensions for %" PRIu32 " features", h->pose_dims,
                        3u * h->joints);
  if (h->basis_dims < 1 || h->basis_dims > PRT_BLOB_PSTR_MAX_BASIS_DIMS)
    return FAIL_CORRUPT("%" PRIu32 " basis dimensions (must be 1..256)", h->basis_dims);
  if (h->model != PRT_BLOB_PSTR_MODEL_DIRECT && h->model != PRT_BLOB_PSTR_MODEL_RESIDUAL)
    return FAIL_CORRUPT("model %" PRIu32 " is not 0 or 1", h->model);
  if (h->bits != 8 && h->bits != 16)
    return FAIL_CORRUPT("%" PRIu32 " bits (must be 8 or 16)", h->bits);
  prt_blob_pstr_layout_of(h->order, h->vertices, h->joints, h->pose_dims, h->basis_dims, h->bits,
                          layout); /* valid fields */
  return PRT_BLOB_OK;
}

/* Every header field; on success *h and *layout are filled. */
static prt_blob_status check_header(const prt_blob_content* content, prt_blob_pstr_header* h,
                                    prt_blob_pstr_layout* layout, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  prt_blob_status st;
  prt_blob_pstr_read_header(p, h);
  st = check_counts(h, layout, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  if (h->model_joint >= h->joints)
    return FAIL_CORRUPT("model joint %" PRIu32 " is not below %" PRIu32 " joints", h->model_joint,
                        h->joints);
  if (!prt_blob_f32_is_finite(h->albedo)) return FAIL_NON_FINITE("albedo is not finite");
  if (h->albedo < 0.0f) return FAIL_CORRUPT("albedo is negative");
  if (h->flags & ~PRT_BLOB_PSTR_KNOWN_FLAGS)
    return FAIL_CORRUPT("unknown flags 0x%" PRIx32, h->flags & ~PRT_BLOB_PSTR_KNOWN_FLAGS);
  if (!prt_blob_bytes_are_zero(p + PRT_BLOB_PSTR_OFF_RESERVED, PRT_BLOB_PSTR_RESERVED_SIZE))
    return FAIL_CORRUPT("reserved header fields are not zero");
  if ((uint64_t)h->vertices != content->vertex_count ||
      (uint64_t)h->vertices != content->section->element_count)
    return FAIL_CORRUPT("header says %" PRIu32 " vertices, element count %" PRIu64
                        ", 'VPOS' has %" PRIu64,
                        h->vertices, content->section->element_count, content->vertex_count);
  return PRT_BLOB_OK;
}

/* Parents (-1, or another joint below J; the model joint's is -1) and the evaluation order (a
 * permutation in which each joint follows its parent). */
static prt_blob_status check_skeleton(const uint8_t* p, const prt_blob_pstr_header* h,
                                      const prt_blob_pstr_layout* l, char* msg, size_t cap) {
  uint8_t placed[PRT_BLOB_PSTR_MAX_JOINTS] = {0};
  uint32_t j, i;
  for (j = 0; j < h->joints; ++j) {
    const int32_t parent = (int32_t)prt_le_load_u32(p + l->joints + PRT_BLOB_PSTR_JOINT_SIZE * j);
    if (parent != -1 && (parent < 0 || (uint32_t)parent >= h->joints || (uint32_t)parent == j))
      return FAIL_CORRUPT("joint %" PRIu32 " has parent %" PRId32, j, parent);
    if (j == h->model_joint && parent != -1)
      return FAIL_CORRUPT("model joint %" PRIu32 " has parent %" PRId32 " (must be -1)", j, parent);
  }
  for (i = 0; i < h->joints; ++i) {
    const uint32_t joint = prt_le_load_u32(p + l->eval_order + 4u * i);
    int32_t parent;
    if (joint >= h->joints || placed[joint])
      return FAIL_CORRUPT("evaluation order entry %" PRIu32 " is joint %" PRIu32
                          " (not a permutation of the joints)",
                          i, joint);
    parent = (int32_t)prt_le_load_u32(p + l->joints + PRT_BLOB_PSTR_JOINT_SIZE * joint);
    if (parent != -1 && !placed[parent])
      return FAIL_CORRUPT("joint %" PRIu32 " comes before its parent %" PRId32
                          " in the evaluation order",
                          joint, parent);
    placed[joint] = 1;
  }
  return PRT_BLOB_OK;
}

/* The index of the first non-finite f32 of the `count` at p, or `count`. */
static uint64_t first_non_finite(const uint8_t* p, uint64_t count) {
  uint64_t i;
  for (i = 0; i < count; ++i)
    if (!prt_blob_f32_is_finite(prt_blob_load_f32(p + 4u * i))) return i;
  return count;
}

/* The joint records' floats (everything after the parent) are finite. */
static prt_blob_status check_joint_floats(const uint8_t* p, const prt_blob_pstr_header* h,
                                          const prt_blob_pstr_layout* l, char* msg, size_t cap) {
  const uint64_t floats = (PRT_BLOB_PSTR_JOINT_SIZE - 4u) / 4u;
  uint32_t j;
  for (j = 0; j < h->joints; ++j) {
    const uint8_t* record = p + l->joints + PRT_BLOB_PSTR_JOINT_SIZE * j;
    if (first_non_finite(record + 4u, floats) < floats)
      return FAIL_NON_FINITE("joint %" PRIu32 " has a float that is not finite", j);
  }
  return PRT_BLOB_OK;
}

/* Pose mean, basis and range, regression and basis parameters: finite; min <= max, scales >= 0. */
static prt_blob_status check_model(const uint8_t* p, const prt_blob_pstr_header* h,
                                   const prt_blob_pstr_layout* l, char* msg, size_t cap) {
  const uint64_t model_floats = (l->basis_values - l->pose_mean) / 4u;
  const uint64_t bad = first_non_finite(p + l->pose_mean, model_floats);
  uint32_t i, k;
  if (bad < model_floats)
    return FAIL_NON_FINITE("model float %" PRIu64 " (byte %" PRIu64 ") is not finite", bad,
                           l->pose_mean + 4u * bad);
  for (i = 0; i < h->pose_dims; ++i) {
    const float lo = prt_blob_load_f32(p + l->pose_range + 8u * i);
    const float hi = prt_blob_load_f32(p + l->pose_range + 8u * i + 4u);
    if (!(lo <= hi))
      return FAIL_CORRUPT("range of pose coordinate %" PRIu32 " has min above max", i);
  }
  for (k = 0; k < h->basis_dims; ++k)
    if (prt_blob_load_f32(p + l->basis_params + 8u * k + 4u) < 0.0f)
      return FAIL_CORRUPT("scale of basis column %" PRIu32 " is negative", k);
  return PRT_BLOB_OK;
}

/* Each vertex's skin: finite position and normal, joint indices below J. */
static prt_blob_status check_skin(const uint8_t* p, const prt_blob_pstr_header* h,
                                  const prt_blob_pstr_layout* l, char* msg, size_t cap) {
  uint32_t v, k;
  for (v = 0; v < h->vertices; ++v) {
    const uint8_t* skin = p + l->skin + (uint64_t)PRT_BLOB_PSTR_SKIN_SIZE * v;
    if (first_non_finite(skin + PRT_BLOB_PSTR_SKIN_OFF_POSITION, 6u) < 6u)
      return FAIL_NON_FINITE("vertex %" PRIu32 " has a position or normal that is not finite", v);
    for (k = 0; k < 4; ++k)
      if (skin[PRT_BLOB_PSTR_SKIN_OFF_JOINTS + k] >= h->joints)
        return FAIL_CORRUPT("vertex %" PRIu32 " names joint %u of %" PRIu32, v,
                            (unsigned)skin[PRT_BLOB_PSTR_SKIN_OFF_JOINTS + k], h->joints);
  }
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_pstr(const prt_blob_content* content, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  const size_t n = content->size;
  prt_blob_pstr_header h;
  prt_blob_pstr_layout l = {0};
  uint64_t values_end;
  prt_blob_status st;
  if (n < PRT_BLOB_PSTR_HEADER_SIZE)
    return FAIL_CORRUPT("%zu bytes cannot hold the 64-byte header", n);
  st = check_header(content, &h, &l, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  if ((uint64_t)n != l.raw_size)
    return FAIL_CORRUPT("%zu raw bytes, the header implies %" PRIu64, n, l.raw_size);
  values_end = l.basis_values + (uint64_t)h.vertices * h.basis_dims * l.value_size;
  if (!prt_blob_bytes_are_zero(p + values_end, (size_t)(l.skin - values_end)))
    return FAIL_CORRUPT("padding after the basis values is not zero");
  st = check_skeleton(p, &h, &l, msg, cap);
  if (st == PRT_BLOB_OK) st = check_joint_floats(p, &h, &l, msg, cap);
  if (st == PRT_BLOB_OK) st = check_model(p, &h, &l, msg, cap);
  if (st == PRT_BLOB_OK) st = check_skin(p, &h, &l, msg, cap);
  return st;
}
