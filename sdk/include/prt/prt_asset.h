/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: loading, validating and inspecting asset blobs (formats/SPEC.md).
 * C99 and C++.
 *
 * Loading from memory is the primitive; files are a convenience. Every load validates the blob
 * before it forms any pointer into it: quick validation always (sizes, magic, versions, section
 * table, bounds, alignment), full validation on request (checksums, finite floats, index ranges,
 * decodability of compressed sections). At both levels every load then decodes the header of
 * each technique's section once and checks it against the section's size (O(1) per technique);
 * the asset keeps what it decoded for the technique's functions. A bad blob gives an error code
 * and a message in the context, never a crash, an out-of-bounds read or an unbounded
 * allocation.
 *
 * Thread safety: load, validate and destroy functions take the context and follow its rule (one
 * thread at a time per context). An asset is immutable once loaded: the const prt_asset*
 * queries may run on any number of threads at once; they never write the context, so they
 * report failures only through their result. */
#ifndef PRT_ASSET_H
#define PRT_ASSET_H

#include <prt/prt_technique.h>
#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Blob format version this runtime reads: major exactly, any minor. */
#define PRT_FORMAT_VERSION_MAJOR 1
#define PRT_FORMAT_VERSION_MINOR 0

/* Section kinds of format 1.0 shared by every technique (formats/SPEC.md §Section kinds). Each
 * technique's own section is declared in its prt_<t>_asset.h (PRT_SECTION_SHTR, ...). */
#define PRT_SECTION_INFO PRT_TAG('I', 'N', 'F', 'O') /* UTF-8 text; element = byte */
#define PRT_SECTION_VPOS PRT_TAG('V', 'P', 'O', 'S') /* float x,y,z per vertex */
#define PRT_SECTION_VNRM PRT_TAG('V', 'N', 'R', 'M') /* float x,y,z per vertex */
#define PRT_SECTION_VTAN PRT_TAG('V', 'T', 'A', 'N') /* float x,y,z per vertex: the warp */
#define PRT_SECTION_TRIS PRT_TAG('T', 'R', 'I', 'S') /* uint32 i0,i1,i2 per triangle */

/* Bits of prt_section_info.flags. */
typedef enum prt_section_flag {
  PRT_SECTION_FLAG_REQUIRED = 0x1 /* a reader that does not know the tag must reject the blob */
} prt_section_flag;

typedef enum prt_validation {
  PRT_VALIDATE_QUICK = 0, /* structure and technique headers: O(section count) */
  PRT_VALIDATE_FULL = 1   /* also checksums, padding, decoded contents */
} prt_validation;

typedef enum prt_codec { PRT_CODEC_NONE = 0, PRT_CODEC_ZSTD = 1 } prt_codec;

typedef struct prt_asset_info {
  size_t struct_size; /* set by the caller: sizeof(prt_asset_info) */
  uint32_t format_major;
  uint32_t format_minor;
  uint32_t flags; /* header flags */
  uint32_t section_count;
  uint64_t total_size;  /* bytes of the blob */
  uint8_t producer[16]; /* opaque id of the writing tool, zero-padded */
  uint32_t borrowed;    /* 1 if the asset reads the caller's bytes (loaded with _borrowed) */
} prt_asset_info;

typedef struct prt_section_info {
  size_t struct_size; /* set by the caller: sizeof(prt_section_info) */
  uint32_t tag;       /* PRT_TAG(...) */
  uint32_t flags;     /* prt_section_flag bits */
  prt_codec codec;
  uint32_t layout_version; /* version of the tag's payload layout */
  uint32_t known;       /* 1 if this runtime knows (tag, layout_version) and checks its contents */
  uint32_t checksum;    /* CRC-32C of the stored bytes */
  uint64_t offset;      /* in the blob */
  uint64_t stored_size; /* bytes in the blob */
  uint64_t raw_size;    /* bytes after decoding */
  uint64_t element_count;
  prt_element_domain domain; /* what an element is; NONE (bytes) for an unknown kind */
  prt_technique technique;   /* the technique whose section this is, NONE for mesh sections */
} prt_section_info;

