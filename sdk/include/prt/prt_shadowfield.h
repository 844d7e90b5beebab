/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: technique `shadowfield`'s scene (docs/shadowfield/design.md, "At run
 * time"): rigid objects, each baked alone, and instances of them that move every frame, shadow
 * each other and light each other by interreflection under a low-frequency environment in SH.
 * C99 and C++.
 *
 * A scene holds objects (one per baked asset) and instances (an object with a rotation R, a
 * translation t and a uniform scale s: world = s R local + t). Every object of a scene has one SH
 * order (the first object's; prt_shadowfield_scene_order). A frame is
 *     prepare (light, eye, settings; pairs of instances that interact)
 *     pass 0 (direct light) ... pass B (bounce B): gather each instance's probes (when the
 *                                                   settings ask for bounce probes), then its
 *                                                   vertices, then, between two passes, project
 *                                                   each instance
 *     output (outgoing radiance per vertex towards the eye, summed over passes 0..p).
 * prt_shadowfield_shade runs all of it on the calling thread, prt_shadowfield_shade_workers on a
 * runtime-owned pool. A game's job system can instead call the range functions below in that
 * order, each stage's calls on any threads at once, with a barrier between stages (a pass reads
 * what the previous stage wrote for every instance).
 *
 * Thread safety: the functions that change the scene (add, set a transform, prepare, shade,
 * destroy) need exclusive use of it; gather, project and output of one stage may run on several
 * threads at once over disjoint ranges. Objects are read, never copied: an asset must outlive the
 * scene. */
#ifndef PRT_SHADOWFIELD_H
#define PRT_SHADOWFIELD_H

#include <prt/prt_asset.h>
#include <prt/prt_context.h>
#include <prt/prt_gl.h>
#include <prt/prt_types.h>
#include <prt/prt_workers.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct prt_shadowfield_scene prt_shadowfield_scene;

/* Light bounces between instances a frame may ask for; buffers for all of them are kept. */
#define PRT_SHADOWFIELD_MAX_BOUNCES 8u
#define PRT_SHADOWFIELD_DEFAULT_BOUNCES 3u

/* An instance's placement: world = scale * rotation * local + translation. */
typedef struct prt_shadowfield_transform {
  size_t struct_size; /* set by the caller: sizeof(prt_shadowfield_transform) */
  float rotation[9];  /* row-major proper rotation (orthonormal to 1e-3, determinant +1) */
  float translation[3];
  float scale; /* > 0, finite */
} prt_shadowfield_transform;

typedef struct prt_shadowfield_settings {
  size_t struct_size; /* set by the caller: sizeof(prt_shadowfield_settings) */
  /* Passes after the direct light, 0..PRT_SHADOWFIELD_MAX_BOUNCES. A zeroed struct gives 0
   * bounces (direct light only); NULL settings give PRT_SHADOWFIELD_DEFAULT_BOUNCES. */
  uint32_t bounces;
  /* PRT_BACKEND_CPU: the scalar evaluation; PRT_BACKEND_SIMD: the same with AVX2 + FMA inner
   * loops (PRT_ERROR_UNSUPPORTED_BACKEND where the context's SIMD ISA lacks them); AUTO: SIMD
   * where usable, else scalar. SIMD agrees with scalar to rounding, not bitwise. GL shades
   * through prt_gl_shadowfield_shade; the CPU entry points refuse it
   * (PRT_ERROR_UNSUPPORTED_BACKEND). */
  prt_backend backend;
  /* Added after 1.0: read only when struct_size reaches it, else 0. 0 (the default): every
   * vertex gathers each bounce's light from the sources' fields itself. > 0: the light a bounce
   * brings is gathered at bounce probes, the corners of a grid of this spacing (in each object's
   * own units) over the cells its vertices fall in, and each vertex interpolates it trilinearly
   * before its own transfer turns it into reflected light. The light arriving at a point does
   * not depend on the surface there, so far fewer points read the fields; near a contact, where
   * it changes within a cell, it is smoothed. An object whose grid has as many corners as
   * vertices keeps gathering per vertex. The direct light is never interpolated. Laying out an
   * object's probes allocates and sorts, at the first prepare with a new spacing (GL then
   * uploads them). */
  float bounce_probe_spacing;
} prt_shadowfield_settings;

