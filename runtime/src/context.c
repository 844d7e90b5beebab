/* SPDX-License-Identifier: MIT */
/* Contexts: allocator plumbing, messages and the last error, version and result strings. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

uint32_t prt_get_version(void) {
  return PRT_VERSION;
}
const char* prt_get_version_string(void) {
  return PRT_VERSION_STRING;
}

const char* prt_result_string(prt_result result) {
  switch (result) {
    case PRT_OK:
      return "PRT_OK: success";
    case PRT_ERROR_INVALID_ARGUMENT:
      return "PRT_ERROR_INVALID_ARGUMENT: invalid argument";
    case PRT_ERROR_INVALID_OPERATION:
      return "PRT_ERROR_INVALID_OPERATION: invalid operation";
    case PRT_ERROR_BUFFER_TOO_SMALL:
      return "PRT_ERROR_BUFFER_TOO_SMALL: buffer too small";
    case PRT_ERROR_NOT_FOUND:
      return "PRT_ERROR_NOT_FOUND: not found";
    case PRT_ERROR_OUT_OF_MEMORY:
      return "PRT_ERROR_OUT_OF_MEMORY: out of memory";
    case PRT_ERROR_IO:
      return "PRT_ERROR_IO: input/output error";
    case PRT_ERROR_BAD_MAGIC:
      return "PRT_ERROR_BAD_MAGIC: not a prtkit blob";
    case PRT_ERROR_UNSUPPORTED_VERSION:
      return "PRT_ERROR_UNSUPPORTED_VERSION: unsupported blob format version";
    case PRT_ERROR_UNSUPPORTED_FEATURE:
      return "PRT_ERROR_UNSUPPORTED_FEATURE: blob needs a feature this runtime lacks";
    case PRT_ERROR_TRUNCATED:
      return "PRT_ERROR_TRUNCATED: blob is truncated";
    case PRT_ERROR_SIZE_MISMATCH:
      return "PRT_ERROR_SIZE_MISMATCH: blob has extra bytes";
    case PRT_ERROR_CORRUPT:
      return "PRT_ERROR_CORRUPT: blob is corrupt";
    case PRT_ERROR_CHECKSUM_MISMATCH:
      return "PRT_ERROR_CHECKSUM_MISMATCH: checksum mismatch";
    case PRT_ERROR_NON_FINITE:
      return "PRT_ERROR_NON_FINITE: non-finite value";
    case PRT_ERROR_INDEX_OUT_OF_RANGE:
      return "PRT_ERROR_INDEX_OUT_OF_RANGE: index out of range";
    case PRT_ERROR_UNSUPPORTED_BACKEND:
      return "PRT_ERROR_UNSUPPORTED_BACKEND: backend not usable";
  }
  return "unknown prt_result";
}

/* Default allocator: malloc with the original pointer stored just below the aligned block. */
static void* default_alloc(void* user, size_t size, size_t align) {
  unsigned char* raw;
  uintptr_t aligned;
  (void)user;
  if (size > SIZE_MAX - align - sizeof(void*)) return NULL;
  raw = (unsigned char*)malloc(size + align + sizeof(void*));
  if (!raw) return NULL;
  aligned = ((uintptr_t)(raw + sizeof(void*)) + (align - 1)) & ~(uintptr_t)(align - 1);
  memcpy((unsigned char*)aligned - sizeof(void*), &raw, sizeof(void*));
  return (void*)aligned;
}

static void default_free(void* user, void* ptr, size_t size) {
  void* raw;
  (void)user;
  (void)size;
  if (!ptr) return;
  memcpy(&raw, (unsigned char*)ptr - sizeof(void*), sizeof(void*));
  free(raw);
}

void* prt_internal_alloc(const prt_allocator* allocator, size_t size, size_t align) {
  return allocator->alloc(allocator->user, size ? size : 1, align);
}

void prt_internal_free(const prt_allocator* allocator, void* ptr, size_t size) {
  if (ptr) allocator->free(allocator->user, ptr, size ? size : 1);
}

void prt_internal_note(const prt_context* context, prt_severity severity, const char* text) {
  if (context && context->message) context->message(context->message_user, PRT_OK, severity, text);
}

prt_result prt_internal_fail(prt_context* context, prt_result result, const char* fmt, ...) {
  va_list args;
  if (!context) return result;
  va_start(args, fmt);
  vsnprintf(context->last_message, sizeof context->last_message, fmt, args);
  va_end(args);
  context->last_result = result;
  if (context->message)
    context->message(context->message_user, result, PRT_SEVERITY_ERROR, context->last_message);
  return result;
}

