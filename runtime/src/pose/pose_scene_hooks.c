/* SPDX-License-Identifier: MIT */
/* Technique `pose` in a loaded scene (scene/scene_internal.h): each character keeps the pose and
 * the turn the game gave it last (its bind pose and no turn at first) and the environment's SH
 * light at its order, and is shaded with prt_pose_shade each frame. The scene's characters do
 * not shadow one another: each one's transfer was learned alone. Public functions only. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../scene/scene_internal.h"

/* One character: object->state. */
typedef struct pose_character {
  prt_scene_object* object;
  uint32_t order;       /* SH order n */
  uint32_t joint_count; /* J */
  int has_translations; /* 0: the last pose gave none (the rest ones are used) */
  int has_scales;
  float rotation[9]; /* world_from_character: the placement's rotation, row-major */
  /* One allocation of `floats` floats: J x 4 rotations, J x 3 translations, J x 3 scales, then
   * the light (n² RGB). */
  float* joint_rotations;
  float* joint_translations;
  float* joint_scales;
  float* light;
  size_t floats;
} pose_character;

typedef struct pose_group {
  uint32_t count;
  pose_character* characters; /* count of them, in the scene's order */
} pose_group;

/* Reads the character's PSTR header and starts it at its bind pose, unturned. */
static prt_result open_character(const prt_allocator* allocator, prt_scene_object* object,
                                 pose_character* c, char* msg, size_t capacity) {
  prt_pose_info info;
  info.struct_size = sizeof info;
  prt_result r = prt_pose_get_info(object->asset, &info);
  if (r != PRT_OK) return prt_scene_hook_failed(object, "prt_pose_get_info", r, msg, capacity);
  if (info.vertex_count != object->vertex_count) {
    snprintf(msg, capacity, "pose object '%s': PSTR has %" PRIu32 " vertices, its mesh %" PRIu32,
             object->name, info.vertex_count, object->vertex_count);
    return PRT_ERROR_CORRUPT;
  }
  const size_t joints = info.joint_count;
  c->floats = 10u * joints + 3u * (size_t)info.order * info.order;
  c->joint_rotations = (float*)prt_internal_alloc(allocator, c->floats * sizeof(float), 16);
  if (!c->joint_rotations) {
    snprintf(msg, capacity, "pose object '%s': out of memory for its pose", object->name);
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  memset(c->joint_rotations, 0, c->floats * sizeof(float));
  c->joint_translations = c->joint_rotations + 4u * joints;
  c->joint_scales = c->joint_translations + 3u * joints;
  c->light = c->joint_scales + 3u * joints;
  c->object = object;
  c->order = info.order;
  c->joint_count = info.joint_count;
  for (int e = 0; e < 9; ++e) c->rotation[e] = e % 4 == 0 ? 1.0f : 0.0f;
  r = prt_pose_bind_pose(object->asset, c->joint_rotations, c->joint_translations, c->joint_scales);
  if (r != PRT_OK) return prt_scene_hook_failed(object, "prt_pose_bind_pose", r, msg, capacity);
  object->state = c;
  return PRT_OK;
}

static void pose_close(const prt_allocator* allocator, void* group) {
  pose_group* g = (pose_group*)group;
  if (!g->characters) return;
  for (uint32_t i = 0; i < g->count; ++i)
    if (g->characters[i].joint_rotations)
      prt_internal_free(allocator, g->characters[i].joint_rotations,
                        g->characters[i].floats * sizeof(float));
  prt_internal_free(allocator, g->characters, (size_t)g->count * sizeof(pose_character));
  g->characters = NULL;
  g->count = 0;
}

static prt_result pose_open(prt_context* context, const prt_allocator* allocator,
                            const prt_scene_options* options, void* group,
                            prt_scene_object* const* objects, uint32_t count, char* msg,
                            size_t capacity) {
  pose_group* g = (pose_group*)group;
  (void)context;
  (void)options;
  const size_t bytes = (size_t)count * sizeof(pose_character);
  g->characters = (pose_character*)prt_internal_alloc(allocator, bytes, 16);
  if (!g->characters) {
    snprintf(msg, capacity, "pose object '%s': out of memory for the scene's characters",
             objects[0]->name);
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  memset(g->characters, 0, bytes);
  g->count = count;
  for (uint32_t i = 0; i < count; ++i) {
    const prt_result r = open_character(allocator, objects[i], &g->characters[i], msg, capacity);
    if (r != PRT_OK) return r;
  }
  return PRT_OK;
}

/* The light is projected once per distinct order and copied to the other characters. */
static prt_result pose_light(prt_context* context, void* group, const prt_env_image* env, char* msg,
                             size_t capacity) {
  pose_group* g = (pose_group*)group;
  (void)context;
  for (uint32_t i = 0; i < g->count; ++i) {
    pose_character* c = &g->characters[i];
    uint32_t same = 0;
    while (same < i && g->characters[same].order != c->order) ++same;
    if (same < i) {
      memcpy(c->light, g->characters[same].light, 3u * (size_t)c->order * c->order * sizeof(float));
      continue;
    }
    const prt_result r = prt_sh_project(c->order, env, c->light);
    if (r != PRT_OK) return prt_scene_hook_failed(c->object, "prt_sh_project", r, msg, capacity);
  }
  return PRT_OK;
}

/* prt_pose_shade's rule for a rotation: finite, of non-zero length (it normalises). */
static int rotation_ok(const float q[4]) {
  double length2 = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (!isfinite(q[i])) return 0;
    length2 += (double)q[i] * q[i];
  }
  return length2 > 0.0;
}

/* Checks every rotation before copying anything: a refused pose leaves the last one in place
 * (prt_scene_set_pose has checked the struct_size and the pointer). */
static prt_result pose_pose(void* group, prt_scene_object* object, const prt_pose_input* pose,
                            char* msg, size_t capacity) {
  pose_character* c = (pose_character*)object->state;
  const size_t joints = c->joint_count;
  (void)group;
  for (uint32_t j = 0; j < c->joint_count; ++j)
    if (!rotation_ok(pose->joint_rotations + 4u * (size_t)j)) {
      snprintf(msg, capacity,
               "pose object '%s': joint %" PRIu32 "'s rotation is zero or not finite", object->name,
               j);
      return PRT_ERROR_INVALID_ARGUMENT;
    }
  memcpy(c->joint_rotations, pose->joint_rotations, 4u * joints * sizeof(float));
  c->has_translations = pose->joint_translations != NULL;
  if (c->has_translations)
    memcpy(c->joint_translations, pose->joint_translations, 3u * joints * sizeof(float));
  c->has_scales = pose->joint_scales != NULL;
  if (c->has_scales) memcpy(c->joint_scales, pose->joint_scales, 3u * joints * sizeof(float));
  return PRT_OK;
}

/* Only the rotation is kept: the light is distant, so moving or resizing the character does not
 * change its radiance; turning it turns the light it sees (prt_pose_light's
 * world_from_character). prt_scene_set_placement has checked the placement by
 * prt_shadowfield_transform's rules; the rotation is kept as given, so that the radiance is
 * prt_pose_shade's for it bit for bit. */
static prt_result pose_place(void* group, prt_scene_object* object,
                             const prt_scene_placement* placement, char* msg, size_t capacity) {
  pose_character* c = (pose_character*)object->state;
  (void)group;
  (void)msg;
  (void)capacity;
  memcpy(c->rotation, placement->rotation, sizeof c->rotation);
  return PRT_OK;
}

static prt_result shade_character(const pose_character* c, const prt_scene_frame* frame) {
  const prt_scene_object* object = c->object;
  prt_pose_input input;
  prt_pose_light light;
  input.struct_size = sizeof input;
  input.joint_rotations = c->joint_rotations;
  input.joint_translations = c->has_translations ? c->joint_translations : NULL;
  input.joint_scales = c->has_scales ? c->joint_scales : NULL;
  light.struct_size = sizeof light;
  light.light_rgb = c->light;
  light.world_from_character = c->rotation;
  light.normals = NULL;
  if (frame->workers)
    return prt_pose_shade_workers(frame->workers, object->asset, frame->backend, &input, &light, 0,
                                  object->vertex_count, object->radiance);
  return prt_pose_shade(object->asset, frame->backend, &input, &light, 0, object->vertex_count,
                        object->radiance);
}

static prt_result pose_shade(void* group, const prt_scene_frame* frame, char* msg,
                             size_t capacity) {
  const pose_group* g = (const pose_group*)group;
  for (uint32_t i = 0; i < g->count; ++i) {
    const prt_result r = shade_character(&g->characters[i], frame);
    if (r != PRT_OK)
      return prt_scene_hook_failed(g->characters[i].object,
                                   frame->workers ? "prt_pose_shade_workers" : "prt_pose_shade", r,
                                   msg, capacity);
  }
  return PRT_OK;
}

const prt_scene_hooks prt_pose_scene_hooks = {
    sizeof(pose_group), pose_open, pose_close, pose_light, pose_place, pose_pose, pose_shade,
};