/* A scene on `context` (its allocator, its record of failures; it must outlive the scene) for
 * at most max_instances instances and as many objects. PRT_ERROR_INVALID_ARGUMENT for NULL
 * pointers or max_instances 0, PRT_ERROR_OUT_OF_MEMORY. */
PRT_API prt_result prt_shadowfield_scene_create(prt_context* context, uint32_t max_instances,
                                                prt_shadowfield_scene** out_scene);
/* NULL is ignored. */
PRT_API void prt_shadowfield_scene_destroy(prt_shadowfield_scene* scene);

/* Adds the asset's shadowfield object; *out_object is its index. PRT_ERROR_NOT_FOUND when the
 * asset has no shadowfield section, PRT_ERROR_INVALID_ARGUMENT when its SH order differs from
 * the scene's, PRT_ERROR_BUFFER_TOO_SMALL when the scene is full. */
PRT_API prt_result prt_shadowfield_scene_add_object(prt_shadowfield_scene* scene,
                                                    const prt_asset* asset, uint32_t* out_object);

/* Adds an instance of `object` at `transform`; *out_instance is its index (instances are
 * numbered 0, 1, ... in the order they are added). It allocates its frame's buffers: the light
 * of every pass (PRT_SHADOWFIELD_MAX_BOUNCES + 1 of them) per vertex and BRDF term, and, when the
 * object has a radiance basis, the field it casts (SRF points x order^2 RGB floats).
 * PRT_ERROR_NOT_FOUND for an unknown object,
 * PRT_ERROR_INVALID_ARGUMENT for a bad transform, PRT_ERROR_BUFFER_TOO_SMALL when full,
 * PRT_ERROR_OUT_OF_MEMORY. */
PRT_API prt_result prt_shadowfield_scene_add_instance(prt_shadowfield_scene* scene, uint32_t object,
                                                      const prt_shadowfield_transform* transform,
                                                      uint32_t* out_instance);
/* Moves an instance (before prepare; a frame in progress must be prepared again). */
PRT_API prt_result prt_shadowfield_scene_set_transform(prt_shadowfield_scene* scene,
                                                       uint32_t instance,
                                                       const prt_shadowfield_transform* transform);

/* How a receiver combines the visibilities of the instances that shadow it
 * (docs/shadowfield/design.md, "Many blockers"). */
typedef enum prt_shadowfield_product {
  /* One SH triple product per blocker after the first: the default. */
  PRT_SHADOWFIELD_PRODUCT_TRIPLE = 0,
  /* The blockers' log visibilities summed and one exponential taken: the cost of a vertex
   * hardly grows with its blockers, so it pays where vertices have many small ones. It reads
   * every visibility below 3 % as 3 %, and a blocker that hides half the sky leaves the light
   * brighter than the triple product does. */
  PRT_SHADOWFIELD_PRODUCT_LOG = 1
} prt_shadowfield_product;

/* Sets the scene's product for the frames to come. PRT_SHADOWFIELD_PRODUCT_LOG computes each
 * object's log occlusion field now, and for objects added later when they are added: as many
 * floats as the object's occlusion field, and work that grows with its points (load time, not
 * frame time). TRIPLE frees them. A GL shader made before the change must be made again.
 * PRT_ERROR_INVALID_ARGUMENT for an unknown product, PRT_ERROR_OUT_OF_MEMORY (the scene keeps
 * its previous product). */
PRT_API prt_result prt_shadowfield_scene_set_product(prt_shadowfield_scene* scene,
                                                     prt_shadowfield_product product);
