/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the `pose` technique (section PSTR, formats/SPEC.md §7.3), the SH
 * transfer of a skinned character learned as a function of its joint rotations, and its
 * shading on the CPU, SIMD and GL backends. C99 and C++.
 *
 * Each frame the game passes the character's joint rotations (the glTF nodes' local `rotation`
 * quaternions, x y z w, in the skin's `joints` order, as its animation system computes them).
 * The runtime turns them into pose features, then into the model's coefficients, then into
 * per-vertex transfer (or, for colour, folds the light into the coefficients first). The PSTR
 * header, the joint table and the evaluation order are checked when the asset is loaded, so
 * these functions read what the load kept. They never allocate and keep no state; an asset is
 * immutable after loading, so any of them may be called on one asset from several threads at
 * once (e.g. disjoint vertex ranges of one frame). */
#ifndef PRT_POSE_ASSET_H
#define PRT_POSE_ASSET_H

#include <prt/prt_asset.h>
#include <prt/prt_gl.h>
#include <prt/prt_types.h>
#include <prt/prt_workers.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The `pose` section (technique PRT_TECHNIQUE_POSE, element = vertex). */
#define PRT_SECTION_PSTR PRT_TAG('P', 'S', 'T', 'R')

/* What the model learned (SPEC §7.3). */
typedef enum prt_pose_model {
  PRT_POSE_MODEL_DIRECT = 0,  /* the paper's: the whole transfer, linear in the pose */
  PRT_POSE_MODEL_RESIDUAL = 1 /* exact unshadowed transfer of the skinned normal + a learned
                                 occlusion residual */
} prt_pose_model;

/* The PSTR header fields. */
typedef struct prt_pose_info {
  size_t struct_size; /* set by the caller: sizeof(prt_pose_info) */
  uint32_t order;     /* SH order n: n² coefficients per vertex */
  uint32_t vertex_count;
  uint32_t joint_count;   /* J: rotations per pose */
  uint32_t feature_count; /* 3 J */
  uint32_t pose_dims;     /* p */
  uint32_t basis_dims;    /* q */
  prt_pose_model model;
  uint32_t bits;        /* 8 or 16 per basis value */
  uint32_t model_joint; /* the joint whose frame is the model frame */
  uint32_t kind;        /* informational: 1 shadowed, 2 interreflected */
  uint32_t bounces;     /* informational */
  float albedo;         /* grey albedo of the exact part of model 1 */
  int clamps_pose;      /* 1: pose coordinates are clamped to the training range */
  size_t model_bytes;   /* pose PCA + regression + vertex basis, as stored uncompressed */
} prt_pose_info;

/* PRT_ERROR_NOT_FOUND when the asset has no PSTR section; PRT_ERROR_INVALID_ARGUMENT for NULL
 * pointers or a struct_size below 1.0's. */
PRT_API prt_result prt_pose_get_info(const prt_asset* asset, prt_pose_info* out_info);

/* One pose of the character. Pointers the caller owns; only joint_rotations is required. */
typedef struct prt_pose_input {
  size_t struct_size;              /* set by the caller: sizeof(prt_pose_input) */
  const float* joint_rotations;    /* J × 4: x y z w, any non-zero length (normalised) */
  const float* joint_translations; /* J × 3 or NULL: the rest translations (skinning only) */
  const float* joint_scales;       /* J × 3 or NULL: the rest scales (skinning only) */
} prt_pose_input;

/* The pose the model is relative to: each joint's bind rotation (J × 4, x y z w; the pose whose
 * features are all 0), rest translation (J × 3) and rest scale (J × 3), in the skin's joint
 * order; any output may be NULL. A game's animation sliders start here. PRT_ERROR_NOT_FOUND
 * without a PSTR section, PRT_ERROR_INVALID_ARGUMENT for a NULL asset. */
PRT_API prt_result prt_pose_bind_pose(const prt_asset* asset, float* out_rotations,
                                      float* out_translations, float* out_scales);

/* The pose features a (3 J floats, radians: SPEC §7.3) of a pose. PRT_ERROR_INVALID_ARGUMENT
 * for NULL pointers or a rotation that is zero or not finite. */
