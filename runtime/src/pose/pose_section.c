/* SPDX-License-Identifier: MIT */
/* Technique `pose` in the runtime's technique table: the PSTR header, size, parents and
 * evaluation order checked against the section at load (either validation level; J <= 256 keeps
 * this bounded), the view every `pose` function reads, and the ties of the `pose` constants to
 * the formats layer's. */
#include <inttypes.h>
#include <stdio.h>

#include "pose_internal.h"
#include "techniques.h"

PRT_STATIC_ASSERT(PRT_SECTION_PSTR == PRT_BLOB_TAG_PSTR, tag_pstr);
PRT_STATIC_ASSERT((int)PRT_POSE_MODEL_DIRECT == (int)PRT_BLOB_PSTR_MODEL_DIRECT, model_direct);
PRT_STATIC_ASSERT((int)PRT_POSE_MODEL_RESIDUAL == (int)PRT_BLOB_PSTR_MODEL_RESIDUAL,
                  model_residual);
PRT_STATIC_ASSERT(PRT_BLOB_PSTR_MAX_ORDER <= PRT_SH_MAX_ORDER, pose_order_fits_sh);
PRT_STATIC_ASSERT(PRT_SH_TRANSFER_SHADOWED == PRT_BLOB_SHTR_KIND_SHADOWED, pose_kind_shadowed);
PRT_STATIC_ASSERT(PRT_SH_TRANSFER_INTERREFLECTED == PRT_BLOB_SHTR_KIND_INTERREFLECTED,
                  pose_kind_interreflected);

static prt_result corrupt(char* msg, size_t capacity, const char* what) {
  snprintf(msg, capacity, "'PSTR': %s", what);
  return PRT_ERROR_CORRUPT;
}

/* The count fields, in the formats checker's order and words. */
static int counts_ok(const prt_blob_pstr_header* h, char* what, size_t size) {
  if (h->order < 1 || h->order > PRT_BLOB_PSTR_MAX_ORDER)
    snprintf(what, size, "order %" PRIu32 " is not in 1..8", h->order);
  else if (h->joints < 1 || h->joints > PRT_BLOB_PSTR_MAX_JOINTS)
    snprintf(what, size, "%" PRIu32 " joints (must be 1..256)", h->joints);
  else if (h->pose_dims > 3u * h->joints)
    snprintf(what, size, "%" PRIu32 " pose dimensions for %" PRIu32 " features", h->pose_dims,
             3u * h->joints);
  else if (h->basis_dims < 1 || h->basis_dims > PRT_BLOB_PSTR_MAX_BASIS_DIMS)
    snprintf(what, size, "%" PRIu32 " basis dimensions (must be 1..256)", h->basis_dims);
  else if (h->model != PRT_BLOB_PSTR_MODEL_DIRECT && h->model != PRT_BLOB_PSTR_MODEL_RESIDUAL)
    snprintf(what, size, "model %" PRIu32 " is not 0 or 1", h->model);
  else if (h->bits != 8 && h->bits != 16)
    snprintf(what, size, "%" PRIu32 " bits (must be 8 or 16)", h->bits);
  else
    return 1;
  return 0;
}

/* The other header fields and the element count. */
static int fields_ok(const prt_blob_pstr_header* h, const uint8_t* p, uint64_t element_count,
                     char* what, size_t size) {
  if (h->model_joint >= h->joints)
    snprintf(what, size, "model joint %" PRIu32 " is not below %" PRIu32 " joints", h->model_joint,
             h->joints);
  else if (!isfinite(h->albedo))
    snprintf(what, size, "albedo is not finite");
  else if (h->albedo < 0.0f)
    snprintf(what, size, "albedo is negative");
  else if (h->flags & ~PRT_BLOB_PSTR_KNOWN_FLAGS)
    snprintf(what, size, "unknown flags 0x%" PRIx32, h->flags & ~PRT_BLOB_PSTR_KNOWN_FLAGS);
  else if (prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_RESERVED) != 0 ||
           prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_RESERVED + 4u) != 0 ||
           prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_RESERVED + 8u) != 0 ||
           prt_le_load_u32(p + PRT_BLOB_PSTR_OFF_RESERVED + 12u) != 0)
    snprintf(what, size, "reserved header fields are not zero");
  else if ((uint64_t)h->vertices != element_count)
    snprintf(what, size, "header says %" PRIu32 " vertices, element count %" PRIu64, h->vertices,
             element_count);
  else
    return 1;
  return 0;
}

