/* SPDX-License-Identifier: MIT */
/* Helpers shared by the runtime's wavelet files (not public): the WVLT view the load decodes,
 * parameterisation checks and the direction -> texel map without argument checks, for per-frame
 * loops. */
#ifndef PRT_RUNTIME_WAVELET_INTERNAL_H
#define PRT_RUNTIME_WAVELET_INTERNAL_H

#include <stdint.h>

#include "internal.h"
#include "sphere_internal.h"
#include "wavelet_shade_simd.h"

#define PRT_WAVELET_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_wavelet_info, pair_count)

/* The WVLT section of a loaded asset, decoded and checked once at load (wavelet_section.c): the
 * header fields, the layout of §7.2 (prt_blob_wvlt_layout_of), which equals the section's size
 * exactly, and rs[V] = P, so that every array below lies inside the section whatever the
 * validation level. Row contents are checked as the rows are walked. */
typedef struct prt_wavelet_view {
  prt_wavelet_info info;
  prt_blob_wvlt_layout layout;
  const uint8_t* section;    /* the section's bytes, layout.raw_size of them */
  const uint8_t* band_scale; /* f32[bands] */
  prt_wavelet_rows rows;     /* light and skip left NULL */
  prt_wavelet_tiles* tiles;  /* runtime-owned repack (wavelet_tiles.c), NULL when not made */
} prt_wavelet_view;

/* The technique entry's attach and release hooks (wavelet_tiles.c). */
prt_result prt_wavelet_attach_tiles(const prt_context* context, const prt_allocator* allocator,
                                    const prt_asset_section* sections, uint32_t section_count,
                                    void* view, char* msg, size_t capacity);
void prt_wavelet_release_tiles(const prt_allocator* allocator, void* view);

/* Fills *out for one tiled call from the prepared light and the skip mask (never NULL); 0 when a
 * corner light that is not skipped is infinite or NaN (the rows must then be shaded instead, as
 * only their stored pairs may meet it). */
int prt_wavelet_tile_light_make(const prt_wavelet_tiles* tiles, const float* light,
                                const uint8_t* skip, prt_wavelet_tile_light* out);

/* 1 when param is known and size a power of two in PRT_WAVELET_MIN_SIZE..PRT_WAVELET_MAX_SIZE. */
int prt_wavelet_domain_valid(uint32_t param, uint32_t size);

/* 1 when texel (x, y) of a paraboloid face has its centre in the disc (SPEC §14): centre
 * a = (2x + 1 - S) / S, so a^2 + b^2 <= 1 is this integer test, exact. */
static inline int prt_paraboloid_texel_inside(uint32_t size, uint32_t x, uint32_t y) {
  const int64_t a = 2 * (int64_t)x + 1 - (int64_t)size, b = 2 * (int64_t)y + 1 - (int64_t)size;
  return a * a + b * b <= (int64_t)size * (int64_t)size;
}

/* 1 when texel (x, y) of a face carries a direction: always on the cube, centre inside the disc
 * on the paraboloid. */
static inline int prt_wavelet_texel_inside(uint32_t param, uint32_t size, uint32_t x, uint32_t y) {
  return param == PRT_WAVELET_PARAM_CUBE || prt_paraboloid_texel_inside(size, x, y);
}

/* The rim rule of SPEC §14 for a disc point (a, b) whose texel is outside. */
uint32_t prt_wavelet_paraboloid_rim_texel(uint32_t size, double a, double b);

/* The paraboloid's texel of disc point (a, b) on a face (index within the face). */
static inline uint32_t prt_wavelet_paraboloid_texel(uint32_t size, double a, double b) {
  const uint32_t tx = prt_face_texel(a, size), ty = prt_face_texel(b, size);
  if (prt_paraboloid_texel_inside(size, tx, ty)) return ty * size + tx;
  return prt_wavelet_paraboloid_rim_texel(size, a, b);
}

/* prt_wavelet_locate for a valid domain and a finite direction of length 1 (the cube accepts
 * any nonzero length). Inline: the resampling calls it for every source texel. */
static inline uint32_t prt_wavelet_locate_unit(uint32_t param, uint32_t size, double x, double y,
                                               double z) {
  if (param == PRT_WAVELET_PARAM_CUBE) {
    double sc, tc;
    const uint32_t face = prt_cube_face_coords(x, y, z, &sc, &tc);
    return (face * size + prt_face_texel(tc, size)) * size + prt_face_texel(sc, size);
  }
  if (y >= 0.0) {
    const double k = 1.0 / (1.0 + y);
    return prt_wavelet_paraboloid_texel(size, x * k, z * k);
  } else {
    const double k = 1.0 / (1.0 - y);
    return size * size + prt_wavelet_paraboloid_texel(size, x * k, -z * k);
  }
}

#endif /* PRT_RUNTIME_WAVELET_INTERNAL_H */
