/* SPDX-License-Identifier: MIT */
/* The SCNE content check (formats/SPEC.md §7.6, full validation). A scene manifest names files:
 * the path rules keep every blob inside the manifest's folder on every platform, whatever the
 * loader does with the path. */
#include "scene_section.h"

#include <inttypes.h>

#include <prt/format/scene_layout.h>

#include "../mesh/mesh_sections.h"
#include "../reader_internal.h"

#define FAIL_CORRUPT(...) prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'SCNE': " __VA_ARGS__)
#define FAIL_NON_FINITE(...) prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap, "'SCNE': " __VA_ARGS__)

/* Every header field, the exact size and the element count; on success *h is filled. */
static prt_blob_status check_header(const prt_blob_content* content, prt_blob_scne_header* h,
                                    char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  const size_t n = content->size;
  uint64_t raw;
  if (n < PRT_BLOB_SCNE_HEADER_SIZE)
    return FAIL_CORRUPT("%zu bytes cannot hold the 16-byte header", n);
  prt_blob_scne_read_header(p, h);
  if (h->objects > PRT_BLOB_SCNE_MAX_OBJECTS)
    return FAIL_CORRUPT("%" PRIu32 " objects (must be at most 65536)", h->objects);
  if (h->record_size < PRT_BLOB_SCNE_RECORD_SIZE || h->record_size % 16u != 0u)
    return FAIL_CORRUPT("record size %" PRIu32 " (must be a multiple of 16, at least 96)",
                        h->record_size);
  if (prt_le_load_u32(p + PRT_BLOB_SCNE_OFF_RESERVED) != 0u)
    return FAIL_CORRUPT("reserved header field is not zero");
  raw = prt_blob_scne_raw_size(h);
  if ((uint64_t)n != raw) return FAIL_CORRUPT("%zu raw bytes, the header implies %" PRIu64, n, raw);
  if ((uint64_t)h->objects != content->section->element_count)
    return FAIL_CORRUPT("header says %" PRIu32 " objects, element count %" PRIu64, h->objects,
                        content->section->element_count);
  return PRT_BLOB_OK;
}

/* A string's size in 1..max and its bytes inside the string table. */
static prt_blob_status check_range(uint32_t i, const char* field, uint32_t offset, uint32_t size,
                                   uint32_t max, uint32_t string_size, char* msg, size_t cap) {
  if (size < 1u || size > max)
    return FAIL_CORRUPT("object %" PRIu32 ": %s size %" PRIu32 " (must be 1..%" PRIu32 ")", i,
                        field, size, max);
  if ((uint64_t)offset + size > string_size)
    return FAIL_CORRUPT("object %" PRIu32 ": %s bytes %" PRIu32 "..%" PRIu64
                        " are not in the %" PRIu32 "-byte string table",
                        i, field, offset, (uint64_t)offset + size - 1u, string_size);
  return PRT_BLOB_OK;
}

/* No NUL byte (readers hand the strings on NUL-terminated) and well-formed UTF-8. */
static prt_blob_status check_text(uint32_t i, const char* field, const uint8_t* s, uint32_t n,
                                  char* msg, size_t cap) {
  uint32_t k;
  size_t bad;
  for (k = 0; k < n; ++k)
    if (s[k] == 0u)
      return FAIL_CORRUPT("object %" PRIu32 ": %s has a NUL byte (byte %" PRIu32 ")", i, field, k);
  bad = prt_blob_utf8_error(s, n);
  if (bad < n) return FAIL_CORRUPT("object %" PRIu32 ": %s is not UTF-8 (byte %zu)", i, field, bad);
  return PRT_BLOB_OK;
}

/* A relative '/'-separated path that stays below the manifest's folder: no backslash (a separator
 * on Windows), no ':' (drive letters, URLs, NTFS streams), no leading '/', and no component that
 * is empty, "." or "..". */