PRT_API prt_shadowfield_product prt_shadowfield_scene_product(const prt_shadowfield_scene* scene);

PRT_API uint32_t prt_shadowfield_scene_order(const prt_shadowfield_scene* scene);
PRT_API uint32_t prt_shadowfield_scene_instance_count(const prt_shadowfield_scene* scene);
/* Vertices of an instance's object; 0 for an unknown instance. */
PRT_API uint32_t prt_shadowfield_instance_vertex_count(const prt_shadowfield_scene* scene,
                                                       uint32_t instance);

/* The whole frame on the calling thread: outgoing radiance of every instance's vertices towards
 * `eye` (world position) under the environment light_sh_rgb (world frame, the scene's order,
 * RGB coefficient-major as prt_sh.h). out_rgb holds one pointer per instance, each to
 * vertex_count x 3 floats (vertex-major), or NULL to skip that instance's output. */
PRT_API prt_result prt_shadowfield_shade(prt_shadowfield_scene* scene, const float* light_sh_rgb,
                                         const float eye[3],
                                         const prt_shadowfield_settings* settings,
                                         float* const* out_rgb);

/* prt_shadowfield_shade split over the pool's threads (prt_workers.h): every stage's vertices
 * and source-field points in contiguous chunks; bitwise the one-thread call's result. */
PRT_API prt_result prt_shadowfield_shade_workers(prt_workers* workers, prt_shadowfield_scene* scene,
                                                 const float* light_sh_rgb, const float eye[3],
                                                 const prt_shadowfield_settings* settings,
                                                 float* const* out_rgb);

/* ---- The frame in stages, for a job system --------------------------------------------------
 * prepare records failures in the context; the range functions write no context (they may run
 * on any thread) and return PRT_ERROR_INVALID_ARGUMENT for a range or pass out of bounds and
 * PRT_ERROR_INVALID_OPERATION before prepare. */

/* Rotates the light into each instance's frame and finds the pairs that interact (bounding
 * spheres within the other's outer shell). May allocate (the pairs' rotations). */
PRT_API prt_result prt_shadowfield_prepare(prt_shadowfield_scene* scene, const float* light_sh_rgb,
                                           const float eye[3],
                                           const prt_shadowfield_settings* settings);
/* Bounce probes that instance has this frame: 0 without prepare, when the settings' spacing is
 * 0, without bounces, when no other instance lights it, or when its object gathers per vertex. */
PRT_API uint32_t prt_shadowfield_instance_probe_count(const prt_shadowfield_scene* scene,
                                                      uint32_t instance);
/* Before each pass's gather, pass 0 included: the probes [first_probe, first_probe +
 * probe_count) of `instance` (prt_shadowfield_instance_probe_count). Pass 0 finds where each
 * probe reads the sources' fields this frame, which the projections need; a bounce gathers
 * their light, which the same pass's gather of the vertices reads. Nothing to do for an
 * instance without probes. */
PRT_API prt_result prt_shadowfield_gather_probes(prt_shadowfield_scene* scene, uint32_t pass,
                                                 uint32_t instance, uint32_t first_probe,
                                                 uint32_t probe_count);
/* Pass `pass` (0: direct, b: bounce b, up to the prepared bounces) of the vertices
 * [first_vertex, first_vertex + vertex_count) of `instance`. */
PRT_API prt_result prt_shadowfield_gather(prt_shadowfield_scene* scene, uint32_t pass,
                                          uint32_t instance, uint32_t first_vertex,
                                          uint32_t vertex_count);
/* After every instance's gather of `pass` and before pass + 1: the basis weights of the
 * radiance the instances [first_instance, first_instance + instance_count) leave in `pass`,
 * and the source field they cast from it. */
PRT_API prt_result prt_shadowfield_project(prt_shadowfield_scene* scene, uint32_t pass,
                                           uint32_t first_instance, uint32_t instance_count);
