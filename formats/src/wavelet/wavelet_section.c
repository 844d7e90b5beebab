/* SPDX-License-Identifier: MIT */
/* The WVLT content check (formats/SPEC.md §7.2, full validation). */
#include "wavelet_section.h"

#include <inttypes.h>

#include <prt/format/wavelet_layout.h>

#include "../reader_internal.h"

/* Band and vertex scales of a WVLT section: finite and >= 0. */
static prt_blob_status check_wvlt_scales(const uint8_t* p, const prt_blob_wvlt_layout* l,
                                         uint32_t vertices, char* msg, size_t cap) {
  uint32_t k, v, c;
  for (k = 0; k < l->bands; ++k) {
    float scale = prt_blob_load_f32(p + l->band_scale + 4u * k);
    if (!prt_blob_f32_is_finite(scale))
      return prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap,
                           "'WVLT': band scale %" PRIu32 " is not finite", k);
    if (scale < 0.0f)
      return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': band scale %" PRIu32 " is negative",
                           k);
  }
  for (v = 0; v < vertices; ++v)
    for (c = 0; c < 3; ++c) {
      float scale = prt_blob_load_f32(p + l->vertex_scale + 12u * (uint64_t)v + 4u * c);
      if (!prt_blob_f32_is_finite(scale))
        return prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap,
                             "'WVLT': vertex %" PRIu32 " scale %" PRIu32 " is not finite", v, c);
      if (scale < 0.0f)
        return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                             "'WVLT': vertex %" PRIu32 " scale %" PRIu32 " is negative", v, c);
    }
  return PRT_BLOB_OK;
}

/* One block's pairs: indices strictly increasing, values in -127..127 and not 0. */
static prt_blob_status check_wvlt_block(const uint8_t* pairs, uint32_t count, uint32_t v,
                                        uint32_t k, char* msg, size_t cap) {
  uint32_t i;
  for (i = 0; i < count; ++i) {
    uint8_t value = pairs[2u * i + 1u];
    if (i > 0 && pairs[2u * i] <= pairs[2u * i - 2u])
      return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                           "'WVLT': vertex %" PRIu32 " block %" PRIu32
                           ": index %u follows %u (indices must strictly increase)",
                           v, k, (unsigned)pairs[2u * i], (unsigned)pairs[2u * i - 2u]);
    if (value == 0u || value == 0x80u)
      return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                           "'WVLT': vertex %" PRIu32 " block %" PRIu32
                           " index %u: value %d is not allowed",
                           v, k, (unsigned)pairs[2u * i], value == 0u ? 0 : -128);
  }
  return PRT_BLOB_OK;
}

/* Row starts, block counts and pairs of a WVLT section (sizes already checked). */
static prt_blob_status check_wvlt_rows(const uint8_t* p, const prt_blob_wvlt_layout* l,
                                       uint32_t vertices, uint32_t pair_count, char* msg,
                                       size_t cap) {
  uint32_t v, k;
  if (prt_le_load_u32(p + l->row_start) != 0)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': row start of vertex 0 is not 0");
  for (v = 0; v < vertices; ++v) {
    const uint32_t start = prt_le_load_u32(p + l->row_start + 4u * (uint64_t)v);
    const uint32_t end = prt_le_load_u32(p + l->row_start + 4u * ((uint64_t)v + 1u));
    const uint8_t* counts = p + l->counts + 2u * (uint64_t)v * l->blocks;
    uint64_t at = start; /* <= pair_count: checked for the previous vertex (or 0) */
    if (end < start || end > pair_count)
      return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                           "'WVLT': row starts of vertex %" PRIu32 " (%" PRIu32 " .. %" PRIu32
                           ") are not increasing within the %" PRIu32 " pairs",
                           v, start, end, pair_count);
    for (k = 0; k < l->blocks; ++k) {
      const uint32_t count = prt_le_load_u16(counts + 2u * k);
      prt_blob_status st;
      if (count > PRT_BLOB_WVLT_BLOCK)
        return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                             "'WVLT': vertex %" PRIu32 " block %" PRIu32 " counts %" PRIu32
                             " non-zeros (at most 256)",
                             v, k, count);
      if (at + count > end)
        return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                             "'WVLT': vertex %" PRIu32 " block %" PRIu32
                             ": block counts exceed the row's %" PRIu32 " pairs",
                             v, k, end - start);
      st = check_wvlt_block(p + l->pairs + 2u * at, count, v, k, msg, cap);
      if (st != PRT_BLOB_OK) return st;
      at += count;
    }
    if (at != end)
      return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                           "'WVLT': vertex %" PRIu32 ": block counts sum to %" PRIu64
                           " but the row has %" PRIu32 " pairs",
                           v, at - start, end - start);
  }
  return PRT_BLOB_OK;
}

/* Param, face size, quantiser, reserved word and vertex count; on success *h and *l are filled. */
static prt_blob_status check_wvlt_header(const prt_blob_content* content, prt_blob_wvlt_header* h,
                                         prt_blob_wvlt_layout* l, char* msg, size_t cap) {
  prt_blob_wvlt_read_header(content->bytes, h);
  if (h->param != PRT_BLOB_WVLT_PARAM_CUBE && h->param != PRT_BLOB_WVLT_PARAM_DUAL_PARABOLOID)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': param %" PRIu32 " is not 0 or 1",
                         h->param);
  if (!prt_blob_wvlt_layout_of(h->param, h->size, h->vertices, h->pair_count, l))
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "'WVLT': face size %" PRIu32 " is not a power of two in 16..128", h->size);
  if (h->quantizer != PRT_BLOB_WVLT_QUANTIZER_VERTEX &&
      h->quantizer != PRT_BLOB_WVLT_QUANTIZER_BAND)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': quantizer %" PRIu32 " is not 0 or 1",
                         h->quantizer);
  if (h->reserved != 0)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': reserved header field is not zero");
  if ((uint64_t)h->vertices != content->vertex_count ||
      (uint64_t)h->vertices != content->section->element_count)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "'WVLT': header says %" PRIu32 " vertices, element count %" PRIu64
                         ", 'VPOS' has %" PRIu64,
                         h->vertices, content->section->element_count, content->vertex_count);
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_wvlt(const prt_blob_content* content, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  const size_t n = content->size;
  prt_blob_wvlt_header h = {0};
  prt_blob_wvlt_layout l = {0};
  prt_blob_status st;
  if (n < PRT_BLOB_WVLT_HEADER_SIZE)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "'WVLT': %zu bytes cannot hold the 32-byte header", n);
  st = check_wvlt_header(content, &h, &l, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  if ((uint64_t)n != l.raw_size)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "'WVLT': %zu raw bytes, the header implies %" PRIu64, n, l.raw_size);
  if (!prt_blob_bytes_are_zero(p + l.payload_end, (size_t)(l.raw_size - l.payload_end)))
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'WVLT': padding is not zero");
  if (prt_le_load_u32(p + l.row_start + 4u * (uint64_t)h.vertices) != h.pair_count)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "'WVLT': the last row start is not the pair count %" PRIu32, h.pair_count);
  st = check_wvlt_scales(p, &l, h.vertices, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  return check_wvlt_rows(p, &l, h.vertices, h.pair_count, msg, cap);
}
