/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the `shadowfield` view the load keeps on an asset (its SFLD header,
 * checked at open, and the object decoded at attach) and the accessor the scene code reads the
 * object through. */
#ifndef PRT_RUNTIME_SHADOWFIELD_ASSET_INTERNAL_H
#define PRT_RUNTIME_SHADOWFIELD_ASSET_INTERNAL_H

#include <prt/format/shadowfield_layout.h>

#include "internal.h"
#include "shadowfield_object.h"

typedef struct prt_sf_view {
  prt_shadowfield_info info;
  prt_blob_sfld_layout layout;
  const uint8_t* data;  /* the SFLD section's decoded bytes */
  prt_sf_object object; /* every array points into `floats` once attached */
  float* floats;        /* owned, from the context's allocator; NULL before attach */
  size_t float_count;
} prt_sf_view;

/* The technique entry's attach and release hooks (shadowfield_asset.c): decode the object,
 * copying the mesh from VPOS and VNRM, into one allocation; free it. */
prt_result prt_sf_attach(const prt_context* context, const prt_allocator* allocator,
                         const prt_asset_section* sections, uint32_t section_count, void* view,
                         char* msg, size_t capacity);
void prt_sf_release(const prt_allocator* allocator, void* view);

/* The object of a loaded `shadowfield` asset, NULL for NULL or an asset without SFLD. Valid as
 * long as the asset; read-only, so any thread may read it. */
const prt_sf_object* prt_internal_sf_object(const prt_asset* asset);

#endif /* PRT_RUNTIME_SHADOWFIELD_ASSET_INTERNAL_H */
