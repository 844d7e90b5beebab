/* SPDX-License-Identifier: MIT */
/* libFuzzer target: validate (quick, full) and load (copying, borrowed; quick, full) arbitrary
 * bytes, then read every decoded section end to end and shade with every technique the blob
 * holds (CPU and SIMD), so that any out-of-bounds access shows up under AddressSanitizer. Built
 * with -fsanitize=fuzzer when PRT_BUILD_FUZZERS=ON, otherwise with fuzz_replay.c as a plain program
 * that replays files (a CTest test runs it on the golden blob). */
#include <prt/prt.h>

#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

/* Reads every byte the asset exposes. */
static unsigned touch_sections(const prt_asset* asset) {
  unsigned sum = 0;
  uint32_t i;
  for (i = 0; i < prt_asset_section_count(asset); ++i) {
    prt_section_info info;
    const void* bytes;
    size_t n, k;
    info.struct_size = sizeof info;
    if (prt_asset_get_section_info(asset, i, &info) != PRT_OK) abort();
    if (prt_asset_section_data(asset, info.tag, &bytes, &n) != PRT_OK) abort();
    if (n != info.raw_size) abort();
    for (k = 0; k < n; ++k) sum += ((const uint8_t*)bytes)[k];
  }
  return sum;
}

/* Shades the first vertices of the blob's `sh` and `wavelet` sections on the CPU and SIMD
 * backends (a corrupt row may return an error at quick validation; never after full validation,
 * which promises every row is well formed). */
static void shade_techniques(const prt_asset* asset, prt_validation level) {
  static const prt_backend backends[2] = {PRT_BACKEND_CPU, PRT_BACKEND_SIMD};
  float out[3 * 16];
  prt_sh_info sh;
  prt_wavelet_info wavelet;
  int b;
  sh.struct_size = sizeof sh;
  wavelet.struct_size = sizeof wavelet;
  if (prt_sh_get_info(asset, &sh) == PRT_OK) {
    float light[3 * 256] = {0.0f};
    const uint32_t count = sh.vertex_count < 16u ? sh.vertex_count : 16u;
    light[0] = light[1] = light[2] = 1.0f;
    for (b = 0; b < 2; ++b) (void)prt_sh_shade(asset, backends[b], light, 0, count, out);
  }
  if (prt_wavelet_get_info(asset, &wavelet) == PRT_OK) {
    const uint32_t count = wavelet.vertex_count < 16u ? wavelet.vertex_count : 16u;
    float* light = (float*)calloc(4u * (size_t)wavelet.coefficient_count, sizeof(float));
    float* row = (float*)malloc(3u * (size_t)wavelet.coefficient_count * sizeof(float));
    prt_result r;
    if (!light || !row) abort();
    light[0] = light[1] = light[2] = 1.0f;
    r = prt_wavelet_prepare_light(asset, light, light, NULL);
    if (level == PRT_VALIDATE_FULL && r != PRT_OK) abort();
    for (b = 0; b < 2; ++b) {
      r = prt_wavelet_shade(asset, backends[b], light, NULL, 0, count, out);
      if (level == PRT_VALIDATE_FULL && r != PRT_OK && r != PRT_ERROR_UNSUPPORTED_BACKEND) abort();
    }
    if (wavelet.vertex_count > 0) {
      r = prt_wavelet_decode_transfer(asset, 0, 1, row);
      if (level == PRT_VALIDATE_FULL && r != PRT_OK) abort();
    }
    free(row);
    free(light);
  }
}

static prt_result load_and_touch(prt_context* context, const void* data, size_t size,
                                 prt_validation level, int borrowed) {
  prt_asset* asset = NULL;
  prt_result r = borrowed ? prt_asset_load_memory_borrowed(context, data, size, level, &asset)
                          : prt_asset_load_memory(context, data, size, level, &asset);
  if (r == PRT_OK) {
    volatile unsigned sink = touch_sections(asset);
    (void)sink;
    shade_techniques(asset, level);
  } else if (asset != NULL) {
    abort(); /* a failed load must not hand out an asset */
  }
  prt_asset_destroy(asset);
  return r;
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prt_context_desc desc;
  prt_context* context = NULL;
  prt_result quick, full, loaded;
  uint8_t* copy;
  char message[256];
  memset(&desc, 0, sizeof desc);
  desc.struct_size = sizeof desc;
  if (prt_context_create(&desc, &context) != PRT_OK) abort();

  quick = prt_asset_validate(context, data, size, PRT_VALIDATE_QUICK, message, sizeof message);
  full = prt_asset_validate(context, data, size, PRT_VALIDATE_FULL, message, sizeof message);
  if (full == PRT_OK && quick != PRT_OK) abort(); /* full validation includes quick */
  load_and_touch(context, data, size, PRT_VALIDATE_QUICK, 0);
  /* Full validation and a fully validated load agree (short of running out of memory). */
  loaded = load_and_touch(context, data, size, PRT_VALIDATE_FULL, 0);
  if (loaded != full && loaded != PRT_ERROR_OUT_OF_MEMORY && full != PRT_ERROR_OUT_OF_MEMORY)
    abort();

  /* Borrowed loading needs 16-byte aligned bytes: an exact-size copy (so the sanitizer sees any
   * over-read), used when malloc happens to align it to 16, as glibc and ASan do. */
  copy = (uint8_t*)malloc(size ? size : 1);
  if (copy) {
    if (size) memcpy(copy, data, size);
    if (((uintptr_t)copy & 15u) == 0) load_and_touch(context, copy, size, PRT_VALIDATE_FULL, 1);
    free(copy);
  }
  prt_context_destroy(context);
  return 0;
}
