/* SPDX-License-Identifier: MIT */
/* The fabric queries of prt_cloth_asset.h on the CLTH view the load checked (cloth_section.c):
 * the header, each fabric's name, default parameters, weave and table bytes, and a fabric by
 * name. Read-only on the asset, no allocation. */
#include <string.h>

#include "cloth_internal.h"
#include "techniques.h"

/* The CLTH view the load decoded, NULL without a CLTH section. */
static const prt_cloth_view* cloth_view(const prt_asset* asset) {
  return (const prt_cloth_view*)prt_internal_view(asset, PRT_TECHNIQUE_CLOTH);
}

prt_result prt_cloth_get_info(const prt_asset* asset, prt_cloth_info* out_info) {
  const prt_cloth_view* view;
  if (!asset || !out_info || !prt_internal_struct_size_ok(out_info, PRT_CLOTH_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  view = cloth_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  prt_internal_write_struct(out_info, &view->info, sizeof view->info);
  return PRT_OK;
}

/* The bytes of the distinct tables the fabric's tangent records name (T and T_c each). */
static size_t fabric_table_bytes(const prt_cloth_view* view, const prt_cloth_fabric_record* f) {
  uint32_t seen[2u * PRT_BLOB_CLTH_MAX_THREAD_TANGENTS];
  uint32_t seen_count = 0, j, k, s;
  uint64_t bytes = 0;
  for (j = 0; j < 2u; ++j)
    for (k = 0; k < f->tangent_count[j]; ++k) {
      prt_cloth_tangent_record t;
      prt_cloth_read_tangent(view, f->first_tangent[j] + k, &t);
      for (s = 0; s < seen_count; ++s)
        if (seen[s] == t.table) break;
      if (s < seen_count) continue; /* counted already */
      seen[seen_count++] = t.table;
      bytes += prt_blob_clth_factor_size(&view->layout, view->factor_rank[t.table][0]) +
               prt_blob_clth_factor_size(&view->layout, view->factor_rank[t.table][1]);
    }
  return (size_t)bytes;
}

prt_result prt_cloth_get_fabric(const prt_asset* asset, uint32_t fabric, const char** out_name,
                                prt_cloth_params* out_params, prt_cloth_weave* out_weave,
                                size_t* out_table_bytes) {
  const prt_cloth_view* view;
  prt_cloth_fabric_record record;
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  if (out_params && !prt_internal_struct_size_ok(out_params, PRT_CLOTH_PARAMS_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (out_weave && !prt_internal_struct_size_ok(out_weave, PRT_CLOTH_WEAVE_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  view = cloth_view(asset);
  if (!view || fabric >= view->info.fabric_count) return PRT_ERROR_NOT_FOUND;
  prt_cloth_read_fabric(view, fabric, &record);
  if (out_name) *out_name = view->names[fabric];
  if (out_params) prt_internal_write_struct(out_params, &record.params, sizeof record.params);
  if (out_weave) {
    prt_cloth_weave weave;
    prt_cloth_fabric_weave(view, &record, &weave);
    prt_internal_write_struct(out_weave, &weave, sizeof weave);
  }
  if (out_table_bytes) *out_table_bytes = fabric_table_bytes(view, &record);
  return PRT_OK;
}

prt_result prt_cloth_find_fabric(const prt_asset* asset, const char* name, uint32_t* out_fabric) {
  const prt_cloth_view* view;
  uint32_t f;
  if (!asset || !name || !out_fabric) return PRT_ERROR_INVALID_ARGUMENT;
  view = cloth_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  for (f = 0; f < view->info.fabric_count; ++f)
    if (strcmp(view->names[f], name) == 0) {
      *out_fabric = f;
      return PRT_OK;
    }
  return PRT_ERROR_NOT_FOUND;
}