/* Loads a blob from memory, copying it: `data` may be freed as soon as this returns.
 * On success *out_asset receives the asset; on failure it is NULL and the context holds the
 * message. Returns PRT_OK, PRT_ERROR_INVALID_ARGUMENT (NULL context/out_asset, bad validation
 * value), PRT_ERROR_OUT_OF_MEMORY, or the blob's validation error (prt_types.h, 20-39), which
 * includes PRT_ERROR_CORRUPT, with a message naming the field, for a technique section whose
 * header does not fit the section (at either validation level). */
PRT_API prt_result prt_asset_load_memory(prt_context* context, const void* data, size_t size,
                                         prt_validation validation, prt_asset** out_asset);

/* Like prt_asset_load_memory() but without copying (zero-copy, e.g. a memory-mapped file):
 * uncompressed sections are read in place. `data` must be 16-byte aligned (else
 * PRT_ERROR_INVALID_ARGUMENT), must stay valid and unchanged until the asset is destroyed, and
 * is never written. Compressed sections are still decoded into memory the asset owns. */
PRT_API prt_result prt_asset_load_memory_borrowed(prt_context* context, const void* data,
                                                  size_t size, prt_validation validation,
                                                  prt_asset** out_asset);

/* Reads the file at `path` (UTF-8 / native path) and loads it like prt_asset_load_memory().
 * Returns PRT_ERROR_IO when the file cannot be opened or read. */
PRT_API prt_result prt_asset_load_file(prt_context* context, const char* path,
                                       prt_validation validation, prt_asset** out_asset);

/* Destroys an asset and frees what it owns (with its context's allocator). NULL is allowed. */
PRT_API void prt_asset_destroy(prt_asset* asset);

/* Validates a blob without creating an asset. Quick validation checks the structure and the
 * technique headers of uncompressed sections, and never decompresses; full validation also
 * checks checksums and padding, and decodes every section (zstd into temporary memory from the
 * context's allocator) to check its contents. So at PRT_VALIDATE_FULL the result is what
 * prt_asset_load_memory() returns for these bytes; at PRT_VALIDATE_QUICK a load can still fail
 * where this passes, on a zstd section that does not decode or whose technique header does not
 * fit (PRT_ERROR_CORRUPT), or on memory. `message` (may be NULL) receives a NUL-terminated one-line
 * report, cut to message_capacity: what is wrong, or a summary of a valid blob. Failures are
 * also recorded in the context. */
PRT_API prt_result prt_asset_validate(prt_context* context, const void* data, size_t size,
                                      prt_validation validation, char* message,
                                      size_t message_capacity);

/* Header facts of a loaded asset. PRT_ERROR_INVALID_ARGUMENT for NULL pointers or a struct_size
 * below 1.0's. */
PRT_API prt_result prt_asset_get_info(const prt_asset* asset, prt_asset_info* out_info);

/* Number of sections (0 for NULL). */
PRT_API uint32_t prt_asset_section_count(const prt_asset* asset);

/* Table entry `index` (< prt_asset_section_count()). PRT_ERROR_NOT_FOUND for a bad index,
 * PRT_ERROR_INVALID_ARGUMENT for NULL pointers or a struct_size below 1.0's. */
PRT_API prt_result prt_asset_get_section_info(const prt_asset* asset, uint32_t index,
                                              prt_section_info* out_info);

/* Index of the section with `tag` (tags are unique in a blob). PRT_ERROR_NOT_FOUND if absent. */
PRT_API prt_result prt_asset_find_section(const prt_asset* asset, uint32_t tag,
                                          uint32_t* out_index);

/* The decoded bytes of the section with `tag`: *out_data points to *out_size (= raw size) bytes
 * that stay valid until the asset is destroyed; 16-byte aligned; little-endian as in the blob.
 * For an empty section *out_data may be NULL. PRT_ERROR_NOT_FOUND if absent. */
PRT_API prt_result prt_asset_section_data(const prt_asset* asset, uint32_t tag,
                                          const void** out_data, size_t* out_size);

/* Copies the decoded bytes of the section with `tag` into dst (capacity bytes). *out_size (may
 * be NULL) receives the raw size, also on PRT_ERROR_BUFFER_TOO_SMALL (dst untouched then), so a
 * first call with capacity 0 asks for the size. PRT_ERROR_NOT_FOUND if absent. */
PRT_API prt_result prt_asset_copy_section(const prt_asset* asset, uint32_t tag, void* dst,
                                          size_t capacity, size_t* out_size);

#ifdef __cplusplus
}
#endif

#endif /* PRT_ASSET_H */
