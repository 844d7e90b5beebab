/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the context and asset structs and shared helpers. */
#ifndef PRT_RUNTIME_INTERNAL_H
#define PRT_RUNTIME_INTERNAL_H

#ifndef PRT_BUILDING_RUNTIME
#error "internal.h is private to the prtkit runtime; include <prt/prt.h> instead"
#endif

#include <prt/format/blob_reader.h>
#include <prt/prt.h>

#define PRT_MESSAGE_CAPACITY 512

struct prt_context {
  prt_allocator allocator;
  prt_message_fn message;
  void* message_user;
  prt_backend backend_limit; /* effective (desc + environment); AUTO = none */
  prt_simd_isa simd_isa;     /* what the SIMD backend uses: min(CPU, limits); NONE if unusable */
  prt_result last_result;
  char last_message[PRT_MESSAGE_CAPACITY];
};

typedef struct prt_asset_section {
  prt_blob_section entry;
  const uint8_t* data; /* decoded bytes (raw_size of them); NULL when raw_size is 0 */
  uint8_t* owned;      /* data when the asset allocated it (zstd), else NULL */
} prt_asset_section;

struct prt_asset {
  prt_context* context;
  prt_allocator allocator;
  prt_blob_header header;
  const uint8_t* bytes; /* the blob */
  uint8_t* owned_bytes; /* bytes when the asset owns a copy, else NULL */
  size_t size;
  prt_asset_section* sections; /* header.section_count of them */
};

/* Allocation through a context's allocator; size 0 is rounded up to 1. */
void* prt_internal_alloc(const prt_allocator* allocator, size_t size, size_t align);
void prt_internal_free(const prt_allocator* allocator, void* ptr, size_t size);

/* Records a failure in the context (last result + message), sends it to the callback, and
 * returns `result`. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
prt_result
prt_internal_fail(prt_context* context, prt_result result, const char* fmt, ...);

/* Sends an informational or warning message to the callback (not recorded as an error). */
void prt_internal_note(const prt_context* context, prt_severity severity, const char* text);

/* Decodes one zstd frame of exactly src_size bytes into exactly dst_size bytes.
 * PRT_OK or PRT_ERROR_CORRUPT with an explanation in msg. */
prt_result prt_internal_zstd_decode(const prt_allocator* allocator, const uint8_t* src,
                                    size_t src_size, uint8_t* dst, size_t dst_size, char* msg,
                                    size_t msg_capacity);

/* CPU detection and limits for a new context (backend.c). */
prt_simd_isa prt_internal_detect_simd_isa(void);

#endif /* PRT_RUNTIME_INTERNAL_H */