static prt_blob_status check_path(uint32_t i, const uint8_t* s, uint32_t n, char* msg, size_t cap) {
  uint32_t k, start;
  const prt_blob_status st = check_text(i, "blob path", s, n, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  for (k = 0; k < n; ++k) {
    if (s[k] == '\\')
      return FAIL_CORRUPT("object %" PRIu32 ": blob path has a backslash (byte %" PRIu32 ")", i, k);
    if (s[k] == ':')
      return FAIL_CORRUPT("object %" PRIu32 ": blob path has a ':' (byte %" PRIu32 ")", i, k);
  }
  if (s[0] == '/') return FAIL_CORRUPT("object %" PRIu32 ": blob path starts with '/'", i);
  for (start = 0, k = 0; k <= n; ++k) {
    uint32_t len;
    if (k < n && s[k] != '/') continue;
    len = k - start;
    if (len == 0u)
      return FAIL_CORRUPT("object %" PRIu32 ": blob path has an empty component (byte %" PRIu32 ")",
                          i, start);
    if ((len == 1u && s[start] == '.') || (len == 2u && s[start] == '.' && s[start + 1] == '.'))
      return FAIL_CORRUPT("object %" PRIu32 ": blob path has a '%s' component (byte %" PRIu32 ")",
                          i, len == 1u ? "." : "..", start);
    start = k + 1u;
  }
  return PRT_BLOB_OK;
}

/* Record i: its fields in the record's order, then its strings and its rest matrix. */
static prt_blob_status check_record(const uint8_t* p, const prt_blob_scne_header* h, uint32_t i,
                                    char* msg, size_t cap) {
  const uint8_t* record = p + PRT_BLOB_SCNE_HEADER_SIZE + (uint64_t)h->record_size * i;
  const uint8_t* strings = p + prt_blob_scne_strings(h);
  prt_blob_scne_record r;
  prt_blob_status st;
  int k;
  prt_blob_scne_read_record(p, h, i, &r);
  for (k = 0; k < 4; ++k) {
    const uint32_t byte = (r.technique >> (8 * k)) & 0xFFu;
    if (byte < 0x20u || byte > 0x7Eu)
      return FAIL_CORRUPT("object %" PRIu32 ": technique tag 0x%08" PRIX32
                          " is not four printable ASCII characters",
                          i, r.technique);
  }
  if (r.flags != 0u)
    return FAIL_CORRUPT("object %" PRIu32 ": unknown flags 0x%" PRIx32, i, r.flags);
  if (prt_le_load_u32(record + PRT_BLOB_SCNE_REC_RESERVED) != 0u)
    return FAIL_CORRUPT("object %" PRIu32 ": reserved field is not zero", i);
  st = check_range(i, "name", r.name_offset, r.name_size, PRT_BLOB_SCNE_MAX_NAME, h->string_size,
                   msg, cap);
  if (st == PRT_BLOB_OK)
    st = check_range(i, "blob path", r.blob_offset, r.blob_size, PRT_BLOB_SCNE_MAX_PATH,
                     h->string_size, msg, cap);
  if (st == PRT_BLOB_OK) st = check_text(i, "name", strings + r.name_offset, r.name_size, msg, cap);
  if (st == PRT_BLOB_OK) st = check_path(i, strings + r.blob_offset, r.blob_size, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  for (k = 0; k < 16; ++k)
    if (!prt_blob_f32_is_finite(r.rest[k]))
      return FAIL_NON_FINITE("object %" PRIu32 ": rest matrix element %d is not finite", i, k);
  /* Column-major: the last row is elements 3, 7, 11, 15. A rest placement is affine. */
  if (r.rest[3] != 0.0f || r.rest[7] != 0.0f || r.rest[11] != 0.0f || r.rest[15] != 1.0f)
    return FAIL_CORRUPT(
        "object %" PRIu32 ": rest matrix's last row is (%g, %g, %g, %g), not (0, 0, 0, 1)", i,
        (double)r.rest[3], (double)r.rest[7], (double)r.rest[11], (double)r.rest[15]);
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_scne(const prt_blob_content* content, char* msg, size_t cap) {
  prt_blob_scne_header h = {0u, 0u, 0u};
  uint32_t i;
  prt_blob_status st = check_header(content, &h, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  for (i = 0; i < h.objects; ++i) {
    st = check_record(content->bytes, &h, i, msg, cap);
    if (st != PRT_BLOB_OK) return st;
  }
  return PRT_BLOB_OK;
}
