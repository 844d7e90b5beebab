/* SPDX-License-Identifier: MIT */
/* Private to the runtime: a loaded scene (prt_scene.h) and what a technique does for it. The
 * shared scene code (runtime/src/scene/) reads the manifest, loads the blobs and hands each
 * technique all of its objects at once through the hooks of its table entry
 * (prt_technique_entry::scene, defined in runtime/src/<t>/<t>_scene_hooks.c); it names no
 * technique. */
#ifndef PRT_RUNTIME_SCENE_INTERNAL_H
#define PRT_RUNTIME_SCENE_INTERNAL_H

#include <prt/prt_scene.h>

#include "../internal.h"

struct prt_technique_entry;

/* One object of the scene. The shared code owns everything here; `state` belongs to the
 * object's technique (set by its open hook, freed by its close hook). */
typedef struct prt_scene_object {
  uint32_t index; /* in the manifest */
  char* name;     /* NUL-terminated copies of the manifest's strings */
  char* blob;
  const struct prt_technique_entry* technique;
  uint32_t node;
  float rest[16];
  prt_asset* asset;
  uint32_t vertex_count; /* VPOS's element count */
  float* radiance;       /* vertex_count RGB triples, written by the technique's shade hook */
  void* state;
  uint32_t group; /* index into prt_scene::groups (shared code only) */
} prt_scene_object;

/* What the hooks may read of the scene's settings. */
typedef struct prt_scene_options {
  uint32_t cloth_lobes; /* prt_scene_desc's, defaulted */
} prt_scene_options;

/* A technique's part in a scene. Every hook writes a one-line message naming the object on
 * failure (msg, capacity bytes); the shared code records it in the context. */
typedef struct prt_scene_hooks {
  size_t group_size; /* bytes of the technique's state for all its objects (zeroed at open) */
  /* Once at load, with the scene's `count` (>= 1) objects of this technique in manifest order,
   * each with its asset loaded and checked to hold the technique's section. Fills `group`; may
   * set each object's state; allocates with `allocator` only. On failure close is still called
   * (on what open left: a zeroed group holds nothing to free). */
  prt_result (*open)(prt_context* context, const prt_allocator* allocator,
                     const prt_scene_options* options, void* group,
                     prt_scene_object* const* objects, uint32_t count, char* msg, size_t capacity);
  void (*close)(const prt_allocator* allocator, void* group);
  /* Turns `env` (validated) into the technique's light for every object of the group. */
  prt_result (*light)(prt_context* context, void* group, const prt_env_image* env, char* msg,
                      size_t capacity);
  /* Optional (NULL: its objects are baked in place, prt_scene_set_placement refuses them). */
  prt_result (*place)(void* group, prt_scene_object* object, const prt_scene_placement* placement,
                      char* msg, size_t capacity);
  /* Optional (NULL: its objects have no joints, prt_scene_set_pose refuses them). The caller has
   * checked pose and pose->joint_rotations are not NULL. */
  prt_result (*pose)(void* group, prt_scene_object* object, const prt_pose_input* pose, char* msg,
                     size_t capacity);
  /* Shades every object of the group into its radiance under the light set last (light has
   * been called at least once). frame->backend is not GL. */
  prt_result (*shade)(void* group, const prt_scene_frame* frame, char* msg, size_t capacity);
} prt_scene_hooks;

/* The hooks' messages: "object 'NAME': FUNCTION failed: RESULT" into msg, returning r; and
 * "object 'NAME': out of memory for the TECHNIQUE WHAT (BYTES bytes)", returning
 * PRT_ERROR_OUT_OF_MEMORY. */
prt_result prt_scene_hook_failed(const prt_scene_object* object, const char* function, prt_result r,
                                 char* msg, size_t capacity);
prt_result prt_scene_hook_out_of_memory(const prt_scene_object* object, const char* what,
                                        size_t bytes, char* msg, size_t capacity);

/* ---- Shared scene code only (scene_load.c, scene_frame.c) ---------------------------------- */

/* The scene's objects of one technique and that technique's state for them. */
typedef struct prt_scene_group {
  const struct prt_technique_entry* technique;
  void* state; /* technique->scene->group_size bytes */
  prt_scene_object** objects;
  uint32_t count;
} prt_scene_group;

struct prt_scene {
  prt_context* context;
  prt_allocator allocator;
  prt_scene_options options;
  prt_scene_object* objects;
  uint32_t object_count;
  prt_scene_group groups[PRT_INTERNAL_MAX_TECHNIQUES]; /* in order of first appearance */
  uint32_t group_count;
  int lit;    /* an environment has been set */
  int shaded; /* the radiance buffers hold a frame */
};

#endif /* PRT_RUNTIME_SCENE_INTERNAL_H */
