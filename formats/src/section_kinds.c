/* SPDX-License-Identifier: MIT */
/* The kind table (formats/SPEC.md §7) and everything the reader derives from it: which kinds
 * are known, which sections a kind needs, whose element count a domain's size is, and which
 * function checks a kind's contents. */
#include <prt/format/section_kinds.h>

#include <inttypes.h>

#include <prt/format/cloth_layout.h>
#include <prt/format/mesh_layout.h>
#include <prt/format/pose_layout.h>
#include <prt/format/scene_layout.h>
#include <prt/format/sh_layout.h>
#include <prt/format/shadowfield_layout.h>
#include <prt/format/wavelet_layout.h>

#include "cloth/cloth_section.h"
#include "mesh/mesh_sections.h"
#include "pose/pose_section.h"
#include "reader_internal.h"
#include "scene/scene_section.h"
#include "sh/sh_section.h"
#include "shadowfield/shadowfield_section.h"
#include "wavelet/wavelet_section.h"

/* One row per kind: tag, layout version, domain, whether its element count is the domain's size,
 * element size (0 = variable), further tags it needs, human name, element noun, content check.
 * Order matters only for messages: relations are checked kind by kind in this order. */
/* clang-format off */
static const prt_blob_kind kKinds[] = {
    {PRT_BLOB_TAG_INFO, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_NONE, 0,
     PRT_BLOB_INFO_ELEMENT_SIZE, {0},
     "text (UTF-8)", "bytes", prt_blob_check_info},
    {PRT_BLOB_TAG_VPOS, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_VERTEX, 1,
     PRT_BLOB_VPOS_ELEMENT_SIZE, {0},
     "vertex positions (3 x f32)", "vertices", prt_blob_check_finite_f32},
    {PRT_BLOB_TAG_TRIS, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_TRIANGLE, 1,
     PRT_BLOB_TRIS_ELEMENT_SIZE, {PRT_BLOB_TAG_VPOS},
     "triangles (3 x u32)", "triangles", prt_blob_check_tris},
    {PRT_BLOB_TAG_VNRM, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_VERTEX, 0,
     PRT_BLOB_VNRM_ELEMENT_SIZE, {0},
     "vertex normals (3 x f32)", "normals", prt_blob_check_finite_f32},
    {PRT_BLOB_TAG_VTAN, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_VERTEX, 0,
     PRT_BLOB_VTAN_ELEMENT_SIZE, {0},
     "vertex tangents (3 x f32)", "tangents", prt_blob_check_finite_f32},
    {PRT_BLOB_TAG_SHTR, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_VERTEX, 0,
     0u, {0},
     "sh transfer (element = vertex)", "transfer vectors", prt_blob_check_shtr},
    {PRT_BLOB_TAG_WVLT, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_VERTEX, 0,
     0u, {0},
     "wavelet transfer (element = vertex)", "transfer rows", prt_blob_check_wvlt},
    {PRT_BLOB_TAG_PSTR, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_VERTEX, 0,
     0u, {0},
     "pose transfer (element = vertex)", "skinned vertices", prt_blob_check_pstr},
    {PRT_BLOB_TAG_CLTH, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_MATERIAL, 1,
     0u, {0},
     "cloth fabrics (element = material)", "fabrics", prt_blob_check_clth},
    {PRT_BLOB_TAG_SFLD, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_OBJECT, 1,
     0u, {PRT_BLOB_TAG_VPOS, PRT_BLOB_TAG_VNRM},
     "shadowfield object (element = object)", "objects", prt_blob_check_sfld},
    {PRT_BLOB_TAG_SCNE, PRT_BLOB_LAYOUT_VERSION_1, PRT_BLOB_DOMAIN_NONE, 0,
     0u, {0},
     "scene manifest (element = object)", "objects", prt_blob_check_scne},
};
/* clang-format on */

#define KIND_COUNT (sizeof kKinds / sizeof kKinds[0])

size_t prt_blob_kind_count(void) {
  return KIND_COUNT;
}

const prt_blob_kind* prt_blob_kind_at(size_t index) {
  return index < KIND_COUNT ? &kKinds[index] : NULL;
}

