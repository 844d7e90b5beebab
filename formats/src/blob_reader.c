/* SPDX-License-Identifier: MIT */
/* Bounds-checked reader core for the container (formats/SPEC.md §8): header, section table,
 * entries, canonical placement, checksums and padding. Offsets and sizes are checked as integers,
 * overflow-checked, before any pointer into the blob is formed from them. What a kind is (its
 * element size, the sections it needs, its content check) comes from the kind table
 * (section_kinds.c); no kind is named here. */
#include <prt/format/blob_reader.h>

#include <inttypes.h>
#include <string.h>

#include "reader_internal.h"

/* Fuzzing builds (formats/CMakeLists.txt) compute every checksum but accept a mismatch: a mutation
 * almost never keeps a CRC-32C right, so otherwise no mutated blob would reach the content checks
 * behind the checksums. Everything else is checked as always. */
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
#define CHECKSUMS_DIFFER(stored, computed) ((void)(stored), (void)(computed), 0)
#else
#define CHECKSUMS_DIFFER(stored, computed) ((stored) != (computed))
#endif

void prt_blob_tag_string(uint32_t tag, char out[5]) {
  int i;
  for (i = 0; i < 4; ++i) {
    char c = (char)((tag >> (8 * i)) & 0xFFu);
    out[i] = (c >= 0x20 && c <= 0x7E) ? c : '?';
  }
  out[4] = '\0';
}

/* *sum = a + b; returns 0 on overflow. */
static int add_u64(uint64_t a, uint64_t b, uint64_t* sum) {
  if (a > UINT64_MAX - b) return 0;
  *sum = a + b;
  return 1;
}

/* *product = a * b; returns 0 on overflow. */
static int mul_u64(uint64_t a, uint64_t b, uint64_t* product) {
  if (a != 0 && b > UINT64_MAX / a) return 0;
  *product = a * b;
  return 1;
}

/* *out = x rounded up to a multiple of 16; returns 0 on overflow. */
static int align16_u64(uint64_t x, uint64_t* out) {
  if (x > UINT64_MAX - (PRT_BLOB_ALIGNMENT - 1)) return 0;
  *out = (x + (PRT_BLOB_ALIGNMENT - 1)) & ~(uint64_t)(PRT_BLOB_ALIGNMENT - 1);
  return 1;
}

static void decode_header(const uint8_t* b, prt_blob_header* h) {
  h->version_major = prt_le_load_u16(b + PRT_BLOB_OFF_VERSION_MAJOR);
  h->version_minor = prt_le_load_u16(b + PRT_BLOB_OFF_VERSION_MINOR);
  h->header_size = prt_le_load_u32(b + PRT_BLOB_OFF_HEADER_SIZE);
  h->flags = prt_le_load_u32(b + PRT_BLOB_OFF_FLAGS);
  h->total_size = prt_le_load_u64(b + PRT_BLOB_OFF_TOTAL_SIZE);
  h->table_offset = prt_le_load_u64(b + PRT_BLOB_OFF_TABLE_OFFSET);
  h->section_count = prt_le_load_u32(b + PRT_BLOB_OFF_SECTION_COUNT);
  h->checksum = prt_le_load_u32(b + PRT_BLOB_OFF_CHECKSUM);
  memcpy(h->producer, b + PRT_BLOB_OFF_PRODUCER, PRT_BLOB_PRODUCER_SIZE);
}

/* Checks the fixed header against the byte count; on success the section table lies inside the
 * blob, starting at header_size. */
