/* SPDX-License-Identifier: MIT */
/* Technique `wavelet` in a loaded scene (scene/scene_internal.h). A light change resamples and
 * transforms the environment once per parameterisation (param, size) among the objects, keeping
 * every coefficient (no selection: the light is not per frame), then folds each object's band
 * scales into its own prepared light and zero-block mask, which its shading reads. Objects are
 * static. */
#include <stdio.h>

#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>

#include "../scene/scene_internal.h"

/* A transformed light shared by the objects of one parameterisation. */
typedef struct wavelet_light {
  prt_wavelet_param param;
  uint32_t size;
  uint32_t coefficient_count;
  float* rgba; /* coefficient_count RGBA quadruples */
} wavelet_light;

typedef struct wavelet_object {
  prt_scene_object* object;
  uint32_t light; /* index in the group's lights */
  uint32_t coefficient_count;
  uint32_t block_count;
  float* prepared;      /* coefficient_count RGBA quadruples */
  uint8_t* zero_blocks; /* block_count bytes */
} wavelet_object;

typedef struct wavelet_group {
  wavelet_object* objects; /* count of them */
  uint32_t count;
  wavelet_light* lights; /* light_count used of count allocated */
  uint32_t light_count;
} wavelet_group;

static size_t rgba_bytes(uint32_t coefficient_count) {
  return (size_t)coefficient_count * 4u * sizeof(float);
}

/* The group's light of (param, size), added (without its buffer) when it is new. */
static uint32_t light_of(wavelet_group* group, const prt_wavelet_info* info) {
  uint32_t i;
  for (i = 0; i < group->light_count; ++i)
    if (group->lights[i].param == info->param && group->lights[i].size == info->size) return i;
  group->lights[i].param = info->param;
  group->lights[i].size = info->size;
  group->lights[i].coefficient_count = info->coefficient_count;
  group->light_count = i + 1u;
  return i;
}

/* One object's state: its WVLT header, its light's index and its prepared-light buffers. */
static prt_result open_object(const prt_allocator* allocator, wavelet_group* group,
                              wavelet_object* state, char* msg, size_t capacity) {
  const prt_scene_object* object = state->object;
  prt_wavelet_info info;
  prt_result r;
  info.struct_size = sizeof info;
  r = prt_wavelet_get_info(object->asset, &info);
  if (r != PRT_OK) return prt_scene_hook_failed(object, "prt_wavelet_get_info", r, msg, capacity);
  if (info.vertex_count != object->vertex_count) {
    snprintf(msg, capacity, "object '%s': WVLT has %u vertices, VPOS %u", object->name,
             (unsigned)info.vertex_count, (unsigned)object->vertex_count);
    return PRT_ERROR_CORRUPT;
  }
  state->light = light_of(group, &info);
  state->coefficient_count = info.coefficient_count;
  state->block_count = info.block_count;
  state->prepared = (float*)prt_internal_alloc(allocator, rgba_bytes(info.coefficient_count), 64);
  if (!state->prepared)
    return prt_scene_hook_out_of_memory(object, "prepared light",
                                        rgba_bytes(info.coefficient_count), msg, capacity);
  state->zero_blocks = (uint8_t*)prt_internal_alloc(allocator, info.block_count, 16);
  if (!state->zero_blocks)
    return prt_scene_hook_out_of_memory(object, "zero-block mask", info.block_count, msg, capacity);
  return PRT_OK;
}

/* The first object that shares light `index` (there is one), for messages. */
static const prt_scene_object* first_user(const wavelet_group* group, uint32_t index) {
  uint32_t j = 0;
  while (group->objects[j].light != index) ++j;
  return group->objects[j].object;
}

/* The buffer of every parameterisation's shared light. */
static prt_result open_lights(const prt_allocator* allocator, wavelet_group* group, char* msg,
                              size_t capacity) {
  uint32_t i;
  for (i = 0; i < group->light_count; ++i) {
    wavelet_light* light = &group->lights[i];
    light->rgba = (float*)prt_internal_alloc(allocator, rgba_bytes(light->coefficient_count), 64);
    if (!light->rgba)
      return prt_scene_hook_out_of_memory(first_user(group, i), "light",
                                          rgba_bytes(light->coefficient_count), msg, capacity);
  }
  return PRT_OK;
}

