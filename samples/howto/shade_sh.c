/* SPDX-License-Identifier: MIT */
/* How to relight an `sh` blob with the runtime alone: load it, describe an environment, project
 * it to SH turned about +Y, and shade every vertex. Usage: shade_sh FILE.prtk [DEGREES]
 * (exit status 0 on success, 1 on a runtime failure, 2 on bad arguments).
 *
 * The environment is made in code so the program needs no image library: a 64 x 32 float RGB
 * lat-long map (prt/prt_env.h: the centre column looks at -Z, the top row is +Y) holding a sky
 * gradient (deep blue at the zenith, pale at the horizon, dark ground below) and a small bright
 * sun. A game describes its own lat-long map or six cube faces the same way, in one
 * prt_env_image that every technique's light takes (see shade_wavelet.c).
 *
 * The vertices are shaded in two halves, as two jobs of a game's job system would do it: each
 * range may run on its own thread (the asset is immutable; see prt_sh_asset.h). */
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

/* Row-major rotation about world +Y by `degrees`: light that came from d comes from R d. */
static void rotation_about_y(double degrees, float r[9]) {
  const double a = degrees * PI / 180.0;
  const float c = (float)cos(a), s = (float)sin(a);
  r[0] = c, r[1] = 0.0f, r[2] = s;
  r[3] = 0.0f, r[4] = 1.0f, r[5] = 0.0f;
  r[6] = -s, r[7] = 0.0f, r[8] = c;
}

/* Shades vertices [first, first+count) into out_rgb + 3*first; prints why on failure. */
static int shade_range(const prt_asset* asset, const float* light, uint32_t first, uint32_t count,
                       float* out_rgb) {
  const prt_result result =
      prt_sh_shade(asset, PRT_BACKEND_AUTO, light, first, count, out_rgb + 3 * (size_t)first);
  if (result != PRT_OK) {
    fprintf(stderr, "shading vertices %u..%u failed: %s\n", (unsigned)first,
            (unsigned)(first + count), prt_result_string(result));
    return 0;
  }
  return 1;
}

int main(int argc, char** argv) {
  prt_context_desc desc = {0};
  prt_context* context = NULL;
  prt_asset* asset = NULL;
  prt_sh_info info = {0};
  prt_env_image env = {0};
  static float environment[ENV_WIDTH * ENV_HEIGHT * 3];
  float light[PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER * 3], rotation[9];
  float* shaded = NULL;
  double degrees = 0.0;
  uint32_t half, v;
  prt_result result;
  int ok = 0;

  if (argc < 2 || argc > 3) {
    fprintf(stderr, "usage: %s FILE.prtk [DEGREES]\n", argv[0]);
    return 2;
  }
  if (argc == 3) {
    char* end = NULL;
    degrees = strtod(argv[2], &end);
    if (end == argv[2] || *end != '\0') {
      fprintf(stderr, "%s: DEGREES must be a number, got '%s'\n", argv[0], argv[2]);
      return 2;
    }
  }
  desc.struct_size = sizeof desc; /* every struct that may grow starts with its size */
  desc.message = print_message;
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT; /* a tool: PRT_BACKEND=cpu may lower the backend */
  if (prt_context_create(&desc, &context) != PRT_OK) return 1;
  if (prt_asset_load_file(context, argv[1], PRT_VALIDATE_FULL, &asset) != PRT_OK) goto done;
  info.struct_size = sizeof info;
  result = prt_sh_get_info(asset, &info);
  if (result != PRT_OK) {
    fprintf(stderr, "%s: no `sh` transfer: %s\n", argv[1], prt_result_string(result));
    goto done;
  }

  /* The light: the map projected at the asset's order, turned by the rotation (which the
   * projection applies to the SH coefficients with prt_sh_rotate). */
  build_environment(environment);
  rotation_about_y(degrees, rotation);
  env.struct_size = sizeof env;
  env.layout = PRT_ENV_LATLONG;
  env.width = ENV_WIDTH;
  env.height = ENV_HEIGHT;
  env.channels = 3;
  env.texels = environment; /* tight rows: row_stride 0 */
  env.rotation = rotation;
  result = prt_sh_project(info.order, &env, light);
  if (result != PRT_OK) {
    fprintf(stderr, "projecting the environment failed: %s\n", prt_result_string(result));
    goto done;
  }

  /* Two vertex ranges, as two jobs would shade them. */
  shaded = (float*)malloc(3 * (size_t)info.vertex_count * sizeof(float) + 1);
  if (!shaded) goto done;
  half = info.vertex_count / 2;
  if (!shade_range(asset, light, 0, half, shaded) ||
      !shade_range(asset, light, half, info.vertex_count - half, shaded)) {
    goto done;
  }

  printf("%s: %u vertices, order %u; environment rotated %g degrees; backend %s\n", argv[1],
         (unsigned)info.vertex_count, (unsigned)info.order, degrees,
         prt_backend_name(prt_context_backend(context)));
  for (v = 0; v < info.vertex_count && v < 4; ++v) {
    printf("vertex %u: rgb %.6f %.6f %.6f\n", (unsigned)v, shaded[3 * v], shaded[3 * v + 1],
           shaded[3 * v + 2]);
  }
  ok = 1;

done:
  free(shaded);
  prt_asset_destroy(asset);
  prt_context_destroy(context);
  return ok ? 0 : 1;
}
