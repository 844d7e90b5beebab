/* SPDX-License-Identifier: MIT */
/* How to relight a `wavelet` blob with the runtime alone: load it, describe an environment,
 * turn it into the asset's light (resample, Haar transform, keep the M most important
 * coefficients, fold in the asset's band scales), and shade every vertex.
 * Usage: shade_wavelet FILE.prtk [M]   (M: light coefficients kept, default 100; exit status 0 on
 * success, 1 on a runtime failure, 2 on bad arguments).
 *
 * The environment is made in code so the program needs no image library: a 64 x 32 float RGB
 * lat-long map (prt/prt_env.h: the centre column looks at -Z, the top row is +Y) holding a sky
 * gradient and a small bright sun, the same map shade_sh.c projects to SH: one prt_env_image
 * describes it for every technique. The light is rebuilt each frame in a game (it may run on any
 * thread, e.g. for frame n+1 while frame n shades); M trades accuracy for speed, since the
 * shading skips every 256-coefficient block the selection left dark (the zero-block mask).
 *
 * The vertices are shaded in two halves, as two jobs of a game's job system would do it: each
 * range may run on its own thread (the asset is immutable; see prt_wavelet_asset.h). */
#include <prt/prt.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define ENV_WIDTH 64
#define ENV_HEIGHT 32
#define PI 3.14159265358979323846

static void print_message(void* user, prt_result result, prt_severity severity, const char* text) {
  static const char* const kSeverity[] = {"debug", "info", "warning", "error"};
  (void)user;
  fprintf(stderr, "prtkit %s (%s): %s\n", kSeverity[severity & 3], prt_result_string(result), text);
}

/* Sky gradient and a sun 40 degrees above the horizon, towards -Z turned 30 degrees to +X. */
static void build_environment(float* rgb) {
  const double sun_elevation = 40.0 * PI / 180.0, sun_azimuth = 30.0 * PI / 180.0;
  const double sun[3] = {cos(sun_elevation) * sin(sun_azimuth), sin(sun_elevation),
                         -cos(sun_elevation) * cos(sun_azimuth)};
  const double sun_cos_radius = cos(6.0 * PI / 180.0);
  int x, y;
  for (y = 0; y < ENV_HEIGHT; ++y) {
    const double theta = PI * (y + 0.5) / ENV_HEIGHT;
    for (x = 0; x < ENV_WIDTH; ++x) {
      const double phi = 2.0 * PI * ((x + 0.5) / ENV_WIDTH - 0.5);
      const double d[3] = {sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi)};
      float* texel = rgb + 3 * (y * ENV_WIDTH + x);
      if (d[1] >= 0.0) { /* sky: blend from pale at the horizon to blue at the zenith */
        const double t = d[1];
        texel[0] = (float)(0.9 - 0.7 * t);
        texel[1] = (float)(0.95 - 0.55 * t);
        texel[2] = (float)(1.0 - 0.2 * t);
      } else { /* ground */
        texel[0] = 0.15f;
        texel[1] = 0.12f;
        texel[2] = 0.1f;
      }
      if (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] > sun_cos_radius) {
        texel[0] += 60.0f;
        texel[1] += 55.0f;
        texel[2] += 45.0f;
      }
    }
  }
}

/* The asset's light from the environment: info.coefficient_count RGBA quadruples, prepared, and
 * the zero-block mask (info.block_count bytes). Prints why on failure. */
static int build_light(const prt_asset* asset, const prt_wavelet_info* info,
                       const prt_env_image* env, uint32_t m, float* light, uint8_t* zero_blocks) {
  prt_result result = prt_wavelet_resample(info->param, info->size, env, light);
  if (result == PRT_OK) result = prt_wavelet_transform_light(info->param, info->size, light);
  if (result == PRT_OK) result = prt_wavelet_select_light(info->param, info->size, m, light);
  if (result == PRT_OK) result = prt_wavelet_prepare_light(asset, light, light, zero_blocks);
  if (result != PRT_OK) {
    fprintf(stderr, "building the light failed: %s\n", prt_result_string(result));
    return 0;
  }
  return 1;
}

