/* SPDX-License-Identifier: MIT */
/* Read-only queries on a loaded asset; they never write the context (thread-safe). */
#include <string.h>

#include "internal.h"

prt_result prt_asset_get_info(const prt_asset* asset, prt_asset_info* out) {
  if (!asset || !out) return PRT_ERROR_INVALID_ARGUMENT;
  memset(out, 0, sizeof *out);
  out->format_major = asset->header.version_major;
  out->format_minor = asset->header.version_minor;
  out->flags = asset->header.flags;
  out->section_count = asset->header.section_count;
  out->total_size = asset->header.total_size;
  memcpy(out->producer, asset->header.producer, sizeof out->producer);
  out->borrowed = asset->owned_bytes == NULL;
  return PRT_OK;
}

uint32_t prt_asset_section_count(const prt_asset* asset) {
  return asset ? asset->header.section_count : 0;
}

prt_result prt_asset_get_section_info(const prt_asset* asset, uint32_t index,
                                      prt_section_info* out) {
  const prt_blob_section* s;
  if (!asset || !out) return PRT_ERROR_INVALID_ARGUMENT;
  if (index >= asset->header.section_count) return PRT_ERROR_NOT_FOUND;
  s = &asset->sections[index].entry;
  out->tag = s->tag;
  out->flags = s->flags;
  out->codec = (prt_codec)s->codec;
  out->layout_version = s->layout_version;
  out->known = prt_blob_find_kind(s->tag, s->layout_version) != NULL;
  out->checksum = s->checksum;
  out->offset = s->offset;
  out->stored_size = s->stored_size;
  out->raw_size = s->raw_size;
  out->element_count = s->element_count;
  return PRT_OK;
}

prt_result prt_asset_find_section(const prt_asset* asset, uint32_t tag, uint32_t* out_index) {
  uint32_t i;
  if (!asset || !out_index) return PRT_ERROR_INVALID_ARGUMENT;
  for (i = 0; i < asset->header.section_count; ++i)
    if (asset->sections[i].entry.tag == tag) {
      *out_index = i;
      return PRT_OK;
    }
  return PRT_ERROR_NOT_FOUND;
}

prt_result prt_asset_section_data(const prt_asset* asset, uint32_t tag, const void** out_data,
                                  size_t* out_size) {
  uint32_t index;
  prt_result r;
  if (!asset || !out_data || !out_size) return PRT_ERROR_INVALID_ARGUMENT;
  *out_data = NULL;
  *out_size = 0;
  r = prt_asset_find_section(asset, tag, &index);
  if (r != PRT_OK) return r;
  *out_data = asset->sections[index].data;
  *out_size = (size_t)asset->sections[index].entry.raw_size;
  return PRT_OK;
}

prt_result prt_asset_copy_section(const prt_asset* asset, uint32_t tag, void* dst, size_t capacity,
                                  size_t* out_size) {
  const void* data;
  size_t size;
  prt_result r;
  if (!asset || (!dst && capacity > 0)) return PRT_ERROR_INVALID_ARGUMENT;
  r = prt_asset_section_data(asset, tag, &data, &size);
  if (r != PRT_OK) return r;
  if (out_size) *out_size = size;
  if (size > capacity) return PRT_ERROR_BUFFER_TOO_SMALL;
  if (size > 0) memcpy(dst, data, size);
  return PRT_OK;
}
