/* SPDX-License-Identifier: MIT */
/* Technique `cloth` in the test-side table of exercises (support/technique_exercises.h): every
 * read of an asset's CLTH section, on every CPU-side backend (the GL shader is exercised by
 * tests/cloth/gl). Plain C99 (the fuzzer is C). */
#ifndef PRT_TEST_CLOTH_EXERCISE_H
#define PRT_TEST_CLOTH_EXERCISE_H

#include <string.h>

#include <prt/prt.h>

/* Samples: a normal overhead seen from above, a tilted frame seen at a grazing angle, a view
 * below the surface (shades to 0) and a warp parallel to the normal (degenerate: 0). */
#define PRT_TEST_CLOTH_SAMPLES 4u

/* Every fabric's record, name and lookup; shading of the first fabrics' samples on each CPU-side
 * backend with their own and with given parameters, default and non-default settings. Returns 0
 * when a call that must succeed failed: every call once the load accepted the CLTH header and
 * records (a backend may only be unsupported), whatever the level. */
static int prt_test_exercise_cloth_fabric(const prt_asset* asset, uint32_t fabric) {
  static const prt_backend backends[3] = {PRT_BACKEND_CPU, PRT_BACKEND_SIMD, PRT_BACKEND_AUTO};
  static const float normals[3 * PRT_TEST_CLOTH_SAMPLES] = {0, 1, 0, 0, 0.6f, 0.8f,
                                                            0, 1, 0, 0, 1,    0};
  static const float warps[3 * PRT_TEST_CLOTH_SAMPLES] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0};
  static const float views[3 * PRT_TEST_CLOTH_SAMPLES] = {0,    1,     0, 0.8f, 0.1f, 0.59f,
                                                          0.6f, -0.8f, 0, 0,    1,    0};
  static const prt_cloth_lobe lobes[3] = {{{0, 1, 0}, 8.0f, {1, 1, 1}},
                                          {{0.6f, 0.0f, 0.8f}, 500.0f, {4, 3, 2}},
                                          {{0, -1, 0}, 0.25f, {0.001f, 0.001f, 0.001f}}};
  const char* name = NULL;
  prt_cloth_params params;
  prt_cloth_weave weave;
  prt_cloth_light light;
  prt_cloth_settings settings;
  prt_cloth_pixels pixels;
  float rgb[3 * PRT_TEST_CLOTH_SAMPLES];
  size_t table_bytes = 0;
  uint32_t found = 0;
  int b;
  prt_result r;
  params.struct_size = sizeof params;
  weave.struct_size = sizeof weave;
  if (prt_cloth_get_fabric(asset, fabric, &name, &params, &weave, &table_bytes) != PRT_OK) return 0;
  if (!name || prt_cloth_find_fabric(asset, name, &found) != PRT_OK) return 0;
  if (prt_cloth_get_fabric(asset, found, &name, NULL, NULL, NULL) != PRT_OK) return 0;
  light.struct_size = sizeof light;
  light.lobe_count = 3;
  light.lobes = lobes;
  memset(&settings, 0, sizeof settings);
  settings.struct_size = sizeof settings;
  settings.flags =
      PRT_CLOTH_KEEP_HIDDEN_LOBES | PRT_CLOTH_KEEP_WEAK_LOBES | PRT_CLOTH_NO_CONE_TABLE;
  settings.theta_segments = 1;
  settings.phi_nodes = 1;
  pixels.struct_size = sizeof pixels;
  pixels.normals = normals;
  pixels.warps = warps;
  pixels.views = views;
  for (b = 0; b < 3; ++b) {
    r = prt_cloth_shade(asset, backends[b], fabric, NULL, &light, NULL, &pixels, 0,
                        PRT_TEST_CLOTH_SAMPLES, rgb);
    if (r != PRT_OK && r != PRT_ERROR_UNSUPPORTED_BACKEND) return 0;
    /* The stored defaults passed back: the load checked their ranges. */
    r = prt_cloth_shade(asset, backends[b], fabric, &params, &light, &settings, &pixels, 1, 2, rgb);
    if (r != PRT_OK && r != PRT_ERROR_UNSUPPORTED_BACKEND) return 0;
  }
  return prt_cloth_shade(asset, PRT_BACKEND_GL, fabric, NULL, &light, NULL, &pixels, 0,
                         PRT_TEST_CLOTH_SAMPLES, rgb) == PRT_ERROR_UNSUPPORTED_BACKEND;
}

static int prt_test_exercise_cloth(const prt_asset* asset, prt_validation level) {
  prt_cloth_info info;
  uint32_t f;
  (void)level; /* the header and records were checked at load, whatever the level */
  info.struct_size = sizeof info;
  if (prt_cloth_get_info(asset, &info) != PRT_OK) return 0;
  for (f = 0; f < info.fabric_count; ++f)
    if (!prt_test_exercise_cloth_fabric(asset, f)) return 0;
  return prt_cloth_get_fabric(asset, info.fabric_count, NULL, NULL, NULL, NULL) ==
         PRT_ERROR_NOT_FOUND;
}

#endif /* PRT_TEST_CLOTH_EXERCISE_H */
