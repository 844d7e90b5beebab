/* SPDX-License-Identifier: MIT */
/* Loading and validating blobs: validate the structure, then (full) checksums, then decode
 * compressed sections, then (full) check the decoded contents. No pointer into the blob is formed
 * before prt_blob_validate_structure() has accepted every offset and size. */
#include <stdio.h>
#include <string.h>

#include "internal.h"
#include "techniques.h"

typedef enum storage_mode {
  STORAGE_COPY,   /* copy the caller's bytes */
  STORAGE_BORROW, /* read the caller's bytes in place */
  STORAGE_ADOPT   /* bytes already allocated with the context's allocator (file loading) */
} storage_mode;

/* Vertex count for index checks: the element count of a known VPOS section, else 0. */
static uint64_t vertex_count(const uint8_t* bytes, const prt_blob_header* h) {
  uint32_t i;
  for (i = 0; i < h->section_count; ++i) {
    prt_blob_section s;
    prt_blob_read_section(bytes, h, i, &s);
    if (s.tag == PRT_BLOB_TAG_VPOS && prt_blob_find_kind(s.tag, s.layout_version))
      return s.element_count;
  }
  return 0;
}

/* Decodes section `s` into a new buffer (zstd) or points into the blob (none). */
static prt_result decode_section(const prt_allocator* allocator, const uint8_t* bytes,
                                 const prt_blob_section* s, prt_asset_section* out, char* msg,
                                 size_t cap) {
  char name[5];
  prt_result r;
  out->entry = *s;
  out->owned = NULL;
  out->data = NULL;
  out->decoded = 1;
  if (s->codec == PRT_BLOB_CODEC_NONE) {
    if (s->raw_size > 0) out->data = bytes + s->offset;
    return PRT_OK;
  }
  /* zstd: raw_size fits size_t and is bounded by the stored size (structure validation). Even an
   * empty section must hold one well-formed frame, so it is decoded too. */
  out->owned = (uint8_t*)prt_internal_alloc(allocator, (size_t)s->raw_size, 16);
  if (!out->owned) {
    prt_blob_tag_string(s->tag, name);
    snprintf(msg, cap, "section '%s': out of memory for %zu decoded bytes", name,
             (size_t)s->raw_size);
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  r = prt_internal_zstd_decode(allocator, bytes + s->offset, (size_t)s->stored_size, out->owned,
                               (size_t)s->raw_size, msg, cap);
  if (r != PRT_OK) {
    size_t used = strlen(msg);
    prt_blob_tag_string(s->tag, name);
    if (used + 16 < cap) { /* name the section after the zstd detail */
      snprintf(msg + used, cap - used, " in section '%s'", name);
    }
    prt_internal_free(allocator, out->owned, (size_t)s->raw_size);
    out->owned = NULL;
    return r;
  }
  if (s->raw_size > 0) {
    out->data = out->owned;
  } else { /* nothing to expose: keep the contract "NULL when empty" */
    prt_internal_free(allocator, out->owned, 0);
    out->owned = NULL;
  }
  return PRT_OK;
}

static void free_sections(const prt_allocator* allocator, prt_asset_section* sections,
                          uint32_t count) {
  uint32_t i;
  if (!sections) return;
  for (i = 0; i < count; ++i)
    prt_internal_free(allocator, sections[i].owned, (size_t)sections[i].entry.raw_size);
  prt_internal_free(allocator, sections, (size_t)count * sizeof *sections);
}

/* What check_and_decode does with the sections once the structure has been checked. */
typedef enum decode_mode {
  DECODE_KEEP,         /* load: decode every section and open the technique views, keep both */
  DECODE_CHECK,        /* full validation: decode and check every section, keep nothing */
  DECODE_IN_PLACE_ONLY /* quick validation: only what needs no decompression, keep nothing */
} decode_mode;

/* Reads and (DECODE_KEEP, DECODE_CHECK) decodes every section, checking the decoded contents at
 * full validation. */
static prt_result decode_sections(const prt_allocator* allocator, const uint8_t* bytes,
                                  const prt_blob_header* h, prt_validation validation,
                                  decode_mode mode, prt_asset_section* sections, char* msg,
                                  size_t cap) {
  const uint64_t vertices = vertex_count(bytes, h);
  uint32_t i;
  for (i = 0; i < h->section_count; ++i) {
    prt_blob_section s;
    prt_result r = PRT_OK;
    prt_blob_read_section(bytes, h, i, &s);
    if (mode == DECODE_IN_PLACE_ONLY && s.codec != PRT_BLOB_CODEC_NONE) {
      sections[i].entry = s; /* left undecoded: its technique header is checked at load */
      continue;
    }
    r = decode_section(allocator, bytes, &s, &sections[i], msg, cap);
    if (r == PRT_OK && validation == PRT_VALIDATE_FULL)
      r = (prt_result)prt_blob_check_content(&s, sections[i].data, vertices, msg, cap);
    if (r != PRT_OK) return r;
  }
  return PRT_OK;
}

/* Every check and every decode; on PRT_OK with DECODE_KEEP, *out_sections holds the decoded
 * sections (caller frees with free_sections) and views[] the technique views (caller frees with
 * prt_internal_free_views). Other modes keep nothing. */
static prt_result check_and_decode(const prt_allocator* allocator, const uint8_t* bytes,
                                   size_t size, prt_validation validation, decode_mode mode,
                                   prt_blob_header* h, prt_asset_section** out_sections,
                                   void* views[PRT_INTERNAL_MAX_TECHNIQUES], char* msg,
                                   size_t cap) {
  prt_asset_section* sections = NULL;
  prt_result r;
  *out_sections = NULL;
  memset(views, 0, PRT_INTERNAL_MAX_TECHNIQUES * sizeof views[0]);
  r = (prt_result)prt_blob_validate_structure(bytes, size, h, msg, cap);
  if (r != PRT_OK) return r;
  if (validation == PRT_VALIDATE_FULL) {
    r = (prt_result)prt_blob_verify_checksums(bytes, h, msg, cap);
    if (r != PRT_OK) return r;
  }
  if (h->section_count > 0) {
    sections = (prt_asset_section*)prt_internal_alloc(
        allocator, (size_t)h->section_count * sizeof *sections, 16);
    if (!sections) {
      snprintf(msg, cap, "out of memory for %u sections", (unsigned)h->section_count);
      return PRT_ERROR_OUT_OF_MEMORY;
    }
    memset(sections, 0, (size_t)h->section_count * sizeof *sections);
  }
  r = decode_sections(allocator, bytes, h, validation, mode, sections, msg, cap);
  if (r == PRT_OK)
    r = prt_internal_open_views(allocator, sections, h->section_count, mode == DECODE_KEEP, views,
                                msg, cap);
  if (r == PRT_OK && mode == DECODE_KEEP) {
    *out_sections = sections;
  } else {
    free_sections(allocator, sections, h->section_count);
  }
  return r;
}

static prt_result load(prt_context* context, const void* data, size_t size,
                       prt_validation validation, storage_mode mode, const char* what,
                       prt_asset** out_asset) {
  const prt_allocator* allocator;
  char msg[PRT_MESSAGE_CAPACITY - 64];
  const uint8_t* bytes = (const uint8_t*)data;
  uint8_t* copy = NULL;
  prt_asset_section* sections = NULL;
  void* views[PRT_INTERNAL_MAX_TECHNIQUES];
  prt_blob_header h;
  prt_asset* asset;
  prt_result r;
  if (out_asset) *out_asset = NULL;
  if (!context || !out_asset || (!data && size > 0) ||
      (validation != PRT_VALIDATE_QUICK && validation != PRT_VALIDATE_FULL))
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT, "%s: invalid argument", what);
  if (mode == STORAGE_BORROW && ((uintptr_t)data % PRT_BLOB_ALIGNMENT) != 0)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "%s: borrowed blob must be 16-byte aligned", what);
  allocator = &context->allocator;
  msg[0] = '\0';
  if (mode == STORAGE_COPY) {
    /* Copy first, then validate what the asset keeps. */
    copy = (uint8_t*)prt_internal_alloc(allocator, size, PRT_BLOB_ALIGNMENT);
    if (!copy)
      return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory (%zu bytes)",
                               what, size);
    if (size > 0) memcpy(copy, bytes, size);
    bytes = copy;
  } else if (mode == STORAGE_ADOPT) {
    copy = (uint8_t*)data;
  }
  r = check_and_decode(allocator, bytes, size, validation, DECODE_KEEP, &h, &sections, views, msg,
                       sizeof msg);
  if (r == PRT_OK)
    r = prt_internal_attach_views(context, allocator, sections, h.section_count, views, msg,
                                  sizeof msg);
  asset = r == PRT_OK ? (prt_asset*)prt_internal_alloc(allocator, sizeof *asset, 16) : NULL;
  if (!asset) {
    if (r == PRT_OK) {
      r = PRT_ERROR_OUT_OF_MEMORY;
      snprintf(msg, sizeof msg, "out of memory");
    }
    if (sections) {
      prt_internal_free_views(allocator, views);
      free_sections(allocator, sections, h.section_count);
    }
    if (mode == STORAGE_COPY) prt_internal_free(allocator, copy, size);
    return prt_internal_fail(context, r, "%s: %s", what, msg);
  }
  asset->context = context;
  asset->allocator = *allocator;
  asset->header = h;
  asset->bytes = bytes;
  asset->owned_bytes = copy;
  asset->size = size;
  asset->sections = sections;
  memcpy(asset->views, views, sizeof asset->views);
  *out_asset = asset;
  return PRT_OK;
}

