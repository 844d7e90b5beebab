/* SPDX-License-Identifier: MIT */
/* Technique `cloth` in a loaded scene (scene/scene_internal.h). A light change fits one set of
 * spherical-Gaussian lobes to the environment for the whole group (the light is the same for
 * every object). Each object is shaded per vertex with its blob's fabric 0 and its own frame (the
 * mesh's VNRM normals and VTAN warps), seen from the frame's eye: the views are rebuilt from VPOS
 * every frame. Objects are static. */
#include <math.h>
#include <stdio.h>

#include <prt/prt_cloth.h>
#include <prt/prt_cloth_asset.h>

#include "../scene/scene_internal.h"

typedef struct cloth_object {
  prt_scene_object* object;
  const float* positions; /* vertex_count x 3 each, in the blob */
  const float* normals;
  const float* warps;
  float* views; /* vertex_count x 3: unit, towards the eye */
  size_t views_bytes;
} cloth_object;

typedef struct cloth_group {
  cloth_object* objects; /* count of them */
  uint32_t count;
  uint32_t lobe_count;
  prt_cloth_lobe* lobes; /* lobe_count of them */
} cloth_group;

static size_t vectors_bytes(uint32_t vertex_count) {
  return (size_t)vertex_count * 3u * sizeof(float);
}

/* A mesh section of one float x,y,z per vertex of the object, or PRT_ERROR_CORRUPT. */
static prt_result mesh_vectors(const prt_scene_object* object, uint32_t tag, const char* name,
                               const float** out, char* msg, size_t capacity) {
  const void* data = NULL;
  size_t size = 0;
  if (prt_asset_section_data(object->asset, tag, &data, &size) != PRT_OK) {
    snprintf(msg, capacity, "object '%s': the cloth blob has no %s section", object->name, name);
    return PRT_ERROR_CORRUPT;
  }
  if (size != vectors_bytes(object->vertex_count) || (size > 0 && !data)) {
    snprintf(msg, capacity, "object '%s': %s holds %zu bytes, not %u vertices x 3 floats",
             object->name, name, size, (unsigned)object->vertex_count);
    return PRT_ERROR_CORRUPT;
  }
  *out = (const float*)data;
  return PRT_OK;
}

/* One object: fabric 0 exists, its mesh vectors, and its views buffer. */
static prt_result open_object(const prt_allocator* allocator, cloth_object* entry, char* msg,
                              size_t capacity) {
  const prt_scene_object* object = entry->object;
  prt_result r = prt_cloth_get_fabric(object->asset, 0, NULL, NULL, NULL, NULL);
  if (r != PRT_OK) return prt_scene_hook_failed(object, "prt_cloth_get_fabric", r, msg, capacity);
  r = mesh_vectors(object, PRT_SECTION_VPOS, "VPOS", &entry->positions, msg, capacity);
  if (r == PRT_OK)
    r = mesh_vectors(object, PRT_SECTION_VNRM, "VNRM", &entry->normals, msg, capacity);
  if (r == PRT_OK) r = mesh_vectors(object, PRT_SECTION_VTAN, "VTAN", &entry->warps, msg, capacity);
  if (r != PRT_OK) return r;
  entry->views_bytes = vectors_bytes(object->vertex_count);
  entry->views = (float*)prt_internal_alloc(allocator, entry->views_bytes, 64);
  if (!entry->views)
    return prt_scene_hook_out_of_memory(object, "views", entry->views_bytes, msg, capacity);
  return PRT_OK;
}

