/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield` in the test-side table of exercises (support/technique_exercises.h):
 * every read of an asset's SFLD section the public API offers, on every CPU-side backend (the GL
 * shader is exercised by tests/shadowfield/gl; here only its refusal without a GL context). A
 * scene of three instances of the asset's object, placed so that each pair's bounding spheres
 * are within the other's outer shell (the occlusion and radiance fields are read) and one scaled
 * and turned, is shaded whole (0 and the default 3 bounces; scalar, SIMD and AUTO; on one thread
 * and on a pool) and in stages (prepare, gather, project, output over split vertex ranges). Plain
 * C99 (the fuzzer is C). */
#ifndef PRT_TEST_SHADOWFIELD_EXERCISE_H
#define PRT_TEST_SHADOWFIELD_EXERCISE_H

#include <stdlib.h>
#include <string.h>

#include <prt/prt.h>

#define PRT_TEST_SHADOWFIELD_INSTANCES 3u

/* A GL loader that has no entry points (no GL context). */
static void* prt_test_shadowfield_no_gl(void* user, const char* name) {
  (void)user, (void)name;
  return NULL;
}

/* Instance i of the exercise's scene: the object's own frame; a copy moved by 0.3 of the OOF
 * grid's radius along every axis, turned 90 degrees about y and halved; one turned 90 degrees
 * about z, doubled and moved the other way. */
static prt_shadowfield_transform prt_test_shadowfield_place(const prt_shadowfield_info* info,
                                                            uint32_t i) {
  static const float kRotations[PRT_TEST_SHADOWFIELD_INSTANCES][9] = {
      {1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 1, 0, 1, 0, -1, 0, 0}, {0, -1, 0, 1, 0, 0, 0, 0, 1}};
  static const float kScales[PRT_TEST_SHADOWFIELD_INSTANCES] = {1.0f, 0.5f, 2.0f};
  static const float kShift[PRT_TEST_SHADOWFIELD_INSTANCES] = {0.0f, 0.3f, -0.3f};
  prt_shadowfield_transform t;
  int c;
  memset(&t, 0, sizeof t);
  t.struct_size = sizeof t;
  memcpy(t.rotation, kRotations[i], sizeof t.rotation);
  for (c = 0; c < 3; ++c) t.translation[c] = kShift[i] * info->oof_shells.radius;
  t.scale = kScales[i];
  return t;
}

/* The frame in stages: prepare, every pass's gather over two vertex ranges per instance, the
 * projections between passes, then each pass's output. Returns 0 when a call failed. */
static int prt_test_shadowfield_stages(prt_shadowfield_scene* scene, const float* light,
                                       const float eye[3], uint32_t bounces, float* rgb) {
  prt_shadowfield_settings settings;
  uint32_t pass, i;
  memset(&settings, 0, sizeof settings);
  settings.struct_size = sizeof settings;
  settings.bounces = bounces;
  settings.backend = PRT_BACKEND_AUTO;
  if (prt_shadowfield_prepare(scene, light, eye, &settings) != PRT_OK) return 0;
  for (pass = 0; pass <= bounces; ++pass) {
    for (i = 0; i < PRT_TEST_SHADOWFIELD_INSTANCES; ++i) {
      const uint32_t v = prt_shadowfield_instance_vertex_count(scene, i), half = v / 2u;
      if (prt_shadowfield_gather(scene, pass, i, 0, half) != PRT_OK ||
          prt_shadowfield_gather(scene, pass, i, half, v - half) != PRT_OK)
        return 0;
    }
    if (pass < bounces &&
        (prt_shadowfield_project(scene, pass, 0, 1) != PRT_OK ||
         prt_shadowfield_project(scene, pass, 1, PRT_TEST_SHADOWFIELD_INSTANCES - 1) != PRT_OK))
      return 0;
  }
  for (pass = 0; pass <= bounces; ++pass)
    for (i = 0; i < PRT_TEST_SHADOWFIELD_INSTANCES; ++i) {
      const uint32_t v = prt_shadowfield_instance_vertex_count(scene, i);
      if (prt_shadowfield_output(scene, i, pass, 0, v, rgb) != PRT_OK) return 0;
    }
  /* A pass beyond the prepared ones is refused, not read. */
  return prt_shadowfield_gather(scene, bounces + 1u, 0, 0, 1) == PRT_ERROR_INVALID_ARGUMENT;
}

/* Whole frames on one backend, 0 and the default bounces; a backend may only be unsupported. */
static int prt_test_shadowfield_shade(prt_shadowfield_scene* scene, prt_workers* workers,
                                      prt_backend backend, const float* light, const float eye[3],
                                      float* const* out) {
  prt_shadowfield_settings settings;
  prt_result r;
  memset(&settings, 0, sizeof settings);
  settings.struct_size = sizeof settings;
  settings.backend = backend;
  r = prt_shadowfield_shade(scene, light, eye, &settings, out);
  if (r == PRT_ERROR_UNSUPPORTED_BACKEND && backend == PRT_BACKEND_SIMD) return 1;
  if (r != PRT_OK) return 0;
  settings.bounces = PRT_SHADOWFIELD_DEFAULT_BOUNCES;
  if (prt_shadowfield_shade(scene, light, eye, &settings, out) != PRT_OK) return 0;
  return !workers ||
         prt_shadowfield_shade_workers(workers, scene, light, eye, &settings, out) == PRT_OK;
}

/* Returns 0 when a call failed that must succeed: every call once the load accepted the SFLD
 * header (the load decoded the object), whatever the level, short of running out of memory. */
static int prt_test_exercise_shadowfield(const prt_asset* asset, prt_validation level) {
  static const prt_backend kBackends[3] = {PRT_BACKEND_CPU, PRT_BACKEND_SIMD, PRT_BACKEND_AUTO};
  prt_shadowfield_info info;
  prt_context* context = NULL;
  prt_shadowfield_scene* scene = NULL;
  prt_workers* workers = NULL;
  prt_workers_desc pool;
  prt_gl_shadowfield* shader = NULL;
  prt_shadowfield_settings gl_settings;
  float* light = NULL;
  float* rgb = NULL;
  float* out[PRT_TEST_SHADOWFIELD_INSTANCES];
  const float eye[3] = {0.7f, 3.0f, 2.0f};
  uint32_t object = 0, i, n2, b;
  size_t v;
  int ok = 0;
  (void)level; /* the header was checked at load, whatever the level */
  info.struct_size = sizeof info;
  if (prt_shadowfield_get_info(asset, &info) != PRT_OK || info.vertex_count == 0) return 0;
  if (prt_context_create(NULL, &context) != PRT_OK) return 0;
  n2 = info.order * info.order;
  v = info.vertex_count;
  light = (float*)calloc(3u * n2, sizeof(float));
  rgb = (float*)calloc(3u * v * PRT_TEST_SHADOWFIELD_INSTANCES, sizeof(float));
  if (!light || !rgb) goto done;
  for (i = 0; i < 3u * n2; ++i) light[i] = i < 3u ? 2.0f + (float)i : 0.5f / (float)(1u + i);
  for (i = 0; i < PRT_TEST_SHADOWFIELD_INSTANCES; ++i) out[i] = rgb + 3u * v * i;
  out[1] = NULL; /* an instance's output may be skipped */

  if (prt_shadowfield_scene_create(context, PRT_TEST_SHADOWFIELD_INSTANCES, &scene) != PRT_OK ||
      prt_shadowfield_scene_add_object(scene, asset, &object) != PRT_OK ||
      prt_shadowfield_scene_order(scene) != info.order)
    goto done;
  for (i = 0; i < PRT_TEST_SHADOWFIELD_INSTANCES; ++i) {
    const prt_shadowfield_transform t = prt_test_shadowfield_place(&info, i);
    uint32_t id = 99;
    if (prt_shadowfield_scene_add_instance(scene, object, &t, &id) != PRT_OK || id != i ||
        prt_shadowfield_instance_vertex_count(scene, i) != info.vertex_count)
      goto done;
  }

  /* The GL backend without a GL context: refused, by the CPU calls and by create. */
  memset(&gl_settings, 0, sizeof gl_settings);
  gl_settings.struct_size = sizeof gl_settings;
  gl_settings.backend = PRT_BACKEND_GL;
  if (prt_shadowfield_shade(scene, light, eye, &gl_settings, out) !=
          PRT_ERROR_UNSUPPORTED_BACKEND ||
      prt_gl_shadowfield_create(scene, prt_test_shadowfield_no_gl, NULL, &shader) !=
          PRT_ERROR_UNSUPPORTED_BACKEND ||
      shader != NULL)
    goto done;

  memset(&pool, 0, sizeof pool);
  pool.struct_size = sizeof pool;
  pool.thread_count = 2;
  if (prt_workers_create(context, &pool, &workers) != PRT_OK) goto done;
  for (b = 0; b < 3; ++b)
    if (!prt_test_shadowfield_shade(scene, b == 2 ? workers : NULL, kBackends[b], light, eye, out))
      goto done;
  if (!prt_test_shadowfield_stages(scene, light, eye, 1, rgb)) goto done;
  /* A moved instance, shaded again. */
  {
    prt_shadowfield_transform t = prt_test_shadowfield_place(&info, 2);
    t.translation[1] += 0.25f * t.translation[0];
    if (prt_shadowfield_scene_set_transform(scene, 2, &t) != PRT_OK ||
        prt_shadowfield_shade(scene, light, eye, NULL, out) != PRT_OK)
      goto done;
  }
  /* The log-space product: its fields made from the object's, then every backend again. Its
   * fields cost hundreds of evaluations per OOF point, so only for grids of a few thousand
   * points (the golden files'), not the largest a fuzzed header may declare. */
  if ((uint64_t)info.oof_shells.shells * 6u * info.oof_shells.face_size *
          info.oof_shells.face_size <=
      4096u) {
    if (prt_shadowfield_scene_set_product(scene, PRT_SHADOWFIELD_PRODUCT_LOG) != PRT_OK ||
        prt_shadowfield_scene_product(scene) != PRT_SHADOWFIELD_PRODUCT_LOG)
      goto done;
    for (b = 0; b < 3; ++b)
      if (!prt_test_shadowfield_shade(scene, b == 2 ? workers : NULL, kBackends[b], light, eye,
                                      out))
        goto done;
  }
  ok = 1;

done:
  prt_workers_destroy(workers);
  prt_shadowfield_scene_destroy(scene);
  prt_context_destroy(context);
  free(light);
  free(rgb);
  return ok;
}

#endif /* PRT_TEST_SHADOWFIELD_EXERCISE_H */
