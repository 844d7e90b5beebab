/* SPDX-License-Identifier: MIT */
/* Technique `sh` in the runtime's technique table: the SHTR header decoded and checked against the
 * section at load (either validation level), the view every `sh` function reads, and the ties of
 * the `sh` constants to the formats layer's. */
#include <inttypes.h>
#include <stdio.h>

#include "internal.h"
#include "sh_internal.h"
#include "techniques.h"

PRT_STATIC_ASSERT(PRT_SECTION_SHTR == PRT_BLOB_TAG_SHTR, tag_shtr);
PRT_STATIC_ASSERT(PRT_SH_MAX_ORDER == PRT_BLOB_SHTR_MAX_ORDER, sh_max_order);
PRT_STATIC_ASSERT(PRT_SH_TRANSFER_UNSHADOWED == PRT_BLOB_SHTR_KIND_UNSHADOWED, kind_unshadowed);
PRT_STATIC_ASSERT(PRT_SH_TRANSFER_SHADOWED == PRT_BLOB_SHTR_KIND_SHADOWED, kind_shadowed);
PRT_STATIC_ASSERT(PRT_SH_TRANSFER_INTERREFLECTED == PRT_BLOB_SHTR_KIND_INTERREFLECTED,
                  kind_interreflected);

static prt_result corrupt(char* msg, size_t capacity, const char* what) {
  snprintf(msg, capacity, "'SHTR': %s", what);
  return PRT_ERROR_CORRUPT;
}

/* Every header field the formats checker checks, in its order and words, without the contents
 * (offsets, scales, padding: full validation). */
static prt_result open_shtr(const prt_asset_section* section, void* out, char* msg,
                            size_t capacity) {
  prt_sh_view* view = (prt_sh_view*)out;
  prt_sh_info* info = &view->info;
  const uint8_t* p = section->data;
  const uint64_t size = section->entry.raw_size;
  char what[160];
  prt_blob_shtr_header header;
  prt_blob_shtr_layout layout;
  if (!p || size < PRT_BLOB_SHTR_HEADER_SIZE) {
    snprintf(what, sizeof what, "%" PRIu64 " bytes cannot hold the 32-byte header", size);
    return corrupt(msg, capacity, what);
  }
  memset(view, 0, sizeof *view);
  prt_blob_shtr_read_header(p, &header);
  info->struct_size = sizeof *info;
  info->order = header.order;
  info->vertex_count = header.vertices;
  info->channels = header.channels;
  info->bits = header.bits;
  info->kind = (prt_sh_transfer_kind)header.kind;
  info->bounces = header.bounces;
  if (info->order < 1 || info->order > PRT_BLOB_SHTR_MAX_ORDER) {
    snprintf(what, sizeof what, "order %" PRIu32 " is not in 1..16", info->order);
    return corrupt(msg, capacity, what);
  }
  if (info->channels != 1 && info->channels != 3) {
    snprintf(what, sizeof what, "%" PRIu32 " channels (must be 1 or 3)", info->channels);
    return corrupt(msg, capacity, what);
  }
  if (info->bits != 8 && info->bits != 16) {
    snprintf(what, sizeof what, "%" PRIu32 " bits (must be 8 or 16)", info->bits);
    return corrupt(msg, capacity, what);
  }
  if (prt_le_load_u32(p + PRT_BLOB_SHTR_OFF_RESERVED) != 0 ||
      prt_le_load_u32(p + PRT_BLOB_SHTR_OFF_RESERVED + 4u) != 0)
    return corrupt(msg, capacity, "reserved header fields are not zero");
  if ((uint64_t)info->vertex_count != section->entry.element_count) {
    snprintf(what, sizeof what, "header says %" PRIu32 " vertices, element count %" PRIu64,
             info->vertex_count, section->entry.element_count);
    return corrupt(msg, capacity, what);
  }
  prt_blob_shtr_layout_of(info->order, info->vertex_count, info->channels, info->bits, &layout);
  if (layout.raw_size != size) {
    snprintf(what, sizeof what, "%" PRIu64 " raw bytes, the header implies %" PRIu64, size,
             layout.raw_size);
    return corrupt(msg, capacity, what);
  }
  view->coefficients = layout.coefficients;
  view->params = p + layout.params;
  view->values = p + layout.values;
  view->value_bytes = (size_t)(layout.payload_end - layout.values);
  return PRT_OK;
}

extern const struct prt_scene_hooks prt_sh_scene_hooks; /* sh/sh_scene_hooks.c */

const prt_technique_entry prt_sh_technique_entry = {
    PRT_TECHNIQUE_SH,    "sh", PRT_BLOB_TAG_SHTR, sizeof(prt_sh_view), open_shtr, NULL, NULL,
    &prt_sh_scene_hooks,
};
