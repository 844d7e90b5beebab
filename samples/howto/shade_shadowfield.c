/* SPDX-License-Identifier: MIT */
/* How to shade a `shadowfield` blob (one rigid object baked alone: its self-shadowed transfer,
 * the occlusion field it casts and the radiance fields it emits) with the runtime alone: load it,
 * put several instances of its object in a scene, each with its own placement, and shade every
 * instance's vertices as the instances shadow and light each other; then move one, as a game
 * does every frame, and shade again. Usage: shade_shadowfield FILE.prtk [INSTANCES [BOUNCES]]
 * (default 3 instances, 2 bounces; exit status 0 on success, 1 on a runtime failure, 2 on bad
 * arguments).
 *
 * The light is made straight in SH so the program needs no image: a sun (the projection of a
 * unit-power delta, prt_sh_eval) over a constant sky. A game would project its environment map
 * with prt_sh_project (see shade_sh.c). A scene may hold several objects (one per blob), all of
 * one SH order; a game's job system can run the frame in stages (prt_shadowfield_prepare,
 * _gather_probes, _gather, _project, _output) or hand it to a runtime pool
 * (prt_shadowfield_shade_workers). On large scenes, settings.bounce_probe_spacing gathers the
 * bounce light on a coarse grid (docs/shadowfield/design.md, "Bounce probes"). */
#include <prt/prt.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define MAX_COEFFICIENTS 36 /* order 6, the largest SFLD holds */
#define MAX_INSTANCES 16

static void print_message(void* user, prt_result result, prt_severity severity, const char* text) {
  static const char* const kSeverity[] = {"debug", "info", "warning", "error"};
  (void)user;
  fprintf(stderr, "prtkit %s (%s): %s\n", kSeverity[severity & 3], prt_result_string(result), text);
}

/* A warm sun from above and in front, over a pale blue sky of constant radiance. */
static int build_light(uint32_t order, float* rgb) {
  const float sun[3] = {0.3f, 0.8f, 0.5f};
  float y[MAX_COEFFICIENTS];
  const float sky = 0.3f * 2.0f * (float)sqrt(PI); /* L_00 of a constant 0.3: 0.3 / y_00 */
  uint32_t i;
  if (prt_sh_eval(order, sun, y) != PRT_OK) return 0;
  for (i = 0; i < order * order; ++i) {
    rgb[3 * i + 0] = 3.0f * y[i];
    rgb[3 * i + 1] = 2.7f * y[i];
    rgb[3 * i + 2] = 2.2f * y[i];
  }
  rgb[0] += 0.8f * sky, rgb[1] += 0.9f * sky, rgb[2] += 1.0f * sky;
  return 1;
}

/* Instance i stands on a row along x, each turned a further 40 degrees about +Y and a little
 * smaller, a bounding radius apart so that neighbours shadow and light each other. */
static prt_shadowfield_transform place(const prt_shadowfield_info* info, uint32_t i) {
  const double angle = 40.0 * i * PI / 180.0;
  const float c = (float)cos(angle), s = (float)sin(angle);
  prt_shadowfield_transform t = {0};
  t.struct_size = sizeof t;
  t.rotation[0] = c, t.rotation[2] = s;
  t.rotation[4] = 1.0f;
  t.rotation[6] = -s, t.rotation[8] = c;
  t.translation[0] = info->oof_shells.radius * (float)i;
  t.scale = 1.0f - 0.1f * (float)(i % 4);
  return t;
}

static int parse_count(const char* text, long min, long max, long* out) {
  char* end = NULL;
  const long value = strtol(text, &end, 10);
  if (end == text || *end != '\0' || value < min || value > max) return 0;
  *out = value;
  return 1;
}

