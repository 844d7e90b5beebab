/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the `shadowfield` technique's baked object (section SFLD,
 * formats/SPEC.md §7.5, docs/shadowfield/design.md). C99 and C++.
 *
 * A `shadowfield` asset holds one rigid object baked alone in its own frame: its self-shadowed
 * transfer per BRDF term, the occlusion field it casts and the radiance fields it emits on two
 * grids of shells around it. The SFLD header is checked against the section's size when the
 * asset is loaded (a header that does not fit fails the load), and the object is decoded into
 * floats the asset owns; an asset is immutable after loading, so any thread may query it. Only
 * full validation checks the stored floats for NaN. */
#ifndef PRT_SHADOWFIELD_ASSET_H
#define PRT_SHADOWFIELD_ASSET_H

#include <prt/prt_asset.h>
#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The `shadowfield` object section (technique PRT_TECHNIQUE_SHADOWFIELD, element = object). */
#define PRT_SECTION_SFLD PRT_TAG('S', 'F', 'L', 'D')

/* A grid of shells around the object's bounding sphere (centre, radius r): `shells` shells from
 * inner r to outer r, evenly spaced in log radius, each with the cell centres of a cube map of
 * face_size x face_size cells per face. */
typedef struct prt_shadowfield_shells {
  float centre[3];    /* object frame */
  float radius;       /* r > 0 */
  float inner;        /* innermost shell / r */
  float outer;        /* outermost shell / r */
  uint32_t shells;    /* 1..64 */
  uint32_t face_size; /* 1..64 */
} prt_shadowfield_shells;

/* The SFLD header fields (formats/SPEC.md §7.5) and the sizes. */
typedef struct prt_shadowfield_info {
  size_t struct_size;    /* set by the caller: sizeof(prt_shadowfield_info) */
  uint32_t order;        /* SH order n, 2..6 */
  uint32_t terms;        /* BRDF terms K, 1..8 (1 when diffuse) */
  uint32_t glossy;       /* 1 glossy (separable BRDF), 0 diffuse */
  uint32_t vertex_count; /* V, the mesh's (VPOS) */
  uint32_t basis_size;   /* N surface-radiance basis functions, 1..64 */
  uint32_t brdf_grid;    /* G: the g table's hemisphere grid is G x G (0 when diffuse) */
  prt_shadowfield_shells oof_shells; /* where the occlusion field is sampled */
  prt_shadowfield_shells srf_shells; /* where the source radiance fields are sampled */
  uint32_t bits;                     /* 8 or 16 per stored value */
  uint64_t bytes;                    /* the section's decoded (raw) size */
  uint64_t decoded_bytes;            /* what the asset allocated for the object's floats */
} prt_shadowfield_info;

/* PRT_ERROR_NOT_FOUND when the asset has no SFLD section; PRT_ERROR_INVALID_ARGUMENT for NULL
 * pointers or a struct_size below 1.0's. */
PRT_API prt_result prt_shadowfield_get_info(const prt_asset* asset, prt_shadowfield_info* out_info);

#ifdef __cplusplus
}
#endif

#endif /* PRT_SHADOWFIELD_ASSET_H */