static prt_result cloth_open(prt_context* context, const prt_allocator* allocator,
                             const prt_scene_options* options, void* state,
                             prt_scene_object* const* objects, uint32_t count, char* msg,
                             size_t capacity) {
  cloth_group* group = (cloth_group*)state;
  const size_t object_bytes = (size_t)count * sizeof *group->objects;
  uint32_t i;
  prt_result r;
  (void)context;
  if (options->cloth_lobes < 1 || options->cloth_lobes > PRT_CLOTH_MAX_LOBES) {
    snprintf(msg, capacity, "object '%s': %u cloth lobes (must be 1..%u)", objects[0]->name,
             (unsigned)options->cloth_lobes, (unsigned)PRT_CLOTH_MAX_LOBES);
    return PRT_ERROR_INVALID_ARGUMENT;
  }
  group->objects = (cloth_object*)prt_internal_alloc(allocator, object_bytes, 16);
  if (!group->objects)
    return prt_scene_hook_out_of_memory(objects[0], "object list", object_bytes, msg, capacity);
  memset(group->objects, 0, object_bytes);
  group->count = count;
  for (i = 0; i < count; ++i) {
    group->objects[i].object = objects[i];
    r = open_object(allocator, &group->objects[i], msg, capacity);
    if (r != PRT_OK) return r;
  }
  group->lobe_count = options->cloth_lobes;
  group->lobes = (prt_cloth_lobe*)prt_internal_alloc(
      allocator, (size_t)group->lobe_count * sizeof *group->lobes, 16);
  if (!group->lobes)
    return prt_scene_hook_out_of_memory(
        objects[0], "lobes", (size_t)group->lobe_count * sizeof *group->lobes, msg, capacity);
  return PRT_OK;
}

static void cloth_close(const prt_allocator* allocator, void* state) {
  cloth_group* group = (cloth_group*)state;
  uint32_t i;
  for (i = 0; group->objects && i < group->count; ++i)
    prt_internal_free(allocator, group->objects[i].views, group->objects[i].views_bytes);
  prt_internal_free(allocator, group->lobes, (size_t)group->lobe_count * sizeof *group->lobes);
  prt_internal_free(allocator, group->objects, (size_t)group->count * sizeof *group->objects);
  memset(group, 0, sizeof *group);
}

static prt_result cloth_light(prt_context* context, void* state, const prt_env_image* env,
                              char* msg, size_t capacity) {
  const cloth_group* group = (const cloth_group*)state;
  prt_cloth_fit_desc desc;
  prt_result r;
  memset(&desc, 0, sizeof desc);
  desc.struct_size = sizeof desc;
  desc.lobe_count = group->lobe_count;
  r = prt_cloth_fit_light(context, env, &desc, group->lobes, NULL);
  return r == PRT_OK ? r
                     : prt_scene_hook_failed(group->objects[0].object, "prt_cloth_fit_light", r,
                                             msg, capacity);
}

/* views[v] = normalize(eye - position[v]), the zero vector where the eye is on the vertex. */
static void fill_views(const cloth_object* entry, const float eye[3]) {
  const uint32_t vertex_count = entry->object->vertex_count;
  uint32_t v, k;
  for (v = 0; v < vertex_count; ++v) {
    const float* position = entry->positions + 3u * (size_t)v;
    float* view = entry->views + 3u * (size_t)v;
    double d[3], length;
    for (k = 0; k < 3; ++k) d[k] = (double)eye[k] - (double)position[k];
    length = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (k = 0; k < 3; ++k) view[k] = length > 0.0 ? (float)(d[k] / length) : 0.0f;
  }
}

static prt_result cloth_shade(void* state, const prt_scene_frame* frame, char* msg,
                              size_t capacity) {
  const cloth_group* group = (const cloth_group*)state;
  prt_cloth_light light;
  uint32_t i;
  light.struct_size = sizeof light;
  light.lobe_count = group->lobe_count;
  light.lobes = group->lobes;
  for (i = 0; i < group->count; ++i) {
    const cloth_object* entry = &group->objects[i];
    prt_scene_object* object = entry->object;
    prt_cloth_pixels pixels;
    prt_result r;
    pixels.struct_size = sizeof pixels;
    pixels.normals = entry->normals;
    pixels.warps = entry->warps;
    pixels.views = entry->views;
    fill_views(entry, frame->eye);
    r = frame->workers ? prt_cloth_shade_workers(frame->workers, object->asset, frame->backend, 0,
                                                 NULL, &light, NULL, &pixels, 0,
                                                 object->vertex_count, object->radiance)
                       : prt_cloth_shade(object->asset, frame->backend, 0, NULL, &light, NULL,
                                         &pixels, 0, object->vertex_count, object->radiance);
    if (r != PRT_OK)
      return prt_scene_hook_failed(
          object, frame->workers ? "prt_cloth_shade_workers" : "prt_cloth_shade", r, msg, capacity);
  }
  return PRT_OK;
}

const prt_scene_hooks prt_cloth_scene_hooks = {
    sizeof(cloth_group), cloth_open, cloth_close, cloth_light, NULL, NULL, cloth_shade,
};
