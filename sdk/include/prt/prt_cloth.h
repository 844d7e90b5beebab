/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the `cloth` technique's maths that needs no asset: the microcylinder
 * fabric model evaluated exactly (docs/cloth/model.md), a brute-force reference of it under an
 * environment given as texels, and the spherical-Gaussian light the shading takes, with a fit of
 * it to an environment image fast enough to run every frame. C99 and C++.
 *
 * Directions are world-space unit vectors pointing away from the surface (towards the light,
 * towards the eye). A surface point's frame is its unit normal `n` and its warp direction `u`
 * (thread 1's; made orthogonal to n by the callee); the weft is v = n x u.
 *
 * Thread safety: pure functions of their arguments, any thread, except where a context is taken
 * (then one thread at a time per context, prt_context.h). */
#ifndef PRT_CLOTH_H
#define PRT_CLOTH_H

#include <prt/prt_context.h>
#include <prt/prt_env.h>
#include <prt/prt_types.h>
#include <prt/prt_workers.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Distinct tangent offsets one thread may have, and repeats of one offset. */
#define PRT_CLOTH_MAX_THREAD_TANGENTS 16u
#define PRT_CLOTH_MAX_MULTIPLICITY 64u

/* The live parameters of one thread (Sadeghi's per-thread scattering; docs/cloth/model.md). */
typedef struct prt_cloth_thread {
  float eta;       /* index of refraction of the fibre, in [1, 4] */
  float albedo[3]; /* volume albedo A, linear RGB, each in [0, 1] */
  float kd;        /* isotropic fraction of volume scattering, in [0, 1] */
  float gamma_s;   /* width of the surface lobe in theta_h, radians, in (0, pi] */
  float gamma_v;   /* width of the volume lobe in theta_h, radians, in (0, pi] */
  float coverage;  /* area fraction a_j of the thread, in [0, 1]; a_1 + a_2 <= 1 */
} prt_cloth_thread;

/* A fabric's live parameters: what shading takes every frame (no re-bake when they change). */
typedef struct prt_cloth_params {
  size_t struct_size; /* set by the caller: sizeof(prt_cloth_params) */
  prt_cloth_thread threads[2]; /* [0] warp (along u), [1] weft (along v) */
} prt_cloth_params;

/* A fabric's weave: each thread's tangent offsets (radians, |offset| <= pi/2), distinct values
 * with their multiplicities. Baked into an asset's tables; the exact model takes it as is. */
typedef struct prt_cloth_weave {
  size_t struct_size; /* set by the caller: sizeof(prt_cloth_weave) */
  uint32_t tangent_count[2]; /* 1..PRT_CLOTH_MAX_THREAD_TANGENTS per thread */
  float offsets[2][PRT_CLOTH_MAX_THREAD_TANGENTS]; /* distinct within a thread */
  uint32_t multiplicity[2][PRT_CLOTH_MAX_THREAD_TANGENTS]; /* each 1..PRT_CLOTH_MAX_MULTIPLICITY */
} prt_cloth_weave;

/* PRT_OK when the parameters / the weave are within the ranges above (every float finite);
 * PRT_ERROR_INVALID_ARGUMENT otherwise or for NULL or a struct_size below 1.0's. */
PRT_API prt_result prt_cloth_params_validate(const prt_cloth_params* params);
PRT_API prt_result prt_cloth_weave_validate(const prt_cloth_weave* weave);

/* The model's kernel k(w_i, w_o) (docs/cloth/model.md, "The cloth"): outgoing radiance is the
 * integral of L(w_i) k(w_i, w_o) over the upper hemisphere, so k includes cos(theta_i), the
 * shadowing/masking weights and the coverages. `normal` and `warp` give the frame (3 floats
 * each); out_rgb gets 3 floats, 0 when w_i or w_o is below the surface. Double precision
 * inside. PRT_ERROR_INVALID_ARGUMENT for NULL pointers, invalid params or weave, a zero or
 * non-finite vector, or a warp parallel to the normal. */
PRT_API prt_result prt_cloth_kernel(const prt_cloth_params* params, const prt_cloth_weave* weave,
                                    const float normal[3], const float warp[3],
                                    const float light_dir[3], const float view_dir[3],
                                    float out_rgb[3]);

/* The shadowing/masking weights of thread `thread` (0 warp, 1 weft): for each of its
 * weave.tangent_count[thread] distinct offsets, W = M P / (the sum of P over the thread's
 * multiset, each offset counted with its multiplicity), per copy of the offset
 * (docs/cloth/model.md); out_weights gets that many floats, all 0 when w_i or w_o is below the
 * surface. What the baker convolves into the asset's tables. Errors as prt_cloth_kernel, and
 * PRT_ERROR_INVALID_ARGUMENT for a thread other than 0 or 1. */
PRT_API prt_result prt_cloth_thread_weights(const prt_cloth_weave* weave, uint32_t thread,
                                            const float normal[3], const float warp[3],
                                            const float light_dir[3], const float view_dir[3],
                                            float* out_weights);

/* ---- The environment as texels, for the brute-force reference --------------------------------
 *
 * An environment map given as its texels: each texel's centre direction and its radiance times
 * its solid angle (so that the sum over texels of rgb * f(dir) is the integral of L f). Any
 * mapping fits (a game or tool lists a lat-long, cube or probe image's texels this way). */
typedef struct prt_cloth_env_texels {
  size_t struct_size;       /* set by the caller: sizeof(prt_cloth_env_texels) */
  uint32_t count;
  const float* directions;  /* count x 3, unit, world */
  const float* power;       /* count x 3: radiance x solid angle (sr), RGB, finite, >= 0 */
} prt_cloth_env_texels;

/* Surface samples to shade: a G-buffer's pixels or a mesh's vertices. */
typedef struct prt_cloth_pixels {
  size_t struct_size;   /* set by the caller: sizeof(prt_cloth_pixels) */
  const float* normals; /* count x 3, unit */
  const float* warps;   /* count x 3: thread 1's direction (made orthogonal to the normal) */
  const float* views;   /* count x 3: unit direction from the surface to the eye */
} prt_cloth_pixels;

/* Brute force: for samples [first, first+count), the sum over every texel above the surface of
 * power x k(texel direction, view), in double; out_rgb gets count x 3 floats (0 for a view below
 * the surface or a sample whose vectors are degenerate). Cost: count x texels x tangents. The
 * ground truth the technique's error is measured against (a quadrature of the map as piecewise
 * constant: its own error is stated by the tools that call it, from a finer quadrature).
 * PRT_ERROR_INVALID_ARGUMENT for NULL pointers, invalid params or weave, bad struct sizes, or a
 * texel outside its contract (a direction not finite or more than 1e-3 from unit length, a power
 * not finite or negative). */
PRT_API prt_result prt_cloth_reference(const prt_cloth_params* params,
                                       const prt_cloth_weave* weave,
                                       const prt_cloth_env_texels* env,
                                       const prt_cloth_pixels* pixels, uint32_t first,
                                       uint32_t count, float* out_rgb);

/* prt_cloth_reference of [first, first+count) split over the pool's threads in contiguous
 * chunks: bitwise the one-range call's result. */
PRT_API prt_result prt_cloth_reference_workers(prt_workers* workers,
                                               const prt_cloth_params* params,
                                               const prt_cloth_weave* weave,
                                               const prt_cloth_env_texels* env,
                                               const prt_cloth_pixels* pixels, uint32_t first,
                                               uint32_t count, float* out_rgb);

/* ---- Spherical-Gaussian light ---------------------------------------------------------------
 *
 * The light shading takes: a sum of K lobes L(w) = sum_k rgb_k exp(sharpness_k (w . axis_k - 1)),
 * world frame (paper 003's G(w; xi, sigma) with sharpness = 2 / sigma^2). */
#define PRT_CLOTH_MIN_SHARPNESS 0.25f
#define PRT_CLOTH_MAX_SHARPNESS 1.0e4f
#define PRT_CLOTH_MAX_LOBES 256u

typedef struct prt_cloth_lobe {
  float axis[3];   /* unit */
  float sharpness; /* lambda, in [PRT_CLOTH_MIN_SHARPNESS, PRT_CLOTH_MAX_SHARPNESS] */
  float rgb[3];    /* amplitude (radiance at the axis), finite, >= 0 */
} prt_cloth_lobe;

typedef struct prt_cloth_light {
  size_t struct_size;           /* set by the caller: sizeof(prt_cloth_light) */
  uint32_t lobe_count;          /* 0..PRT_CLOTH_MAX_LOBES */
  const prt_cloth_lobe* lobes;
} prt_cloth_light;

/* PRT_OK when every lobe is within the ranges above (an axis within 1e-3 of unit length);
 * PRT_ERROR_INVALID_ARGUMENT otherwise. */
PRT_API prt_result prt_cloth_light_validate(const prt_cloth_light* light);

/* How prt_cloth_fit_light works; a zero-initialised struct with struct_size set gives the
 * defaults. */
typedef struct prt_cloth_fit_desc {
  size_t struct_size;   /* set by the caller: sizeof(prt_cloth_fit_desc) */
  uint32_t lobe_count;  /* K, 1..PRT_CLOTH_MAX_LOBES; 0: 10 */
  uint32_t resolution;  /* the map is first averaged onto a lat-long grid of 2R x R; 0: 64 */
  uint32_t iterations;  /* clustering iterations; 0: 8 */
} prt_cloth_fit_desc;

typedef struct prt_cloth_fit_report {
  size_t struct_size;    /* set by the caller: sizeof(prt_cloth_fit_report) */
  uint32_t lobe_count;   /* lobes written (fewer than asked when the map has fewer lit cells) */
  float relative_error;  /* RMS radiance error over the sphere / RMS radiance, on the grid */
  float power_error;     /* |sum of lobe powers - map power| / map power */
} prt_cloth_fit_report;

/* Fits lobes to an environment image (fast enough for a dynamic light each frame): bright
 * compact sources get lobes of their own, the rest is clustered by direction and each cluster
 * becomes the lobe with its power, mean direction and spread; deterministic. out_lobes receives
 * lobe_count lobes (as many as asked; unused ones get rgb 0); `report` may be NULL. Scratch is
 * allocated with the context's allocator and freed before return; failures are recorded in the
 * context. PRT_ERROR_INVALID_ARGUMENT for NULL pointers, an invalid env (prt_env_image_validate)
 * or desc, PRT_ERROR_OUT_OF_MEMORY when the allocator fails. */
PRT_API prt_result prt_cloth_fit_light(prt_context* context, const prt_env_image* env,
                                       const prt_cloth_fit_desc* desc, prt_cloth_lobe* out_lobes,
                                       prt_cloth_fit_report* report);

#ifdef __cplusplus
}
#endif

#endif /* PRT_CLOTH_H */
