/* SPDX-License-Identifier: MIT */
/* The section kinds this reader knows: one table (formats/src/section_kinds.c), one row per
 * (tag, layout version), formats/SPEC.md §7. The container reader (blob_reader.h) knows no kind
 * by name: element sizes, dependencies between kinds, element counts and content checks all come
 * from this table. Adding a kind adds a row, its layout header and its checker. C99. */
#ifndef PRT_FORMAT_SECTION_KINDS_H
#define PRT_FORMAT_SECTION_KINDS_H

#include <prt/format/blob_reader.h>

#ifdef __cplusplus
extern "C" {
#endif

/* What one element of a section is attached to. A kind with a domain other than NONE has one
 * element per member of the domain; the domain's size is the element count of the one kind that
 * counts it (counts_domain), which every other kind of the domain must match. */
typedef enum prt_blob_domain {
  PRT_BLOB_DOMAIN_NONE = 0,     /* elements are bytes attached to nothing (e.g. INFO text) */
  PRT_BLOB_DOMAIN_VERTEX = 1,   /* one element per mesh vertex; VPOS counts them */
  PRT_BLOB_DOMAIN_TRIANGLE = 2, /* one element per triangle; TRIS counts them */
  PRT_BLOB_DOMAIN_MATERIAL = 3, /* one element per material, as tables shaded per pixel */
  PRT_BLOB_DOMAIN_OBJECT = 4    /* one element per rigid object, as fields combined across
                                 * instances */
} prt_blob_domain;

#define PRT_BLOB_KIND_MAX_DEPENDENCIES 4u

/* What a content check sees: one known section's decoded bytes and the blob's domain sizes. */
typedef struct prt_blob_content {
  const prt_blob_section* section;
  const uint8_t* bytes;  /* section->raw_size decoded bytes; NULL when there are none */
  size_t size;           /* section->raw_size */
  uint64_t vertex_count; /* element count of the blob's VPOS section, 0 without one */
} prt_blob_content;

/* Full-validation check of one section's decoded bytes (prt_blob_check_content). On failure it
 * writes a NUL-terminated message to msg (may be NULL), cut to msg_capacity. */
typedef prt_blob_status (*prt_blob_check_fn)(const prt_blob_content* content, char* msg,
                                             size_t msg_capacity);

struct prt_blob_kind {
  uint32_t tag;
  uint8_t layout_version;
  prt_blob_domain domain;
  uint8_t counts_domain; /* 1 if this kind's element count is its domain's size */
  uint32_t element_size; /* bytes per element in the raw (decoded) bytes; 0 = variable size
                          * (element_count <= raw_size, exact size checked by content) */
  /* Tags of further known sections this kind needs (besides its domain's counting kind); unused
   * entries are 0. */
  uint32_t depends_on[PRT_BLOB_KIND_MAX_DEPENDENCIES];
  const char* name;                /* human name, e.g. "vertex normals (3 x f32)" */
  const char* element_noun;        /* plural noun of one element in messages, e.g. "normals" */
  prt_blob_check_fn check_content; /* NULL: any bytes are valid */
};

/* Number of rows of the kind table, and row i (< prt_blob_kind_count(), else NULL). */
size_t prt_blob_kind_count(void);
const prt_blob_kind* prt_blob_kind_at(size_t index);

/* The kind whose element count is the size of `domain`, or NULL (PRT_BLOB_DOMAIN_NONE, and a
 * domain no kind counts yet). */
const prt_blob_kind* prt_blob_domain_counter(prt_blob_domain domain);

/* The size of `domain` in a structurally valid blob: the element count of its known counting
 * section, 0 when the blob has none. Same precondition as prt_blob_read_section(). */
uint64_t prt_blob_domain_count(const void* data, const prt_blob_header* header,
                               prt_blob_domain domain);

#ifdef __cplusplus
}
#endif

#endif /* PRT_FORMAT_SECTION_KINDS_H */
