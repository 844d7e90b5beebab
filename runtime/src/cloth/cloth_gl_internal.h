/* SPDX-License-Identifier: MIT */
/* Private to the runtime: what cloth's GL backend (cloth_gl.c) and its shaders (cloth_gl_glsl.c)
 * share: the uniform block a shade call fills, mirrored field by field by the fragment shader's
 * `Call` block (std140: every member a vec4 or uvec4, or an array of them), and the shaders'
 * sources. */
#ifndef PRT_RUNTIME_CLOTH_GL_INTERNAL_H
#define PRT_RUNTIME_CLOTH_GL_INTERNAL_H

#include <stdint.h>

#include "cloth_shade_internal.h"

/* Distinct tangents of a fabric (both threads). */
#define PRT_CLOTH_GL_MAX_TANGENTS (2u * PRT_CLOTH_MAX_THREAD_TANGENTS)

/* tangent_bits: the thread (0 warp, 1 weft), the table read mirrored, and a fibre standing
 * vertical (cos tau below 1e-9: the phi range is a whole half or nothing). */
#define PRT_CLOTH_GL_TANGENT_WEFT 1u
#define PRT_CLOTH_GL_TANGENT_MIRROR 2u
#define PRT_CLOTH_GL_TANGENT_VERTICAL 4u
/* lobe_bits: bit 2 j + p is set when part p (0 surface, 1 volume lobe) of thread j is merged
 * into the lobe's own theta window (cloth_integrals.c); the lobe's lower sharpness level from
 * bit 8 up. */
#define PRT_CLOTH_GL_LEVEL_SHIFT 8u

/* One factorisation in the table buffer: word offsets (from the section's first table byte) of
 * its u scales, v scales, v values and u values. */
typedef struct prt_cloth_gl_factor {
  uint32_t u_scale, v_scale, v_values, u_values;
} prt_cloth_gl_factor;

typedef struct prt_cloth_gl_block {
  uint32_t counts[4];         /* lobes, tangents, theta segments, phi nodes */
  uint32_t misc[4];           /* settings flags, viewport x, viewport y, 0 */
  float thread_scatter[2][4]; /* per thread: eta, k_d, gamma_s, gamma_v */
  float thread_albedo[2][4];  /* per thread: albedo RGB, 0 */
  float tangent_angles[PRT_CLOTH_GL_MAX_TANGENTS][4];  /* sin tau, cos tau, weight, -tan tau */
  float tangent_support[PRT_CLOTH_GL_MAX_TANGENTS][4]; /* the theta support's ends, 0, 0 */
  uint32_t tangent_bits[PRT_CLOTH_GL_MAX_TANGENTS][4]; /* PRT_CLOTH_GL_TANGENT_*, rank of T,
                                                          rank of T_c, 0 */
  prt_cloth_gl_factor tangent_full[PRT_CLOTH_GL_MAX_TANGENTS]; /* T */
  prt_cloth_gl_factor tangent_cone[PRT_CLOTH_GL_MAX_TANGENTS]; /* T_c */
  float lobe_axis[PRT_CLOTH_MAX_LOBES][4];                     /* unit axis, sharpness */
  float lobe_rgb[PRT_CLOTH_MAX_LOBES][4];  /* amplitude, weight of the upper sharpness level */
  uint32_t lobe_bits[PRT_CLOTH_MAX_LOBES]; /* as uvec4[MAX_LOBES / 4] in the shader */
} prt_cloth_gl_block;

/* The most terms of a panel's moment series (the fragment shader's SERIES_TERMS). */
#define PRT_CLOTH_GL_SERIES_TERMS 28u

/* GL guarantees uniform blocks of 16 KiB. */
PRT_STATIC_ASSERT(sizeof(prt_cloth_gl_block) <= 16384u, cloth_gl_block_fits);
PRT_STATIC_ASSERT(PRT_CLOTH_MAX_LOBES % 4u == 0u, cloth_gl_lobe_bits_pack);

/* The shaders. The fragment shader's sources follow a header the backend writes (the #version
 * line and the asset's constants: BITS, MAX_RANK, XI_SIZE, LEVELS, VIEW_THETA, VIEW_PHI,
 * MAX_TANGENTS, MAX_LOBES, TABLE_SHIFT: the table texture is 2^TABLE_SHIFT texels wide,
 * SERIES_TERMS). */
extern const char prt_cloth_gl_vertex_source[];
#define PRT_CLOTH_GL_FRAGMENT_PARTS 4
extern const char* const prt_cloth_gl_fragment_sources[PRT_CLOTH_GL_FRAGMENT_PARTS];

#endif /* PRT_RUNTIME_CLOTH_GL_INTERNAL_H */
