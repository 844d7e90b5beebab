/* SPDX-License-Identifier: MIT */
/* Private to the runtime: one baked `shadowfield` object as the scene evaluation reads it
 * (docs/shadowfield/design.md), decoded from its blob at load (shadowfield_asset.c) into floats
 * owned by the asset. Every array is in the object's own frame, with the layouts of the baker's
 * ShadowfieldObject (baker/include/prt/baker/shadowfield/shadowfield_object.hpp). */
#ifndef PRT_RUNTIME_SHADOWFIELD_OBJECT_H
#define PRT_RUNTIME_SHADOWFIELD_OBJECT_H

#include <stdint.h>

#include <prt/format/shadowfield_shells.h>

typedef struct prt_sf_object {
  uint32_t order;        /* SH order n, 2..6 */
  uint32_t terms;        /* BRDF terms K (1 for a diffuse surface) */
  uint32_t glossy;       /* 1: g_k read from g_table; 0: diffuse, g = 1 */
  uint32_t vertex_count; /* V */
  uint32_t basis_size;   /* N */
  uint32_t brdf_grid;    /* G: the g table's hemisphere grid is G x G (0 when diffuse) */

  const float* positions; /* V x 3 */
  const float* normals;   /* V x 3, unit */
  const float* albedo;    /* V x 3, linear RGB */
  const float* transfer;  /* V x K x n^2: [(v K + k) n^2 + i] */
  const float* g_table;   /* K x G^2: [k G^2 + cell], cell = j G + i on the concentric map */

  prt_sf_shells oof_shells;
  const float* oof; /* points x n^2 */

  const float* basis;          /* N x V */
  const float* vertex_weights; /* V */
  const float* basis_inverse;  /* N x N, row-major: A^-1 */

  prt_sf_shells srf_shells;
  const float* srf; /* N x K x points x n^2: [((i K + k) points + p) n^2 + c] */
} prt_sf_object;

#endif /* PRT_RUNTIME_SHADOWFIELD_OBJECT_H */