static prt_result wavelet_open(prt_context* context, const prt_allocator* allocator,
                               const prt_scene_options* options, void* state,
                               prt_scene_object* const* objects, uint32_t count, char* msg,
                               size_t capacity) {
  wavelet_group* group = (wavelet_group*)state;
  const size_t object_bytes = (size_t)count * sizeof *group->objects;
  const size_t light_bytes = (size_t)count * sizeof *group->lights;
  uint32_t i;
  prt_result r;
  (void)context, (void)options;
  group->objects = (wavelet_object*)prt_internal_alloc(allocator, object_bytes, 16);
  if (!group->objects)
    return prt_scene_hook_out_of_memory(objects[0], "object list", object_bytes, msg, capacity);
  memset(group->objects, 0, object_bytes);
  group->count = count;
  group->lights = (wavelet_light*)prt_internal_alloc(allocator, light_bytes, 16);
  if (!group->lights)
    return prt_scene_hook_out_of_memory(objects[0], "light list", light_bytes, msg, capacity);
  memset(group->lights, 0, light_bytes);
  for (i = 0; i < count; ++i) {
    group->objects[i].object = objects[i];
    r = open_object(allocator, group, &group->objects[i], msg, capacity);
    if (r != PRT_OK) return r;
  }
  return open_lights(allocator, group, msg, capacity);
}

static void wavelet_close(const prt_allocator* allocator, void* state) {
  wavelet_group* group = (wavelet_group*)state;
  uint32_t i;
  for (i = 0; group->objects && i < group->count; ++i) {
    wavelet_object* object = &group->objects[i];
    prt_internal_free(allocator, object->prepared, rgba_bytes(object->coefficient_count));
    prt_internal_free(allocator, object->zero_blocks, object->block_count);
  }
  for (i = 0; group->lights && i < group->light_count; ++i)
    prt_internal_free(allocator, group->lights[i].rgba,
                      rgba_bytes(group->lights[i].coefficient_count));
  prt_internal_free(allocator, group->lights, (size_t)group->count * sizeof *group->lights);
  prt_internal_free(allocator, group->objects, (size_t)group->count * sizeof *group->objects);
  memset(group, 0, sizeof *group);
}

/* Resamples and transforms the light of parameterisation `index` (every coefficient kept). */
static prt_result make_light(const wavelet_group* group, uint32_t index, const prt_env_image* env,
                             char* msg, size_t capacity) {
  const wavelet_light* light = &group->lights[index];
  const char* function = "prt_wavelet_resample";
  prt_result r = prt_wavelet_resample(light->param, light->size, env, light->rgba);
  if (r == PRT_OK) {
    function = "prt_wavelet_transform_light";
    r = prt_wavelet_transform_light(light->param, light->size, light->rgba);
  }
  return r == PRT_OK ? r
                     : prt_scene_hook_failed(first_user(group, index), function, r, msg, capacity);
}

static prt_result wavelet_light_hook(prt_context* context, void* state, const prt_env_image* env,
                                     char* msg, size_t capacity) {
  const wavelet_group* group = (const wavelet_group*)state;
  uint32_t i;
  (void)context;
  for (i = 0; i < group->light_count; ++i) {
    const prt_result r = make_light(group, i, env, msg, capacity);
    if (r != PRT_OK) return r;
  }
  for (i = 0; i < group->count; ++i) {
    const wavelet_object* object = &group->objects[i];
    const prt_result r =
        prt_wavelet_prepare_light(object->object->asset, group->lights[object->light].rgba,
                                  object->prepared, object->zero_blocks);
    if (r != PRT_OK)
      return prt_scene_hook_failed(object->object, "prt_wavelet_prepare_light", r, msg, capacity);
  }
  return PRT_OK;
}

static prt_result wavelet_shade(void* state, const prt_scene_frame* frame, char* msg,
                                size_t capacity) {
  const wavelet_group* group = (const wavelet_group*)state;
  uint32_t i;
  for (i = 0; i < group->count; ++i) {
    const wavelet_object* entry = &group->objects[i];
    prt_scene_object* object = entry->object;
    const prt_result r =
        frame->workers
            ? prt_wavelet_shade_workers(frame->workers, object->asset, frame->backend,
                                        entry->prepared, entry->zero_blocks, 0,
                                        object->vertex_count, object->radiance)
            : prt_wavelet_shade(object->asset, frame->backend, entry->prepared, entry->zero_blocks,
                                0, object->vertex_count, object->radiance);
    if (r != PRT_OK)
      return prt_scene_hook_failed(
          object, frame->workers ? "prt_wavelet_shade_workers" : "prt_wavelet_shade", r, msg,
          capacity);
  }
  return PRT_OK;
}

const prt_scene_hooks prt_wavelet_scene_hooks = {
    sizeof(wavelet_group), wavelet_open, wavelet_close, wavelet_light_hook, NULL, NULL,
    wavelet_shade,
};
