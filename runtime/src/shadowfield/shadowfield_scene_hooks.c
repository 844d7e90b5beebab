/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield` in a loaded scene (scene/scene_internal.h): the scene's shadowfield
 * objects shadow and light one another, so they go into one prt_shadowfield_scene, one instance
 * each (at its rest: the identity, since every blob is baked at its rest placement), moved by
 * prt_scene_set_placement and shaded together each frame. A prt_shadowfield_scene holds objects
 * of one SH order only (its triple products are of that order), so objects of different orders
 * go into different shadowfield scenes, one per order, and then do NOT shadow or light one
 * another. Public functions only. */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include <prt/prt_shadowfield.h>
#include <prt/prt_shadowfield_asset.h>

#include "../scene/scene_internal.h"

/* An object's place: object->state. */
typedef struct sf_member {
  uint32_t order;    /* its shadowfield scene: sets[order] */
  uint32_t instance; /* its instance there */
} sf_member;

/* The shadowfield scene of one SH order. */
typedef struct sf_set {
  prt_shadowfield_scene* scene; /* NULL: no object of this order */
  uint32_t first;               /* its objects: objects[first + i] is instance i's, i < size */
  uint32_t size;
  float* light; /* order² RGB */
} sf_set;

typedef struct sf_group {
  prt_context* context;
  uint32_t object_count;
  sf_member* members;         /* object_count, in the scene's order */
  prt_scene_object** objects; /* object_count, by order, then instance */
  float** outs;               /* object_count: the shade's outputs, as `objects` */
  sf_set sets[PRT_SH_MAX_ORDER + 1];
} sf_group;

static size_t light_bytes(uint32_t order) {
  return 3u * (size_t)order * order * sizeof(float);
}

/* A failure of a function that records its message in the context. */
static prt_result failed(const sf_group* g, char* msg, size_t capacity,
                         const prt_scene_object* object, const char* function, prt_result result) {
  snprintf(msg, capacity, "shadowfield object '%s': %s failed (%s): %s", object->name, function,
           prt_result_string(result), prt_context_last_message(g->context));
  return result;
}

/* A failure of a whole shadowfield scene: names its first object. */
static prt_result set_failed(const sf_group* g, uint32_t order, char* msg, size_t capacity,
                             const char* function, prt_result result, int from_context) {
  const sf_set* set = &g->sets[order];
  snprintf(msg, capacity,
           "shadowfield objects of SH order %" PRIu32 " ('%s' first, %" PRIu32
           " in all): %s failed (%s)%s%s",
           order, g->objects[set->first]->name, set->size, function, prt_result_string(result),
           from_context ? ": " : "", from_context ? prt_context_last_message(g->context) : "");
  return result;
}

static void sf_close(const prt_allocator* allocator, void* group) {
  sf_group* g = (sf_group*)group;
  for (uint32_t order = 1; order <= PRT_SH_MAX_ORDER; ++order) {
    prt_shadowfield_scene_destroy(g->sets[order].scene);
    if (g->sets[order].light)
      prt_internal_free(allocator, g->sets[order].light, light_bytes(order));
  }
  const size_t n = g->object_count;
  if (g->members) prt_internal_free(allocator, g->members, n * sizeof(sf_member));
  if (g->objects) prt_internal_free(allocator, g->objects, n * sizeof(prt_scene_object*));
  if (g->outs) prt_internal_free(allocator, g->outs, n * sizeof(float*));
  memset(g, 0, sizeof *g);
}

static prt_result alloc_arrays(const prt_allocator* allocator, sf_group* g,
                               const prt_scene_object* first, uint32_t count, char* msg,
                               size_t capacity) {
  g->object_count = count;
  g->members = (sf_member*)prt_internal_alloc(allocator, count * sizeof(sf_member), 16);
  g->objects =
      (prt_scene_object**)prt_internal_alloc(allocator, count * sizeof(prt_scene_object*), 16);
  g->outs = (float**)prt_internal_alloc(allocator, count * sizeof(float*), 16);
  if (!g->members || !g->objects || !g->outs) {
    snprintf(msg, capacity, "shadowfield object '%s': out of memory for the scene's objects",
             first->name);
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  memset(g->members, 0, count * sizeof(sf_member));
  memset(g->objects, 0, count * sizeof(prt_scene_object*));
  memset(g->outs, 0, count * sizeof(float*));
  return PRT_OK;
}

/* Each object's order (members[i].order) and the objects of each order (sets[order].size). */
static prt_result count_orders(sf_group* g, prt_scene_object* const* objects, char* msg,
                               size_t capacity) {
  for (uint32_t i = 0; i < g->object_count; ++i) {
    prt_shadowfield_info info;
    info.struct_size = sizeof info;
    const prt_result r = prt_shadowfield_get_info(objects[i]->asset, &info);
    if (r != PRT_OK) {
      snprintf(msg, capacity, "shadowfield object '%s': prt_shadowfield_get_info failed (%s)",
               objects[i]->name, prt_result_string(r));
      return r;
    }
    if (info.order < 1u || info.order > PRT_SH_MAX_ORDER ||
        info.vertex_count != objects[i]->vertex_count) {
      snprintf(msg, capacity,
               "shadowfield object '%s': SFLD of order %" PRIu32 " and %" PRIu32
               " vertices, its mesh %" PRIu32 " vertices",
               objects[i]->name, info.order, info.vertex_count, objects[i]->vertex_count);
      return PRT_ERROR_CORRUPT;
    }
    g->members[i].order = info.order;
    g->sets[info.order].size++;
  }
  return PRT_OK;
}

/* For each order that has objects: its shadowfield scene (max_instances: those objects) and
 * its light buffer. */
static prt_result create_sets(const prt_allocator* allocator, sf_group* g,
                              prt_scene_object* const* objects, char* msg, size_t capacity) {
  uint32_t first = 0;
  for (uint32_t order = 1; order <= PRT_SH_MAX_ORDER; ++order) {
    sf_set* set = &g->sets[order];
    if (set->size == 0u) continue;
    set->first = first;
    first += set->size;
    uint32_t i = 0;
    while (g->members[i].order != order) ++i; /* the order's first object, to name */
    const prt_result r = prt_shadowfield_scene_create(g->context, set->size, &set->scene);
    if (r != PRT_OK) return failed(g, msg, capacity, objects[i], "prt_shadowfield_scene_create", r);
    set->light = (float*)prt_internal_alloc(allocator, light_bytes(order), 16);
    if (!set->light) {
      snprintf(msg, capacity, "shadowfield object '%s': out of memory for its light",
               objects[i]->name);
      return PRT_ERROR_OUT_OF_MEMORY;
    }
    memset(set->light, 0, light_bytes(order));
  }
  return PRT_OK;
}

/* The object into its order's scene, one instance at the identity (its rest). */
static prt_result add_object(sf_group* g, prt_scene_object* object, sf_member* member, char* msg,
                             size_t capacity) {
  sf_set* set = &g->sets[member->order];
  prt_shadowfield_transform identity;
  uint32_t index;
  memset(&identity, 0, sizeof identity);
  identity.struct_size = sizeof identity;
  identity.rotation[0] = identity.rotation[4] = identity.rotation[8] = 1.0f;
  identity.scale = 1.0f;
  prt_result r = prt_shadowfield_scene_add_object(set->scene, object->asset, &index);
  if (r != PRT_OK) return failed(g, msg, capacity, object, "prt_shadowfield_scene_add_object", r);
  r = prt_shadowfield_scene_add_instance(set->scene, index, &identity, &member->instance);
  if (r != PRT_OK) return failed(g, msg, capacity, object, "prt_shadowfield_scene_add_instance", r);
  g->objects[set->first + member->instance] = object;
  object->state = member;
  return PRT_OK;
}

static prt_result sf_open(prt_context* context, const prt_allocator* allocator,
                          const prt_scene_options* options, void* group,
                          prt_scene_object* const* objects, uint32_t count, char* msg,
                          size_t capacity) {
  sf_group* g = (sf_group*)group;
  (void)options;
  g->context = context;
  prt_result r = alloc_arrays(allocator, g, objects[0], count, msg, capacity);
  if (r == PRT_OK) r = count_orders(g, objects, msg, capacity);
  if (r == PRT_OK) r = create_sets(allocator, g, objects, msg, capacity);
  for (uint32_t i = 0; r == PRT_OK && i < count; ++i)
    r = add_object(g, objects[i], &g->members[i], msg, capacity);
  return r;
}

static prt_result sf_light(prt_context* context, void* group, const prt_env_image* env, char* msg,
                           size_t capacity) {
  sf_group* g = (sf_group*)group;
  (void)context;
  for (uint32_t order = 1; order <= PRT_SH_MAX_ORDER; ++order) {
    if (!g->sets[order].scene) continue;
    const prt_result r = prt_sh_project(order, env, g->sets[order].light);
    if (r != PRT_OK) return set_failed(g, order, msg, capacity, "prt_sh_project", r, 0);
  }
  return PRT_OK;
}

/* prt_scene_placement and prt_shadowfield_transform mean the same (scale · rotation · rest +
 * translation); the shadowfield scene checks it. */
static prt_result sf_place(void* group, prt_scene_object* object,
                           const prt_scene_placement* placement, char* msg, size_t capacity) {
  sf_group* g = (sf_group*)group;
  const sf_member* member = (const sf_member*)object->state;
  prt_shadowfield_transform transform;
  transform.struct_size = sizeof transform;
  memcpy(transform.rotation, placement->rotation, sizeof transform.rotation);
  memcpy(transform.translation, placement->translation, sizeof transform.translation);
  transform.scale = placement->scale;
  const prt_result r = prt_shadowfield_scene_set_transform(g->sets[member->order].scene,
                                                           member->instance, &transform);
  if (r != PRT_OK)
    return failed(g, msg, capacity, object, "prt_shadowfield_scene_set_transform", r);
  return PRT_OK;
}

static prt_result shade_set(sf_group* g, sf_set* set, const prt_scene_frame* frame) {
  prt_shadowfield_settings settings;
  memset(&settings, 0, sizeof settings);
  settings.struct_size = sizeof settings;
  settings.bounces = PRT_SHADOWFIELD_DEFAULT_BOUNCES;
  settings.backend = frame->backend;
  float** outs = g->outs + set->first;
  for (uint32_t i = 0; i < set->size; ++i) outs[i] = g->objects[set->first + i]->radiance;
  if (frame->workers)
    return prt_shadowfield_shade_workers(frame->workers, set->scene, set->light, frame->eye,
                                         &settings, outs);
  return prt_shadowfield_shade(set->scene, set->light, frame->eye, &settings, outs);
}

static prt_result sf_shade(void* group, const prt_scene_frame* frame, char* msg, size_t capacity) {
  sf_group* g = (sf_group*)group;
  for (uint32_t order = 1; order <= PRT_SH_MAX_ORDER; ++order) {
    if (!g->sets[order].scene) continue;
    const prt_result r = shade_set(g, &g->sets[order], frame);
    if (r != PRT_OK)
      return set_failed(g, order, msg, capacity,
                        frame->workers ? "prt_shadowfield_shade_workers" : "prt_shadowfield_shade",
                        r, 1);
  }
  return PRT_OK;
}

const prt_scene_hooks prt_shadowfield_scene_hooks = {
    sizeof(sf_group), sf_open, sf_close, sf_light, sf_place, NULL, sf_shade,
};
