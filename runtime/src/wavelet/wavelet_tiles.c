/* SPDX-License-Identifier: MIT */
/* The WVLT rows repacked at load into 8-vertex tiles for the AVX2 kernel (prt_wavelet_tiles,
 * wavelet_shade_simd.h): the coarse corners dense, the rest by coefficient within 32-coefficient
 * units. The repack walks every row with the bounds checks shading makes; a row those checks
 * reject, one that stores a coefficient twice (possible only at quick validation: the repack
 * holds one value per coefficient and lane), or a tile too large for its 16-bit offsets leaves
 * the asset without tiles, so that shading keeps reading the blob rows and reports what they
 * always did. */
#include <string.h>

#include "internal.h"
#include "wavelet_internal.h"

/* Where pair (block k, index i) of a row falls: *face, and its corner index or -1 (a fine
 * pair). */
static int corner_of(const prt_wavelet_tiles* t, uint32_t shift, uint32_t k, uint32_t i,
                     uint32_t* face) {
  const uint32_t j = PRT_BLOB_WVLT_BLOCK * k + i;
  const uint32_t within = j & ((1u << (2u * shift)) - 1u);
  const uint32_t x = within & (t->size - 1u), y = within >> shift;
  *face = j >> (2u * shift);
  return x < PRT_WAVELET_CORNER && y < PRT_WAVELET_CORNER ? (int)(y * PRT_WAVELET_CORNER + x) : -1;
}

/* Whether block k holds corner coefficients: blocks are whole rows of a face (or a face), so
 * those that start above row 8. */
static int corner_block(uint32_t shift, uint32_t k) {
  const uint32_t within = (PRT_BLOB_WVLT_BLOCK * k) & ((1u << (2u * shift)) - 1u);
  return (within >> shift) < PRT_WAVELET_CORNER;
}

/* Checks row v as shading does (row range, every count <= 256 and within the row, counts use up
 * the row); 0 when it fails. */
static int row_ok(const prt_wavelet_rows* rows, uint32_t v) {
  const uint8_t* counts = rows->counts + 2u * (size_t)v * rows->blocks;
  uint32_t start, end, at, k;
  if (!prt_wavelet_row_range(rows, v, &start, &end)) return 0;
  for (at = start, k = 0; k < rows->blocks; ++k) {
    const uint32_t n = prt_le_load_u16(counts + 2u * k);
    if (n > PRT_BLOB_WVLT_BLOCK || n > end - at) return 0;
    at += n;
  }
  return at == end;
}

/* Bytes after the values: the kernel loads a record's values 8 bytes at a time. */
#define PRT_WAVELET_VALUES_PAD 8u

/* A tile's fine pairs of one block by coefficient: each lane's value and the lanes that store
 * it. */
typedef struct fine_block {
  int8_t q[PRT_BLOB_WVLT_BLOCK][PRT_WAVELET_TILE];
  uint8_t lanes[PRT_BLOB_WVLT_BLOCK];
} fine_block;

static uint32_t popcount8(uint32_t m) {
  uint32_t n = 0;
  for (; m; m &= m - 1u) ++n;
  return n;
}

/* Walks the fine pairs of tile `tile` (rows already checked) block by block: counts its records
 * and values into *records and *values, and when `write` is set stores them at those positions
 * (t's arrays allocated). 0 when a lane stores a fine coefficient twice or the tile outgrows the
 * 16-bit offsets. */
