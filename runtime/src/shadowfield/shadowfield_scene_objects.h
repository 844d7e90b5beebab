/* SPDX-License-Identifier: MIT */
/* Private to the runtime: where the scene takes its objects from. A loaded asset's shadowfield
 * object is decoded at load by the section's code (shadowfield_asset.c); the scene only reads
 * it through this function. */
#ifndef PRT_RUNTIME_SHADOWFIELD_SCENE_OBJECTS_H
#define PRT_RUNTIME_SHADOWFIELD_SCENE_OBJECTS_H

#include <prt/prt_asset.h>

#include "shadowfield_object.h"

/* The asset's decoded object, owned by the asset; NULL when it has no shadowfield section. */
const prt_sf_object* prt_internal_sf_object(const prt_asset* asset);

#endif /* PRT_RUNTIME_SHADOWFIELD_SCENE_OBJECTS_H */
