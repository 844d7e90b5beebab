/* SPDX-License-Identifier: MIT */
/* How to shade a `pose` blob (a skinned character's learned transfer) with the runtime alone:
 * load it, start from the bind pose, bend one joint as a game's animation system would, and
 * shade every vertex under a light turned with the character. Usage:
 * shade_pose FILE.prtk [JOINT [DEGREES]] (exit status 0 on success, 1 on a runtime failure, 2 on
 * bad arguments).
 *
 * The light is made straight in SH so the program needs no image: a sun (the projection of a
 * unit-power delta, prt_sh_eval) over a constant sky. A game would project its environment map
 * with prt_sh_project (see shade_sh.c). The character stands in the world turned 90 degrees about
 * +Y (world_from_character); the runtime turns the light into the character's model frame. */
#include <prt/prt.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define MAX_COEFFICIENTS 64 /* order 8 */

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

/* q = q * (rotation by `degrees` about the joint's local x axis): bends the joint. */
static void bend(float* q, double degrees) {
  const double h = 0.5 * degrees * PI / 180.0;
  const float s = (float)sin(h), c = (float)cos(h);
  const float x = q[0], y = q[1], z = q[2], w = q[3];
  q[0] = w * s + x * c;
  q[1] = y * c + z * s;
  q[2] = z * c - y * s;
  q[3] = w * c - x * s;
}

static int parse_arguments(int argc, char** argv, long* joint, double* degrees) {
  char* end = NULL;
  if (argc < 2 || argc > 4) {
    fprintf(stderr, "usage: %s FILE.prtk [JOINT [DEGREES]]\n", argv[0]);
    return 0;
  }
  if (argc >= 3) {
    *joint = strtol(argv[2], &end, 10);
    if (end == argv[2] || *end != '\0' || *joint < 0) {
      fprintf(stderr, "%s: JOINT must be a joint index, got '%s'\n", argv[0], argv[2]);
      return 0;
    }
  }
  if (argc == 4) {
    *degrees = strtod(argv[3], &end);
    if (end == argv[3] || *end != '\0') {
      fprintf(stderr, "%s: DEGREES must be a number, got '%s'\n", argv[0], argv[3]);
      return 0;
    }
  }
  return 1;
}

int main(int argc, char** argv) {
  static const float kQuarterTurnAboutY[9] = {0, 0, 1, 0, 1, 0, -1, 0, 0};
  prt_context_desc desc = {0};
  prt_context* context = NULL;
  prt_asset* asset = NULL;
  prt_pose_info info = {0};
  prt_pose_input pose = {0};
  prt_pose_light light = {0};
  float light_rgb[MAX_COEFFICIENTS * 3];
  float *rotations = NULL, *shaded = NULL;
  long joint = -1;
  double degrees = 40.0;
  uint32_t half, v;
  prt_result result;
  int ok = 0;

  if (!parse_arguments(argc, argv, &joint, &degrees)) return 2;
  desc.struct_size = sizeof desc;
  desc.message = print_message;
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  if (prt_context_create(&desc, &context) != PRT_OK) return 1;
  if (prt_asset_load_file(context, argv[1], PRT_VALIDATE_FULL, &asset) != PRT_OK) goto done;
  info.struct_size = sizeof info;
  result = prt_pose_get_info(asset, &info);
  if (result != PRT_OK) {
    fprintf(stderr, "%s: no `pose` model: %s\n", argv[1], prt_result_string(result));
    goto done;
  }
  if (joint < 0) joint = info.joint_count / 2;
  if (joint >= (long)info.joint_count) {
    fprintf(stderr, "%s: JOINT must be below %u\n", argv[0], (unsigned)info.joint_count);
    goto done;
  }

  /* The pose: every joint at its bind rotation, then one joint bent. */
  rotations = (float*)malloc(4 * (size_t)info.joint_count * sizeof(float));
  shaded = (float*)malloc(3 * (size_t)info.vertex_count * sizeof(float) + 1);
  if (!rotations || !shaded) goto done;
  if (prt_pose_bind_pose(asset, rotations, NULL, NULL) != PRT_OK) goto done;
  bend(rotations + 4 * joint, degrees);
  pose.struct_size = sizeof pose;
  pose.joint_rotations = rotations;

  if (!build_light(info.order, light_rgb)) goto done;
  light.struct_size = sizeof light;
  light.light_rgb = light_rgb;
  light.world_from_character = kQuarterTurnAboutY;

  /* Two vertex ranges, as two jobs would shade them. */
  half = info.vertex_count / 2;
  if (prt_pose_shade(asset, PRT_BACKEND_AUTO, &pose, &light, 0, half, shaded) != PRT_OK ||
      prt_pose_shade(asset, PRT_BACKEND_AUTO, &pose, &light, half, info.vertex_count - half,
                     shaded + 3 * (size_t)half) != PRT_OK) {
    goto done;
  }
  printf(
      "%s: %u vertices, %u joints, %s model PCA(%u, %u), %u bytes; joint %ld bent %g "
      "degrees; backend %s\n",
      argv[1], (unsigned)info.vertex_count, (unsigned)info.joint_count,
      info.model == PRT_POSE_MODEL_DIRECT ? "direct" : "residual", (unsigned)info.pose_dims,
      (unsigned)info.basis_dims, (unsigned)info.model_bytes, joint, degrees,
      prt_backend_name(prt_context_backend(context)));
  for (v = 0; v < info.vertex_count && v < 4; ++v) {
    printf("vertex %u: rgb %.6f %.6f %.6f\n", (unsigned)v, shaded[3 * v], shaded[3 * v + 1],
           shaded[3 * v + 2]);
  }
  ok = 1;

done:
  free(rotations);
  free(shaded);
  prt_asset_destroy(asset);
  prt_context_destroy(context);
  return ok ? 0 : 1;
}