prt_result prt_asset_load_memory(prt_context* context, const void* data, size_t size,
                                 prt_validation validation, prt_asset** out_asset) {
  return load(context, data, size, validation, STORAGE_COPY, "prt_asset_load_memory", out_asset);
}

prt_result prt_asset_load_memory_borrowed(prt_context* context, const void* data, size_t size,
                                          prt_validation validation, prt_asset** out_asset) {
  return load(context, data, size, validation, STORAGE_BORROW, "prt_asset_load_memory_borrowed",
              out_asset);
}

/* Reads a whole file into memory from the context's allocator. */
static prt_result read_file(prt_context* context, const char* path, uint8_t** out_bytes,
                            size_t* out_size) {
  FILE* f = fopen(path, "rb");
  long length;
  uint8_t* bytes;
  *out_bytes = NULL;
  *out_size = 0;
  if (!f)
    return prt_internal_fail(context, PRT_ERROR_IO, "prt_asset_load_file: cannot open '%s'", path);
  /* A directory opens on some systems but cannot be read; find out before sizing it. */
  if (fgetc(f) == EOF && ferror(f)) {
    fclose(f);
    return prt_internal_fail(context, PRT_ERROR_IO, "prt_asset_load_file: cannot read '%s'", path);
  }
  if (fseek(f, 0, SEEK_END) != 0 || (length = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
    fclose(f);
    return prt_internal_fail(context, PRT_ERROR_IO, "prt_asset_load_file: cannot size '%s'", path);
  }
  bytes = (uint8_t*)prt_internal_alloc(&context->allocator, (size_t)length, PRT_BLOB_ALIGNMENT);
  if (!bytes) {
    fclose(f);
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY,
                             "prt_asset_load_file: out of memory for '%s' (%ld bytes)", path,
                             length);
  }
  if (fread(bytes, 1, (size_t)length, f) != (size_t)length) {
    fclose(f);
    prt_internal_free(&context->allocator, bytes, (size_t)length);
    return prt_internal_fail(context, PRT_ERROR_IO, "prt_asset_load_file: cannot read '%s'", path);
  }
  fclose(f);
  *out_bytes = bytes;
  *out_size = (size_t)length;
  return PRT_OK;
}

