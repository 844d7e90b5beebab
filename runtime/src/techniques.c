/* SPDX-License-Identifier: MIT */
/* The technique table (techniques.h) and what shared code does with it: the views opened at
 * load, the public technique queries. Adding a technique adds one row here. */
#include <stdio.h>

#include "techniques.h"

extern const prt_technique_entry prt_sh_technique_entry;      /* sh/sh_section.c */
extern const prt_technique_entry prt_wavelet_technique_entry; /* wavelet/wavelet_section.c */
extern const prt_technique_entry prt_pose_technique_entry;    /* pose/pose_section.c */
extern const prt_technique_entry prt_cloth_technique_entry;   /* cloth/cloth_section.c */
/* shadowfield/shadowfield_section.c */
extern const prt_technique_entry prt_shadowfield_technique_entry;

/* One row per technique. */
/* clang-format off */
static const prt_technique_entry* const kTechniques[] = {
    &prt_sh_technique_entry,
    &prt_wavelet_technique_entry,
    &prt_pose_technique_entry,
    &prt_cloth_technique_entry,
    &prt_shadowfield_technique_entry,
};
/* clang-format on */

#define TECHNIQUE_COUNT (sizeof kTechniques / sizeof kTechniques[0])

PRT_STATIC_ASSERT(PRT_TECHNIQUE_SH < PRT_INTERNAL_MAX_TECHNIQUES &&
                      PRT_TECHNIQUE_WAVELET < PRT_INTERNAL_MAX_TECHNIQUES &&
                      PRT_TECHNIQUE_POSE < PRT_INTERNAL_MAX_TECHNIQUES &&
                      PRT_TECHNIQUE_CLOTH < PRT_INTERNAL_MAX_TECHNIQUES &&
                      PRT_TECHNIQUE_SHADOWFIELD < PRT_INTERNAL_MAX_TECHNIQUES,
                  technique_values_fit_a_bit_set);

const prt_technique_entry* prt_internal_technique(prt_technique technique) {
  size_t i;
  for (i = 0; i < TECHNIQUE_COUNT; ++i)
    if (kTechniques[i]->technique == technique) return kTechniques[i];
  return NULL;
}

const prt_technique_entry* prt_internal_technique_of_tag(uint32_t tag) {
  size_t i;
  for (i = 0; i < TECHNIQUE_COUNT; ++i)
    if (kTechniques[i]->section_tag == tag) return kTechniques[i];
  return NULL;
}

void prt_internal_free_views(const prt_allocator* allocator,
                             void* views[PRT_INTERNAL_MAX_TECHNIQUES]) {
  size_t i;
  for (i = 0; i < TECHNIQUE_COUNT; ++i) {
    const prt_technique_entry* t = kTechniques[i];
    if (views[t->technique] && t->release) t->release(allocator, views[t->technique]);
    prt_internal_free(allocator, views[t->technique], t->view_size);
    views[t->technique] = NULL;
  }
}

prt_result prt_internal_attach_views(const prt_context* context, const prt_allocator* allocator,
                                     const prt_asset_section* sections, uint32_t section_count,
                                     void* views[PRT_INTERNAL_MAX_TECHNIQUES], char* msg,
                                     size_t capacity) {
  size_t i;
  for (i = 0; i < TECHNIQUE_COUNT; ++i) {
    const prt_technique_entry* t = kTechniques[i];
    prt_result r;
    if (!views[t->technique] || !t->attach) continue;
    r = t->attach(context, allocator, sections, section_count, views[t->technique], msg, capacity);
    if (r == PRT_ERROR_OUT_OF_MEMORY)
      snprintf(msg, capacity, "out of memory for the '%s' section's runtime data", t->name);
    if (r != PRT_OK) return r;
  }
  return PRT_OK;
}

/* The section with the technique's tag (tags are unique after structure validation), if this
 * reader knows its layout version: an optional section of an unknown version passes validation
 * unchecked, so the technique treats it as absent rather than read it. */
static const prt_asset_section* find_section(const prt_asset_section* sections, uint32_t count,
                                             uint32_t tag) {
  uint32_t i;
  for (i = 0; i < count; ++i)
    if (sections[i].entry.tag == tag)
      return prt_blob_find_kind(tag, sections[i].entry.layout_version) ? &sections[i] : NULL;
  return NULL;
}

prt_result prt_internal_open_views(const prt_allocator* allocator,
                                   const prt_asset_section* sections, uint32_t section_count,
                                   int keep, void* views[PRT_INTERNAL_MAX_TECHNIQUES], char* msg,
                                   size_t capacity) {
  size_t i;
  for (i = 0; i < PRT_INTERNAL_MAX_TECHNIQUES; ++i) views[i] = NULL;
  for (i = 0; i < TECHNIQUE_COUNT; ++i) {
    const prt_technique_entry* t = kTechniques[i];
    const prt_asset_section* s = find_section(sections, section_count, t->section_tag);
    void* view;
    prt_result r;
    if (!s || !s->decoded) continue;
    view = prt_internal_alloc(allocator, t->view_size, 16);
    if (!view) {
      prt_internal_free_views(allocator, views);
      snprintf(msg, capacity, "out of memory for the '%s' section's view", t->name);
      return PRT_ERROR_OUT_OF_MEMORY;
    }
    memset(view, 0, t->view_size); /* release hooks read what open left unset as empty */
    views[t->technique] = view;
    r = t->open(s, view, msg, capacity);
    if (r != PRT_OK) {
      prt_internal_free_views(allocator, views);
      return r;
    }
  }
  if (!keep) prt_internal_free_views(allocator, views);
  return PRT_OK;
}

prt_result prt_technique_get_info(prt_technique technique, prt_technique_info* out) {
  const prt_technique_entry* t = prt_internal_technique(technique);
  const prt_blob_kind* kind;
  prt_technique_info info;
  if (!out || !prt_internal_struct_size_ok(out, PRT_TECHNIQUE_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (!t) return PRT_ERROR_NOT_FOUND;
  memset(&info, 0, sizeof info);
  info.struct_size = sizeof info;
  info.technique = t->technique;
  info.name = t->name;
  info.section_tag = t->section_tag;
  kind = prt_blob_find_kind(t->section_tag, PRT_BLOB_LAYOUT_VERSION_1);
  info.domain = kind ? (prt_element_domain)kind->domain : PRT_ELEMENT_DOMAIN_NONE;
  prt_internal_write_struct(out, &info, sizeof info);
  return PRT_OK;
}

uint32_t prt_asset_techniques(const prt_asset* asset) {
  uint32_t set = 0;
  size_t i;
  if (!asset) return 0;
  for (i = 0; i < TECHNIQUE_COUNT; ++i)
    if (asset->views[kTechniques[i]->technique]) set |= 1u << kTechniques[i]->technique;
  return set;
}