static int32_t parent_of(const uint8_t* p, const prt_blob_pstr_layout* l, uint32_t j) {
  return (int32_t)prt_le_load_u32(p + l->joints + (uint64_t)PRT_BLOB_PSTR_JOINT_SIZE * j);
}

/* Parents and evaluation order, in the formats checker's order and words: what makes the
 * skeleton's walk (pose_model.c) read only joints already placed. */
static int skeleton_ok(const prt_blob_pstr_header* h, const uint8_t* p,
                       const prt_blob_pstr_layout* l, char* what, size_t size) {
  uint8_t placed[PRT_BLOB_PSTR_MAX_JOINTS] = {0};
  uint32_t j, i;
  for (j = 0; j < h->joints; ++j) {
    const int32_t parent = parent_of(p, l, j);
    if (parent != -1 && (parent < 0 || (uint32_t)parent >= h->joints || (uint32_t)parent == j)) {
      snprintf(what, size, "joint %" PRIu32 " has parent %" PRId32, j, parent);
      return 0;
    }
    if (j == h->model_joint && parent != -1) {
      snprintf(what, size, "model joint %" PRIu32 " has parent %" PRId32 " (must be -1)", j,
               parent);
      return 0;
    }
  }
  for (i = 0; i < h->joints; ++i) {
    const uint32_t joint = prt_le_load_u32(p + l->eval_order + 4u * i);
    if (joint >= h->joints || placed[joint]) {
      snprintf(what, size,
               "evaluation order entry %" PRIu32 " is joint %" PRIu32
               " (not a permutation of the joints)",
               i, joint);
      return 0;
    }
    if (parent_of(p, l, joint) != -1 && !placed[parent_of(p, l, joint)]) {
      snprintf(what, size,
               "joint %" PRIu32 " comes before its parent %" PRId32 " in the evaluation order",
               joint, parent_of(p, l, joint));
      return 0;
    }
    placed[joint] = 1;
  }
  return 1;
}

static void fill_info(const prt_blob_pstr_header* h, const prt_blob_pstr_layout* l,
                      prt_pose_info* info) {
  info->struct_size = sizeof *info;
  info->order = h->order;
  info->vertex_count = h->vertices;
  info->joint_count = h->joints;
  info->feature_count = 3u * h->joints;
  info->pose_dims = h->pose_dims;
  info->basis_dims = h->basis_dims;
  info->model = (prt_pose_model)h->model;
  info->bits = h->bits;
  info->model_joint = h->model_joint;
  info->kind = h->kind;
  info->bounces = h->bounces;
  info->albedo = h->albedo;
  info->clamps_pose = (h->flags & PRT_BLOB_PSTR_FLAG_CLAMP) != 0;
  info->model_bytes = (size_t)(l->skin - l->pose_mean);
}

static prt_result open_pstr(const prt_asset_section* section, void* out, char* msg,
                            size_t capacity) {
  prt_pose_view* view = (prt_pose_view*)out;
  const uint8_t* p = section->data;
  const uint64_t size = section->entry.raw_size;
  char what[160];
  prt_blob_pstr_header h;
  prt_blob_pstr_layout l;
  if (!p || size < PRT_BLOB_PSTR_HEADER_SIZE) {
    snprintf(what, sizeof what, "%" PRIu64 " bytes cannot hold the 64-byte header", size);
    return corrupt(msg, capacity, what);
  }
  memset(view, 0, sizeof *view);
  prt_blob_pstr_read_header(p, &h);
  if (!counts_ok(&h, what, sizeof what)) return corrupt(msg, capacity, what);
  prt_blob_pstr_layout_of(h.order, h.vertices, h.joints, h.pose_dims, h.basis_dims, h.bits, &l);
  if (!fields_ok(&h, p, section->entry.element_count, what, sizeof what))
    return corrupt(msg, capacity, what);
  if (l.raw_size != size) {
    snprintf(what, sizeof what, "%" PRIu64 " raw bytes, the header implies %" PRIu64, size,
             l.raw_size);
    return corrupt(msg, capacity, what);
  }
  if (!skeleton_ok(&h, p, &l, what, sizeof what)) return corrupt(msg, capacity, what);
  fill_info(&h, &l, &view->info);
  view->layout = l;
  view->data = p;
  return PRT_OK;
}

extern const struct prt_scene_hooks prt_pose_scene_hooks;

const prt_technique_entry prt_pose_technique_entry = {
    PRT_TECHNIQUE_POSE,
    "pose",
    PRT_BLOB_TAG_PSTR,
    sizeof(prt_pose_view),
    open_pstr,
    NULL,                  /* attach */
    NULL,                  /* release */
    &prt_pose_scene_hooks, /* pose_scene_hooks.c */
};