static prt_blob_status check_header(const uint8_t* b, size_t size, prt_blob_header* h, char* msg,
                                    size_t cap) {
  uint64_t table_bytes, table_end;
  if (size < 4)
    return prt_blob_fail(PRT_BLOB_TRUNCATED, msg, cap, "blob of %zu bytes is too short", size);
  if (b[0] != PRT_BLOB_MAGIC_0 || b[1] != PRT_BLOB_MAGIC_1 || b[2] != PRT_BLOB_MAGIC_2 ||
      b[3] != PRT_BLOB_MAGIC_3)
    return prt_blob_fail(PRT_BLOB_BAD_MAGIC, msg, cap, "not a prtkit blob (magic is not \"PRTK\")");
  if (size < PRT_BLOB_HEADER_SIZE)
    return prt_blob_fail(PRT_BLOB_TRUNCATED, msg, cap,
                         "blob of %zu bytes is shorter than its 64-byte header", size);
  decode_header(b, h);
  if (h->version_major != PRT_BLOB_VERSION_MAJOR)
    return prt_blob_fail(PRT_BLOB_UNSUPPORTED_VERSION, msg, cap,
                         "format version %u.%u is not supported (this reader reads %u.x)",
                         (unsigned)h->version_major, (unsigned)h->version_minor,
                         (unsigned)PRT_BLOB_VERSION_MAJOR);
  if (h->header_size < PRT_BLOB_HEADER_SIZE || h->header_size % PRT_BLOB_ALIGNMENT != 0)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "header size %" PRIu32 " is not a multiple of 16 >= 64", h->header_size);
  if (h->total_size > (uint64_t)size)
    return prt_blob_fail(PRT_BLOB_TRUNCATED, msg, cap,
                         "blob is truncated: header says %" PRIu64 " bytes, %zu present",
                         h->total_size, size);
  if (h->total_size < (uint64_t)size)
    return prt_blob_fail(PRT_BLOB_SIZE_MISMATCH, msg, cap,
                         "blob has %zu bytes but its header says %" PRIu64 " (extra bytes)", size,
                         h->total_size);
  if (h->header_size > h->total_size)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "header size %" PRIu32 " exceeds the blob size", h->header_size);
  if ((h->flags & PRT_BLOB_FLAGS_CRITICAL_MASK & ~PRT_BLOB_FLAGS_KNOWN) != 0)
    return prt_blob_fail(PRT_BLOB_UNSUPPORTED_FEATURE, msg, cap,
                         "unknown critical header flags 0x%04" PRIx32,
                         h->flags & PRT_BLOB_FLAGS_CRITICAL_MASK);
  if (!prt_blob_bytes_are_zero(b + PRT_BLOB_OFF_RESERVED, PRT_BLOB_RESERVED_SIZE))
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "reserved header bytes are not zero");
  if (h->section_count > PRT_BLOB_MAX_SECTIONS)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section count %" PRIu32 " exceeds the maximum %u", h->section_count,
                         PRT_BLOB_MAX_SECTIONS);
  if (h->table_offset != h->header_size)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section table offset %" PRIu64 " does not follow the %" PRIu32
                         "-byte header",
                         h->table_offset, h->header_size);
  table_bytes = (uint64_t)h->section_count * PRT_BLOB_SECTION_ENTRY_SIZE; /* < 2^18, no overflow */
  if (!add_u64(h->table_offset, table_bytes, &table_end) || table_end > h->total_size)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section table (%" PRIu32 " entries) exceeds the blob", h->section_count);
  return PRT_BLOB_OK;
}

void prt_blob_read_section(const void* data, const prt_blob_header* header, uint32_t index,
                           prt_blob_section* s) {
  const uint8_t* e = (const uint8_t*)data + (size_t)header->table_offset +
                     (size_t)index * PRT_BLOB_SECTION_ENTRY_SIZE;
  s->tag = prt_le_load_u32(e + PRT_BLOB_SEC_OFF_TAG);
  s->flags = prt_le_load_u16(e + PRT_BLOB_SEC_OFF_FLAGS);
  s->codec = e[PRT_BLOB_SEC_OFF_CODEC];
  s->layout_version = e[PRT_BLOB_SEC_OFF_LAYOUT_VERSION];
  s->checksum = prt_le_load_u32(e + PRT_BLOB_SEC_OFF_CHECKSUM);
  s->offset = prt_le_load_u64(e + PRT_BLOB_SEC_OFF_OFFSET);
  s->stored_size = prt_le_load_u64(e + PRT_BLOB_SEC_OFF_STORED_SIZE);
  s->raw_size = prt_le_load_u64(e + PRT_BLOB_SEC_OFF_RAW_SIZE);
  s->element_count = prt_le_load_u64(e + PRT_BLOB_SEC_OFF_ELEMENT_COUNT);
}

static int tag_is_printable(uint32_t tag) {
  int i;
  for (i = 0; i < 4; ++i) {
    uint32_t c = (tag >> (8 * i)) & 0xFFu;
    if (c < 0x20 || c > 0x7E) return 0;
  }
  return 1;
}

