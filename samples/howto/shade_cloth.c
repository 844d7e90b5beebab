/* SPDX-License-Identifier: MIT */
/* How to shade a `cloth` blob (woven fabrics' tables, baked by `prt-bake bake cloth`) with the
 * runtime alone: load it, pick a fabric by name, change one of its live parameters (no re-bake),
 * and shade every vertex of the blob's mesh from its normal, its warp (the thread direction,
 * VTAN) and the direction to a camera, under a light of spherical Gaussians. Usage:
 * shade_cloth FILE.prtk [FABRIC] (exit status 0 on success, 1 on a runtime failure, 2 on bad
 * arguments).
 *
 * The light is made straight in lobes so the program needs no image: a sharp warm sun over a
 * wide blue sky lobe and a dim ground bounce. A game would fit its environment map with
 * prt_cloth_fit_light every frame, or load a static fit the baker wrote. A G-buffer renderer
 * would pass per-pixel normals, warps and views instead of the vertices' (or draw with
 * prt_gl_cloth_shade). */
#include <prt/prt.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void print_message(void* user, prt_result result, prt_severity severity, const char* text) {
  static const char* const kSeverity[] = {"debug", "info", "warning", "error"};
  (void)user;
  fprintf(stderr, "prtkit %s (%s): %s\n", kSeverity[severity & 3], prt_result_string(result), text);
}

/* The mesh the blob carries: positions, normals and warps, 3 floats per vertex each. */
static int mesh_section(const prt_asset* asset, uint32_t tag, const float** data, size_t* count) {
  const void* bytes = NULL;
  size_t size = 0;
  if (prt_asset_section_data(asset, tag, &bytes, &size) != PRT_OK) return 0;
  *data = (const float*)bytes;
  *count = size / (3 * sizeof(float));
  return 1;
}

int main(int argc, char** argv) {
  static const prt_cloth_lobe kLobes[3] = {
      {{0.36f, 0.80f, 0.48f}, 2000.0f, {400.0f, 360.0f, 300.0f}}, /* sun */
      {{0.0f, 1.0f, 0.0f}, 2.0f, {0.35f, 0.45f, 0.65f}},          /* sky */
      {{0.0f, -1.0f, 0.0f}, 1.0f, {0.10f, 0.09f, 0.08f}}};        /* ground bounce */
  const float eye[3] = {0.0f, 3.0f, 4.0f};
  prt_context_desc desc = {0};
  prt_context* context = NULL;
  prt_asset* asset = NULL;
  prt_cloth_info info = {0};
  prt_cloth_params params = {0};
  prt_cloth_light light = {0};
  prt_cloth_pixels pixels = {0};
  const float *positions = NULL, *normals = NULL, *warps = NULL;
  float *views = NULL, *shaded = NULL;
  size_t count = 0, normal_count = 0, warp_count = 0, v;
  uint32_t fabric = 0, half;
  const char* name = NULL;
  int ok = 0;

  if (argc < 2 || argc > 3) {
    fprintf(stderr, "usage: %s FILE.prtk [FABRIC]\n", argv[0]);
    return 2;
  }
  desc.struct_size = sizeof desc;
  desc.message = print_message;
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  if (prt_context_create(&desc, &context) != PRT_OK) return 1;
  if (prt_asset_load_file(context, argv[1], PRT_VALIDATE_FULL, &asset) != PRT_OK) goto done;
  info.struct_size = sizeof info;
  if (prt_cloth_get_info(asset, &info) != PRT_OK) {
    fprintf(stderr, "%s: no `cloth` section\n", argv[1]);
    goto done;
  }
  if (argc == 3 && prt_cloth_find_fabric(asset, argv[2], &fabric) != PRT_OK) {
    fprintf(stderr, "%s: no fabric '%s'\n", argv[1], argv[2]);
    goto done;
  }
  if (!mesh_section(asset, PRT_SECTION_VPOS, &positions, &count) ||
      !mesh_section(asset, PRT_SECTION_VNRM, &normals, &normal_count) ||
      !mesh_section(asset, PRT_SECTION_VTAN, &warps, &warp_count) || normal_count != count ||
      warp_count != count || count == 0) {
    fprintf(stderr, "%s: the blob has no mesh with normals and warps to shade\n", argv[1]);
    goto done;
  }

  /* The fabric's own parameters, then a live edit: the warp threads' albedo turned greener. */
  params.struct_size = sizeof params;
  if (prt_cloth_get_fabric(asset, fabric, &name, &params, NULL, NULL) != PRT_OK) goto done;
  params.threads[0].albedo[1] = 0.9f;

  /* Each vertex seen from the camera: the unit direction from the vertex to the eye. */
  views = (float*)malloc(3 * count * sizeof(float));
  shaded = (float*)malloc(3 * count * sizeof(float));
  if (!views || !shaded) goto done;
  for (v = 0; v < count; ++v) {
    const float d[3] = {eye[0] - positions[3 * v], eye[1] - positions[3 * v + 1],
                        eye[2] - positions[3 * v + 2]};
    const float length = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    views[3 * v] = d[0] / length, views[3 * v + 1] = d[1] / length;
    views[3 * v + 2] = d[2] / length;
  }
  pixels.struct_size = sizeof pixels;
  pixels.normals = normals;
  pixels.warps = warps;
  pixels.views = views;
  light.struct_size = sizeof light;
  light.lobe_count = 3;
  light.lobes = kLobes;

  /* Two vertex ranges, as two jobs would shade them; NULL settings: the defaults. */
  half = (uint32_t)(count / 2);
  if (prt_cloth_shade(asset, PRT_BACKEND_AUTO, fabric, &params, &light, NULL, &pixels, 0, half,
                      shaded) != PRT_OK ||
      prt_cloth_shade(asset, PRT_BACKEND_AUTO, fabric, &params, &light, NULL, &pixels, half,
                      (uint32_t)count - half, shaded + 3 * (size_t)half) != PRT_OK)
    goto done;
  printf("%s: fabric %u '%s' of %u, %u tables, %u-bit; %u vertices; backend %s\n", argv[1],
         (unsigned)fabric, name, (unsigned)info.fabric_count, (unsigned)info.table_count,
         (unsigned)info.bits, (unsigned)count, prt_backend_name(prt_context_backend(context)));
  for (v = 0; v < count && v < 4; ++v)
    printf("vertex %u: rgb %.6f %.6f %.6f\n", (unsigned)v, shaded[3 * v], shaded[3 * v + 1],
           shaded[3 * v + 2]);
  ok = 1;

done:
  free(views);
  free(shaded);
  prt_asset_destroy(asset);
  prt_context_destroy(context);
  return ok ? 0 : 1;
}
