/* SPDX-License-Identifier: MIT */
/* Content checks of the mesh kinds INFO, VPOS, VNRM, VTAN and TRIS (formats/SPEC.md §7). */
#ifndef PRT_FORMAT_MESH_SECTIONS_H
#define PRT_FORMAT_MESH_SECTIONS_H

#include <prt/format/section_kinds.h>

/* The index of the first byte of the n at p that does not start a well-formed UTF-8 sequence, or
 * n when they are all UTF-8 (also used for CLTH's fabric names). */
size_t prt_blob_utf8_error(const uint8_t* p, size_t n);
/* INFO: well-formed UTF-8 (no overlong forms, surrogates or code points above U+10FFFF). */
prt_blob_status prt_blob_check_info(const prt_blob_content* content, char* msg, size_t cap);
/* VPOS, VNRM, VTAN: every f32 finite. */
prt_blob_status prt_blob_check_finite_f32(const prt_blob_content* content, char* msg, size_t cap);
/* TRIS: every index below the vertex count. */
prt_blob_status prt_blob_check_tris(const prt_blob_content* content, char* msg, size_t cap);

#endif /* PRT_FORMAT_MESH_SECTIONS_H */
