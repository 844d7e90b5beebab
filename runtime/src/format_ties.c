/* SPDX-License-Identifier: MIT */
/* The public constants that restate the formats layer's, tied to them at compile time (the
 * formats layer depends on nothing, so it cannot include the sdk): a change on one side that the
 * other misses breaks the build. The ties of a technique's own constants sit in its folder
 * (<t>/<t>_section.c). */
#include "internal.h"

/* Format version and shared section kinds. */
PRT_STATIC_ASSERT(PRT_FORMAT_VERSION_MAJOR == PRT_BLOB_VERSION_MAJOR, format_major);
PRT_STATIC_ASSERT(PRT_FORMAT_VERSION_MINOR == PRT_BLOB_VERSION_MINOR, format_minor);
PRT_STATIC_ASSERT(PRT_TAG('P', 'R', 'T', 'K') == PRT_BLOB_TAG('P', 'R', 'T', 'K'), tag_macro);
PRT_STATIC_ASSERT(PRT_SECTION_INFO == PRT_BLOB_TAG_INFO, tag_info);
PRT_STATIC_ASSERT(PRT_SECTION_VPOS == PRT_BLOB_TAG_VPOS, tag_vpos);
PRT_STATIC_ASSERT(PRT_SECTION_VNRM == PRT_BLOB_TAG_VNRM, tag_vnrm);
PRT_STATIC_ASSERT(PRT_SECTION_VTAN == PRT_BLOB_TAG_VTAN, tag_vtan);
PRT_STATIC_ASSERT(PRT_SECTION_TRIS == PRT_BLOB_TAG_TRIS, tag_tris);
PRT_STATIC_ASSERT(PRT_SECTION_FLAG_REQUIRED == PRT_BLOB_SECTION_REQUIRED, section_flag_required);
PRT_STATIC_ASSERT(PRT_CODEC_NONE == PRT_BLOB_CODEC_NONE, codec_none);
PRT_STATIC_ASSERT(PRT_CODEC_ZSTD == PRT_BLOB_CODEC_ZSTD, codec_zstd);

/* The element domains (prt_section_info.domain is read from the kind table). */
PRT_STATIC_ASSERT((int)PRT_ELEMENT_DOMAIN_NONE == (int)PRT_BLOB_DOMAIN_NONE, domain_none);
PRT_STATIC_ASSERT((int)PRT_ELEMENT_DOMAIN_VERTEX == (int)PRT_BLOB_DOMAIN_VERTEX, domain_vertex);
PRT_STATIC_ASSERT((int)PRT_ELEMENT_DOMAIN_TRIANGLE == (int)PRT_BLOB_DOMAIN_TRIANGLE,
                  domain_triangle);
PRT_STATIC_ASSERT((int)PRT_ELEMENT_DOMAIN_MATERIAL == (int)PRT_BLOB_DOMAIN_MATERIAL,
                  domain_material);
PRT_STATIC_ASSERT((int)PRT_ELEMENT_DOMAIN_OBJECT == (int)PRT_BLOB_DOMAIN_OBJECT, domain_object);

/* Every reader status is returned as the prt_result of the same number. */
PRT_STATIC_ASSERT((int)PRT_BLOB_OK == (int)PRT_OK, status_ok);
PRT_STATIC_ASSERT((int)PRT_BLOB_INVALID_ARGUMENT == (int)PRT_ERROR_INVALID_ARGUMENT,
                  status_invalid_argument);
PRT_STATIC_ASSERT((int)PRT_BLOB_BAD_MAGIC == (int)PRT_ERROR_BAD_MAGIC, status_bad_magic);
PRT_STATIC_ASSERT((int)PRT_BLOB_UNSUPPORTED_VERSION == (int)PRT_ERROR_UNSUPPORTED_VERSION,
                  status_unsupported_version);
PRT_STATIC_ASSERT((int)PRT_BLOB_UNSUPPORTED_FEATURE == (int)PRT_ERROR_UNSUPPORTED_FEATURE,
                  status_unsupported_feature);
PRT_STATIC_ASSERT((int)PRT_BLOB_TRUNCATED == (int)PRT_ERROR_TRUNCATED, status_truncated);
PRT_STATIC_ASSERT((int)PRT_BLOB_SIZE_MISMATCH == (int)PRT_ERROR_SIZE_MISMATCH,
                  status_size_mismatch);
PRT_STATIC_ASSERT((int)PRT_BLOB_CORRUPT == (int)PRT_ERROR_CORRUPT, status_corrupt);
PRT_STATIC_ASSERT((int)PRT_BLOB_CHECKSUM_MISMATCH == (int)PRT_ERROR_CHECKSUM_MISMATCH,
                  status_checksum_mismatch);
PRT_STATIC_ASSERT((int)PRT_BLOB_NON_FINITE == (int)PRT_ERROR_NON_FINITE, status_non_finite);
PRT_STATIC_ASSERT((int)PRT_BLOB_INDEX_OUT_OF_RANGE == (int)PRT_ERROR_INDEX_OUT_OF_RANGE,
                  status_index_out_of_range);
