/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield`'s scene: how blockers' visibilities combine (prt_shadowfield_product)
 * and the log-space product's fields it needs (shadowfield_log.h). */
#include <string.h>

#include "../internal.h"
#include "shadowfield_scene.h"

void prt_sf_scene_free_log_fields(prt_shadowfield_scene* scene) {
  for (uint32_t o = 0; o < scene->max_instances; ++o) {
    prt_sf_log_field* field = &scene->log_fields[o];
    if (field->values)
      prt_internal_free(&scene->allocator, field->values, field->floats * sizeof(float));
    memset(field, 0, sizeof *field);
  }
  prt_sf_sphere_rule_free(&scene->allocator, &scene->exp_rule);
}

prt_result prt_sf_scene_build_log_fields(prt_shadowfield_scene* scene, uint32_t objects) {
  prt_context* context = scene->context;
  if (scene->order == 0u) return PRT_OK; /* no object yet: built when the first is added */
  const prt_allocator* allocator = &scene->allocator;
  if (!scene->exp_rule.eval) {
    const prt_result built = prt_sf_exp_rule_build(allocator, scene->order, &scene->exp_rule);
    if (built != PRT_OK) return prt_internal_fail(context, built, "shadowfield exponential rule");
  }
  prt_sf_sphere_rule fine;
  const prt_result built = prt_sf_log_rule_build(allocator, scene->order, &fine);
  if (built != PRT_OK) return prt_internal_fail(context, built, "shadowfield log rule");
  const uint32_t n2 = scene->order * scene->order;
  prt_result result = PRT_OK;
  for (uint32_t o = 0; o < objects && result == PRT_OK; ++o) {
    prt_sf_log_field* field = &scene->log_fields[o];
    if (field->values) continue;
    const prt_sf_object* object = scene->objects[o];
    const uint64_t points = prt_sf_point_count(&object->oof_shells);
    const size_t floats = (size_t)points * n2;
    field->values = (float*)prt_internal_alloc(allocator, floats * sizeof(float), 16);
    if (!field->values) {
      result = prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY,
                                 "shadowfield log occlusion field of object %u", o);
      break;
    }
    field->floats = floats;
    prt_sf_log_of_field(&fine, object->oof, points, PRT_SF_LOG_FLOOR, field->values);
  }
  prt_sf_sphere_rule_free(allocator, &fine);
  return result;
}

prt_result prt_shadowfield_scene_set_product(prt_shadowfield_scene* scene,
                                             prt_shadowfield_product product) {
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (product != PRT_SHADOWFIELD_PRODUCT_TRIPLE && product != PRT_SHADOWFIELD_PRODUCT_LOG)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_shadowfield_scene_set_product: product %d", (int)product);
  if (product == scene->product) return PRT_OK;
  if (product == PRT_SHADOWFIELD_PRODUCT_LOG) {
    const prt_result built = prt_sf_scene_build_log_fields(scene, scene->object_count);
    if (built != PRT_OK) {
      prt_sf_scene_free_log_fields(scene);
      return built;
    }
  } else {
    prt_sf_scene_free_log_fields(scene);
  }
  scene->product = product;
  scene->prepared = 0u;
  return PRT_OK;
}

prt_shadowfield_product prt_shadowfield_scene_product(const prt_shadowfield_scene* scene) {
  return scene ? scene->product : PRT_SHADOWFIELD_PRODUCT_TRIPLE;
}
