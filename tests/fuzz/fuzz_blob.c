/* SPDX-License-Identifier: MIT */
/* libFuzzer target: validate (quick, full) and load (copying, borrowed; quick, full) arbitrary
 * bytes, then read every decoded section end to end and exercise every technique the blob holds
 * (prt_asset_techniques() and the test-side table of exercises, one row per technique), and load
 * it as a scene manifest, so that any out-of-bounds access shows up under AddressSanitizer. Built
 * with -fsanitize=fuzzer when PRT_BUILD_FUZZERS=ON, otherwise with fuzz_replay.c as a plain program
 * that replays files (a CTest test runs it on the golden blobs). */
#include <prt/prt.h>

#include <stdlib.h>
#include <string.h>

#include "../support/technique_exercises.h"

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

static prt_result load_and_touch(prt_context* context, const void* data, size_t size,
                                 prt_validation level, int borrowed) {
  prt_asset* asset = NULL;
  prt_result r = borrowed ? prt_asset_load_memory_borrowed(context, data, size, level, &asset)
                          : prt_asset_load_memory(context, data, size, level, &asset);
  if (r == PRT_OK) {
    volatile unsigned sink = touch_sections(asset);
    (void)sink;
    /* A corrupt row may fail at quick validation; after full validation every call succeeds. */
    if (!prt_test_exercise_techniques(asset, level)) abort();
  } else if (asset != NULL) {
    abort(); /* a failed load must not hand out an asset */
  }
  prt_asset_destroy(asset);
  return r;
}

/* The fuzzer has no files: every blob a manifest names fails to load, so a scene load succeeds
 * only for a manifest of no objects, which must then light and shade. */
static prt_result refuse_blob(void* user, prt_context* context, const char* path,
                              prt_validation validation, prt_asset** out_asset) {
  (void)user;
  (void)context;
  (void)validation;
  if (!path || !*path) abort(); /* the manifest's checker refuses empty paths */
  *out_asset = NULL;
  return PRT_ERROR_IO;
}

static void load_as_scene(prt_context* context, const void* data, size_t size,
                          prt_validation level) {
  static const float sky[3] = {1.0f, 1.0f, 1.0f};
  prt_scene_desc desc;
  prt_scene_frame frame;
  prt_env_image env;
  prt_scene* scene = NULL;
  memset(&desc, 0, sizeof desc);
  desc.struct_size = sizeof desc;
  desc.validation = level;
  desc.load_blob = refuse_blob;
  if (prt_scene_load_memory(context, data, size, &desc, &scene) != PRT_OK) {
    if (scene) abort();
    return;
  }
  if (prt_scene_object_count(scene) != 0) abort();
  memset(&env, 0, sizeof env);
  env.struct_size = sizeof env;
  env.layout = PRT_ENV_LATLONG;
  env.width = env.height = 1;
  env.channels = 3;
  env.texels = sky;
  memset(&frame, 0, sizeof frame);
  frame.struct_size = sizeof frame;
  if (prt_scene_set_environment(scene, &env) != PRT_OK || prt_scene_shade(scene, &frame) != PRT_OK)
    abort();
  prt_scene_destroy(scene);
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prt_context* context = NULL;
  prt_result quick, full, quick_loaded, loaded;
  uint8_t* copy;
  char message[256];
  if (prt_context_create(NULL, &context) != PRT_OK) abort();

  quick = prt_asset_validate(context, data, size, PRT_VALIDATE_QUICK, message, sizeof message);
  full = prt_asset_validate(context, data, size, PRT_VALIDATE_FULL, message, sizeof message);
  if (full == PRT_OK && quick != PRT_OK) abort(); /* full validation includes quick */
  /* A quick load checks what quick validation checks, and every technique header besides. */
  quick_loaded = load_and_touch(context, data, size, PRT_VALIDATE_QUICK, 0);
  if (quick_loaded == PRT_OK && quick != PRT_OK) abort();
  /* Full validation and a fully validated load agree (short of running out of memory). */
  loaded = load_and_touch(context, data, size, PRT_VALIDATE_FULL, 0);
  if (loaded != full && loaded != PRT_ERROR_OUT_OF_MEMORY && full != PRT_ERROR_OUT_OF_MEMORY)
    abort();
  load_as_scene(context, data, size, PRT_VALIDATE_QUICK);
  load_as_scene(context, data, size, PRT_VALIDATE_FULL);

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
