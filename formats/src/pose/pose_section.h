/* SPDX-License-Identifier: MIT */
/* Content check of the `pose` section PSTR (formats/SPEC.md §7.3). */
#ifndef PRT_FORMAT_POSE_SECTION_H
#define PRT_FORMAT_POSE_SECTION_H

#include <prt/format/section_kinds.h>

/* Every header field, the exact size, zero padding, the parents and the evaluation order, every
 * float finite, basis scales >= 0, range min <= max and every skin joint index < J. */
prt_blob_status prt_blob_check_pstr(const prt_blob_content* content, char* msg, size_t cap);

#endif /* PRT_FORMAT_POSE_SECTION_H */