static int tile_fine(const prt_wavelet_rows* rows, uint32_t vertices, prt_wavelet_tiles* t,
                     uint32_t shift, uint32_t tile, int write, uint32_t* records, uint32_t* values,
                     fine_block* b) {
  const uint32_t first = tile * PRT_WAVELET_TILE, record0 = *records, value0 = *values;
  uint32_t at[PRT_WAVELET_TILE], lane, k, i, u, f;
  for (lane = 0; lane < PRT_WAVELET_TILE; ++lane)
    at[lane] = first + lane < vertices
                   ? prt_le_load_u32(rows->row_start + 4u * ((size_t)first + lane))
                   : 0;
  for (k = 0; k < rows->blocks; ++k) {
    memset(b->lanes, 0, sizeof b->lanes);
    for (lane = 0; lane < PRT_WAVELET_TILE && first + lane < vertices; ++lane) {
      const uint32_t v = first + lane;
      const uint32_t n = prt_le_load_u16(rows->counts + 2u * ((size_t)v * rows->blocks + k));
      const uint8_t* pair = rows->pairs + 2u * (size_t)at[lane];
      for (i = 0; i < n; ++i, pair += 2) {
        if (corner_of(t, shift, k, pair[0], &f) >= 0) continue;
        if (b->lanes[pair[0]] & (1u << lane)) return 0;
        b->lanes[pair[0]] |= (uint8_t)(1u << lane);
        b->q[pair[0]][lane] = (int8_t)pair[1];
      }
      at[lane] += n;
    }
    for (u = 0; u < PRT_WAVELET_UNITS_PER_BLOCK; ++u) {
      const size_t unit = (size_t)tile * t->units + PRT_WAVELET_UNITS_PER_BLOCK * k + u;
      const uint32_t unit_value = *values;
      uint32_t stored = 0;
      if (*records - record0 > UINT16_MAX || *values - value0 > UINT16_MAX) return 0;
      if (write) {
        uint16_t* unit_first = (uint16_t*)(uintptr_t)t->unit_first;
        unit_first[2u * unit] = (uint16_t)(*records - record0);
        unit_first[2u * unit + 1u] = (uint16_t)(*values - value0);
      }
      for (i = 0; i < PRT_WAVELET_UNIT; ++i) {
        const uint32_t c = PRT_WAVELET_UNIT * u + i, lanes = b->lanes[c];
        if (!lanes) continue;
        stored |= 1u << i;
        if (write) {
          uint8_t* record = (uint8_t*)(uintptr_t)t->records + 2u * (size_t)*records;
          int8_t* value = (int8_t*)(uintptr_t)t->values + *values;
          record[0] = (uint8_t)lanes;
          record[1] = (uint8_t)(*values - unit_value); /* < 256: a unit holds 32 x 8 values */
          for (lane = 0; lane < PRT_WAVELET_TILE; ++lane)
            if (lanes & (1u << lane)) *value++ = b->q[c][lane];
        }
        *records += 1u;
        *values += popcount8(lanes);
      }
      if (write) ((uint32_t*)(uintptr_t)t->unit_stored)[unit] = stored;
    }
  }
  return 1;
}

static size_t round_up(size_t n) {
  return (n + 31u) & ~(size_t)31u;
}

void prt_wavelet_release_tiles(const prt_allocator* allocator, void* view_memory) {
  prt_wavelet_view* view = (prt_wavelet_view*)view_memory;
  if (!view->tiles) return;
  prt_internal_free(allocator, view->tiles->memory, view->tiles->bytes);
  prt_internal_free(allocator, view->tiles, sizeof *view->tiles);
  view->tiles = NULL;
}

/* Fills the tile arrays from valid rows; 0 when a row stores a coefficient twice. */
static int fill_tiles(const prt_wavelet_rows* rows, uint32_t vertices, prt_wavelet_tiles* t,
                      uint32_t shift, fine_block* b) {
  uint8_t* mask = (uint8_t*)(uintptr_t)t->face_mask;
  uint32_t* slab_start = (uint32_t*)(uintptr_t)t->slab_start;
  int8_t* slabs = (int8_t*)(uintptr_t)t->slabs;
  float* scale = (float*)(uintptr_t)t->scale;
  uint32_t* tile_first = (uint32_t*)(uintptr_t)t->tile_first;
  uint32_t tile, slab = 0, records = 0, values = 0;
  for (tile = 0; tile < t->tiles; ++tile) {
    const uint32_t first = tile * PRT_WAVELET_TILE;
    uint32_t slab_of[PRT_WAVELET_MAX_FACES];
    uint32_t lane, k, f, c, i;
    uint8_t faces = 0;
    /* The tile's faces with a corner pair first, so its slabs can be placed. */
    for (lane = 0; lane < PRT_WAVELET_TILE && first + lane < vertices; ++lane) {
      const uint32_t v = first + lane;
      const uint8_t* counts = rows->counts + 2u * (size_t)v * rows->blocks;
      uint32_t p = prt_le_load_u32(rows->row_start + 4u * (size_t)v);
      for (k = 0; k < rows->blocks; ++k) {
        const uint32_t n = prt_le_load_u16(counts + 2u * k);
        if (corner_block(shift, k))
          for (i = 0; i < n; ++i)
            if (corner_of(t, shift, k, rows->pairs[2u * ((size_t)p + i)], &f) >= 0)
              faces |= (uint8_t)(1u << f);
        p += n;
      }
    }
    mask[tile] = faces;
    slab_start[tile] = slab;
    for (f = 0; f < t->faces; ++f)
      if (faces & (1u << f)) slab_of[f] = slab++;
    memset(slabs + (size_t)PRT_WAVELET_CORNER_COEFFICIENTS * PRT_WAVELET_TILE * slab_start[tile], 0,
           (size_t)PRT_WAVELET_CORNER_COEFFICIENTS * PRT_WAVELET_TILE * (slab - slab_start[tile]));
    for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) {
      const uint32_t v = first + lane;
      for (c = 0; c < 3; ++c)
        scale[(3u * (size_t)tile + c) * PRT_WAVELET_TILE + lane] =
            v < vertices ? prt_wavelet_vertex_scale(rows, v, c) : 0.0f;
    }
    /* The corner pairs into the slabs. */
    for (lane = 0; lane < PRT_WAVELET_TILE && first + lane < vertices; ++lane) {
      const uint32_t v = first + lane;
      const uint8_t* counts = rows->counts + 2u * (size_t)v * rows->blocks;
      uint32_t p = prt_le_load_u32(rows->row_start + 4u * (size_t)v);
      for (k = 0; k < rows->blocks; ++k) {
        const uint32_t n = prt_le_load_u16(counts + 2u * k);
        if (corner_block(shift, k))
          for (i = 0; i < n; ++i) {
            const uint8_t* pair = rows->pairs + 2u * ((size_t)p + i);
            const int corner = corner_of(t, shift, k, pair[0], &f);
            int8_t* q;
            if (corner < 0) continue;
            q = slabs +
                ((size_t)slab_of[f] * PRT_WAVELET_CORNER_COEFFICIENTS + (uint32_t)corner) *
                    PRT_WAVELET_TILE +
                lane;
            if (*q != 0) return 0; /* stored twice: the dense form holds one value */
            *q = (int8_t)pair[1];
          }
        p += n;
      }
    }
    tile_first[2u * tile] = records;
    tile_first[2u * tile + 1u] = values;
    if (!tile_fine(rows, vertices, t, shift, tile, 1, &records, &values, b)) return 0;
  }
  tile_first[2u * t->tiles] = records;
  tile_first[2u * t->tiles + 1u] = values;
  return 1;
}

