/* SPDX-License-Identifier: MIT */
/* Technique `sh` in a loaded scene (scene/scene_internal.h): one projection of the environment
 * for the whole group, at the highest SH order among its objects. Coefficient (l, m) sits at the
 * same index at every order and is projected the same way (prt_sh.h), so an object of a lower
 * order shades with the prefix of that light (its order² RGB triples). Objects are static. */
#include <stdio.h>

#include <prt/prt_sh.h>
#include <prt/prt_sh_asset.h>

#include "../scene/scene_internal.h"

typedef struct sh_group {
  prt_scene_object** objects; /* count of them, the shared code's */
  uint32_t count;
  uint32_t max_order;
  float* light; /* max_order² RGB coefficients, coefficient-major */
} sh_group;

static size_t light_bytes(uint32_t order) {
  return (size_t)order * order * 3u * sizeof(float);
}

/* Each object's order (its SHTR header), checked against the vertices the scene shades. */
static prt_result read_orders(sh_group* group, char* msg, size_t capacity) {
  uint32_t i;
  for (i = 0; i < group->count; ++i) {
    const prt_scene_object* object = group->objects[i];
    prt_sh_info info;
    prt_result r;
    info.struct_size = sizeof info;
    r = prt_sh_get_info(object->asset, &info);
    if (r != PRT_OK) return prt_scene_hook_failed(object, "prt_sh_get_info", r, msg, capacity);
    if (info.vertex_count != object->vertex_count) {
      snprintf(msg, capacity, "object '%s': SHTR has %u vertices, VPOS %u", object->name,
               (unsigned)info.vertex_count, (unsigned)object->vertex_count);
      return PRT_ERROR_CORRUPT;
    }
    if (info.order > group->max_order) group->max_order = info.order;
  }
  return PRT_OK;
}

static prt_result sh_open(prt_context* context, const prt_allocator* allocator,
                          const prt_scene_options* options, void* state,
                          prt_scene_object* const* objects, uint32_t count, char* msg,
                          size_t capacity) {
  sh_group* group = (sh_group*)state;
  const size_t list_bytes = (size_t)count * sizeof *group->objects;
  prt_result r;
  (void)context, (void)options;
  group->objects = (prt_scene_object**)prt_internal_alloc(allocator, list_bytes, 16);
  if (!group->objects)
    return prt_scene_hook_out_of_memory(objects[0], "object list", list_bytes, msg, capacity);
  memcpy(group->objects, objects, list_bytes);
  group->count = count;
  r = read_orders(group, msg, capacity);
  if (r != PRT_OK) return r;
  group->light = (float*)prt_internal_alloc(allocator, light_bytes(group->max_order), 64);
  if (!group->light)
    return prt_scene_hook_out_of_memory(objects[0], "light", light_bytes(group->max_order), msg,
                                        capacity);
  return PRT_OK;
}

static void sh_close(const prt_allocator* allocator, void* state) {
  sh_group* group = (sh_group*)state;
  prt_internal_free(allocator, group->light, light_bytes(group->max_order));
  prt_internal_free(allocator, group->objects, (size_t)group->count * sizeof *group->objects);
  memset(group, 0, sizeof *group);
}

static prt_result sh_light(prt_context* context, void* state, const prt_env_image* env, char* msg,
                           size_t capacity) {
  sh_group* group = (sh_group*)state;
  const prt_result r = prt_sh_project(group->max_order, env, group->light);
  (void)context;
  return r == PRT_OK ? r
                     : prt_scene_hook_failed(group->objects[0], "prt_sh_project", r, msg, capacity);
}

static prt_result sh_shade(void* state, const prt_scene_frame* frame, char* msg, size_t capacity) {
  const sh_group* group = (const sh_group*)state;
  uint32_t i;
  for (i = 0; i < group->count; ++i) {
    prt_scene_object* object = group->objects[i];
    const prt_result r =
        frame->workers
            ? prt_sh_shade_workers(frame->workers, object->asset, frame->backend, group->light, 0,
                                   object->vertex_count, object->radiance)
            : prt_sh_shade(object->asset, frame->backend, group->light, 0, object->vertex_count,
                           object->radiance);
    if (r != PRT_OK)
      return prt_scene_hook_failed(object, frame->workers ? "prt_sh_shade_workers" : "prt_sh_shade",
                                   r, msg, capacity);
  }
  return PRT_OK;
}

const prt_scene_hooks prt_sh_scene_hooks = {
    sizeof(sh_group), sh_open, sh_close, sh_light, NULL, NULL, sh_shade,
};
