/* SPDX-License-Identifier: MIT */
/* Content check of the `sh` transfer section SHTR (formats/SPEC.md §7.1). */
#ifndef PRT_FORMAT_SH_SECTION_H
#define PRT_FORMAT_SH_SECTION_H

#include <prt/format/section_kinds.h>

/* Every header field, the exact size, zero padding, finite offsets and finite non-negative
 * scales. Quantised values need no check (any is valid). */
prt_blob_status prt_blob_check_shtr(const prt_blob_content* content, char* msg, size_t cap);

#endif /* PRT_FORMAT_SH_SECTION_H */
