/* SPDX-License-Identifier: MIT */
/* Content check of the `wavelet` transfer section WVLT (formats/SPEC.md §7.2). */
#ifndef PRT_FORMAT_WAVELET_SECTION_H
#define PRT_FORMAT_WAVELET_SECTION_H

#include <prt/format/section_kinds.h>

/* Every header field, the exact size, zero padding, finite non-negative scales, row starts,
 * block counts, indices and values. */
prt_blob_status prt_blob_check_wvlt(const prt_blob_content* content, char* msg, size_t cap);

#endif /* PRT_FORMAT_WAVELET_SECTION_H */