const prt_blob_kind* prt_blob_find_kind(uint32_t tag, uint8_t layout_version) {
  size_t i;
  for (i = 0; i < KIND_COUNT; ++i)
    if (kKinds[i].tag == tag && kKinds[i].layout_version == layout_version) return &kKinds[i];
  return NULL;
}

const prt_blob_kind* prt_blob_domain_counter(prt_blob_domain domain) {
  size_t i;
  if (domain == PRT_BLOB_DOMAIN_NONE) return NULL;
  for (i = 0; i < KIND_COUNT; ++i)
    if (kKinds[i].domain == domain && kKinds[i].counts_domain) return &kKinds[i];
  return NULL;
}

/* The known section with this tag (any known layout version); returns 0 when there is none. */
static int find_known(const void* data, const prt_blob_header* h, uint32_t tag,
                      prt_blob_section* out) {
  uint32_t i;
  for (i = 0; i < h->section_count; ++i) {
    prt_blob_read_section(data, h, i, out);
    if (out->tag == tag && prt_blob_find_kind(out->tag, out->layout_version)) return 1;
  }
  return 0;
}

uint64_t prt_blob_domain_count(const void* data, const prt_blob_header* header,
                               prt_blob_domain domain) {
  const prt_blob_kind* counter = prt_blob_domain_counter(domain);
  prt_blob_section s;
  return counter && find_known(data, header, counter->tag, &s) ? s.element_count : 0;
}

static prt_blob_status needs(const char* name, uint32_t tag, char* msg, size_t cap) {
  char needed[5];
  prt_blob_tag_string(tag, needed);
  return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "section '%s' needs a '%s' section", name,
                       needed);
}

/* The relations of one kind whose section `s` is in the blob. */
static prt_blob_status check_kind_relations(const void* data, const prt_blob_header* h,
                                            const prt_blob_kind* kind, const prt_blob_section* s,
                                            char* msg, size_t cap) {
  const prt_blob_kind* counter = prt_blob_domain_counter(kind->domain);
  prt_blob_section other;
  char name[5];
  size_t d;
  prt_blob_tag_string(kind->tag, name);
  for (d = 0; d < PRT_BLOB_KIND_MAX_DEPENDENCIES && kind->depends_on[d] != 0; ++d)
    if (!find_known(data, h, kind->depends_on[d], &other))
      return needs(name, kind->depends_on[d], msg, cap);
  if (kind->counts_domain || !counter) return PRT_BLOB_OK;
  if (!find_known(data, h, counter->tag, &other)) return needs(name, counter->tag, msg, cap);
  if (s->element_count != other.element_count)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'%s' has %" PRIu64 " %s for %" PRIu64 " %s",
                         name, s->element_count, kind->element_noun, other.element_count,
                         counter->element_noun);
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_relations(const void* data, const prt_blob_header* h, char* msg,
                                         size_t cap) {
  size_t k;
  for (k = 0; k < KIND_COUNT; ++k) {
    prt_blob_section s;
    prt_blob_status st;
    if (!find_known(data, h, kKinds[k].tag, &s) || s.layout_version != kKinds[k].layout_version)
      continue;
    st = check_kind_relations(data, h, &kKinds[k], &s, msg, cap);
    if (st != PRT_BLOB_OK) return st;
  }
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_content(const prt_blob_section* s, const void* raw,
                                       uint64_t vertex_count, char* msg, size_t cap) {
  const prt_blob_kind* kind = prt_blob_find_kind(s->tag, s->layout_version);
  prt_blob_content content;
  if (!kind) return PRT_BLOB_OK;
  if (s->raw_size > 0 && !raw)
    return prt_blob_fail(PRT_BLOB_INVALID_ARGUMENT, msg, cap, "section bytes are NULL");
  if (!kind->check_content) return PRT_BLOB_OK;
  content.section = s;
  content.bytes = (const uint8_t*)raw;
  content.size = (size_t)s->raw_size;
  content.vertex_count = vertex_count;
  return kind->check_content(&content, msg, cap);
}
