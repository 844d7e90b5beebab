/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API: the techniques this runtime knows, the element domain of a section, and
 * which techniques a loaded blob holds. C99 and C++.
 *
 * A technique is one precomputed-radiance-transfer method with its own section kind, headers
 * (prt_<t>.h for its maths, prt_<t>_asset.h for its section) and shading functions. Its section
 * stores one record per element of a domain: a vertex (`sh`, `wavelet`, `pose`), a triangle, a
 * material (tables shaded per pixel: `cloth`) or an object (fields combined across instances:
 * `shadowfield`).
 * Code that handles every technique the same way (a tool listing a blob, a fuzzer, a viewer) loops
 * over prt_asset_techniques() and asks prt_technique_get_info() instead of naming techniques.
 *
 * Thread safety: pure functions of their arguments (and of an immutable asset); any thread. */
#ifndef PRT_TECHNIQUE_H
#define PRT_TECHNIQUE_H

#include <prt/prt_types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The techniques. 0 is none; the values stay below 32 so that a set of them fits a uint32_t bit
 * mask, bit (1u << technique). */
typedef enum prt_technique {
  PRT_TECHNIQUE_NONE = 0,
  PRT_TECHNIQUE_SH = 1,      /* per-vertex SH transfer (prt_sh.h, prt_sh_asset.h) */
  PRT_TECHNIQUE_WAVELET = 2, /* per-vertex Haar wavelet transfer (prt_wavelet*.h) */
  PRT_TECHNIQUE_POSE = 3,    /* per-vertex SH transfer of a skinned character (prt_pose_asset.h) */
  PRT_TECHNIQUE_CLOTH = 4,   /* per-pixel woven cloth from per-fabric tables (prt_cloth*.h) */
  PRT_TECHNIQUE_SHADOWFIELD = 5 /* rigid objects' shadow and radiance fields
                                 * (prt_shadowfield_asset.h) */
} prt_technique;

/* What one element of a section is (formats/SPEC.md, section kinds). */
typedef enum prt_element_domain {
  PRT_ELEMENT_DOMAIN_NONE = 0,     /* plain bytes (e.g. INFO text): element = byte */
  PRT_ELEMENT_DOMAIN_VERTEX = 1,   /* one element per vertex (VPOS's element count) */
  PRT_ELEMENT_DOMAIN_TRIANGLE = 2, /* one element per triangle */
  PRT_ELEMENT_DOMAIN_MATERIAL = 3, /* one element per material, shaded per pixel */
  PRT_ELEMENT_DOMAIN_OBJECT = 4    /* one element per rigid object, combined across instances */
} prt_element_domain;

typedef struct prt_technique_info {
  size_t struct_size; /* set by the caller: sizeof(prt_technique_info) */
  prt_technique technique;
  const char* name;     /* "sh", "wavelet": the name used by folders, tools and docs (static) */
  uint32_t section_tag; /* PRT_TAG of the technique's section, e.g. PRT_SECTION_SHTR */
  prt_element_domain domain; /* what one element of that section is */
} prt_technique_info;

/* Describes a technique this runtime implements. PRT_ERROR_INVALID_ARGUMENT for a NULL out or a
 * struct_size below 1.0's, PRT_ERROR_NOT_FOUND for PRT_TECHNIQUE_NONE or a value this runtime
 * does not know. */
PRT_API prt_result prt_technique_get_info(prt_technique technique, prt_technique_info* out_info);

/* The techniques whose section the asset holds, as bits (1u << technique); 0 for NULL or a blob
 * of mesh sections only. Each technique in the set has passed its load-time checks, so its
 * functions accept the asset. */
PRT_API uint32_t prt_asset_techniques(const prt_asset* asset);

#ifdef __cplusplus
}
#endif

#endif /* PRT_TECHNIQUE_H */
