/* SPDX-License-Identifier: MIT */
/* Read-only queries on a loaded asset; they never write the context (thread-safe). */
#include <string.h>

#include "internal.h"
#include "techniques.h"

prt_result prt_asset_get_info(const prt_asset* asset, prt_asset_info* out) {
  prt_asset_info info;
  if (!asset || !out || !prt_internal_struct_size_ok(out, PRT_ASSET_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  memset(&info, 0, sizeof info);
  info.struct_size = sizeof info;
  info.format_major = asset->header.version_major;
  info.format_minor = asset->header.version_minor;
  info.flags = asset->header.flags;
  info.section_count = asset->header.section_count;
  info.total_size = asset->header.total_size;
  memcpy(info.producer, asset->header.producer, sizeof info.producer);
  info.borrowed = asset->owned_bytes == NULL;
  prt_internal_write_struct(out, &info, sizeof info);
  return PRT_OK;
}

uint32_t prt_asset_section_count(const prt_asset* asset) {
  return asset ? asset->header.section_count : 0;
}

prt_result prt_asset_get_section_info(const prt_asset* asset, uint32_t index,
                                      prt_section_info* out) {
  const prt_blob_section* s;
  const prt_blob_kind* kind;
  const prt_technique_entry* technique;
  prt_section_info info;
  if (!asset || !out || !prt_internal_struct_size_ok(out, PRT_SECTION_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (index >= asset->header.section_count) return PRT_ERROR_NOT_FOUND;
  s = &asset->sections[index].entry;
  memset(&info, 0, sizeof info);
  info.struct_size = sizeof info;
  info.tag = s->tag;
  info.flags = s->flags;
  info.codec = (prt_codec)s->codec;
  info.layout_version = s->layout_version;
  kind = prt_blob_find_kind(s->tag, s->layout_version);
  info.known = kind != NULL;
  info.checksum = s->checksum;
  info.offset = s->offset;
  info.stored_size = s->stored_size;
  info.raw_size = s->raw_size;
  info.element_count = s->element_count;
  info.domain = kind ? (prt_element_domain)kind->domain : PRT_ELEMENT_DOMAIN_NONE;
  technique = kind ? prt_internal_technique_of_tag(s->tag) : NULL;
  info.technique = technique ? technique->technique : PRT_TECHNIQUE_NONE;
  prt_internal_write_struct(out, &info, sizeof info);
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
