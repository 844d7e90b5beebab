/* SPDX-License-Identifier: MIT */
/* A loaded scene's frames (prt_scene.h): the environment turned into every technique's light,
 * placements and poses handed to the technique that has them, and one shade over all groups.
 * Each call checks its arguments, finds the object's group and leaves the rest to the hooks. */
#include <math.h>
#include <stdio.h>

#include "../techniques.h"
#include "scene_internal.h"

#define PLACEMENT_SIZE_1_0 PRT_SIZE_THROUGH(prt_scene_placement, scale)
#define FRAME_SIZE_1_0 PRT_SIZE_THROUGH(prt_scene_frame, workers)
#define POSE_INPUT_SIZE_1_0 PRT_SIZE_THROUGH(prt_pose_input, joint_scales)

prt_result prt_scene_set_environment(prt_scene* scene, const prt_env_image* env) {
  char msg[PRT_MESSAGE_CAPACITY / 2];
  uint32_t g;
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (prt_env_image_validate(env) != PRT_OK)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_scene_set_environment: the environment image is invalid "
                             "(prt_env_image_validate)");
  for (g = 0; g < scene->group_count; ++g) {
    prt_scene_group* group = &scene->groups[g];
    prt_result r;
    msg[0] = '\0';
    r = group->technique->scene->light(scene->context, group->state, env, msg, sizeof msg);
    if (r != PRT_OK) {
      scene->lit = 0; /* some groups hold the new light, some the old: no frame until set again */
      return prt_internal_fail(scene->context, r, "prt_scene_set_environment: %s", msg);
    }
  }
  scene->lit = 1;
  return PRT_OK;
}

/* The object at `index`, or NULL after recording why not. */
static prt_scene_object* object_at(prt_scene* scene, uint32_t index, const char* function) {
  if (index < scene->object_count) return &scene->objects[index];
  prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                    "%s: object %u is past the scene's %u objects", function, (unsigned)index,
                    (unsigned)scene->object_count);
  return NULL;
}

static int placement_ok(const prt_scene_placement* p) {
  const float* r = p->rotation;
  double det;
  int i, j;
  for (i = 0; i < 9; ++i)
    if (!isfinite(r[i])) return 0;
  for (i = 0; i < 3; ++i)
    if (!isfinite(p->translation[i])) return 0;
  if (!isfinite(p->scale) || !(p->scale > 0.0f)) return 0;
  for (i = 0; i < 3; ++i)
    for (j = 0; j < 3; ++j) {
      const double dot = (double)r[3 * i] * r[3 * j] + (double)r[3 * i + 1] * r[3 * j + 1] +
                         (double)r[3 * i + 2] * r[3 * j + 2];
      if (fabs(dot - (i == j ? 1.0 : 0.0)) > 1e-3) return 0;
    }
  det = (double)r[0] * (r[4] * r[8] - r[5] * r[7]) - (double)r[1] * (r[3] * r[8] - r[5] * r[6]) +
        (double)r[2] * (r[3] * r[7] - r[4] * r[6]);
  return det > 0.0;
}

prt_result prt_scene_set_placement(prt_scene* scene, uint32_t index,
                                   const prt_scene_placement* placement) {
  char msg[PRT_MESSAGE_CAPACITY / 2];
  prt_scene_object* o;
  prt_result r;
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (!placement || !prt_internal_struct_size_ok(placement, PLACEMENT_SIZE_1_0) ||
      !placement_ok(placement))
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_scene_set_placement: the placement is not a proper rotation, "
                             "finite translation and positive scale");
  if (!(o = object_at(scene, index, "prt_scene_set_placement"))) return PRT_ERROR_INVALID_ARGUMENT;
  if (!o->technique->scene->place)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_OPERATION,
                             "prt_scene_set_placement: object '%s' (%s) does not move: its "
                             "transfer is baked in place",
                             o->name, o->technique->name);
  msg[0] = '\0';
  r = o->technique->scene->place(scene->groups[o->group].state, o, placement, msg, sizeof msg);
  return r == PRT_OK ? r : prt_internal_fail(scene->context, r, "prt_scene_set_placement: %s", msg);
}

prt_result prt_scene_set_pose(prt_scene* scene, uint32_t index, const prt_pose_input* pose) {
  char msg[PRT_MESSAGE_CAPACITY / 2];
  prt_scene_object* o;
  prt_result r;
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (!pose || !prt_internal_struct_size_ok(pose, POSE_INPUT_SIZE_1_0) || !pose->joint_rotations)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_scene_set_pose: invalid argument");
  if (!(o = object_at(scene, index, "prt_scene_set_pose"))) return PRT_ERROR_INVALID_ARGUMENT;
  if (!o->technique->scene->pose)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_OPERATION,
                             "prt_scene_set_pose: object '%s' (%s) has no joints", o->name,
                             o->technique->name);
  msg[0] = '\0';
  r = o->technique->scene->pose(scene->groups[o->group].state, o, pose, msg, sizeof msg);
  return r == PRT_OK ? r : prt_internal_fail(scene->context, r, "prt_scene_set_pose: %s", msg);
}

static prt_result check_frame(prt_scene* scene, const prt_scene_frame* frame) {
  if (!frame || !prt_internal_struct_size_ok(frame, FRAME_SIZE_1_0) ||
      (frame->backend != PRT_BACKEND_AUTO && frame->backend != PRT_BACKEND_CPU &&
       frame->backend != PRT_BACKEND_SIMD && frame->backend != PRT_BACKEND_GL) ||
      !isfinite(frame->eye[0]) || !isfinite(frame->eye[1]) || !isfinite(frame->eye[2]))
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_scene_shade: invalid frame (struct_size, backend or eye)");
  if (frame->backend == PRT_BACKEND_GL)
    return prt_internal_fail(scene->context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "prt_scene_shade: a scene shades on the CPU-side backends; GL "
                             "shading runs through each technique's prt_gl_<t> shader");
  if (!scene->lit)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_OPERATION,
                             "prt_scene_shade: no environment has been set "
                             "(prt_scene_set_environment)");
  return PRT_OK;
}

prt_result prt_scene_shade(prt_scene* scene, const prt_scene_frame* frame) {
  char msg[PRT_MESSAGE_CAPACITY / 2];
  prt_result r;
  uint32_t g;
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  r = check_frame(scene, frame);
  if (r != PRT_OK) return r;
  for (g = 0; g < scene->group_count; ++g) {
    prt_scene_group* group = &scene->groups[g];
    msg[0] = '\0';
    r = group->technique->scene->shade(group->state, frame, msg, sizeof msg);
    if (r != PRT_OK) {
      scene->shaded = 0; /* the buffers now mix two frames */
      return prt_internal_fail(scene->context, r, "prt_scene_shade: %s", msg);
    }
  }
  scene->shaded = 1;
  return PRT_OK;
}

const float* prt_scene_object_radiance(const prt_scene* scene, uint32_t index) {
  if (!scene || !scene->shaded || index >= scene->object_count) return NULL;
  return scene->objects[index].radiance;
}
