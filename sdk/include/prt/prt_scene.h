/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: a baked scene, loaded in one call and shaded in one call per frame.
 * C99 and C++.
 *
 * `prt-bake scene` writes one blob per object and a scene manifest (OUT/scene.prts, a blob
 * whose SCNE section lists the objects: formats/SPEC.md §7.6). prt_scene_load_file reads the
 * manifest and every object's blob, and groups the objects by technique. Each frame the game
 * says what changed (the environment, where moving objects are, the characters' poses) and
 * calls prt_scene_shade once: every technique shades all of its objects, each on the backend
 * the frame asks for (AUTO: each technique's best CPU-side backend).
 *
 * Where the objects are. Every blob is baked in world space at the scene's rest placement (the
 * manifest's rest_transform of the object's node). Static objects (`sh`, `wavelet`, `cloth`)
 * are shaded in place: their transfer includes the shadows of their static surroundings. A
 * moving rigid object (`shadowfield`) is placed relative to its rest: a game that moves its
 * node to world matrix W passes the similarity nearest W · rest⁻¹. A character (`pose`) is
 * posed by its joints' rotations and turned by its placement's rotation.
 *
 * What the scene does not do: moving objects shadow one another (those of one SH order: a
 * `shadowfield` scene per order) but not the static objects (those were baked without them), and
 * GL shading runs through each technique's prt_gl_<t> shader on the objects' assets, not
 * through this call.
 *
 * Thread safety: a scene is used by one thread at a time; it records failures in its context. */
#ifndef PRT_SCENE_H
#define PRT_SCENE_H

#include <prt/prt_asset.h>
#include <prt/prt_backend.h>
#include <prt/prt_cloth.h>
#include <prt/prt_env.h>
#include <prt/prt_pose_asset.h>
#include <prt/prt_technique.h>
#include <prt/prt_types.h>
#include <prt/prt_workers.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The manifest's section (formats/SPEC.md §7.6). */
#define PRT_SECTION_SCNE PRT_TAG('S', 'C', 'N', 'E')

typedef struct prt_scene prt_scene;

/* Reads the blob an object names (`path`, relative to the manifest, '/'-separated) into a new
 * asset on `context`, for a game with its own files (an archive, a streaming system). Returns
 * PRT_OK with *out_asset set, or a failure (recorded in the context, as prt_asset_load_* do). */
typedef prt_result (*prt_scene_blob_loader_fn)(void* user, prt_context* context, const char* path,
                                               prt_validation validation, prt_asset** out_asset);

/* How a scene is loaded; NULL (or a zeroed struct with struct_size set) gives the defaults. */
typedef struct prt_scene_desc {
  size_t struct_size;        /* set by the caller: sizeof(prt_scene_desc) */
  prt_validation validation; /* of the manifest and of every blob; QUICK (0) by default */
  /* NULL: each blob is read with prt_asset_load_file from the manifest's folder (load_file) or
   * from base_dir (load_memory; NULL there: the current folder). */
  prt_scene_blob_loader_fn load_blob;
  void* load_blob_user;
  const char* base_dir;
  /* The cloth objects' light: lobes fitted to each environment (prt_cloth_fit_light), at most
   * PRT_CLOTH_MAX_LOBES; 0: 64. */
  uint32_t cloth_lobes;
} prt_scene_desc;

/* Loads the manifest at `path` and every blob it names. On failure *out_scene is NULL, nothing
 * stays allocated, and the context's message names the object and its blob:
 * PRT_ERROR_INVALID_ARGUMENT (NULL pointers, a struct_size below 1.0's, a bad validation value or
 * lobe count), PRT_ERROR_IO,
 * PRT_ERROR_OUT_OF_MEMORY, the manifest's or a blob's validation error,
 * PRT_ERROR_UNSUPPORTED_FEATURE for an object whose technique this runtime does not implement,
 * PRT_ERROR_CORRUPT for a blob without its object's technique section or a manifest without a
 * SCNE section, or a technique's refusal of its objects. */
PRT_API prt_result prt_scene_load_file(prt_context* context, const char* path,
                                       const prt_scene_desc* desc, prt_scene** out_scene);
/* The same from the manifest's bytes (copied: `data` may be freed when this returns). */
PRT_API prt_result prt_scene_load_memory(prt_context* context, const void* data, size_t size,
                                         const prt_scene_desc* desc, prt_scene** out_scene);
/* Frees the scene and its objects' assets. NULL is ignored. */
PRT_API void prt_scene_destroy(prt_scene* scene);

PRT_API uint32_t prt_scene_object_count(const prt_scene* scene);

typedef struct prt_scene_object_info {
  size_t struct_size; /* set by the caller: sizeof(prt_scene_object_info) */
  const char* name;   /* unique in a baked scene; valid while the scene lives */
  const char* blob;   /* the blob's path as the manifest gives it */
  prt_technique technique;
  uint32_t node;            /* the glTF node, 0xFFFFFFFF for none */
  float rest_transform[16]; /* column-major world matrix of the node at rest */
  const prt_asset* asset;   /* the object's blob, for its mesh sections and technique queries */
  uint32_t vertex_count;    /* radiance values per shade (VPOS's element count) */
  int moves;                /* 1: prt_scene_set_placement applies to it */
  int poses;                /* 1: prt_scene_set_pose applies to it */
} prt_scene_object_info;

/* PRT_ERROR_NOT_FOUND for an index past the count; PRT_ERROR_INVALID_ARGUMENT for NULL or a
 * struct_size below 1.0's. */
PRT_API prt_result prt_scene_get_object(const prt_scene* scene, uint32_t index,
                                        prt_scene_object_info* out_info);
/* The first object named `name`; PRT_ERROR_NOT_FOUND when there is none. */
PRT_API prt_result prt_scene_find_object(const prt_scene* scene, const char* name,
                                         uint32_t* out_index);

/* Turns an environment into the light of every technique in the scene (SH projections,
 * wavelet lights, cloth lobes): work of a light change, not of every frame. The scene keeps
 * no pointer into `env`. PRT_ERROR_INVALID_ARGUMENT for an env prt_env_image_validate refuses,
 * PRT_ERROR_OUT_OF_MEMORY. */
PRT_API prt_result prt_scene_set_environment(prt_scene* scene, const prt_env_image* env);

/* Where a moving object is, relative to its rest: world = scale · rotation · rest + translation,
 * as prt_shadowfield_transform. */
typedef struct prt_scene_placement {
  size_t struct_size; /* set by the caller: sizeof(prt_scene_placement) */
  float rotation[9];  /* row-major proper rotation (orthonormal to 1e-3, determinant +1) */
  float translation[3];
  float scale; /* > 0, finite */
} prt_scene_placement;

/* Places an object for the frames to come (every object starts at its rest: identity).
 * PRT_ERROR_INVALID_OPERATION for an object that does not move (its info's `moves` is 0: its
 * transfer is baked in place), PRT_ERROR_INVALID_ARGUMENT for a bad placement or index. */
PRT_API prt_result prt_scene_set_placement(prt_scene* scene, uint32_t object,
                                           const prt_scene_placement* placement);

/* Poses a character for the frames to come (the scene copies the rotations; every character
 * starts at its bind pose). PRT_ERROR_INVALID_OPERATION for an object that has no joints (its
 * info's `poses` is 0), PRT_ERROR_INVALID_ARGUMENT for bad pointers, rotations or index. */
PRT_API prt_result prt_scene_set_pose(prt_scene* scene, uint32_t object,
                                      const prt_pose_input* pose);

typedef struct prt_scene_frame {
  size_t struct_size;   /* set by the caller: sizeof(prt_scene_frame) */
  prt_backend backend;  /* AUTO: each technique's best CPU-side backend; GL: refused */
  float eye[3];         /* world position of the camera (view-dependent techniques) */
  prt_workers* workers; /* NULL: the calling thread; else each technique's shading spread over
                           the pool (bitwise the one-thread result) */
} prt_scene_frame;

/* Shades every object under the environment set last, at its placement and pose, into its
 * radiance (prt_scene_object_radiance). PRT_ERROR_INVALID_OPERATION before an environment is
 * set, PRT_ERROR_UNSUPPORTED_BACKEND as each technique's shading, PRT_ERROR_INVALID_ARGUMENT for
 * NULL pointers or a struct_size below 1.0's. On failure the message names the object. */
PRT_API prt_result prt_scene_shade(prt_scene* scene, const prt_scene_frame* frame);

/* The object's outgoing radiance from the last prt_scene_shade: vertex_count RGB triples,
 * vertex-major, as its technique's own shading writes them (prt_sh_shade, prt_wavelet_shade,
 * prt_pose_shade, prt_cloth_shade with each vertex seen from the eye, prt_shadowfield_shade).
 * NULL for an index past the count or before the first shade. Valid until the scene is shaded
 * again or destroyed. */
PRT_API const float* prt_scene_object_radiance(const prt_scene* scene, uint32_t object);

#ifdef __cplusplus
}
#endif

#endif /* PRT_SCENE_H */
