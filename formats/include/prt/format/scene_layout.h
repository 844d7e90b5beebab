/* SPDX-License-Identifier: MIT */
/* The scene manifest section SCNE, layout version 1 (formats/SPEC.md §7.6): what `prt-bake scene`
 * baked, one record per object (its technique, name, blob file and rest placement), then a table
 * of the records' strings. A scene manifest is a blob whose only known sections are SCNE and an
 * optional INFO; each object's data is in a blob of its own, named by a path relative to the
 * manifest's folder. Element = object (element count = object count); the raw size follows from
 * the header. Plain C99, pure functions. */
#ifndef PRT_FORMAT_SCENE_LAYOUT_H
#define PRT_FORMAT_SCENE_LAYOUT_H

#include <prt/format/blob_layout.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRT_BLOB_TAG_SCNE PRT_BLOB_TAG('S', 'C', 'N', 'E')

#define PRT_BLOB_SCNE_HEADER_SIZE 16u
#define PRT_BLOB_SCNE_OFF_OBJECTS 0u     /* u32: object count, 0..PRT_BLOB_SCNE_MAX_OBJECTS */
#define PRT_BLOB_SCNE_OFF_RECORD_SIZE 4u /* u32: bytes per record, >= 96, a multiple of 16 */
#define PRT_BLOB_SCNE_OFF_STRING_SIZE 8u /* u32: bytes of the string table */
#define PRT_BLOB_SCNE_OFF_RESERVED 12u   /* u32, zero */
#define PRT_BLOB_SCNE_MAX_OBJECTS 65536u

/* One record; a later layout may make records longer (readers skip bytes past these). */
#define PRT_BLOB_SCNE_RECORD_SIZE 96u
#define PRT_BLOB_SCNE_REC_TECHNIQUE 0u    /* u32: the tag of the technique section of its blob */
#define PRT_BLOB_SCNE_REC_FLAGS 4u        /* u32: zero in layout 1 */
#define PRT_BLOB_SCNE_REC_NAME_OFFSET 8u  /* u32: into the string table */
#define PRT_BLOB_SCNE_REC_NAME_SIZE 12u   /* u32: 1..PRT_BLOB_SCNE_MAX_NAME bytes of UTF-8 */
#define PRT_BLOB_SCNE_REC_BLOB_OFFSET 16u /* u32: into the string table */
#define PRT_BLOB_SCNE_REC_BLOB_SIZE 20u   /* u32: 1..PRT_BLOB_SCNE_MAX_PATH bytes */
#define PRT_BLOB_SCNE_REC_NODE 24u        /* u32: the glTF node, 0xFFFFFFFF for none */
#define PRT_BLOB_SCNE_REC_RESERVED 28u    /* u32, zero */
#define PRT_BLOB_SCNE_REC_REST 32u        /* f32[16]: column-major world matrix at rest */
#define PRT_BLOB_SCNE_MAX_NAME 255u
#define PRT_BLOB_SCNE_MAX_PATH 1024u
#define PRT_BLOB_SCNE_NO_NODE 0xFFFFFFFFu

/* The header fields, as stored. */
typedef struct prt_blob_scne_header {
  uint32_t objects;
  uint32_t record_size;
  uint32_t string_size;
} prt_blob_scne_header;

/* One record's fields, as stored; the strings are byte ranges of the string table. */
typedef struct prt_blob_scne_record {
  uint32_t technique;
  uint32_t flags;
  uint32_t name_offset, name_size;
  uint32_t blob_offset, blob_size;
  uint32_t node;
  float rest[16];
} prt_blob_scne_record;

static inline float prt_blob_scne_load_f32(const uint8_t* p) {
  const uint32_t bits = prt_le_load_u32(p);
  float f;
  memcpy(&f, &bits, sizeof f);
  return f;
}

static inline void prt_blob_scne_read_header(const uint8_t* p, prt_blob_scne_header* out) {
  out->objects = prt_le_load_u32(p + PRT_BLOB_SCNE_OFF_OBJECTS);
  out->record_size = prt_le_load_u32(p + PRT_BLOB_SCNE_OFF_RECORD_SIZE);
  out->string_size = prt_le_load_u32(p + PRT_BLOB_SCNE_OFF_STRING_SIZE);
}

/* The section's raw size for these header fields (64-bit: no overflow for any u32 fields). */
static inline uint64_t prt_blob_scne_raw_size(const prt_blob_scne_header* h) {
  return (uint64_t)PRT_BLOB_SCNE_HEADER_SIZE + (uint64_t)h->objects * h->record_size +
         h->string_size;
}

/* Byte offset of the string table in the section. */
static inline uint64_t prt_blob_scne_strings(const prt_blob_scne_header* h) {
  return (uint64_t)PRT_BLOB_SCNE_HEADER_SIZE + (uint64_t)h->objects * h->record_size;
}

/* Reads record i (< h->objects) of a section whose raw size the header matches. */
static inline void prt_blob_scne_read_record(const uint8_t* section, const prt_blob_scne_header* h,
                                             uint32_t i, prt_blob_scne_record* out) {
  const uint8_t* p = section + PRT_BLOB_SCNE_HEADER_SIZE + (size_t)i * h->record_size;
  int k;
  out->technique = prt_le_load_u32(p + PRT_BLOB_SCNE_REC_TECHNIQUE);
  out->flags = prt_le_load_u32(p + PRT_BLOB_SCNE_REC_FLAGS);
  out->name_offset = prt_le_load_u32(p + PRT_BLOB_SCNE_REC_NAME_OFFSET);
  out->name_size = prt_le_load_u32(p + PRT_BLOB_SCNE_REC_NAME_SIZE);
  out->blob_offset = prt_le_load_u32(p + PRT_BLOB_SCNE_REC_BLOB_OFFSET);
  out->blob_size = prt_le_load_u32(p + PRT_BLOB_SCNE_REC_BLOB_SIZE);
  out->node = prt_le_load_u32(p + PRT_BLOB_SCNE_REC_NODE);
  for (k = 0; k < 16; ++k)
    out->rest[k] = prt_blob_scne_load_f32(p + PRT_BLOB_SCNE_REC_REST + 4 * k);
}

#ifdef __cplusplus
}
#endif

#endif /* PRT_FORMAT_SCENE_LAYOUT_H */
