/* SPDX-License-Identifier: MIT */
/* zstd decoding of one section, with the context's allocator behind zstd's own allocations. */
#include <stdio.h>

#define ZSTD_STATIC_LINKING_ONLY /* ZSTD_customMem, ZSTD_createDCtx_advanced */
#include <zstd.h>

#include "internal.h"

/* zstd's allocator has no size on free; keep it in a 16-byte prefix. */
static void* zstd_alloc(void* opaque, size_t size) {
  const prt_allocator* allocator = (const prt_allocator*)opaque;
  unsigned char* block;
  if (size > SIZE_MAX - 16) return NULL;
  block = (unsigned char*)prt_internal_alloc(allocator, size + 16, 16);
  if (!block) return NULL;
  *(size_t*)block = size + 16;
  return block + 16;
}

static void zstd_free(void* opaque, void* address) {
  const prt_allocator* allocator = (const prt_allocator*)opaque;
  unsigned char* block;
  if (!address) return;
  block = (unsigned char*)address - 16;
  prt_internal_free(allocator, block, *(size_t*)block);
}

prt_result prt_internal_zstd_decode(const prt_allocator* allocator, const uint8_t* src,
                                    size_t src_size, uint8_t* dst, size_t dst_size, char* msg,
                                    size_t cap) {
  ZSTD_customMem mem;
  ZSTD_DCtx* dctx;
  unsigned long long content_size = ZSTD_getFrameContentSize(src, src_size);
  size_t frame_size = ZSTD_findFrameCompressedSize(src, src_size);
  size_t n;
  if (content_size == ZSTD_CONTENTSIZE_ERROR || content_size == ZSTD_CONTENTSIZE_UNKNOWN ||
      content_size != (unsigned long long)dst_size) {
    snprintf(msg, cap, "zstd frame header does not declare the raw size %zu", dst_size);
    return PRT_ERROR_CORRUPT;
  }
  if (ZSTD_isError(frame_size) || frame_size != src_size) {
    snprintf(msg, cap, "stored bytes are not exactly one zstd frame");
    return PRT_ERROR_CORRUPT;
  }
  mem.customAlloc = zstd_alloc;
  mem.customFree = zstd_free;
  mem.opaque = (void*)allocator;
  dctx = ZSTD_createDCtx_advanced(mem);
  if (!dctx) {
    snprintf(msg, cap, "out of memory for a zstd decoder");
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  n = ZSTD_decompressDCtx(dctx, dst, dst_size, src, src_size);
  ZSTD_freeDCtx(dctx);
  if (ZSTD_isError(n) || n != dst_size) {
    snprintf(msg, cap, "zstd data does not decode to %zu bytes (%s)", dst_size,
             ZSTD_isError(n) ? ZSTD_getErrorName(n) : "size differs");
    return PRT_ERROR_CORRUPT;
  }
  return PRT_OK;
}
