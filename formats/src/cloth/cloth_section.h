/* SPDX-License-Identifier: MIT */
/* Content check of the `cloth` section CLTH (formats/SPEC.md §7.4). */
#ifndef PRT_FORMAT_CLOTH_SECTION_H
#define PRT_FORMAT_CLOTH_SECTION_H

#include <prt/format/section_kinds.h>

/* Every header field, every fabric, thread, tangent and table record, the exact size from the
 * ranks, then the names (UTF-8, distinct), each thread's offsets (distinct) and every table's
 * data: scales finite and >= 0, no value -128 / -32768, zero padding. */
prt_blob_status prt_blob_check_clth(const prt_blob_content* content, char* msg, size_t cap);

#endif /* PRT_FORMAT_CLOTH_SECTION_H */