/* Sizes and counts of one entry, given where it must start (`expected_offset`). */
static prt_blob_status check_entry(const uint8_t* b, const prt_blob_header* h, uint32_t i,
                                   const prt_blob_section* s, uint64_t expected_offset, char* msg,
                                   size_t cap) {
  char name[5];
  const prt_blob_kind* kind = prt_blob_find_kind(s->tag, s->layout_version);
  uint64_t end, bound;
  prt_blob_tag_string(s->tag, name);
  if (!tag_is_printable(s->tag))
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section %" PRIu32 ": tag is not printable ASCII", i);
  if ((s->flags & ~PRT_BLOB_SECTION_FLAGS_KNOWN) != 0)
    return prt_blob_fail(PRT_BLOB_UNSUPPORTED_FEATURE, msg, cap,
                         "section %" PRIu32 " '%s': unknown flags 0x%04x", i, name,
                         (unsigned)s->flags);
  if (prt_le_load_u32(b + h->table_offset + (uint64_t)i * PRT_BLOB_SECTION_ENTRY_SIZE +
                      PRT_BLOB_SEC_OFF_RESERVED) != 0)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section %" PRIu32 " '%s': reserved field not zero", i, name);
  if (s->codec != PRT_BLOB_CODEC_NONE && s->codec != PRT_BLOB_CODEC_ZSTD)
    return prt_blob_fail(PRT_BLOB_UNSUPPORTED_FEATURE, msg, cap,
                         "section %" PRIu32 " '%s': unknown codec %u", i, name, (unsigned)s->codec);
  if (!kind && (s->flags & PRT_BLOB_SECTION_REQUIRED))
    return prt_blob_fail(PRT_BLOB_UNSUPPORTED_FEATURE, msg, cap,
                         "section %" PRIu32
                         " '%s' layout version %u is required but not known to this "
                         "reader",
                         i, name, (unsigned)s->layout_version);
  if (s->offset != expected_offset)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section %" PRIu32 " '%s': offset %" PRIu64 " is not the expected %" PRIu64
                         " (sections are packed in table order at 16-byte alignment)",
                         i, name, s->offset, expected_offset);
  if (!add_u64(s->offset, s->stored_size, &end) || end > h->total_size)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section %" PRIu32 " '%s': %" PRIu64 " bytes at offset %" PRIu64
                         " run past the end of the blob",
                         i, name, s->stored_size, s->offset);
  if (s->codec == PRT_BLOB_CODEC_NONE && s->stored_size != s->raw_size)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section %" PRIu32 " '%s': uncompressed but stored size %" PRIu64
                         " != raw size %" PRIu64,
                         i, name, s->stored_size, s->raw_size);
  if (s->codec == PRT_BLOB_CODEC_ZSTD &&
      (s->stored_size < PRT_BLOB_ZSTD_MIN_FRAME ||
       !mul_u64(s->stored_size, PRT_BLOB_ZSTD_MAX_RATIO, &bound) || s->raw_size > bound))
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section %" PRIu32 " '%s': zstd sizes implausible (stored %" PRIu64
                         ", raw %" PRIu64 ")",
                         i, name, s->stored_size, s->raw_size);
  if (s->raw_size > (uint64_t)SIZE_MAX)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "section %" PRIu32 " '%s': raw size too large",
                         i, name);
  if (kind && kind->element_size != 0) {
    uint64_t expected_raw;
    if (!mul_u64(s->element_count, kind->element_size, &expected_raw) ||
        expected_raw != s->raw_size)
      return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                           "section %" PRIu32 " '%s': %" PRIu64 " elements of %" PRIu32
                           " bytes do not make %" PRIu64 " raw bytes",
                           i, name, s->element_count, kind->element_size, s->raw_size);
  } else if (s->element_count > s->raw_size) {
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "section %" PRIu32 " '%s': %" PRIu64 " elements cannot fit in %" PRIu64
                         " bytes",
                         i, name, s->element_count, s->raw_size);
  }
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_validate_structure(const void* data, size_t size, prt_blob_header* header,
                                            char* msg, size_t cap) {
  const uint8_t* b = (const uint8_t*)data;
  prt_blob_header h;
  prt_blob_status st;
  uint64_t expected_offset = 0, end;
  uint32_t i, j;
  if (!data && size > 0)
    return prt_blob_fail(PRT_BLOB_INVALID_ARGUMENT, msg, cap, "blob pointer is NULL");
  if (!data) return prt_blob_fail(PRT_BLOB_TRUNCATED, msg, cap, "blob is empty");
  st = check_header(b, size, &h, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  /* The table ends inside the blob (check_header), so this cannot overflow. */
  end = h.table_offset + (uint64_t)h.section_count * PRT_BLOB_SECTION_ENTRY_SIZE;
  for (i = 0; i < h.section_count; ++i) {
    prt_blob_section s;
    prt_blob_read_section(data, &h, i, &s);
    if (!align16_u64(end, &expected_offset))
      return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "section %" PRIu32 ": offset overflows", i);
    st = check_entry(b, &h, i, &s, expected_offset, msg, cap);
    if (st != PRT_BLOB_OK) return st;
    end = s.offset + s.stored_size; /* checked in check_entry */
    for (j = 0; j < i; ++j) {
      const uint8_t* earlier = b + h.table_offset + (uint64_t)j * PRT_BLOB_SECTION_ENTRY_SIZE;
      if (prt_le_load_u32(earlier + PRT_BLOB_SEC_OFF_TAG) == s.tag) {
        char name[5];
        prt_blob_tag_string(s.tag, name);
        return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                             "sections %" PRIu32 " and %" PRIu32 " have the same tag '%s'", j, i,
                             name);
      }
    }
  }
  if (!align16_u64(end, &expected_offset) || expected_offset != h.total_size)
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                         "blob size %" PRIu64
                         " is not the end of its last section padded to 16 (%" PRIu64 ")",
                         h.total_size, expected_offset);
  st = prt_blob_check_relations(data, &h, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  if (header) *header = h;
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_verify_checksums(const void* data, const prt_blob_header* h, char* msg,
                                          size_t cap) {
  static const uint8_t kZeros[4] = {0, 0, 0, 0};
  const uint8_t* b = (const uint8_t*)data;
  size_t table_bytes = (size_t)h->section_count * PRT_BLOB_SECTION_ENTRY_SIZE;
  uint32_t crc, i;
  uint64_t end;
  crc = prt_crc32c(0, b, PRT_BLOB_OFF_CHECKSUM);
  crc = prt_crc32c(crc, kZeros, 4);
  crc = prt_crc32c(crc, b + PRT_BLOB_OFF_CHECKSUM + 4, h->header_size - PRT_BLOB_OFF_CHECKSUM - 4);
  crc = prt_crc32c(crc, b + h->table_offset, table_bytes);
  if (CHECKSUMS_DIFFER(h->checksum, crc))
    return prt_blob_fail(PRT_BLOB_CHECKSUM_MISMATCH, msg, cap,
                         "header checksum mismatch (stored 0x%08" PRIx32 ", computed 0x%08" PRIx32
                         ")",
                         h->checksum, crc);
  end = h->table_offset + table_bytes;
  for (i = 0; i < h->section_count; ++i) {
    prt_blob_section s;
    char name[5];
    prt_blob_read_section(data, h, i, &s);
    prt_blob_tag_string(s.tag, name);
    if (!prt_blob_bytes_are_zero(b + end, (size_t)(s.offset - end)))
      return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap,
                           "padding before section %" PRIu32 " '%s' is not zero", i, name);
    crc = prt_crc32c(0, b + s.offset, (size_t)s.stored_size);
    if (CHECKSUMS_DIFFER(s.checksum, crc))
      return prt_blob_fail(PRT_BLOB_CHECKSUM_MISMATCH, msg, cap,
                           "section %" PRIu32 " '%s': checksum mismatch (stored 0x%08" PRIx32
                           ", computed 0x%08" PRIx32 ")",
                           i, name, s.checksum, crc);
    end = s.offset + s.stored_size;
  }
  if (!prt_blob_bytes_are_zero(b + end, (size_t)(h->total_size - end)))
    return prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "padding after the last section is not zero");
  return PRT_BLOB_OK;
}