/* After the last pass: the outgoing radiance towards the prepared eye of the vertices
 * [first_vertex, first_vertex + vertex_count) of `instance` summed over passes 0..through_pass
 * (so through_pass = b is the radiance after b bounces), into out_rgb (vertex_count x 3). */
PRT_API prt_result prt_shadowfield_output(const prt_shadowfield_scene* scene, uint32_t instance,
                                          uint32_t through_pass, uint32_t first_vertex,
                                          uint32_t vertex_count, float* out_rgb);

/* ---- The GL backend (prt/prt_gl.h) ----------------------------------------------------------
 * The frame's per-vertex work (the direct light through the blockers' occlusion fields, the
 * bounces through the sources' radiance fields, the outgoing radiance) and, between two passes,
 * each source's basis projection and the field it casts, in a compute shader; the preparation
 * (prt_shadowfield_prepare) on the CPU. A frame reads nothing back. The output is one GL buffer
 * (SSBO) of RGB floats per vertex, the instances one after another.
 *
 * Create it after adding the scene's objects and instances; transforms may change between
 * frames. The GL calls need the GL context current, as prt_gl.h says; create and shade record
 * failures in the scene's context (shade, like prt_shadowfield_shade, changes the scene and
 * needs exclusive use of it), read and the output queries write no context. After a GL shade the
 * scene's CPU stages (gather, project, output) need prepare again. GL state: shade uses the
 * current program and the SSBO bindings 0 to 7, read the generic SSBO binding; both leave them
 * 0. */
typedef struct prt_gl_shadowfield prt_gl_shadowfield;

/* The buffers and program for `scene` (which must outlive it). PRT_ERROR_INVALID_ARGUMENT for
 * NULL arguments, PRT_ERROR_INVALID_OPERATION for a scene without instances,
 * PRT_ERROR_UNSUPPORTED_BACKEND when the context's backend limit excludes GL, the loader lacks
 * an entry point, the GL version is below 4.3 or a buffer exceeds the SSBO limit,
 * PRT_ERROR_OUT_OF_MEMORY. */
PRT_API prt_result prt_gl_shadowfield_create(prt_shadowfield_scene* scene, prt_gl_loader_fn loader,
                                             void* loader_user, prt_gl_shadowfield** out_shader);
/* NULL is ignored. */
PRT_API void prt_gl_shadowfield_destroy(prt_gl_shadowfield* shader);

/* prt_shadowfield_shade on GL into the output buffer, with the same arguments and failures;
 * settings->backend may be AUTO or GL (CPU and SIMD: PRT_ERROR_UNSUPPORTED_BACKEND).
 * PRT_ERROR_INVALID_OPERATION when the scene gained objects or instances since create. */
PRT_API prt_result prt_gl_shadowfield_shade(prt_gl_shadowfield* shader, const float* light_sh_rgb,
                                            const float eye[3],
                                            const prt_shadowfield_settings* settings);

/* The GL name of the output buffer, and where an instance's vertices start in it (in vertices:
 * its RGB is at floats 3 (first + v)); 0 for NULL or an unknown instance. */
PRT_API uint32_t prt_gl_shadowfield_output_buffer(const prt_gl_shadowfield* shader);
PRT_API uint32_t prt_gl_shadowfield_output_first(const prt_gl_shadowfield* shader,
                                                 uint32_t instance);
/* Reads the output of vertices [first_vertex, first_vertex + vertex_count) of `instance` into
 * out_rgb (vertex_count x 3). PRT_ERROR_INVALID_ARGUMENT for a bad instance or range. */
PRT_API prt_result prt_gl_shadowfield_read(prt_gl_shadowfield* shader, uint32_t instance,
                                           uint32_t first_vertex, uint32_t vertex_count,
                                           float* out_rgb);

#ifdef __cplusplus
}
#endif

#endif /* PRT_SHADOWFIELD_H */
