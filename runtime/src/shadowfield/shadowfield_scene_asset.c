/* SPDX-License-Identifier: MIT */
/* A loaded asset's shadowfield object into a scene (prt_shadowfield_scene_add_object). */
#include "../internal.h"
#include "shadowfield_asset_internal.h"
#include "shadowfield_scene.h"

prt_result prt_shadowfield_scene_add_object(prt_shadowfield_scene* scene, const prt_asset* asset,
                                            uint32_t* out_object) {
  if (!scene || !asset || !out_object) return PRT_ERROR_INVALID_ARGUMENT;
  const prt_sf_object* object = prt_internal_sf_object(asset);
  if (!object)
    return prt_internal_fail(scene->context, PRT_ERROR_NOT_FOUND,
                             "prt_shadowfield_scene_add_object: the asset has no shadowfield "
                             "object");
  return prt_internal_sf_scene_add_object(scene, object, out_object);
}
