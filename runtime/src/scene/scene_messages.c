/* SPDX-License-Identifier: MIT */
/* The messages every technique's scene hooks write (scene_internal.h), worded once. */
#include <stdio.h>

#include "../techniques.h"
#include "scene_internal.h"

prt_result prt_scene_hook_failed(const prt_scene_object* object, const char* function, prt_result r,
                                 char* msg, size_t capacity) {
  snprintf(msg, capacity, "object '%s': %s failed: %s", object->name, function,
           prt_result_string(r));
  return r;
}

prt_result prt_scene_hook_out_of_memory(const prt_scene_object* object, const char* what,
                                        size_t bytes, char* msg, size_t capacity) {
  snprintf(msg, capacity, "object '%s': out of memory for the %s %s (%zu bytes)", object->name,
           object->technique->name, what, bytes);
  return PRT_ERROR_OUT_OF_MEMORY;
}