PRT_API prt_result prt_pose_features(const prt_asset* asset, const prt_pose_input* pose,
                                     float* out_features);

/* The pose coordinates z (p floats, clamped when the asset says so) and the model coefficients
 * y (q·n² floats, y[k][c] at k n² + c) of a pose; either output may be NULL. */
PRT_API prt_result prt_pose_coefficients(const prt_asset* asset, const prt_pose_input* pose,
                                         float* out_coordinates, float* out_coefficients);

/* Skinned positions and normals of vertices [first, first+count) in the model frame (3 floats
 * each; either output may be NULL), and the model frame's placement in the character's space
 * (out_model_frame: 12 floats, the 3×4 [R_m | o_m] row-major; may be NULL). */
PRT_API prt_result prt_pose_skin(const prt_asset* asset, const prt_pose_input* pose,
                                 uint32_t first_vertex, uint32_t vertex_count, float* out_positions,
                                 float* out_normals, float* out_model_frame);

/* What a shading call needs besides the pose. */
typedef struct prt_pose_light {
  size_t struct_size;     /* set by the caller: sizeof(prt_pose_light) */
  const float* light_rgb; /* n² RGB coefficients, coefficient-major, in the world frame */
  const float* world_from_character; /* row-major 3×3 rotation placing the character's space in
                                        the world, or NULL for the identity */
  const float* normals; /* model-frame skinned normals of the shaded range (count × 3, e.g. from
                           prt_pose_skin or the game's own skinning) for model 1, or NULL: the
                           runtime skins them */
} prt_pose_light;

/* Transfer of vertices [first, first+count) at a pose: count·n² floats, vertex-major, in the
 * model frame (SPEC §7.3), t_00 kept within [0, albedo / (2√π)] (the uniform sky's bounds, which
 * a learned model can cross on poses past its training; shading clamps the same way).
 * `normals` as in prt_pose_light (model 1; NULL: skinned here).
 *   PRT_BACKEND_AUTO : the context's best CPU-side backend;
 *   PRT_BACKEND_CPU  : the scalar reference, summed in double;
 *   PRT_BACKEND_SIMD : AVX2+FMA kernels, summed in float (within the conformance bound);
 *   PRT_BACKEND_GL   : PRT_ERROR_UNSUPPORTED_BACKEND (GL shading runs through a
 *                      prt_gl_pose_shader, below).
 * PRT_ERROR_UNSUPPORTED_BACKEND when the backend is not usable in the asset's context,
 * PRT_ERROR_NOT_FOUND without a PSTR section, PRT_ERROR_INVALID_ARGUMENT for bad pointers,
 * ranges, rotations or backend values. */
PRT_API prt_result prt_pose_transfer(const prt_asset* asset, prt_backend backend,
                                     const prt_pose_input* pose, const float* normals,
                                     uint32_t first_vertex, uint32_t vertex_count, float* out);

/* Outgoing radiance (white albedo; multiply by the surface's own) of vertices [first,
 * first+count) at a pose under a light: count × 3 floats. The light is rotated into the model
 * frame and folded into the coefficients first (3 q weights), so a vertex costs q
 * multiply-adds per channel plus, for model 1, its exact part. Backends and errors as
 * prt_pose_transfer. */
PRT_API prt_result prt_pose_shade(const prt_asset* asset, prt_backend backend,
                                  const prt_pose_input* pose, const prt_pose_light* light,
                                  uint32_t first_vertex, uint32_t vertex_count, float* out_rgb);

/* prt_pose_shade of [first, first+count) split over the pool's threads in contiguous chunks:
 * bitwise the one-range call's result. Errors as prt_sh_shade_workers. */
PRT_API prt_result prt_pose_shade_workers(prt_workers* workers, const prt_asset* asset,
                                          prt_backend backend, const prt_pose_input* pose,
                                          const prt_pose_light* light, uint32_t first_vertex,
                                          uint32_t vertex_count, float* out_rgb);

