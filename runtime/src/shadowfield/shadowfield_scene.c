/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield`'s scene: objects, instances and their transforms, and the frame's
 * preparation (docs/shadowfield/design.md, "At run time", step 1 and the light's rotation). */
#include "shadowfield_scene.h"

#include <math.h>
#include <string.h>

#include "../internal.h"

/* ---- Scene and objects ----------------------------------------------------------------------- */

prt_result prt_shadowfield_scene_create(prt_context* context, uint32_t max_instances,
                                        prt_shadowfield_scene** out_scene) {
  if (out_scene) *out_scene = NULL;
  if (!context || !out_scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (max_instances == 0u)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_shadowfield_scene_create: max_instances is 0");
  const prt_allocator* allocator = &context->allocator;
  prt_shadowfield_scene* scene =
      (prt_shadowfield_scene*)prt_internal_alloc(allocator, sizeof(prt_shadowfield_scene), 16);
  if (!scene) return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "shadowfield scene");
  memset(scene, 0, sizeof *scene);
  scene->context = context;
  scene->allocator = context->allocator;
  scene->max_instances = max_instances;
  scene->objects = (const prt_sf_object**)prt_internal_alloc(
      allocator, (size_t)max_instances * sizeof(const prt_sf_object*), 16);
  scene->instances = (prt_sf_instance*)prt_internal_alloc(
      allocator, (size_t)max_instances * sizeof(prt_sf_instance), 16);
  scene->log_fields = (prt_sf_log_field*)prt_internal_alloc(
      allocator, (size_t)max_instances * sizeof(prt_sf_log_field), 16);
  if (scene->log_fields)
    memset(scene->log_fields, 0, (size_t)max_instances * sizeof(prt_sf_log_field));
  scene->probes = (prt_sf_probes*)prt_internal_alloc(
      allocator, (size_t)max_instances * sizeof(prt_sf_probes), 16);
  if (scene->probes) memset(scene->probes, 0, (size_t)max_instances * sizeof(prt_sf_probes));
  if (!scene->objects || !scene->instances || !scene->log_fields || !scene->probes) {
    prt_shadowfield_scene_destroy(scene);
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "shadowfield scene");
  }
  *out_scene = scene;
  return PRT_OK;
}

static void free_floats(const prt_allocator* allocator, float* data, size_t count) {
  if (data) prt_internal_free(allocator, data, count * sizeof(float));
}

/* An instance's frame stamps, one per vertex (at least one, so the allocation is never 0). */
static size_t stamp_bytes(uint32_t vertex_count) {
  return (vertex_count > 0u ? vertex_count : 1u) * sizeof(uint32_t);
}

static void free_stamps(const prt_allocator* allocator, uint32_t* data, uint32_t vertex_count) {
  if (data) prt_internal_free(allocator, data, stamp_bytes(vertex_count));
}

void prt_shadowfield_scene_destroy(prt_shadowfield_scene* scene) {
  if (!scene) return;
  const prt_allocator* allocator = &scene->allocator;
  for (uint32_t i = 0; i < scene->instance_count; ++i) {
    prt_sf_instance* instance = &scene->instances[i];
    free_floats(allocator, instance->incident, instance->incident_floats);
    free_floats(allocator, instance->weights, instance->weights_floats);
    free_floats(allocator, instance->field, instance->field_floats);
    if (instance->needed) prt_internal_free(allocator, instance->needed, instance->needed_bytes);
    free_floats(allocator, instance->light_product, instance->light_product_floats);
    if (instance->located) prt_internal_free(allocator, instance->located, instance->located_bytes);
  }
  prt_sf_free_probes(scene);
  if (scene->probes)
    prt_internal_free(allocator, scene->probes,
                      (size_t)scene->max_instances * sizeof(prt_sf_probes));
  if (scene->pairs)
    prt_internal_free(allocator, scene->pairs, scene->pair_capacity * sizeof(prt_sf_pair));
  if (scene->cells)
    prt_internal_free(allocator, scene->cells, scene->cell_capacity * sizeof(prt_sf_cell));
  free_floats(allocator, scene->turned, scene->turned_capacity);
  prt_sf_gaunt_free(allocator, &scene->gaunt);
  if (scene->log_fields) {
    prt_sf_scene_free_log_fields(scene);
    prt_internal_free(allocator, scene->log_fields,
                      (size_t)scene->max_instances * sizeof(prt_sf_log_field));
  }
  if (scene->objects)
    prt_internal_free(allocator, scene->objects,
                      (size_t)scene->max_instances * sizeof(const prt_sf_object*));
  if (scene->instances)
    prt_internal_free(allocator, scene->instances,
                      (size_t)scene->max_instances * sizeof(prt_sf_instance));
  prt_internal_free(allocator, scene, sizeof *scene);
}

static int shells_ok(const prt_sf_shells* grid) {
  return grid->shells >= 1u && grid->face_size >= 1u && grid->radius > 0.0f && grid->inner > 0.0f &&
         grid->outer >= grid->inner && isfinite(grid->outer) && isfinite(grid->centre[0]) &&
         isfinite(grid->centre[1]) && isfinite(grid->centre[2]);
}

/* What the evaluation relies on; the decoding checked the rest (sizes against the blob). */
static const char* object_problem(const prt_sf_object* o) {
  if (o->order < 1u || o->order > PRT_SF_GAUNT_MAX_ORDER) return "an SH order outside 1..6";
  if (o->terms < 1u || o->terms > PRT_SF_MAX_TERMS || (!o->glossy && o->terms != 1u))
    return "a BRDF term count outside 1..64 (1 when diffuse)";
  if (o->vertex_count == 0u || !o->positions || !o->normals || !o->albedo || !o->transfer)
    return "no vertices";
  if (o->glossy && (o->brdf_grid == 0u || !o->g_table)) return "a glossy BRDF without g table";
  if (!shells_ok(&o->oof_shells) || !o->oof) return "no occlusion field";
  if (o->basis_size > 0u && (!o->basis || !o->vertex_weights || !o->basis_inverse ||
                             !shells_ok(&o->srf_shells) || !o->srf))
    return "a radiance basis without its source fields";
  /* The frame's cells (prt_sf_cell) index grid points in 32 bits. */
  if (prt_sf_point_count(&o->oof_shells) > UINT32_MAX ||
      (o->basis_size > 0u && prt_sf_point_count(&o->srf_shells) > UINT32_MAX))
    return "a grid of 2^32 points or more";
  return NULL;
}

prt_result prt_internal_sf_scene_add_object(prt_shadowfield_scene* scene,
                                            const prt_sf_object* object, uint32_t* out_object) {
  if (!scene || !object || !out_object) return PRT_ERROR_INVALID_ARGUMENT;
  prt_context* context = scene->context;
  const char* problem = object_problem(object);
  if (problem)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT, "shadowfield object: %s",
                             problem);
  if (scene->order != 0u && object->order != scene->order)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "shadowfield object of order %u in a scene of order %u", object->order,
                             scene->order);
  if (scene->object_count >= scene->max_instances)
    return prt_internal_fail(context, PRT_ERROR_BUFFER_TOO_SMALL,
                             "shadowfield scene is full (%u objects)", scene->max_instances);
  if (scene->order == 0u) {
    const prt_result built = prt_sf_gaunt_build(&scene->allocator, object->order, &scene->gaunt);
    if (built != PRT_OK)
      return prt_internal_fail(context, built, "shadowfield triple-product tensor");
    scene->order = object->order;
  }
  scene->objects[scene->object_count] = object;
  if (scene->product == PRT_SHADOWFIELD_PRODUCT_LOG) {
    const prt_result built = prt_sf_scene_build_log_fields(scene, scene->object_count + 1u);
    if (built != PRT_OK && scene->object_count == 0u) {
      /* The scene takes its order from its first object: it has none yet. */
      prt_sf_sphere_rule_free(&scene->allocator, &scene->exp_rule);
      prt_sf_gaunt_free(&scene->allocator, &scene->gaunt);
      scene->order = 0u;
    }
    if (built != PRT_OK) return built;
  }
  *out_object = scene->object_count++;
  return PRT_OK;
}

/* ---- Instances ------------------------------------------------------------------------------- */

/* Checks a transform and writes its rotation orthonormalised (Gram-Schmidt on the rows), so
 * that products of rotations stay rotations. NULL when it is valid. */
static const char* take_transform(const prt_shadowfield_transform* transform, float rotation[9],
                                  float translation[3], float* scale) {
  if (!transform) return "a NULL transform";
  if (!prt_internal_struct_size_ok(transform, sizeof(prt_shadowfield_transform)))
    return "a transform struct_size below 1.0's";
  const float* r = transform->rotation;
  for (int e = 0; e < 9; ++e)
    if (!isfinite(r[e])) return "a rotation that is not finite";
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const float dot =
          r[3 * a] * r[3 * b] + r[3 * a + 1] * r[3 * b + 1] + r[3 * a + 2] * r[3 * b + 2];
      if (fabsf(dot - (a == b ? 1.0f : 0.0f)) > 1e-3f) return "a rotation that is not orthonormal";
    }
  const float det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                    r[2] * (r[3] * r[7] - r[4] * r[6]);
  if (!(det > 0.0f)) return "a rotation with determinant -1";
  if (!(transform->scale > 0.0f) || !isfinite(transform->scale)) return "a scale not > 0";
  for (int c = 0; c < 3; ++c)
    if (!isfinite(transform->translation[c])) return "a translation that is not finite";
  double rows[3][3];
  for (int a = 0; a < 3; ++a) {
    for (int c = 0; c < 3; ++c) rows[a][c] = r[3 * a + c];
    for (int b = 0; b < a; ++b) {
      const double dot =
          rows[a][0] * rows[b][0] + rows[a][1] * rows[b][1] + rows[a][2] * rows[b][2];
      for (int c = 0; c < 3; ++c) rows[a][c] -= dot * rows[b][c];
    }
    const double length =
        sqrt(rows[a][0] * rows[a][0] + rows[a][1] * rows[a][1] + rows[a][2] * rows[a][2]);
    for (int c = 0; c < 3; ++c) rows[a][c] /= length;
  }
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) rotation[3 * a + c] = (float)rows[a][c];
  for (int c = 0; c < 3; ++c) translation[c] = transform->translation[c];
  *scale = transform->scale;
  return NULL;
}

static float* alloc_floats(const prt_allocator* allocator, size_t count) {
  float* data = (float*)prt_internal_alloc(allocator, count * sizeof(float), 16);
  if (data) memset(data, 0, count * sizeof(float));
  return data;
}

prt_result prt_shadowfield_scene_add_instance(prt_shadowfield_scene* scene, uint32_t object,
                                              const prt_shadowfield_transform* transform,
                                              uint32_t* out_instance) {
  if (!scene || !out_instance) return PRT_ERROR_INVALID_ARGUMENT;
  prt_context* context = scene->context;
  if (object >= scene->object_count)
    return prt_internal_fail(context, PRT_ERROR_NOT_FOUND, "shadowfield: no object %u", object);
  if (scene->instance_count >= scene->max_instances)
    return prt_internal_fail(context, PRT_ERROR_BUFFER_TOO_SMALL,
                             "shadowfield scene is full (%u instances)", scene->max_instances);
  prt_sf_instance* instance = &scene->instances[scene->instance_count];
  memset(instance, 0, sizeof *instance);
  const char* problem =
      take_transform(transform, instance->rotation, instance->translation, &instance->scale);
  if (problem)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT, "shadowfield instance: %s",
                             problem);
  const prt_sf_object* o = scene->objects[object];
  const uint32_t n2 = o->order * o->order;
  instance->object = object;
  instance->incident_floats = (size_t)PRT_SF_PASSES * o->vertex_count * o->terms * 3u;
  instance->incident = alloc_floats(&scene->allocator, instance->incident_floats);
  instance->light_product_floats = (size_t)3u * n2 * n2;
  instance->light_product = alloc_floats(&scene->allocator, instance->light_product_floats);
  instance->located_bytes = stamp_bytes(o->vertex_count);
  instance->located = (uint32_t*)prt_internal_alloc(&scene->allocator, instance->located_bytes, 16);
  if (instance->located) memset(instance->located, 0, instance->located_bytes);
  int failed =
      instance->incident == NULL || instance->light_product == NULL || instance->located == NULL;
  if (o->basis_size > 0u) {
    instance->weights_floats = 2u * (size_t)o->basis_size * o->terms * 3u;
    instance->weights = alloc_floats(&scene->allocator, instance->weights_floats);
    instance->field_floats = (size_t)prt_sf_point_count(&o->srf_shells) * n2 * 3u;
    instance->field = alloc_floats(&scene->allocator, instance->field_floats);
    instance->needed_bytes = prt_sf_point_count(&o->srf_shells);
    instance->needed = (uint8_t*)prt_internal_alloc(&scene->allocator, instance->needed_bytes, 16);
    failed = failed || !instance->weights || !instance->field || !instance->needed;
  }
  if (failed) {
    free_floats(&scene->allocator, instance->incident, instance->incident_floats);
    free_floats(&scene->allocator, instance->weights, instance->weights_floats);
    free_floats(&scene->allocator, instance->field, instance->field_floats);
    if (instance->needed)
      prt_internal_free(&scene->allocator, instance->needed, prt_sf_point_count(&o->srf_shells));
    free_floats(&scene->allocator, instance->light_product, instance->light_product_floats);
    free_stamps(&scene->allocator, instance->located, o->vertex_count);
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "shadowfield instance buffers");
  }
  scene->prepared = 0u;
  *out_instance = scene->instance_count++;
  return PRT_OK;
}

prt_result prt_shadowfield_scene_set_transform(prt_shadowfield_scene* scene, uint32_t instance,
                                               const prt_shadowfield_transform* transform) {
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (instance >= scene->instance_count)
    return prt_internal_fail(scene->context, PRT_ERROR_NOT_FOUND, "shadowfield: no instance %u",
                             instance);
  float rotation[9], translation[3], scale;
  const char* problem = take_transform(transform, rotation, translation, &scale);
  if (problem)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                             "shadowfield instance %u: %s", instance, problem);
  prt_sf_instance* target = &scene->instances[instance];
  memcpy(target->rotation, rotation, sizeof rotation);
  memcpy(target->translation, translation, sizeof translation);
  target->scale = scale;
  scene->prepared = 0u;
  return PRT_OK;
}

uint32_t prt_shadowfield_scene_order(const prt_shadowfield_scene* scene) {
  return scene ? scene->order : 0u;
}

uint32_t prt_shadowfield_scene_instance_count(const prt_shadowfield_scene* scene) {
  return scene ? scene->instance_count : 0u;
}

uint32_t prt_shadowfield_instance_vertex_count(const prt_shadowfield_scene* scene,
                                               uint32_t instance) {
  if (!scene || instance >= scene->instance_count) return 0u;
  return scene->objects[scene->instances[instance].object]->vertex_count;
}
