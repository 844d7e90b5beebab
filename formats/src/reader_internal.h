/* SPDX-License-Identifier: MIT */
/* Helpers shared by the container reader and the section checkers; not installed. */
#ifndef PRT_FORMAT_READER_INTERNAL_H
#define PRT_FORMAT_READER_INTERNAL_H

#include <prt/format/section_kinds.h>

/* Writes the printf-style message to msg (when msg and cap allow) and returns status. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
prt_blob_status
prt_blob_fail(prt_blob_status status, char* msg, size_t cap, const char* fmt, ...);

/* 1 if the n bytes at p are all zero. */
int prt_blob_bytes_are_zero(const uint8_t* p, size_t n);

/* The little-endian f32 at p. */
float prt_blob_load_f32(const uint8_t* p);

/* 1 if f is neither NaN nor infinite. */
int prt_blob_f32_is_finite(float f);

/* Kind relations, the last quick check (SPEC.md §8.1 check 27): for every known section, the
 * tags it depends on are present and its element count is its domain's size. */
prt_blob_status prt_blob_check_relations(const void* data, const prt_blob_header* header, char* msg,
                                         size_t cap);

#endif /* PRT_FORMAT_READER_INTERNAL_H */
