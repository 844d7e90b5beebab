/* SPDX-License-Identifier: MIT */
/* prtkit blob container, format 1.x: the byte layout shared by the writer and the reader
 * (header, section table, codecs, tags, byte order, checksum). The layout of each section kind's
 * payload has its own header (mesh_layout.h, sh_layout.h, wavelet_layout.h).
 *
 * Normative description: formats/SPEC.md. Everything is little-endian and read or written byte
 * by byte through the helpers below, so parsing never depends on host alignment or endianness.
 * Plain C99, no dependencies. All functions here are pure and thread-safe. */
#ifndef PRT_FORMAT_BLOB_LAYOUT_H
#define PRT_FORMAT_BLOB_LAYOUT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Version ------------------------------------------------------------------------------ */

#define PRT_BLOB_MAGIC_0 'P'
#define PRT_BLOB_MAGIC_1 'R'
#define PRT_BLOB_MAGIC_2 'T'
#define PRT_BLOB_MAGIC_3 'K'
#define PRT_BLOB_VERSION_MAJOR 1 /* a reader accepts exactly this major version */
#define PRT_BLOB_VERSION_MINOR 0 /* ... and any minor version (newer ones too) */

/* ---- Header (64 bytes at offset 0) ----------------------------------------------------------- */

#define PRT_BLOB_HEADER_SIZE 64u
#define PRT_BLOB_ALIGNMENT 16u
#define PRT_BLOB_PRODUCER_SIZE 16u
#define PRT_BLOB_RESERVED_SIZE 8u

#define PRT_BLOB_OFF_MAGIC 0u          /* u8[4] "PRTK" */
#define PRT_BLOB_OFF_VERSION_MAJOR 4u  /* u16 */
#define PRT_BLOB_OFF_VERSION_MINOR 6u  /* u16 */
#define PRT_BLOB_OFF_HEADER_SIZE 8u    /* u32, >= 64, multiple of 16 */
#define PRT_BLOB_OFF_FLAGS 12u         /* u32, see PRT_BLOB_FLAGS_* */
#define PRT_BLOB_OFF_TOTAL_SIZE 16u    /* u64, the size of the whole blob */
#define PRT_BLOB_OFF_TABLE_OFFSET 24u  /* u64, where the section table starts */
#define PRT_BLOB_OFF_SECTION_COUNT 32u /* u32 */
#define PRT_BLOB_OFF_CHECKSUM 36u      /* u32, CRC-32C of header (this field as 0) + table */
#define PRT_BLOB_OFF_PRODUCER 40u      /* u8[16], opaque id of the writing tool */
#define PRT_BLOB_OFF_RESERVED 56u      /* u8[8], zero */

/* Header flags. Bits 0-15 are critical: a reader rejects a blob with a critical bit it does not
 * know. Bits 16-31 are informational and ignored when unknown. Format 1.0 defines none. */
#define PRT_BLOB_FLAGS_CRITICAL_MASK 0x0000FFFFu
#define PRT_BLOB_FLAGS_KNOWN 0u

/* Upper bound on section_count; keeps the table small and its size far from overflow. */
#define PRT_BLOB_MAX_SECTIONS 4096u

/* ---- Section table entry (48 bytes each, section_count of them) ----------------------------- */

#define PRT_BLOB_SECTION_ENTRY_SIZE 48u
#define PRT_BLOB_SEC_OFF_TAG 0u            /* u8[4] four-character code */
#define PRT_BLOB_SEC_OFF_FLAGS 4u          /* u16, see PRT_BLOB_SECTION_* */
#define PRT_BLOB_SEC_OFF_CODEC 6u          /* u8, PRT_BLOB_CODEC_* */
#define PRT_BLOB_SEC_OFF_LAYOUT_VERSION 7u /* u8, version of this tag's payload layout */
#define PRT_BLOB_SEC_OFF_CHECKSUM 8u       /* u32, CRC-32C of the stored bytes */
#define PRT_BLOB_SEC_OFF_RESERVED 12u      /* u32, zero */
#define PRT_BLOB_SEC_OFF_OFFSET 16u        /* u64, from the start of the blob, 16-byte aligned */
#define PRT_BLOB_SEC_OFF_STORED_SIZE 24u   /* u64, bytes in the blob */
#define PRT_BLOB_SEC_OFF_RAW_SIZE 32u      /* u64, bytes after decoding */
#define PRT_BLOB_SEC_OFF_ELEMENT_COUNT 40u /* u64, elements of the tag's element type */

