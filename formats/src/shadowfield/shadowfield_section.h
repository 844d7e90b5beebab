/* SPDX-License-Identifier: MIT */
/* Content check of the `shadowfield` section SFLD (formats/SPEC.md §7.5). */
#ifndef PRT_FORMAT_SHADOWFIELD_SECTION_H
#define PRT_FORMAT_SHADOWFIELD_SECTION_H

#include <prt/format/section_kinds.h>

/* Every header field (prt_blob_sfld_check_header), then block by block in section order: every
 * f32 finite, albedo in [0, 1], vertex weights >= 0, scales >= 0, zero padding. Quantised values
 * need no check (any is valid). */
prt_blob_status prt_blob_check_sfld(const prt_blob_content* content, char* msg, size_t cap);

#endif /* PRT_FORMAT_SHADOWFIELD_SECTION_H */