/* ---- GL (prt_gl.h: loader, thread and GL state contract) --------------------------------------
 *
 * The quantised vertex basis (and, for model 1, the skin records: bind normal, joints, weights)
 * is uploaded once, as stored. Each shade call does the per-frame work on the CPU with the
 * scalar code (features, coordinates, coefficients, the light rotated into the model frame and
 * folded into 3 q weights, and for model 1 the joints' skinning matrices K_j and the exact
 * part's weights factor_c L'[c]) and uploads those few floats; one compute invocation per
 * vertex then sums the basis values against the weights in float and, for model 1, blends its
 * skinning matrix, skins its normal (or reads the caller's) and adds the exact part's SH sum.
 * Results match the scalar reference up to float rounding (tests/pose/gl: the bound the
 * conformance test holds GL to). GL state touched: the current program, the generic
 * GL_SHADER_STORAGE_BUFFER binding, the indexed GL_SHADER_STORAGE_BUFFER bindings 0 and 2
 * (model 1: 0 to 4) and the indexed GL_UNIFORM_BUFFER binding 0, all left 0 afterwards. */

/* GPU-side `pose` shading of one asset: the static data uploaded once, shaded per frame. */
typedef struct prt_gl_pose_shader prt_gl_pose_shader;

/* Uploads the asset's PSTR basis values (and skin records for model 1) to GL buffers and
 * compiles the compute shader. `context` is the calling thread's context: failures are recorded
 * there (the asset may belong to another context) and its backend limit decides whether GL may
 * be used. The asset must outlive the shader; the shader is allocated with the asset's
 * allocator. GL errors the application left pending are cleared before the upload is checked.
 * PRT_ERROR_INVALID_ARGUMENT for NULL pointers; PRT_ERROR_NOT_FOUND without a PSTR section;
 * PRT_ERROR_UNSUPPORTED_BACKEND when GL is compiled out, limited away by the context, an entry
 * point is missing (the message names it), the GL context is older than 4.3, the shader does
 * not compile (the message quotes the log), or the asset's buffers exceed
 * GL_MAX_SHADER_STORAGE_BLOCK_SIZE; PRT_ERROR_OUT_OF_MEMORY when the allocator or GL runs out. */
PRT_API prt_result prt_gl_pose_create(prt_context* context, const prt_asset* asset,
                                      prt_gl_loader_fn loader, void* loader_user,
                                      prt_gl_pose_shader** out_shader);

/* Deletes the GL objects and frees the shader; NULL is ignored. Needs the GL context current. */
PRT_API void prt_gl_pose_destroy(prt_gl_pose_shader* shader);

/* Shades vertices [first, first+count) at a pose under a light (both as prt_pose_shade; for
 * model 1, light->normals, when given, are the count normals of the range and are uploaded)
 * into the same vertices of the output buffer (other vertices keep their values). Returns once
 * the work is queued (no CPU wait); a memory barrier is issued so that vertex fetch, shaders and
 * buffer reads see the result. Writes no context: PRT_OK, or PRT_ERROR_INVALID_ARGUMENT for a
 * NULL shader, pose or light, a bad struct_size, rotation or world rotation, or a range outside
 * the asset (nothing is issued to GL then). */
PRT_API prt_result prt_gl_pose_shade(prt_gl_pose_shader* shader, const prt_pose_input* pose,
                                     const prt_pose_light* light, uint32_t first_vertex,
                                     uint32_t vertex_count);

/* The GL name of the output buffer: one tightly packed RGB float triple per vertex of the asset
 * (12-byte stride, vertex v at byte 12 v), usable directly as a vertex attribute buffer. Owned
 * by the shader; 0 for NULL. */
PRT_API uint32_t prt_gl_pose_output_buffer(const prt_gl_pose_shader* shader);

/* Reads shaded RGB of vertices [first, first+count) back to the CPU (waits for the GPU):
 * count*3 floats. For tools and tests. Writes no context: PRT_OK, or
 * PRT_ERROR_INVALID_ARGUMENT for a NULL shader, a NULL out_rgb with count > 0 or a range
 * outside the asset. */
PRT_API prt_result prt_gl_pose_read(prt_gl_pose_shader* shader, uint32_t first_vertex,
                                    uint32_t vertex_count, float* out_rgb);

#ifdef __cplusplus
}
#endif

#endif /* PRT_POSE_ASSET_H */
