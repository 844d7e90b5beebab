/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the context and asset structs and shared helpers. */
#ifndef PRT_RUNTIME_INTERNAL_H
#define PRT_RUNTIME_INTERNAL_H

#ifndef PRT_BUILDING_RUNTIME
#error "internal.h is private to the prtkit runtime; include <prt/prt.h> instead"
#endif

#include <stddef.h>
#include <string.h>

#include <prt/format/blob_reader.h>
#include <prt/prt.h>

#define PRT_MESSAGE_CAPACITY 512

/* A compile-time check in C99: a negative array size when `cond` is false. */
#define PRT_STATIC_ASSERT(cond, name) typedef char prt_static_assert_##name[(cond) ? 1 : -1]

/* Bytes of `type` up to the end of `member`. A struct's 1.0 size is this for its last 1.0
 * member: the smallest struct_size a caller built against 1.0 passes. A member added later goes
 * after it, and the 1.0 size stays where it is. */
#define PRT_SIZE_THROUGH(type, member) (offsetof(type, member) + sizeof(((type*)0)->member))

#define PRT_CONTEXT_DESC_SIZE_1_0 PRT_SIZE_THROUGH(prt_context_desc, flags)
#define PRT_BACKEND_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_backend_info, note)
#define PRT_ASSET_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_asset_info, borrowed)
#define PRT_SECTION_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_section_info, technique)
#define PRT_TECHNIQUE_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_technique_info, domain)
#define PRT_ENV_IMAGE_SIZE_1_0 PRT_SIZE_THROUGH(prt_env_image, rotation)

/* Techniques are numbered below this (their set is a uint32_t of bits 1u << technique). */
#define PRT_INTERNAL_MAX_TECHNIQUES 32u

struct prt_context {
  prt_allocator allocator;
  prt_message_fn message;
  void* message_user;
  prt_backend backend_limit; /* effective (desc + environment); AUTO = none */
  prt_simd_isa simd_isa;     /* what the SIMD backend uses: min(CPU, limits); NONE if unusable */
  int simd_unlimited;        /* no SIMD ISA limit given (desc or environment) */
  prt_result last_result;
  char last_message[PRT_MESSAGE_CAPACITY];
};

typedef struct prt_asset_section {
  prt_blob_section entry;
  const uint8_t* data; /* decoded bytes (raw_size of them); NULL when raw_size is 0 */
  uint8_t* owned;      /* data when the asset allocated it (zstd), else NULL */
  int decoded;         /* 0 only for a zstd section quick validation did not decode */
} prt_asset_section;

struct prt_asset {
  prt_context* context;
  prt_allocator allocator;
  prt_blob_header header;
  const uint8_t* bytes; /* the blob */
  uint8_t* owned_bytes; /* bytes when the asset owns a copy, else NULL */
  size_t size;
  prt_asset_section* sections; /* header.section_count of them */
  /* Per technique value: its section's view, decoded and checked at load (techniques.h); NULL
   * when the blob has no such section. */
  void* views[PRT_INTERNAL_MAX_TECHNIQUES];
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

/* 1 when a caller's struct_size reaches the struct's 1.0 size. */
static inline int prt_internal_struct_size_ok(const void* caller_struct, size_t size_1_0) {
  size_t struct_size;
  memcpy(&struct_size, caller_struct, sizeof struct_size);
  return struct_size >= size_1_0;
}

/* Writes the runtime's filled-in `full` (full_size bytes, struct_size first) into the caller's
 * struct as far as the caller's struct_size reaches, leaving struct_size as the caller set it. */
static inline void prt_internal_write_struct(void* caller_struct, const void* full,
                                             size_t full_size) {
  size_t struct_size;
  memcpy(&struct_size, caller_struct, sizeof struct_size);
  if (struct_size > full_size) struct_size = full_size;
  if (struct_size > sizeof(size_t))
    memcpy((char*)caller_struct + sizeof(size_t), (const char*)full + sizeof(size_t),
           struct_size - sizeof(size_t));
}

/* CPU detection and limits for a new context (backend.c). */
prt_simd_isa prt_internal_detect_simd_isa(void);

/* The instruction set the context's SIMD backend uses: NONE when the SIMD backend is not usable
 * there (compiled out, CPU, ISA limit or backend limit), as prt_backend_get_info reports it. */
prt_simd_isa prt_internal_simd_isa(const prt_context* context);
/* 1 when kernels may go beyond AVX2 to AVX-512 F + DQ: the context uses AVX2 and was given no
 * ISA limit (a limit of AVX2 means no more than AVX2; prt_simd_isa has no AVX-512 value), and
 * the CPU and OS support it. */
int prt_internal_simd_avx512(const prt_context* context);

#endif /* PRT_RUNTIME_INTERNAL_H */