prt_result prt_wavelet_attach_tiles(const prt_context* context, const prt_allocator* allocator,
                                    const prt_asset_section* sections, uint32_t section_count,
                                    void* view_memory, char* msg, size_t capacity) {
  prt_wavelet_view* view = (prt_wavelet_view*)view_memory;
  const prt_wavelet_rows* rows = &view->rows;
  const uint32_t vertices = view->info.vertex_count;
  prt_wavelet_tiles header, *t;
  size_t off_mask, off_slab_start, off_scale, off_tile_first, off_unit_stored, off_unit_first,
      off_slabs, off_records, off_values;
  uint32_t shift = 0, tile, slabs = 0, records = 0, values = 0;
  fine_block* block;
  uint8_t* memory;
  int made;
  (void)sections, (void)section_count, (void)msg, (void)capacity; /* needs only its own view */
  if (prt_internal_simd_isa(context) < PRT_SIMD_ISA_AVX2 || vertices == 0) return PRT_OK;
  memset(&header, 0, sizeof header);
  header.tiles = (vertices + PRT_WAVELET_TILE - 1u) / PRT_WAVELET_TILE;
  header.faces = view->info.faces;
  header.size = view->info.size;
  header.units = rows->blocks * PRT_WAVELET_UNITS_PER_BLOCK;
  while ((1u << shift) < header.size) ++shift;
  if (header.faces > PRT_WAVELET_MAX_FACES) return PRT_OK;
  block = (fine_block*)prt_internal_alloc(allocator, sizeof *block, 16);
  if (!block) return PRT_ERROR_OUT_OF_MEMORY;
  /* Sizes: every row checked, the slabs, records and values counted. */
  for (tile = 0; tile < header.tiles; ++tile) {
    uint32_t lane, faces = 0, f;
    for (lane = 0; lane < PRT_WAVELET_TILE && tile * PRT_WAVELET_TILE + lane < vertices; ++lane) {
      const uint32_t v = tile * PRT_WAVELET_TILE + lane;
      const uint8_t* counts = rows->counts + 2u * (size_t)v * rows->blocks;
      uint32_t p, k, i;
      if (!row_ok(rows, v)) break; /* the rows shade, and report it */
      p = prt_le_load_u32(rows->row_start + 4u * (size_t)v);
      for (k = 0; k < rows->blocks; ++k) {
        const uint32_t n = prt_le_load_u16(counts + 2u * k);
        if (corner_block(shift, k))
          for (i = 0; i < n; ++i)
            if (corner_of(&header, shift, k, rows->pairs[2u * ((size_t)p + i)], &f) >= 0)
              faces |= 1u << f;
        p += n;
      }
    }
    if (lane < PRT_WAVELET_TILE && tile * PRT_WAVELET_TILE + lane < vertices) break;
    if (!tile_fine(rows, vertices, &header, shift, tile, 0, &records, &values, block)) break;
    for (f = 0; f < header.faces; ++f) slabs += (faces >> f) & 1u;
  }
  if (tile < header.tiles) {
    prt_internal_free(allocator, block, sizeof *block);
    return PRT_OK;
  }
  off_mask = 0;
  off_slab_start = round_up(off_mask + header.tiles);
  off_scale = round_up(off_slab_start + 4u * (size_t)header.tiles);
  off_tile_first = round_up(off_scale + 4u * 3u * PRT_WAVELET_TILE * (size_t)header.tiles);
  off_unit_stored = round_up(off_tile_first + 8u * ((size_t)header.tiles + 1u));
  off_unit_first = round_up(off_unit_stored + 4u * (size_t)header.tiles * header.units);
  off_slabs = round_up(off_unit_first + 4u * (size_t)header.tiles * header.units);
  off_records =
      round_up(off_slabs + (size_t)PRT_WAVELET_CORNER_COEFFICIENTS * PRT_WAVELET_TILE * slabs);
  off_values = round_up(off_records + 2u * (size_t)records);
  header.bytes = round_up(off_values + (size_t)values + PRT_WAVELET_VALUES_PAD);
  t = (prt_wavelet_tiles*)prt_internal_alloc(allocator, sizeof *t, 16);
  memory = t ? (uint8_t*)prt_internal_alloc(allocator, header.bytes, 32) : NULL;
  if (!memory) {
    if (t) prt_internal_free(allocator, t, sizeof *t);
    prt_internal_free(allocator, block, sizeof *block);
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  *t = header;
  memset(memory + off_values + values, 0, header.bytes - off_values - values);
  t->memory = memory;
  t->face_mask = memory + off_mask;
  t->slab_start = (const uint32_t*)(const void*)(memory + off_slab_start);
  t->scale = (const float*)(const void*)(memory + off_scale);
  t->tile_first = (const uint32_t*)(const void*)(memory + off_tile_first);
  t->unit_stored = (const uint32_t*)(const void*)(memory + off_unit_stored);
  t->unit_first = (const uint16_t*)(const void*)(memory + off_unit_first);
  t->slabs = (const int8_t*)(const void*)(memory + off_slabs);
  t->records = memory + off_records;
  t->values = (const int8_t*)(const void*)(memory + off_values);
  view->tiles = t;
  made = fill_tiles(rows, vertices, t, shift, block);
  prt_internal_free(allocator, block, sizeof *block);
  if (!made) prt_wavelet_release_tiles(allocator, view);
  return PRT_OK;
}

/* 1 when f is neither infinite nor NaN. */
static int finite_f32(float f) {
  return f - f == 0.0f;
}

int prt_wavelet_tile_light_make(const prt_wavelet_tiles* tiles, const float* light,
                                const uint8_t* skip, prt_wavelet_tile_light* out) {
  const uint32_t face_size = tiles->size * tiles->size;
  uint32_t f, c, ch, u, last_group = UINT32_MAX;
  out->light = light;
  out->lit_units = 0;
  out->lit_groups = 0;
  memset(out->corner, 0, sizeof out->corner);
  memset(out->face_lit, 0, sizeof out->face_lit);
  for (f = 0; f < tiles->faces; ++f)
    for (c = 0; c < PRT_WAVELET_CORNER_COEFFICIENTS; ++c) {
      const size_t j =
          ((size_t)f * tiles->size + c / PRT_WAVELET_CORNER) * tiles->size + c % PRT_WAVELET_CORNER;
      if (skip[j / PRT_BLOB_WVLT_BLOCK]) continue;
      for (ch = 0; ch < 3; ++ch) {
        const float value = light[4u * j + ch];
        /* A dense corner multiplies its light by the zeros of absent pairs too: only finite
         * light keeps those products exactly 0. */
        if (!finite_f32(value)) return 0;
        out->corner[f][c][ch] = value;
        out->face_lit[f] |= value != 0.0f;
      }
    }
  for (u = 0; u < tiles->units; ++u) {
    const uint32_t first = u * PRT_WAVELET_UNIT;
    uint32_t i, lit = 0;
    if (skip[u / PRT_WAVELET_UNITS_PER_BLOCK]) continue;
    for (i = 0; i < PRT_WAVELET_UNIT; ++i) {
      const uint32_t j = first + i, within = j % face_size;
      const float* l = light + 4u * (size_t)j;
      if (within / tiles->size < PRT_WAVELET_CORNER && within % tiles->size < PRT_WAVELET_CORNER)
        continue; /* the dense part's */
      if (l[0] == 0.0f && l[1] == 0.0f && l[2] == 0.0f) continue;
      /* The lanes that do not store a lit coefficient multiply its light by 0 too: as for the
       * corners, only finite light keeps those products exactly 0. */
      if (!finite_f32(l[0]) || !finite_f32(l[1]) || !finite_f32(l[2])) return 0;
      lit |= 1u << i;
    }
    if (!lit) continue;
    out->unit[out->lit_units] = (uint16_t)u;
    out->lit[out->lit_units++] = lit;
    if (u / (PRT_WAVELET_GROUP / PRT_WAVELET_UNIT) != last_group) ++out->lit_groups;
    last_group = u / (PRT_WAVELET_GROUP / PRT_WAVELET_UNIT);
  }
  return 1;
}
