/* SPDX-License-Identifier: MIT */
/* Content check of the scene manifest section SCNE (formats/SPEC.md §7.6). */
#ifndef PRT_FORMAT_SCENE_SECTION_H
#define PRT_FORMAT_SCENE_SECTION_H

#include <prt/format/section_kinds.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Every header field, the exact size, the element count, then every record: its technique tag,
 * flags and reserved word, its name and blob path (ranges inside the string table, no NUL, UTF-8;
 * the path relative, '/'-separated, without empty, "." or ".." components) and its rest matrix
 * (finite, last row 0 0 0 1). O(objects + string table); names are not checked to be distinct.
 * The scene writer (scene_writer.cpp) runs it too, so that it never writes what this refuses. */
prt_blob_status prt_blob_check_scne(const prt_blob_content* content, char* msg, size_t cap);

#ifdef __cplusplus
}
#endif

#endif /* PRT_FORMAT_SCENE_SECTION_H */
