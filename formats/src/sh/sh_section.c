/* SPDX-License-Identifier: MIT */
/* The SHTR content check (formats/SPEC.md §7.1, full validation). */
#include "sh_section.h"

#include <inttypes.h>

#include <prt/format/sh_layout.h>

#include "../reader_internal.h"

/* Order, channels, bits, reserved words and vertex count; on success *layout is filled. */
static prt_blob_status check_header(const prt_blob_content* content, prt_blob_shtr_layout* layout,
                                    char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  prt_blob_shtr_header h;
  prt_blob_shtr_read_header(p, &h);
  if (h.order < 1 || h.order > PRT_BLOB_SHTR_MAX_ORDER)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': order %" PRIu32 " is not in 1..16",
                         h.order);
  if (h.channels != 1 && h.channels != 3)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "'SHTR': %" PRIu32 " channels (must be 1 or 3)", h.channels);
  if (h.bits != 8 && h.bits != 16)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': %" PRIu32 " bits (must be 8 or 16)",
                         h.bits);
  if (!prt_blob_bytes_are_zero(p + PRT_BLOB_SHTR_OFF_RESERVED, PRT_BLOB_SHTR_RESERVED_SIZE))
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': reserved header fields are not zero");
  if ((uint64_t)h.vertices != content->vertex_count ||
      (uint64_t)h.vertices != content->section->element_count)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "'SHTR': header says %" PRIu32 " vertices, element count %" PRIu64
                         ", 'VPOS' has %" PRIu64,
                         h.vertices, content->section->element_count, content->vertex_count);
  prt_blob_shtr_layout_of(h.order, h.vertices, h.channels, h.bits, layout); /* valid fields */
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_shtr(const prt_blob_content* content, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  const size_t n = content->size;
  prt_blob_shtr_layout l = {0};
  prt_blob_status st;
  uint32_t j;
  if (n < PRT_BLOB_SHTR_HEADER_SIZE)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "'SHTR': %zu bytes cannot hold the 32-byte header", n);
  st = check_header(content, &l, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  if ((uint64_t)n != l.raw_size)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "'SHTR': %zu raw bytes, the header implies %" PRIu64, n, l.raw_size);
  if (!prt_blob_bytes_are_zero(p + l.payload_end, (size_t)(l.raw_size - l.payload_end)))
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'SHTR': padding is not zero");
  for (j = 0; j < l.coefficients; ++j) {
    const uint8_t* pair = p + l.params + PRT_BLOB_SHTR_PARAM_SIZE * j;
    float offset = prt_blob_load_f32(pair);
    float scale = prt_blob_load_f32(pair + 4u);
    if (!prt_blob_f32_is_finite(offset) || !prt_blob_f32_is_finite(scale))
      return prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap,
                           "'SHTR': offset or scale of coefficient %" PRIu32 " is not finite", j);
    if (scale < 0.0f)
      return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                           "'SHTR': scale of coefficient %" PRIu32 " is negative", j);
  }
  return PRT_BLOB_OK;
}
