/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield` in the runtime's technique table: the SFLD header checked against the
 * section at load (either validation level) by the formats layer's own header check, the view
 * the object is decoded into, and the ties of the sdk's constants and structs to the formats
 * layer's. */
#include <stdio.h>

#include "shadowfield_asset_internal.h"
#include "techniques.h"

PRT_STATIC_ASSERT(PRT_SECTION_SFLD == PRT_BLOB_TAG_SFLD, tag_sfld);
PRT_STATIC_ASSERT(sizeof(prt_shadowfield_shells) == sizeof(prt_sf_shells), shells_size);
PRT_STATIC_ASSERT(offsetof(prt_shadowfield_shells, radius) == offsetof(prt_sf_shells, radius) &&
                      offsetof(prt_shadowfield_shells, shells) == offsetof(prt_sf_shells, shells) &&
                      offsetof(prt_shadowfield_shells, face_size) ==
                          offsetof(prt_sf_shells, face_size),
                  shells_fields);

static void copy_shells(const prt_sf_shells* in, prt_shadowfield_shells* out) {
  memcpy(out, in, sizeof *out);
}

/* Every header field and the exact size, as full validation checks them (the same function), with
 * CORRUPT for every failure; VPOS's vertex count is compared at attach, where the mesh is seen. */
static prt_result open_sfld(const prt_asset_section* section, void* out, char* msg,
                            size_t capacity) {
  prt_sf_view* view = (prt_sf_view*)out;
  prt_blob_sfld_header h;
  if (prt_blob_sfld_check_header(section->data, (size_t)section->entry.raw_size,
                                 section->entry.element_count, UINT64_MAX, &view->layout, msg,
                                 capacity) != PRT_BLOB_OK)
    return PRT_ERROR_CORRUPT;
  prt_blob_sfld_read_header(section->data, &h);
  view->data = section->data;
  view->info.struct_size = sizeof view->info;
  view->info.order = h.order;
  view->info.terms = h.terms;
  view->info.glossy = h.glossy;
  view->info.vertex_count = h.vertices;
  view->info.basis_size = h.basis_size;
  view->info.brdf_grid = h.brdf_grid;
  copy_shells(&h.oof_shells, &view->info.oof_shells);
  copy_shells(&h.srf_shells, &view->info.srf_shells);
  view->info.bits = h.bits;
  view->info.bytes = section->entry.raw_size;
  return PRT_OK;
}

extern const struct prt_scene_hooks prt_shadowfield_scene_hooks; /* shadowfield_scene_hooks.c */

const prt_technique_entry prt_shadowfield_technique_entry = {
    PRT_TECHNIQUE_SHADOWFIELD,
    "shadowfield",
    PRT_BLOB_TAG_SFLD,
    sizeof(prt_sf_view),
    open_sfld,
    prt_sf_attach,
    prt_sf_release,
    &prt_shadowfield_scene_hooks,
};