/* The lower of two limits where AUTO (0) means "no limit". */
static int lower_limit(int a, int b) {
  if (a == 0) return b;
  if (b == 0) return a;
  return a < b ? a : b;
}

/* Applies PRT_BACKEND / PRT_SIMD_ISA; unknown values are reported and ignored. */
static void apply_environment(prt_context* c, prt_simd_isa* isa_limit) {
  static const char* const kBackends[] = {"auto", "cpu", "simd", "gl"};
  static const char* const kIsas[] = {"auto", "none", "sse4.1", "avx2", "avx512"};
  const char* backend = getenv("PRT_BACKEND");
  const char* isa = getenv("PRT_SIMD_ISA");
  int i, found;
  if (backend) {
    for (i = 0, found = 0; i < (int)(sizeof kBackends / sizeof kBackends[0]); ++i)
      if (strcmp(backend, kBackends[i]) == 0) {
        c->backend_limit = (prt_backend)lower_limit(c->backend_limit, i);
        found = 1;
      }
    if (!found)
      prt_internal_note(c, PRT_SEVERITY_WARNING,
                        "PRT_BACKEND must be auto, cpu, simd or gl; ignoring its value");
  }
  if (isa) {
    for (i = 0, found = 0; i < (int)(sizeof kIsas / sizeof kIsas[0]); ++i)
      if (strcmp(isa, kIsas[i]) == 0) {
        *isa_limit = (prt_simd_isa)lower_limit(*isa_limit, i);
        found = 1;
      }
    if (!found)
      prt_internal_note(
          c, PRT_SEVERITY_WARNING,
          "PRT_SIMD_ISA must be auto, none, sse4.1, avx2 or avx512; ignoring its value");
  }
}

/* The caller's description as far as its struct_size reaches, the rest at its defaults (0). */
static prt_result read_desc(const prt_context_desc* desc, prt_context_desc* out) {
  memset(out, 0, sizeof *out);
  out->struct_size = sizeof *out;
  if (!desc) return PRT_OK;
  if (!prt_internal_struct_size_ok(desc, PRT_CONTEXT_DESC_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  memcpy(out, desc, desc->struct_size < sizeof *out ? desc->struct_size : sizeof *out);
  return PRT_OK;
}

prt_result prt_context_create(const prt_context_desc* caller_desc, prt_context** out_context) {
  prt_allocator allocator = {default_alloc, default_free, NULL};
  prt_context_desc desc;
  prt_simd_isa isa_limit;
  prt_context* c;
  if (!out_context) return PRT_ERROR_INVALID_ARGUMENT;
  *out_context = NULL;
  if (read_desc(caller_desc, &desc) != PRT_OK) return PRT_ERROR_INVALID_ARGUMENT;
  if (desc.allocator) {
    if (!desc.allocator->alloc || !desc.allocator->free) return PRT_ERROR_INVALID_ARGUMENT;
    allocator = *desc.allocator;
  }
  if ((unsigned)desc.backend_limit > PRT_BACKEND_GL ||
      (unsigned)desc.simd_isa_limit > PRT_SIMD_ISA_AVX512 ||
      (desc.flags & ~(uint32_t)PRT_CONTEXT_READ_ENVIRONMENT) != 0)
    return PRT_ERROR_INVALID_ARGUMENT;
  c = (prt_context*)prt_internal_alloc(&allocator, sizeof *c, 16);
  if (!c) return PRT_ERROR_OUT_OF_MEMORY;
  memset(c, 0, sizeof *c);
  c->allocator = allocator;
  c->message = desc.message;
  c->message_user = desc.message_user;
  c->backend_limit = desc.backend_limit;
  isa_limit = desc.simd_isa_limit;
  if (desc.flags & PRT_CONTEXT_READ_ENVIRONMENT) apply_environment(c, &isa_limit);
  c->simd_isa = (prt_simd_isa)lower_limit(prt_internal_detect_simd_isa(), isa_limit);
  c->last_result = PRT_OK;
  *out_context = c;
  return PRT_OK;
}

void prt_context_destroy(prt_context* context) {
  prt_allocator allocator;
  if (!context) return;
  allocator = context->allocator;
  prt_internal_free(&allocator, context, sizeof *context);
}

prt_result prt_context_last_result(const prt_context* context) {
  return context ? context->last_result : PRT_ERROR_INVALID_ARGUMENT;
}

const char* prt_context_last_message(const prt_context* context) {
  return context ? context->last_message : "";
}

void prt_context_clear_error(prt_context* context) {
  if (!context) return;
  context->last_result = PRT_OK;
  context->last_message[0] = '\0';
}
