/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: basic types shared by every header: result codes, message severities,
 * the caller-supplied allocator and message callback, opaque handles. C99 and C++.
 *
 * Structs that may grow (descriptions the caller fills in and infos the runtime fills in) start
 * with `size_t struct_size`, which the caller sets to sizeof(the struct) as its headers declare
 * it, for input and output structs alike. A struct_size below the struct's size in prtkit 1.0 is
 * PRT_ERROR_INVALID_ARGUMENT. The runtime reads and writes only the first struct_size bytes: an
 * input field a caller's older struct lacks takes its default (as if 0), and an output struct is
 * written only as far as it reaches (struct_size itself is left as the caller set it). So a
 * program built against older headers keeps working with a newer library, and the reverse.
 *
 * Thread safety: everything declared here is a type or a constant; prt_result_string() is pure
 * and may be called from any thread. */
#ifndef PRT_TYPES_H
#define PRT_TYPES_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32) && defined(PRT_SHARED)
#if defined(PRT_BUILDING_RUNTIME)
#define PRT_API __declspec(dllexport)
#else
#define PRT_API __declspec(dllimport)
#endif
#elif defined(__GNUC__)
#define PRT_API __attribute__((visibility("default")))
#else
#define PRT_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result of every fallible call. PRT_OK is 0; failures are positive and grouped by tens. */
typedef enum prt_result {
  PRT_OK = 0,

  /* 1-9: the caller's use of the API */
  PRT_ERROR_INVALID_ARGUMENT = 1,  /* NULL where not allowed, bad enum, bad alignment, ... */
  PRT_ERROR_INVALID_OPERATION = 2, /* a valid call at the wrong time */
  PRT_ERROR_BUFFER_TOO_SMALL = 3,  /* a caller-supplied output buffer is too small */
  PRT_ERROR_NOT_FOUND = 4,         /* no section with that tag, no such index */

  /* 10-19: resources */
  PRT_ERROR_OUT_OF_MEMORY = 10, /* the allocator returned NULL, or a size does not fit size_t */
  PRT_ERROR_IO = 11,            /* a file could not be opened or read */

  /* 20-39: the blob (formats/SPEC.md §Validation says which check gives which code) */
  PRT_ERROR_BAD_MAGIC = 20,           /* not a prtkit blob */
  PRT_ERROR_UNSUPPORTED_VERSION = 21, /* another major format version */
  PRT_ERROR_UNSUPPORTED_FEATURE = 22, /* unknown required section, critical flag or codec */
  PRT_ERROR_TRUNCATED = 23,           /* fewer bytes than the header says */
  PRT_ERROR_SIZE_MISMATCH = 24,       /* more bytes than the header says */
  PRT_ERROR_CORRUPT = 25,             /* inconsistent sizes, offsets, counts, padding, zstd data */
  PRT_ERROR_CHECKSUM_MISMATCH = 26,   /* header or section CRC-32C differs (full validation) */
  PRT_ERROR_NON_FINITE = 27,          /* NaN or Inf where finite floats are required (full) */
  PRT_ERROR_INDEX_OUT_OF_RANGE = 28,  /* an index beyond its array (full) */

  /* 40-49: backends */
  PRT_ERROR_UNSUPPORTED_BACKEND = 40 /* not compiled in, not usable on this CPU, or forced off */
} prt_result;

/* A static English name and description of a result code, e.g. "PRT_ERROR_TRUNCATED: ...".
 * Never NULL; unknown codes give "unknown prt_result". */
PRT_API const char* prt_result_string(prt_result result);

/* Severity of a message passed to the message callback. */
typedef enum prt_severity {
  PRT_SEVERITY_DEBUG = 0,
  PRT_SEVERITY_INFO = 1,
  PRT_SEVERITY_WARNING = 2,
  PRT_SEVERITY_ERROR = 3
} prt_severity;

/* Caller-supplied allocator. alloc returns `size` bytes aligned to `align` (a power of two,
 * at most 4096) or NULL; free receives the pointer and the size it was allocated with.
 * Both may be called from any thread that uses the context or its assets' destroy functions. */
typedef struct prt_allocator {
  void* (*alloc)(void* user, size_t size, size_t align);
  void (*free)(void* user, void* ptr, size_t size);
  void* user;
} prt_allocator;

/* Caller-supplied message sink. The runtime never prints; it reports through this callback (if
 * set) and records the last error message in the context. `text` is valid only during the call.
 * Called on the thread that made the API call. */
typedef void (*prt_message_fn)(void* user, prt_result result, prt_severity severity,
                               const char* text);

/* Evaluation backends (prt_backend.h). */
typedef enum prt_backend {
  PRT_BACKEND_AUTO = 0, /* the best usable one; as a limit: no limit */
  PRT_BACKEND_CPU = 1,  /* scalar reference, always usable */
  PRT_BACKEND_SIMD = 2, /* x86 SSE4.1 / AVX2+FMA, picked at run time */
  PRT_BACKEND_GL = 3    /* OpenGL, with the game's context and loader */
} prt_backend;

/* SIMD instruction sets, in increasing order. */
typedef enum prt_simd_isa {
  PRT_SIMD_ISA_AUTO = 0, /* as a limit: no limit */
  PRT_SIMD_ISA_NONE = 1,
  PRT_SIMD_ISA_SSE41 = 2,
  PRT_SIMD_ISA_AVX2 = 3,  /* AVX2 + FMA */
  PRT_SIMD_ISA_AVX512 = 4 /* AVX2 + FMA + AVX-512 F/BW/DQ/VL/VNNI, with the OS saving its state */
} prt_simd_isa;

/* Opaque handles. */
typedef struct prt_context prt_context;
typedef struct prt_asset prt_asset;

/* Section tag from four ASCII characters in file order (formats/SPEC.md §Section table). */
#define PRT_TAG(a, b, c, d)                                                                  \
  ((uint32_t)(uint8_t)(a) | ((uint32_t)(uint8_t)(b) << 8) | ((uint32_t)(uint8_t)(c) << 16) | \
   ((uint32_t)(uint8_t)(d) << 24))

#ifdef __cplusplus
}
#endif

#endif /* PRT_TYPES_H */