#define PRT_BLOB_SECTION_REQUIRED 0x0001u /* a reader that does not know the tag must reject */
#define PRT_BLOB_SECTION_FLAGS_KNOWN 0x0001u

#define PRT_BLOB_CODEC_NONE 0u /* stored bytes are the raw bytes */
#define PRT_BLOB_CODEC_ZSTD 1u /* stored bytes are one zstd frame */

/* A zstd block decodes to at most 128 KiB and costs at least 4 stored bytes, so no valid frame
 * expands by more than this factor; a larger raw_size claim is rejected before allocating. */
#define PRT_BLOB_ZSTD_MAX_RATIO 32768u
/* Smallest possible zstd frame: 4-byte magic, 2-byte frame header, 3-byte empty last block. */
#define PRT_BLOB_ZSTD_MIN_FRAME 9u

/* ---- Section tags ------------------------------------------------------------------------- */

/* A tag is the four ASCII characters in file order, read as a little-endian u32. */
#define PRT_BLOB_TAG(a, b, c, d)                                                             \
  ((uint32_t)(uint8_t)(a) | ((uint32_t)(uint8_t)(b) << 8) | ((uint32_t)(uint8_t)(c) << 16) | \
   ((uint32_t)(uint8_t)(d) << 24))

#define PRT_BLOB_LAYOUT_VERSION_1 1u /* the layout version of every 1.0 kind */

/* ---- Little-endian load/store, byte by byte ------------------------------------------------- */

static inline uint16_t prt_le_load_u16(const uint8_t* p) {
  return (uint16_t)(p[0] | (p[1] << 8));
}
static inline uint32_t prt_le_load_u32(const uint8_t* p) {
  return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}
static inline uint64_t prt_le_load_u64(const uint8_t* p) {
  return (uint64_t)prt_le_load_u32(p) | ((uint64_t)prt_le_load_u32(p + 4) << 32);
}
static inline void prt_le_store_u16(uint8_t* p, uint16_t v) {
  p[0] = (uint8_t)v;
  p[1] = (uint8_t)(v >> 8);
}
static inline void prt_le_store_u32(uint8_t* p, uint32_t v) {
  p[0] = (uint8_t)v;
  p[1] = (uint8_t)(v >> 8);
  p[2] = (uint8_t)(v >> 16);
  p[3] = (uint8_t)(v >> 24);
}
static inline void prt_le_store_u64(uint8_t* p, uint64_t v) {
  prt_le_store_u32(p, (uint32_t)v);
  prt_le_store_u32(p + 4, (uint32_t)(v >> 32));
}

/* ---- CRC-32C (Castagnoli) ------------------------------------------------------------------- */

/* CRC-32C: reflected polynomial 0x82F63B78, initial value 0xFFFFFFFF, final xor 0xFFFFFFFF
 * (the iSCSI / ext4 checksum). crc32c("123456789") == 0xE3069283.
 * Chain calls by passing the previous result as crc; start with crc = 0. */
uint32_t prt_crc32c(uint32_t crc, const void* data, size_t size);

#ifdef __cplusplus
}
#endif

/* The layouts of the 1.0 section kinds, one header per kind family (section_kinds.h lists the
 * kinds). Included here so that code including only this header keeps finding them; a new kind's
 * header is included by name where it is used. */
#include <prt/format/mesh_layout.h>
#include <prt/format/sh_layout.h>
#include <prt/format/wavelet_layout.h>

#endif /* PRT_FORMAT_BLOB_LAYOUT_H */
