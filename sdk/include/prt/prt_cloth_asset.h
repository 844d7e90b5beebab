/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the `cloth` technique's section CLTH (formats/SPEC.md §7.4): woven
 * fabrics with their baked shadowing/masking tables, shaded per pixel (or per vertex) from the
 * surface's frame and the view under a spherical-Gaussian light, on the CPU, SIMD and GL
 * backends. C99 and C++.
 *
 * Each fabric of the asset has a name, default live parameters (prt_cloth_params) and a weave
 * (each thread's tangent offsets) whose tables were baked. Shading takes any live parameters for
 * a fabric (eta, albedo, k_d, gamma_s, gamma_v, coverage: edited live, no re-bake) and the light
 * as lobes (prt_cloth.h). What it computes, and how, is docs/cloth/method.md. The CLTH header,
 * records and sizes are checked when the asset is loaded, so these functions read what the load
 * kept. They never allocate and keep no state; any of them may be called on one asset from
 * several threads at once (e.g. disjoint pixel ranges of one frame). */
#ifndef PRT_CLOTH_ASSET_H
#define PRT_CLOTH_ASSET_H

#include <prt/prt_asset.h>
#include <prt/prt_cloth.h>
#include <prt/prt_gl.h>
#include <prt/prt_types.h>
#include <prt/prt_workers.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The `cloth` section (technique PRT_TECHNIQUE_CLOTH, element = material: one fabric). */
#define PRT_SECTION_CLTH PRT_TAG('C', 'L', 'T', 'H')

/* The CLTH header fields. */
typedef struct prt_cloth_info {
  size_t struct_size;      /* set by the caller: sizeof(prt_cloth_info) */
  uint32_t fabric_count;
  uint32_t table_count;
  uint32_t xi_size;        /* octahedral nodes per side of the lobe-direction grid */
  uint32_t lambda_levels;  /* lobe-sharpness levels */
  float lambda_min, lambda_max;
  uint32_t view_theta, view_phi; /* view-direction grid */
  uint32_t bits;           /* 8 or 16 per stored factor value */
  size_t table_bytes;      /* the tables' data as stored uncompressed, all fabrics */
} prt_cloth_info;

/* PRT_ERROR_NOT_FOUND when the asset has no CLTH section; PRT_ERROR_INVALID_ARGUMENT for NULL
 * pointers or a struct_size below 1.0's. */
PRT_API prt_result prt_cloth_get_info(const prt_asset* asset, prt_cloth_info* out_info);

/* One fabric: its name (a NUL-terminated string owned by the asset, e.g. "linen_plain"), default
 * live parameters, weave and the bytes of its tables (each table counted once per fabric that
 * uses it). Any output may be NULL. PRT_ERROR_NOT_FOUND without a CLTH section or for an index
 * >= fabric_count. */
PRT_API prt_result prt_cloth_get_fabric(const prt_asset* asset, uint32_t fabric,
                                        const char** out_name, prt_cloth_params* out_params,
                                        prt_cloth_weave* out_weave, size_t* out_table_bytes);

/* The index of the fabric of that name, or PRT_ERROR_NOT_FOUND. */
PRT_API prt_result prt_cloth_find_fabric(const prt_asset* asset, const char* name,
                                         uint32_t* out_fabric);

/* The shading's own switches, for measuring what each part of the method costs and gains (the
 * defaults are the fastest at the stated accuracy: leave them unless measuring). */
#define PRT_CLOTH_KEEP_HIDDEN_LOBES 1u /* do not skip lobes that lie wholly below a pixel's horizon */
#define PRT_CLOTH_KEEP_WEAK_LOBES 2u   /* do not skip lobes below weak_lobe of the light's power */
#define PRT_CLOTH_NO_CONE_TABLE 4u     /* weight every part by T alone (paper 003's factorisation) */
/* SIMD: compute what a pixel's frame alone decides for every batch of pixels, instead of reusing
 * it while batches share one frame (the same result either way; for measuring the reuse). */
#define PRT_CLOTH_NO_FRAME_CACHE 8u
/* SIMD: shade each copy of a tangent of multiplicity m apart (weight 1/m each) instead of once; and
 * recompute per tangent the terms a pixel's lobe shares across its tangents (the lobe in the
 * pixel's frame, table cells). For measuring what deduplication and sharing save. */
#define PRT_CLOTH_TANGENT_COPIES 16u
#define PRT_CLOTH_NO_LOBE_SHARING 32u
/* Paper 003 as printed, for measuring; scalar backend only. Each puts back one of the paper's
 * printed errors that the method fixes (docs/cloth/method.md, "What the paper gets wrong"):
 *   PAPER_PHI_DOMAIN     : phi over the fibre's whole front, |phi| < pi/2, also where it lies
 *                          below the cloth's horizon (lobes wholly below it are kept: they leak);
 *   PAPER_THETA_SEGMENTS : theta over [-pi/2, pi/2] in 6 equal segments, the integrand's smooth
 *                          factor linear on each, times each part's Gaussian in theta in closed
 *                          form (the light's lobe taken as a Gaussian; theta_segments not read);
 *   PAPER_SCHLICK        : Schlick's approximation, F_0 + (1 - F_0)(1 - c)^5 at c =
 *                          cos(theta_d) cos(phi_d/2), in place of the exact Fresnel term (surface
 *                          and volume parts): Eq. 13 as it should read;
 *   PAPER_SCHLICK_ANGLE  : Schlick's term at cos(theta_d) cos(phi_d), as printed;
 *   PAPER_SCHLICK_CUBE   : Schlick's term's binomial sum cut after the cube, as printed;
 *   PAPER_FRESNEL        : all three, Eq. 13 as printed (either of the last two implies Schlick);
 *   PAPER_NARROW_GU      : the lobed parts' Gaussian g_u of Eq. 4 as printed, standard deviation
 *                          gamma / sqrt 2 (every use of gamma_s and gamma_v).
 * (The paper's full-sphere denominator of T is a property of the baked tables.) As when the SIMD
 * ISA lacks AVX2: PRT_BACKEND_AUTO shades such a call on the scalar reference and an explicit
 * PRT_BACKEND_SIMD is PRT_ERROR_UNSUPPORTED_BACKEND; prt_gl_cloth_shade refuses them too. */
#define PRT_CLOTH_PAPER_PHI_DOMAIN 64u
#define PRT_CLOTH_PAPER_THETA_SEGMENTS 128u
#define PRT_CLOTH_PAPER_SCHLICK 256u
#define PRT_CLOTH_PAPER_NARROW_GU 512u
#define PRT_CLOTH_PAPER_SCHLICK_ANGLE 1024u
#define PRT_CLOTH_PAPER_SCHLICK_CUBE 2048u
#define PRT_CLOTH_PAPER_FRESNEL \
  (PRT_CLOTH_PAPER_SCHLICK | PRT_CLOTH_PAPER_SCHLICK_ANGLE | PRT_CLOTH_PAPER_SCHLICK_CUBE)
#define PRT_CLOTH_PAPER_FLAGS                                                              \
  (PRT_CLOTH_PAPER_PHI_DOMAIN | PRT_CLOTH_PAPER_THETA_SEGMENTS | PRT_CLOTH_PAPER_FRESNEL | \
   PRT_CLOTH_PAPER_NARROW_GU)

typedef struct prt_cloth_settings {
  size_t struct_size;     /* set by the caller: sizeof(prt_cloth_settings) */
  uint32_t flags;         /* PRT_CLOTH_* above */
  float weak_lobe;        /* a lobe whose power is below this fraction of the light's total is
                             skipped; 0: 1e-3 */
  uint32_t theta_segments; /* panels (of three nodes) per theta window, 1..16; 0: 2 */
  uint32_t phi_nodes;      /* nodes of each phi integral, 1..8; 0: 3 */
} prt_cloth_settings;

/* Outgoing radiance of samples [first, first+count) (pixels->normals[3 i] ..., i in the range)
 * of fabric `fabric` under `light`, into out_rgb (count x 3 floats, sample-major; 0 where the
 * view is below the surface). `params` NULL: the fabric's own; `settings` NULL: the defaults.
 *   PRT_BACKEND_AUTO : the context's best CPU-side backend;
 *   PRT_BACKEND_CPU  : the scalar reference of the method, in double;
 *   PRT_BACKEND_SIMD : AVX2+FMA kernels, eight samples at a time, in float (within the
 *                      conformance bound of tests/cloth); not with PRT_CLOTH_PAPER_FLAGS;
 *   PRT_BACKEND_GL   : PRT_ERROR_UNSUPPORTED_BACKEND (GL shading runs through a
 *                      prt_gl_cloth_shader, below).
 * PRT_ERROR_UNSUPPORTED_BACKEND when the backend is not usable in the asset's context or with the
 * settings,
 * PRT_ERROR_NOT_FOUND without a CLTH section or for a fabric index out of range,
 * PRT_ERROR_INVALID_ARGUMENT for NULL pointers, invalid params, light or settings, bad struct
 * sizes or a backend value out of range. Degenerate samples (a zero vector, a warp parallel to
 * the normal) shade to 0. */
PRT_API prt_result prt_cloth_shade(const prt_asset* asset, prt_backend backend, uint32_t fabric,
                                   const prt_cloth_params* params, const prt_cloth_light* light,
                                   const prt_cloth_settings* settings,
                                   const prt_cloth_pixels* pixels, uint32_t first, uint32_t count,
                                   float* out_rgb);

/* prt_cloth_shade of [first, first+count) split over the pool's threads in contiguous chunks:
 * bitwise the one-range call's result. */
PRT_API prt_result prt_cloth_shade_workers(prt_workers* workers, const prt_asset* asset,
                                           prt_backend backend, uint32_t fabric,
                                           const prt_cloth_params* params,
                                           const prt_cloth_light* light,
                                           const prt_cloth_settings* settings,
                                           const prt_cloth_pixels* pixels, uint32_t first,
                                           uint32_t count, float* out_rgb);

/* ---- GL (prt_gl.h: loader, thread and GL state contract) --------------------------------------
 *
 * A fragment shader shades a G-buffer: the game renders its cloth's world-space normal, warp
 * and view direction (unit vectors) into three float textures, and prt_gl_cloth_shade draws one
 * full-screen triangle over the viewport that writes each pixel's radiance (RGB, alpha 1) to the
 * bound draw framebuffer's colour attachment 0; pixels whose normal texel is (0, 0, 0) are
 * discarded (not cloth). The tables are uploaded once as one integer texture; the light,
 * parameters and per-lobe terms are a uniform block, so live parameters never re-upload them.
 * The shader evaluates the same method as the CPU backends in float (tests/cloth/gl: the bound
 * GL is held to); a light with many lobes is drawn in several passes added by blending (some
 * drivers cap a pixel's loop iterations). GL state touched by shade: the current program, the
 * vertex array binding, texture units 0..3 (2D bindings and sampler bindings, the active unit
 * left at 0), the uniform buffer binding 0 and the generic binding, depth test and face culling
 * (disabled), blending (on for passes after the first; its functions restored, left off); all
 * restored to 0 / off afterwards. create also touches texture unit 3's binding and saves and
 * restores the pixel-unpack state. The viewport and framebuffer are the caller's. */

typedef struct prt_gl_cloth_shader prt_gl_cloth_shader;

/* Uploads the asset's tables and compiles the shader on the GL context current on this thread.
 * `context` records failures and its backend limit decides whether GL may be used. The asset must
 * outlive the shader. PRT_ERROR_INVALID_ARGUMENT for NULL pointers; PRT_ERROR_NOT_FOUND without a
 * CLTH section; PRT_ERROR_UNSUPPORTED_BACKEND when GL is compiled out, limited away, an entry
 * point is missing, the context is older than 4.3 or the shader does not compile (the message
 * quotes the log); PRT_ERROR_OUT_OF_MEMORY when the allocator or GL runs out. */
PRT_API prt_result prt_gl_cloth_create(prt_context* context, const prt_asset* asset,
                                       prt_gl_loader_fn loader, void* loader_user,
                                       prt_gl_cloth_shader** out_shader);

/* Deletes the GL objects and frees the shader; NULL is ignored. Needs the GL context current. */
PRT_API void prt_gl_cloth_destroy(prt_gl_cloth_shader* shader);

/* The G-buffer: GL texture names of 2D textures holding RGB(A) float (or half float) unit
 * vectors, world space, one texel per pixel of the viewport. */
typedef struct prt_gl_cloth_gbuffer {
  size_t struct_size; /* set by the caller: sizeof(prt_gl_cloth_gbuffer) */
  uint32_t normal_texture;
  uint32_t warp_texture;
  uint32_t view_texture;
} prt_gl_cloth_gbuffer;

/* Shades the G-buffer into the bound draw framebuffer as above, with fabric, params, light and
 * settings as prt_cloth_shade. Returns once the draw is queued. Writes no context:
 * PRT_OK, PRT_ERROR_NOT_FOUND for a fabric index out of range, PRT_ERROR_INVALID_ARGUMENT for a
 * NULL shader, light or gbuffer, invalid params, light or settings, PRT_ERROR_UNSUPPORTED_BACKEND
 * for settings with PRT_CLOTH_PAPER_FLAGS (nothing is issued then). */
PRT_API prt_result prt_gl_cloth_shade(prt_gl_cloth_shader* shader, uint32_t fabric,
                                      const prt_cloth_params* params,
                                      const prt_cloth_light* light,
                                      const prt_cloth_settings* settings,
                                      const prt_gl_cloth_gbuffer* gbuffer);

#ifdef __cplusplus
}
#endif

#endif /* PRT_CLOTH_ASSET_H */