int main(int argc, char** argv) {
  const float eye[3] = {0.0f, 3.0f, 5.0f};
  prt_context_desc desc = {0};
  prt_context* context = NULL;
  prt_asset* asset = NULL;
  prt_shadowfield_scene* scene = NULL;
  prt_shadowfield_info info = {0};
  prt_shadowfield_settings settings = {0};
  prt_shadowfield_transform moved;
  float light[3 * MAX_COEFFICIENTS];
  float* shaded[MAX_INSTANCES] = {0};
  long instances = 3, bounces = 2;
  uint32_t object = 0, i, v;
  prt_result r;
  int ok = 0;

  if (argc < 2 || argc > 4 || (argc >= 3 && !parse_count(argv[2], 1, MAX_INSTANCES, &instances)) ||
      (argc >= 4 && !parse_count(argv[3], 0, PRT_SHADOWFIELD_MAX_BOUNCES, &bounces))) {
    fprintf(stderr, "usage: %s FILE.prtk [INSTANCES (1..%d) [BOUNCES (0..%u)]]\n", argv[0],
            MAX_INSTANCES, PRT_SHADOWFIELD_MAX_BOUNCES);
    return 2;
  }
  desc.struct_size = sizeof desc;
  desc.message = print_message;
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  if (prt_context_create(&desc, &context) != PRT_OK) return 1;
  if (prt_asset_load_file(context, argv[1], PRT_VALIDATE_FULL, &asset) != PRT_OK) goto done;
  info.struct_size = sizeof info;
  r = prt_shadowfield_get_info(asset, &info);
  if (r != PRT_OK) {
    fprintf(stderr, "%s: no `shadowfield` object: %s\n", argv[1], prt_result_string(r));
    goto done;
  }

  /* The scene: the asset's object once, then its instances; buffers are allocated here, not
   * per frame. The asset must outlive the scene. */
  if (prt_shadowfield_scene_create(context, (uint32_t)instances, &scene) != PRT_OK ||
      prt_shadowfield_scene_add_object(scene, asset, &object) != PRT_OK)
    goto done;
  for (i = 0; i < (uint32_t)instances; ++i) {
    const prt_shadowfield_transform t = place(&info, i);
    uint32_t id;
    if (prt_shadowfield_scene_add_instance(scene, object, &t, &id) != PRT_OK) goto done;
    shaded[i] = (float*)malloc(3 * sizeof(float) * info.vertex_count);
    if (!shaded[i]) goto done;
  }
  if (!build_light(info.order, light)) goto done;

  /* A frame: SIMD where the CPU has AVX2 and FMA, else the scalar evaluation. */
  settings.struct_size = sizeof settings;
  settings.bounces = (uint32_t)bounces;
  settings.backend = PRT_BACKEND_SIMD;
  r = prt_shadowfield_shade(scene, light, eye, &settings, shaded);
  if (r == PRT_ERROR_UNSUPPORTED_BACKEND) {
    settings.backend = PRT_BACKEND_CPU;
    r = prt_shadowfield_shade(scene, light, eye, &settings, shaded);
  }
  if (r != PRT_OK) goto done;
  printf(
      "%s: %u vertices, order %u, %s (%u BRDF term(s)), basis %u; %ld instances, %ld bounces; "
      "backend %s\n",
      argv[1], (unsigned)info.vertex_count, (unsigned)info.order,
      info.glossy ? "glossy" : "diffuse", (unsigned)info.terms, (unsigned)info.basis_size,
      instances, bounces, prt_backend_name(settings.backend));
  for (i = 0; i < (uint32_t)instances && i < 2; ++i)
    for (v = 0; v < info.vertex_count && v < 2; ++v)
      printf("instance %u vertex %u: rgb %.6f %.6f %.6f\n", (unsigned)i, (unsigned)v,
             shaded[i][3 * v], shaded[i][3 * v + 1], shaded[i][3 * v + 2]);

  /* The next frame: the last instance lifted by a bounding radius; its neighbours' shadows and
   * bounce light follow. */
  moved = place(&info, (uint32_t)instances - 1u);
  moved.translation[1] += info.oof_shells.radius;
  if (prt_shadowfield_scene_set_transform(scene, (uint32_t)instances - 1u, &moved) != PRT_OK ||
      prt_shadowfield_shade(scene, light, eye, &settings, shaded) != PRT_OK)
    goto done;
  printf("instance %ld lifted: instance 0 vertex 0: rgb %.6f %.6f %.6f\n", instances - 1,
         shaded[0][0], shaded[0][1], shaded[0][2]);
  ok = 1;

done:
  for (i = 0; i < MAX_INSTANCES; ++i) free(shaded[i]);
  prt_shadowfield_scene_destroy(scene);
  prt_asset_destroy(asset);
  prt_context_destroy(context);
  return ok ? 0 : 1;
}
