/* SPDX-License-Identifier: MIT */
/* The `wavelet` transfer section WVLT, layout version 1 (formats/SPEC.md §7.2): a 32-byte
 * header, band and vertex scales, row starts, u16 block counts and (u8 index, i8 value) pairs.
 * Element = vertex; the raw size follows from the header (prt_blob_wvlt_layout_of). Plain C99,
 * pure functions. */
#ifndef PRT_FORMAT_WAVELET_LAYOUT_H
#define PRT_FORMAT_WAVELET_LAYOUT_H

#include <prt/format/blob_layout.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRT_BLOB_TAG_WVLT PRT_BLOB_TAG('W', 'V', 'L', 'T')

#define PRT_BLOB_WVLT_HEADER_SIZE 32u
#define PRT_BLOB_WVLT_BLOCK 256u        /* coefficients per block; also the most non-zeros in one */
#define PRT_BLOB_WVLT_OFF_PARAM 0u      /* u32: PRT_BLOB_WVLT_PARAM_* */
#define PRT_BLOB_WVLT_OFF_SIZE 4u       /* u32: face size S, power of two 16..128 */
#define PRT_BLOB_WVLT_OFF_VERTICES 8u   /* u32: V = VPOS element count */
#define PRT_BLOB_WVLT_OFF_QUANTIZER 12u /* u32: PRT_BLOB_WVLT_QUANTIZER_* */
#define PRT_BLOB_WVLT_OFF_KEEP 16u      /* u32, informational */
#define PRT_BLOB_WVLT_OFF_BOUNCES 20u   /* u32, informational */
#define PRT_BLOB_WVLT_OFF_PAIR_COUNT 24u /* u32: P, total stored non-zeros */
#define PRT_BLOB_WVLT_OFF_RESERVED 28u   /* u32, zero */
#define PRT_BLOB_WVLT_PARAM_CUBE 0u
#define PRT_BLOB_WVLT_PARAM_DUAL_PARABOLOID 1u
#define PRT_BLOB_WVLT_CUBE_FACES 6u
#define PRT_BLOB_WVLT_DUAL_PARABOLOID_FACES 2u
#define PRT_BLOB_WVLT_QUANTIZER_VERTEX 0u /* one scale per vertex (the report's scheme) */
#define PRT_BLOB_WVLT_QUANTIZER_BAND 1u   /* one scale per face and wavelet level */
#define PRT_BLOB_WVLT_MIN_SIZE 16u
#define PRT_BLOB_WVLT_MAX_SIZE 128u

/* The header fields, as stored. */
typedef struct prt_blob_wvlt_header {
  uint32_t param;
  uint32_t size;
  uint32_t vertices;
  uint32_t quantizer;
  uint32_t keep;
  uint32_t bounces;
  uint32_t pair_count;
  uint32_t reserved;
} prt_blob_wvlt_header;

/* Reads the header from the section's first PRT_BLOB_WVLT_HEADER_SIZE bytes (the caller checks
 * that they are there). */
static inline void prt_blob_wvlt_read_header(const uint8_t* p, prt_blob_wvlt_header* out) {
  out->param = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_PARAM);
  out->size = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_SIZE);
  out->vertices = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_VERTICES);
  out->quantizer = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_QUANTIZER);
  out->keep = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_KEEP);
  out->bounces = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_BOUNCES);
  out->pair_count = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_PAIR_COUNT);
  out->reserved = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_RESERVED);
}

/* Where the parts of a WVLT section lie, from its header fields; all offsets in bytes from the
 * section's first byte. With V < 2^32, P < 2^32 and at most 384 blocks nothing overflows 64 bits.
 */
typedef struct prt_blob_wvlt_layout {
  uint32_t faces;        /* F: 6 cube, 2 dual paraboloid */
  uint32_t bands;        /* F * (log2 S + 1) band scales */
  uint32_t coefficients; /* F * S^2 per row */
  uint32_t blocks;       /* B = coefficients / 256 per row */
  uint64_t band_scale;   /* f32[bands] */
  uint64_t vertex_scale; /* f32[V][3] */
  uint64_t row_start;    /* u32[V + 1] */
  uint64_t counts;       /* u16[V][B] */
  uint64_t pairs;        /* u8[P][2] */
  uint64_t payload_end;  /* pairs + 2 P */
  uint64_t raw_size;     /* payload_end rounded up to a multiple of 4 */
} prt_blob_wvlt_layout;

/* Fills *out for valid param and size and returns 1; returns 0 (out untouched) otherwise. */
static inline int prt_blob_wvlt_layout_of(uint32_t param, uint32_t size, uint32_t vertices,
                                          uint32_t pair_count, prt_blob_wvlt_layout* out) {
  uint32_t log2_size = 0;
  if (param != PRT_BLOB_WVLT_PARAM_CUBE && param != PRT_BLOB_WVLT_PARAM_DUAL_PARABOLOID) return 0;
  if (size < PRT_BLOB_WVLT_MIN_SIZE || size > PRT_BLOB_WVLT_MAX_SIZE || (size & (size - 1u)) != 0)
    return 0;
  while ((1u << log2_size) < size) ++log2_size;
  out->faces = param == PRT_BLOB_WVLT_PARAM_CUBE ? PRT_BLOB_WVLT_CUBE_FACES
                                                 : PRT_BLOB_WVLT_DUAL_PARABOLOID_FACES;
  out->bands = out->faces * (log2_size + 1u);
  out->coefficients = out->faces * size * size;
  out->blocks = out->coefficients / PRT_BLOB_WVLT_BLOCK;
  out->band_scale = PRT_BLOB_WVLT_HEADER_SIZE;
  out->vertex_scale = out->band_scale + 4u * (uint64_t)out->bands;
  out->row_start = out->vertex_scale + 12u * (uint64_t)vertices;
  out->counts = out->row_start + 4u * ((uint64_t)vertices + 1u);
  out->pairs = out->counts + 2u * (uint64_t)vertices * out->blocks;
  out->payload_end = out->pairs + 2u * (uint64_t)pair_count;
  out->raw_size = (out->payload_end + 3u) & ~(uint64_t)3u;
  return 1;
}

#ifdef __cplusplus
}
#endif

#endif /* PRT_FORMAT_WAVELET_LAYOUT_H */
