/* SPDX-License-Identifier: MIT */
/* Bounds-checked reader core for the prtkit blob container (formats/SPEC.md). C99, no
 * dependencies, no allocation. Every check runs on offsets and sizes with overflow-checked
 * arithmetic before any pointer into the blob is formed.
 *
 * Use: prt_blob_validate_structure() (the "quick" checks, SPEC.md §Validation), then, for full
 * validation, prt_blob_verify_checksums() and prt_blob_check_content() on each section's decoded
 * bytes. prt_blob_read_section() is only meaningful after the structure has been validated.
 *
 * Thread safety: all functions are pure (they read the blob and write only their outputs), so any
 * number of threads may call them at once, also on the same blob. */
#ifndef PRT_FORMAT_BLOB_READER_H
#define PRT_FORMAT_BLOB_READER_H

#include <prt/format/blob_layout.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Outcome of a check. The numbers equal the corresponding prt_result codes of the runtime. */
typedef enum prt_blob_status {
  PRT_BLOB_OK = 0,
  PRT_BLOB_INVALID_ARGUMENT = 1,
  PRT_BLOB_BAD_MAGIC = 20,
  PRT_BLOB_UNSUPPORTED_VERSION = 21,
  PRT_BLOB_UNSUPPORTED_FEATURE = 22,
  PRT_BLOB_TRUNCATED = 23,
  PRT_BLOB_SIZE_MISMATCH = 24,
  PRT_BLOB_CORRUPT = 25,
  PRT_BLOB_CHECKSUM_MISMATCH = 26,
  PRT_BLOB_NON_FINITE = 27,
  PRT_BLOB_INDEX_OUT_OF_RANGE = 28
} prt_blob_status;

/* The decoded fixed header. */
typedef struct prt_blob_header {
  uint16_t version_major;
  uint16_t version_minor;
  uint32_t header_size;
  uint32_t flags;
  uint32_t section_count;
  uint64_t total_size;
  uint64_t table_offset;
  uint32_t checksum;
  uint8_t producer[PRT_BLOB_PRODUCER_SIZE];
} prt_blob_header;

/* One decoded section-table entry. */
typedef struct prt_blob_section {
  uint32_t tag;
  uint16_t flags;
  uint8_t codec;
  uint8_t layout_version;
  uint32_t checksum;
  uint64_t offset;
  uint64_t stored_size;
  uint64_t raw_size;
  uint64_t element_count;
} prt_blob_section;

/* A section kind this reader knows (tag + layout version): one row of the kind table,
 * section_kinds.h. */
typedef struct prt_blob_kind prt_blob_kind;

/* The known kind for (tag, layout_version), or NULL when this reader does not know it. */
const prt_blob_kind* prt_blob_find_kind(uint32_t tag, uint8_t layout_version);

/* Quick validation: size, magic, version, header fields, section table and every entry (bounds,
 * alignment, canonical placement, codec, sizes, element counts, flags, unknown required tags,
 * duplicate tags, the dependencies and element counts the kind table states). O(section_count^2) in
 * the worst case with at most PRT_BLOB_MAX_SECTIONS sections. On PRT_BLOB_OK, *header (may be NULL)
 * holds the header. On failure, msg (may be NULL) receives a NUL-terminated explanation, cut to
 * msg_capacity. */
prt_blob_status prt_blob_validate_structure(const void* data, size_t size, prt_blob_header* header,
                                            char* msg, size_t msg_capacity);

/* Decodes table entry `index` (< header->section_count). Precondition: the blob passed
 * prt_blob_validate_structure(), which produced *header. */
void prt_blob_read_section(const void* data, const prt_blob_header* header, uint32_t index,
                           prt_blob_section* section);

/* Full validation, part 1: the header checksum, every section's checksum and zero padding
 * between and after sections. Same precondition as prt_blob_read_section(). */
prt_blob_status prt_blob_verify_checksums(const void* data, const prt_blob_header* header,
                                          char* msg, size_t msg_capacity);

/* Full validation, part 2: checks the decoded bytes of one known section (`raw` holds
 * section->raw_size bytes) with its kind's check function (section_kinds.h): finite floats,
 * indices below vertex_count (the VPOS element count, 0 when absent), well-formed UTF-8, each
 * technique's own rules. Unknown kinds pass. */
prt_blob_status prt_blob_check_content(const prt_blob_section* section, const void* raw,
                                       uint64_t vertex_count, char* msg, size_t msg_capacity);

/* Writes the tag as 4 printable characters plus NUL into out (non-printable bytes become '?'). */
void prt_blob_tag_string(uint32_t tag, char out[5]);

#ifdef __cplusplus
}
#endif

/* The kind table, which describes what the checks above check. */
#include <prt/format/section_kinds.h>

#endif /* PRT_FORMAT_BLOB_READER_H */
