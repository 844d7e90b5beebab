/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the sparse rows of a WVLT section (formats/SPEC.md §7.2) as the shading
 * loops see them, the bounds checks every loop makes while it walks a row, and the SIMD kernels
 * of technique `wavelet` (one file per instruction set, compiled with that ISA's flags; only
 * wavelet_asset.c calls them, and only when the context's SIMD ISA allows it).
 *
 * The light is prepared once per frame (prt_wavelet_prepare_light): band scales folded in, RGBA
 * per coefficient. Vertex v then shades as
 *   radiance[c] = vs[v][c] * sum over the row's pairs (block k, index i, value q) of
 *                 q * prepared[256 k + i][c],
 * so a pair costs one 16-byte load of the light and one multiply-add of four lanes. A block whose
 * prepared light is all zero (prt_wavelet_prepare_light's zero-block mask) adds exactly 0, so
 * every kernel skips the pairs of the blocks the caller's mask marks: with M light coefficients
 * selected, the time follows the blocks they touch. With AVX2 the load also repacks the rows into
 * tiles (prt_wavelet_tiles below) for a kernel whose time follows the 64-coefficient groups the
 * light touches; the row kernels stay the reference layout's and take the lights it would not
 * speed up. */
#ifndef PRT_WAVELET_SHADE_SIMD_H
#define PRT_WAVELET_SHADE_SIMD_H

#include <prt/format/blob_layout.h>
#include <prt/prt_types.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* The parts of a WVLT section one shading call reads, and the prepared light. */
typedef struct prt_wavelet_rows {
  const uint8_t* vertex_scale; /* f32[V][3] */
  const uint8_t* row_start;    /* u32[V + 1] */
  const uint8_t* counts;       /* u16[V][blocks] */
  const uint8_t* pairs;        /* u8[pair_count][2] */
  const float* light;          /* prepared light: 4 floats per coefficient, 256 * blocks of them */
  const uint8_t* skip;         /* per block: non-zero to skip its pairs (never NULL) */
  uint32_t blocks;
  uint32_t pair_count;
} prt_wavelet_rows;

static inline float prt_wavelet_load_f32(const uint8_t* p) {
  uint32_t bits = prt_le_load_u32(p);
  float f;
  memcpy(&f, &bits, sizeof f);
  return f;
}

/* The most blocks a row has: 6 faces of 128^2 coefficients. */
#define PRT_WAVELET_MAX_BLOCKS (6u * 128u * 128u / PRT_BLOB_WVLT_BLOCK)

/* Row v's pair range [*start, *end); 0 when the row starts are not increasing within the
 * section's pairs (possible only in a blob loaded with quick validation). */
static inline int prt_wavelet_row_range(const prt_wavelet_rows* rows, uint32_t v, uint32_t* start,
                                        uint32_t* end) {
  *start = prt_le_load_u32(rows->row_start + 4u * (size_t)v);
  *end = prt_le_load_u32(rows->row_start + 4u * ((size_t)v + 1u));
  return *start <= *end && *end <= rows->pair_count;
}

/* Vertex v's scale, channel c. */
static inline float prt_wavelet_vertex_scale(const prt_wavelet_rows* rows, uint32_t v, uint32_t c) {
  return prt_wavelet_load_f32(rows->vertex_scale + 12u * (size_t)v + 4u * c);
}

/* Shades vertices [first, first+count) into out_rgb (3 floats each). PRT_OK, or
 * PRT_ERROR_CORRUPT at the first row with a block count above 256 or block counts that disagree
 * with its row starts (reads stay inside the section; out_rgb is then partly written). */
typedef prt_result (*prt_wavelet_kernel)(const prt_wavelet_rows* rows, uint32_t first,
                                         uint32_t count, float* out_rgb);

/* The rows repacked at load for the tiled kernel (wavelet_tiles.c), 8 vertices per tile. Per tile
 * and face, the coarse corner (Mallat levels -1..2: the 8 x 8 coefficients x, y < 8) dense as i8
 * with the tile's vertices in lanes, stored only for the faces where some vertex of the tile has
 * a non-zero there. The other ("fine") pairs by 32-coefficient unit: per tile and unit a mask of
 * the coefficients some vertex of the tile stores, and per such coefficient a record (which
 * lanes store it, where their values start) and the values of those lanes, in lane order. A
 * kernel then visits, per tile, only the coefficients both stored and lit, and expands each one's
 * values into the 8 lanes: its cost follows the non-zero light, not the pairs it shares a unit
 * with. Lanes past the last vertex hold zeros. */
#define PRT_WAVELET_TILE 8u
#define PRT_WAVELET_CORNER 8u /* coarse corner side: levels -1..2 */
#define PRT_WAVELET_CORNER_COEFFICIENTS (PRT_WAVELET_CORNER * PRT_WAVELET_CORNER)
#define PRT_WAVELET_MAX_FACES 6u
#define PRT_WAVELET_GROUP 64u /* the granularity tiles_pay weighs (wavelet_asset.c) */
#define PRT_WAVELET_GROUPS_PER_BLOCK (PRT_BLOB_WVLT_BLOCK / PRT_WAVELET_GROUP)
#define PRT_WAVELET_MAX_GROUPS (PRT_WAVELET_MAX_BLOCKS * PRT_WAVELET_GROUPS_PER_BLOCK)
/* A unit's values fill at most 32 x 8 = 256 bytes, so a record's offset fits a byte. */
#define PRT_WAVELET_UNIT 32u
#define PRT_WAVELET_UNITS_PER_BLOCK (PRT_BLOB_WVLT_BLOCK / PRT_WAVELET_UNIT)
#define PRT_WAVELET_MAX_UNITS (PRT_WAVELET_MAX_BLOCKS * PRT_WAVELET_UNITS_PER_BLOCK)

typedef struct prt_wavelet_tiles {
  uint32_t tiles, faces, size, units;
  const uint8_t* face_mask;    /* u8[tiles]: bit f when face f has a stored corner slab */
  const uint32_t* slab_start;  /* u32[tiles]: index of the tile's first slab */
  const int8_t* slabs;         /* i8[slabs][64 corner coefficients, y * 8 + x][8 lanes] */
  const float* scale;          /* f32[tiles][3 channels][8 lanes]: vs */
  const uint32_t* tile_first;  /* u32[tiles + 1][2]: first record, first value of each tile */
  const uint32_t* unit_stored; /* u32[tiles][units]: bit i when a lane stores coefficient i */
  const uint16_t* unit_first;  /* u16[tiles][units][2]: first record, first value, in the tile */
  const uint8_t* records;      /* u8[][2]: lane mask, offset of the values from the unit's */
  const int8_t* values;        /* i8[]: the stored lanes' values, 8 bytes of padding after */
  void* memory;                /* the one allocation holding the arrays */
  size_t bytes;
} prt_wavelet_tiles;

/* The light a tiled kernel reads in one call: the prepared light; the units whose fine light is
 * not all zero (not skipped by the caller's mask), each with the mask of its non-zero
 * coefficients; per face the corner's RGBA light (zero where the mask skips its block) and
 * whether any of it is non-zero. */
typedef struct prt_wavelet_tile_light {
  const float* light;
  uint32_t lit_units;  /* entries in unit and lit */
  uint32_t lit_groups; /* 64-coefficient groups with a lit unit: what tiles_pay weighs */
  uint16_t unit[PRT_WAVELET_MAX_UNITS];
  uint32_t lit[PRT_WAVELET_MAX_UNITS];
  float corner[PRT_WAVELET_MAX_FACES][PRT_WAVELET_CORNER_COEFFICIENTS][4];
  uint8_t face_lit[PRT_WAVELET_MAX_FACES];
} prt_wavelet_tile_light;

/* Shades vertices [first, first+count) of the tiles into out_rgb. Each vertex's sum is computed
 * in one order whatever the range (its tile is shaded whole, only the range written). */
typedef void (*prt_wavelet_tile_kernel)(const prt_wavelet_tiles* tiles,
                                        const prt_wavelet_tile_light* light, uint32_t first,
                                        uint32_t count, float* out_rgb);

#if defined(PRT_HAS_X86_SIMD)
void prt_wavelet_shade_tiles_avx2(const prt_wavelet_tiles* tiles,
                                  const prt_wavelet_tile_light* light, uint32_t first,
                                  uint32_t count, float* out_rgb);
prt_result prt_wavelet_shade_sse41(const prt_wavelet_rows* rows, uint32_t first, uint32_t count,
                                   float* out_rgb);
prt_result prt_wavelet_shade_avx2(const prt_wavelet_rows* rows, uint32_t first, uint32_t count,
                                  float* out_rgb);
#endif

#endif /* PRT_WAVELET_SHADE_SIMD_H */
