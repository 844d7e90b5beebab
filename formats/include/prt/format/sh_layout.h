/* SPDX-License-Identifier: MIT */
/* The `sh` transfer section SHTR, layout version 1 (formats/SPEC.md §7.1): a 32-byte header,
 * one (offset, scale) f32 pair per channel and coefficient, then the quantised values,
 * vertex-major. Element = vertex; the raw size follows from the header (prt_blob_shtr_layout_of).
 * Plain C99, pure functions. */
#ifndef PRT_FORMAT_SH_LAYOUT_H
#define PRT_FORMAT_SH_LAYOUT_H

#include <prt/format/blob_layout.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRT_BLOB_TAG_SHTR PRT_BLOB_TAG('S', 'H', 'T', 'R')

#define PRT_BLOB_SHTR_HEADER_SIZE 32u
#define PRT_BLOB_SHTR_MAX_ORDER 16u
#define PRT_BLOB_SHTR_OFF_ORDER 0u     /* u32: SH order n, 1..16 (n^2 coefficients) */
#define PRT_BLOB_SHTR_OFF_VERTICES 4u  /* u32: V = VPOS element count */
#define PRT_BLOB_SHTR_OFF_CHANNELS 8u  /* u32: 1 grey (used for R, G and B) or 3 RGB */
#define PRT_BLOB_SHTR_OFF_BITS 12u     /* u32: bits per quantised value, 8 or 16 */
#define PRT_BLOB_SHTR_OFF_KIND 16u     /* u32, informational: PRT_BLOB_SHTR_KIND_* */
#define PRT_BLOB_SHTR_OFF_BOUNCES 20u  /* u32, informational */
#define PRT_BLOB_SHTR_OFF_RESERVED 24u /* u32[2], zero */
#define PRT_BLOB_SHTR_RESERVED_SIZE 8u
#define PRT_BLOB_SHTR_PARAM_SIZE 8u /* f32 offset, f32 scale per channel and coefficient */
#define PRT_BLOB_SHTR_KIND_UNSHADOWED 0u
#define PRT_BLOB_SHTR_KIND_SHADOWED 1u
#define PRT_BLOB_SHTR_KIND_INTERREFLECTED 2u

/* The header fields, as stored. */
typedef struct prt_blob_shtr_header {
  uint32_t order;
  uint32_t vertices;
  uint32_t channels;
  uint32_t bits;
  uint32_t kind;
  uint32_t bounces;
} prt_blob_shtr_header;

/* Reads the header from the section's first PRT_BLOB_SHTR_HEADER_SIZE bytes (the caller checks
 * that they are there). The reserved words are not part of it. */
static inline void prt_blob_shtr_read_header(const uint8_t* p, prt_blob_shtr_header* out) {
  out->order = prt_le_load_u32(p + PRT_BLOB_SHTR_OFF_ORDER);
  out->vertices = prt_le_load_u32(p + PRT_BLOB_SHTR_OFF_VERTICES);
  out->channels = prt_le_load_u32(p + PRT_BLOB_SHTR_OFF_CHANNELS);
  out->bits = prt_le_load_u32(p + PRT_BLOB_SHTR_OFF_BITS);
  out->kind = prt_le_load_u32(p + PRT_BLOB_SHTR_OFF_KIND);
  out->bounces = prt_le_load_u32(p + PRT_BLOB_SHTR_OFF_BOUNCES);
}

/* Where the parts of a SHTR section lie, from its header fields; offsets in bytes from the
 * section's first byte. Pair j (j = c n^2 + k, channel c, coefficient k) is at
 * params + 8 j; the value of vertex v and pair j at values + (v coefficients + j) value_size. */
typedef struct prt_blob_shtr_layout {
  uint32_t coefficients; /* C n^2 (offset, scale) pairs, and values per vertex */
  uint32_t value_size;   /* bytes per quantised value: bits / 8 */
  uint64_t params;       /* f32[coefficients][2]: offset, scale */
  uint64_t values;       /* u8 or u16 [V][coefficients] */
  uint64_t payload_end;  /* values + V coefficients value_size */
  uint64_t raw_size;     /* payload_end rounded up to a multiple of 4 */
} prt_blob_shtr_layout;

/* Fills *out for an order in 1..16, 1 or 3 channels and 8 or 16 bits and returns 1; returns 0
 * (out untouched) otherwise. With coefficients <= 768 and V < 2^32 nothing overflows 64 bits. */
static inline int prt_blob_shtr_layout_of(uint32_t order, uint32_t vertices, uint32_t channels,
                                          uint32_t bits, prt_blob_shtr_layout* out) {
  if (order < 1u || order > PRT_BLOB_SHTR_MAX_ORDER) return 0;
  if (channels != 1u && channels != 3u) return 0;
  if (bits != 8u && bits != 16u) return 0;
  out->coefficients = channels * order * order;
  out->value_size = bits / 8u;
  out->params = PRT_BLOB_SHTR_HEADER_SIZE;
  out->values = out->params + PRT_BLOB_SHTR_PARAM_SIZE * (uint64_t)out->coefficients;
  out->payload_end = out->values + (uint64_t)vertices * out->coefficients * out->value_size;
  out->raw_size = (out->payload_end + 3u) & ~(uint64_t)3u;
  return 1;
}

#ifdef __cplusplus
}
#endif

#endif /* PRT_FORMAT_SH_LAYOUT_H */