prt_result prt_asset_load_file(prt_context* context, const char* path, prt_validation validation,
                               prt_asset** out_asset) {
  uint8_t* bytes;
  size_t size;
  prt_result r;
  char what[PRT_MESSAGE_CAPACITY / 2];
  if (out_asset) *out_asset = NULL;
  if (!context || !path || !out_asset)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_asset_load_file: invalid argument");
  r = read_file(context, path, &bytes, &size);
  if (r != PRT_OK) return r;
  snprintf(what, sizeof what, "prt_asset_load_file: '%s'", path);
  r = load(context, bytes, size, validation, STORAGE_ADOPT, what, out_asset);
  if (r != PRT_OK) prt_internal_free(&context->allocator, bytes, size);
  return r;
}

void prt_asset_destroy(prt_asset* asset) {
  prt_allocator allocator;
  if (!asset) return;
  allocator = asset->allocator;
  prt_internal_free_views(&allocator, asset->views);
  free_sections(&allocator, asset->sections, asset->header.section_count);
  prt_internal_free(&allocator, asset->owned_bytes, asset->size);
  prt_internal_free(&allocator, asset, sizeof *asset);
}

prt_result prt_asset_validate(prt_context* context, const void* data, size_t size,
                              prt_validation validation, char* message, size_t capacity) {
  char msg[PRT_MESSAGE_CAPACITY - 64];
  prt_asset_section* sections = NULL;
  void* views[PRT_INTERNAL_MAX_TECHNIQUES];
  prt_blob_header h;
  prt_result r;
  if (message && capacity > 0) message[0] = '\0';
  if (!context || (!data && size > 0) ||
      (validation != PRT_VALIDATE_QUICK && validation != PRT_VALIDATE_FULL)) {
    if (message && capacity > 0) snprintf(message, capacity, "invalid argument");
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_asset_validate: invalid argument");
  }
  msg[0] = '\0';
  r = check_and_decode(&context->allocator, (const uint8_t*)data, size, validation,
                       validation == PRT_VALIDATE_FULL ? DECODE_CHECK : DECODE_IN_PLACE_ONLY, &h,
                       &sections, views, msg, sizeof msg);
  if (r != PRT_OK) {
    if (message && capacity > 0) snprintf(message, capacity, "%s", msg);
    return prt_internal_fail(context, r, "prt_asset_validate: %s", msg);
  }
  if (message && capacity > 0)
    snprintf(message, capacity, "valid (%s): format %u.%u, %u sections, %zu bytes",
             validation == PRT_VALIDATE_FULL ? "full" : "quick", (unsigned)h.version_major,
             (unsigned)h.version_minor, (unsigned)h.section_count, size);
  return PRT_OK;
}
