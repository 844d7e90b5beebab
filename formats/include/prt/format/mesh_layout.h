/* SPDX-License-Identifier: MIT */
/* The mesh section kinds of format 1.0 (formats/SPEC.md §7): INFO, VPOS, VNRM, VTAN, TRIS. Their
 * payloads are plain arrays of fixed-size elements. Plain C99. */
#ifndef PRT_FORMAT_MESH_LAYOUT_H
#define PRT_FORMAT_MESH_LAYOUT_H

#include <prt/format/blob_layout.h>

#define PRT_BLOB_TAG_INFO PRT_BLOB_TAG('I', 'N', 'F', 'O') /* UTF-8 text, element = byte */
#define PRT_BLOB_TAG_VPOS PRT_BLOB_TAG('V', 'P', 'O', 'S') /* f32 x,y,z per vertex */
#define PRT_BLOB_TAG_VNRM PRT_BLOB_TAG('V', 'N', 'R', 'M') /* f32 x,y,z per vertex */
#define PRT_BLOB_TAG_VTAN PRT_BLOB_TAG('V', 'T', 'A', 'N') /* f32 x,y,z per vertex: the warp */
#define PRT_BLOB_TAG_TRIS PRT_BLOB_TAG('T', 'R', 'I', 'S') /* u32 i0,i1,i2 per triangle */

#define PRT_BLOB_INFO_ELEMENT_SIZE 1u  /* one byte of text */
#define PRT_BLOB_VPOS_ELEMENT_SIZE 12u /* 3 x f32 */
#define PRT_BLOB_VNRM_ELEMENT_SIZE 12u /* 3 x f32 */
#define PRT_BLOB_VTAN_ELEMENT_SIZE 12u /* 3 x f32 */
#define PRT_BLOB_TRIS_ELEMENT_SIZE 12u /* 3 x u32 */

#endif /* PRT_FORMAT_MESH_LAYOUT_H */