/* Shades vertices [first, first+count) into out_rgb + 3*first; prints why on failure. */
static int shade_range(const prt_asset* asset, const float* light, const uint8_t* zero_blocks,
                       uint32_t first, uint32_t count, float* out_rgb) {
  const prt_result result = prt_wavelet_shade(asset, PRT_BACKEND_AUTO, light, zero_blocks, first,
                                              count, out_rgb + 3 * (size_t)first);
  if (result != PRT_OK) {
    fprintf(stderr, "shading vertices %u..%u failed: %s\n", (unsigned)first,
            (unsigned)(first + count), prt_result_string(result));
    return 0;
  }
  return 1;
}

/* Parses M; returns 0 when `text` is not a whole number. */
static int parse_m(const char* text, uint32_t* m) {
  char* end = NULL;
  const unsigned long value = strtoul(text, &end, 10);
  if (end == text || *end != '\0' || text[0] == '-' || value > 0xFFFFFFFFul) return 0;
  *m = (uint32_t)value;
  return 1;
}

int main(int argc, char** argv) {
  prt_context_desc desc = {0};
  prt_context* context = NULL;
  prt_asset* asset = NULL;
  prt_wavelet_info info = {0};
  prt_env_image env = {0};
  static float environment[ENV_WIDTH * ENV_HEIGHT * 3];
  float* light = NULL;
  float* shaded = NULL;
  uint8_t* zero_blocks = NULL;
  uint32_t m = 100, half, v, dark = 0, details;
  prt_result result;
  int ok = 0;

  if (argc < 2 || argc > 3 || (argc == 3 && !parse_m(argv[2], &m))) {
    fprintf(stderr, "usage: %s FILE.prtk [M]  (M: light coefficients kept, a whole number)\n",
            argv[0]);
    return 2;
  }
  desc.struct_size = sizeof desc; /* every struct that may grow starts with its size */
  desc.message = print_message;
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT; /* a tool: PRT_BACKEND=cpu may lower the backend */
  if (prt_context_create(&desc, &context) != PRT_OK) return 1;
  if (prt_asset_load_file(context, argv[1], PRT_VALIDATE_FULL, &asset) != PRT_OK) goto done;
  info.struct_size = sizeof info;
  result = prt_wavelet_get_info(asset, &info);
  if (result != PRT_OK) {
    fprintf(stderr, "%s: no `wavelet` transfer: %s\n", argv[1], prt_result_string(result));
    goto done;
  }

  /* The environment, described once, as prt_sh_project would take it too. */
  build_environment(environment);
  env.struct_size = sizeof env;
  env.layout = PRT_ENV_LATLONG;
  env.width = ENV_WIDTH;
  env.height = ENV_HEIGHT;
  env.channels = 3;
  env.texels = environment; /* tight rows: row_stride 0; no rotation */

  light = (float*)malloc(4 * (size_t)info.coefficient_count * sizeof(float));
  zero_blocks = (uint8_t*)malloc(info.block_count);
  shaded = (float*)malloc(3 * (size_t)info.vertex_count * sizeof(float) + 1);
  if (!light || !zero_blocks || !shaded) goto done;
  if (!build_light(asset, &info, &env, m, light, zero_blocks)) goto done;
  for (v = 0; v < info.block_count; ++v) dark += zero_blocks[v];

  /* Two vertex ranges, as two jobs would shade them; the mask skips the dark blocks. */
  half = info.vertex_count / 2;
  if (!shade_range(asset, light, zero_blocks, 0, half, shaded) ||
      !shade_range(asset, light, zero_blocks, half, info.vertex_count - half, shaded)) {
    goto done;
  }

  details = info.coefficient_count - info.faces; /* every face keeps its scaling coefficient */
  printf(
      "%s: %u vertices, %s %u; %u + %u light coefficients kept, %u of %u blocks dark; "
      "backend %s\n",
      argv[1], (unsigned)info.vertex_count,
      info.param == PRT_WAVELET_PARAM_CUBE ? "cube" : "dual paraboloid", (unsigned)info.size,
      (unsigned)info.faces, (unsigned)(m < details ? m : details), (unsigned)dark,
      (unsigned)info.block_count, prt_backend_name(prt_context_backend(context)));
  for (v = 0; v < info.vertex_count && v < 4; ++v) {
    printf("vertex %u: rgb %.6f %.6f %.6f\n", (unsigned)v, shaded[3 * v], shaded[3 * v + 1],
           shaded[3 * v + 2]);
  }
  ok = 1;

done:
  free(shaded);
  free(zero_blocks);
  free(light);
  prt_asset_destroy(asset);
  prt_context_destroy(context);
  return ok ? 0 : 1;
}
