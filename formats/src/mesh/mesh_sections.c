/* SPDX-License-Identifier: MIT */
/* The mesh kinds' content checks (formats/SPEC.md §7, full validation). */
#include "mesh_sections.h"

#include <inttypes.h>

#include "../reader_internal.h"

/* Length of the well-formed UTF-8 sequence at p (n bytes left), or 0 if it is malformed. */
static size_t utf8_sequence_length(const uint8_t* p, size_t n) {
  uint32_t cp;
  size_t len, k;
  if (p[0] < 0x80) return 1;
  if (p[0] >= 0xC2 && p[0] <= 0xDF)
    len = 2, cp = p[0] & 0x1Fu;
  else if (p[0] >= 0xE0 && p[0] <= 0xEF)
    len = 3, cp = p[0] & 0x0Fu;
  else if (p[0] >= 0xF0 && p[0] <= 0xF4)
    len = 4, cp = p[0] & 0x07u;
  else
    return 0;
  if (len > n) return 0;
  for (k = 1; k < len; ++k) {
    if ((p[k] & 0xC0u) != 0x80u) return 0;
    cp = (cp << 6) | (p[k] & 0x3Fu);
  }
  if ((len == 3 && cp < 0x800) || (len == 4 && cp < 0x10000) || cp > 0x10FFFF ||
      (cp >= 0xD800 && cp <= 0xDFFF))
    return 0; /* overlong, out of range or a surrogate */
  return len;
}

size_t prt_blob_utf8_error(const uint8_t* p, size_t n) {
  size_t i;
  for (i = 0; i < n;) {
    size_t len = utf8_sequence_length(p + i, n - i);
    if (len == 0) return i;
    i += len;
  }
  return n;
}

prt_blob_status prt_blob_check_info(const prt_blob_content* content, char* msg, size_t cap) {
  const size_t bad = prt_blob_utf8_error(content->bytes, content->size);
  if (bad < content->size)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'INFO' is not UTF-8 (byte %zu)", bad);
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_finite_f32(const prt_blob_content* content, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  size_t i;
  for (i = 0; i + 4 <= content->size; i += 4) {
    uint32_t bits = prt_le_load_u32(p + i);
    if ((bits & 0x7F800000u) == 0x7F800000u) { /* exponent all ones: Inf or NaN */
      char name[5];
      prt_blob_tag_string(content->section->tag, name);
      return prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap,
                           "'%s': float %zu (element %zu) is not finite", name, i / 4, i / 12);
    }
  }
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_tris(const prt_blob_content* content, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  size_t i;
  for (i = 0; i + 4 <= content->size; i += 4) {
    uint32_t index = prt_le_load_u32(p + i);
    if ((uint64_t)index >= content->vertex_count)
      return prt_blob_fail(PRT_BLOB_INDEX_OUT_OF_RANGE, msg, cap,
                           "'TRIS': index %" PRIu32
                           " of triangle %zu is not below the vertex count %" PRIu64,
                           index, i / 12, content->vertex_count);
  }
  return PRT_BLOB_OK;
}
