/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the technique table. Each technique defines its entry in its own
 * folder (runtime/src/<t>/<t>_section.c); techniques.c declares and lists the entries once. Shared
 * code (loading, queries) loops over the table and never names a technique. */
#ifndef PRT_RUNTIME_TECHNIQUES_H
#define PRT_RUNTIME_TECHNIQUES_H

#include "internal.h"

typedef struct prt_technique_entry {
  prt_technique technique;
  const char* name;     /* folder, tool and document name */
  uint32_t section_tag; /* the technique's section kind (its domain: the formats kind table) */
  size_t view_size;     /* bytes of the view `open` fills, kept on the asset */
  /* Decodes the section's header and checks it against the section's size and element count,
   * in O(1), so that every later read of the technique stays inside the section whatever the
   * validation level: fills *view (view_size bytes, pointing into section->data), or returns
   * PRT_ERROR_CORRUPT with msg naming the field. */
  prt_result (*open)(const prt_asset_section* section, void* view, char* msg, size_t capacity);
  /* Optional (NULL: none): once the asset is loaded, may add runtime-owned data to its view from
   * the context's allocator (e.g. a layout the context's kernels read faster, or the technique's
   * data decoded together with the mesh sections among `sections`, all decoded): PRT_OK, also
   * when it adds nothing (the view works as opened), PRT_ERROR_OUT_OF_MEMORY, or
   * PRT_ERROR_CORRUPT with msg naming what does not match. */
  prt_result (*attach)(const prt_context* context, const prt_allocator* allocator,
                       const prt_asset_section* sections, uint32_t section_count, void* view,
                       char* msg, size_t capacity);
  /* Optional: frees what attach added; called on every view before it is freed (views start
   * zeroed, so a view attach never saw holds nothing to free). */
  void (*release)(const prt_allocator* allocator, void* view);
  /* Its part in a loaded scene (scene/scene_internal.h); NULL: a scene refuses its objects. */
  const struct prt_scene_hooks* scene;
} prt_technique_entry;

/* The entry of `technique`, NULL when this runtime does not implement it. */
const prt_technique_entry* prt_internal_technique(prt_technique technique);

/* The entry whose section has `tag`, NULL for a mesh section or an unknown tag. */
const prt_technique_entry* prt_internal_technique_of_tag(uint32_t tag);

/* Opens the view of every technique whose section is among `sections` (skipping zstd sections
 * left undecoded), allocated with `allocator` into views[technique]. With keep == 0 the views are
 * freed again (validation only). On failure nothing stays allocated and msg names the section and
 * the field. */
prt_result prt_internal_open_views(const prt_allocator* allocator,
                                   const prt_asset_section* sections, uint32_t section_count,
                                   int keep, void* views[PRT_INTERNAL_MAX_TECHNIQUES], char* msg,
                                   size_t capacity);

/* Runs every technique's attach hook on the views of a loaded asset, whose decoded sections are
 * `sections`; on failure msg names the technique (the caller frees the views). */
prt_result prt_internal_attach_views(const prt_context* context, const prt_allocator* allocator,
                                     const prt_asset_section* sections, uint32_t section_count,
                                     void* views[PRT_INTERNAL_MAX_TECHNIQUES], char* msg,
                                     size_t capacity);

/* Frees the views prt_internal_open_views kept (and what attach added). */
void prt_internal_free_views(const prt_allocator* allocator,
                             void* views[PRT_INTERNAL_MAX_TECHNIQUES]);

/* The view `technique`'s open hook filled for this asset, NULL when the blob has no such
 * section (its functions then return PRT_ERROR_NOT_FOUND). */
static inline const void* prt_internal_view(const prt_asset* asset, prt_technique technique) {
  return (unsigned)technique < PRT_INTERNAL_MAX_TECHNIQUES ? asset->views[technique] : NULL;
}

#endif /* PRT_RUNTIME_TECHNIQUES_H */
