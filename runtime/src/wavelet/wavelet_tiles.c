/* SPDX-License-Identifier: MIT */
/* The WVLT rows repacked at load into 8-vertex tiles for the AVX2 kernel (prt_wavelet_tiles,
 * wavelet_shade_simd.h): the coarse corners dense, the rest sparse in group-major order. The
 * repack walks every row with the bounds checks shading makes; a row those checks reject, or one
 * that stores a corner coefficient twice (possible only at quick validation), leaves the asset
 * without tiles, so that shading keeps reading the blob rows and reports what they always did. */
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

/* Bytes after the fine pairs: the kernel copies runs 32 bytes at a time. */
#define PRT_WAVELET_FINE_PAD 32u

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

/* Fills the tile arrays from valid rows; 0 when a row stores a corner coefficient twice. */
static int fill_tiles(const prt_wavelet_rows* rows, uint32_t vertices, prt_wavelet_tiles* t,
                      uint32_t shift) {
  uint8_t* mask = (uint8_t*)(uintptr_t)t->face_mask;
  uint32_t* slab_start = (uint32_t*)(uintptr_t)t->slab_start;
  int8_t* slabs = (int8_t*)(uintptr_t)t->slabs;
  float* scale = (float*)(uintptr_t)t->scale;
  uint32_t* fine_start = (uint32_t*)(uintptr_t)t->fine_start;
  uint8_t* fine_count = (uint8_t*)(uintptr_t)t->fine_count;
  uint8_t* fine_pairs = (uint8_t*)(uintptr_t)t->fine_pairs;
  uint32_t tile, slab = 0, fine = 0;
  for (tile = 0; tile < t->tiles; ++tile) {
    const uint32_t first = tile * PRT_WAVELET_TILE;
    uint32_t at[PRT_WAVELET_TILE], slab_of[PRT_WAVELET_MAX_FACES];
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
      at[lane] = v < vertices ? prt_le_load_u32(rows->row_start + 4u * (size_t)v) : 0;
      for (c = 0; c < 3; ++c)
        scale[(3u * (size_t)tile + c) * PRT_WAVELET_TILE + lane] =
            v < vertices ? prt_wavelet_vertex_scale(rows, v, c) : 0.0f;
    }
    fine_start[tile] = fine;
    /* Block by block: each lane's fine pairs counted by group, then placed group after group,
     * lane after lane within a group (stored order within a lane). */
    for (k = 0; k < rows->blocks; ++k) {
      uint8_t* count = fine_count + ((size_t)tile * t->groups + PRT_WAVELET_GROUPS_PER_BLOCK * k) *
                                        PRT_WAVELET_TILE;
      uint32_t n[PRT_WAVELET_TILE], place[PRT_WAVELET_GROUPS_PER_BLOCK][PRT_WAVELET_TILE];
      uint32_t g, next = fine;
      memset(count, 0, PRT_WAVELET_GROUPS_PER_BLOCK * PRT_WAVELET_TILE);
      for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) {
        const uint32_t v = first + lane;
        const uint8_t* pair = rows->pairs + 2u * (size_t)at[lane];
        n[lane] =
            v < vertices ? prt_le_load_u16(rows->counts + 2u * ((size_t)v * rows->blocks + k)) : 0;
        for (i = 0; i < n[lane]; ++i, pair += 2) {
          uint8_t* c = count + (pair[0] / PRT_WAVELET_GROUP) * PRT_WAVELET_TILE + lane;
          if (corner_of(t, shift, k, pair[0], &f) >= 0) continue;
          if (*c == UINT8_MAX) return 0; /* only repeated indices get here */
          ++*c;
        }
      }
      for (g = 0; g < PRT_WAVELET_GROUPS_PER_BLOCK; ++g)
        for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) {
          place[g][lane] = next;
          next += count[g * PRT_WAVELET_TILE + lane];
        }
      for (lane = 0; lane < PRT_WAVELET_TILE; ++lane) {
        const uint8_t* pair = rows->pairs + 2u * (size_t)at[lane];
        for (i = 0; i < n[lane]; ++i, pair += 2) {
          const int corner = corner_of(t, shift, k, pair[0], &f);
          if (corner >= 0) {
            int8_t* q = slabs +
                        ((size_t)slab_of[f] * PRT_WAVELET_CORNER_COEFFICIENTS + (uint32_t)corner) *
                            PRT_WAVELET_TILE +
                        lane;
            if (*q != 0) return 0; /* stored twice: the dense form holds one value */
            *q = (int8_t)pair[1];
          } else {
            uint32_t* to = &place[pair[0] / PRT_WAVELET_GROUP][lane];
            fine_pairs[2u * (size_t)*to] = (uint8_t)(pair[0] % PRT_WAVELET_GROUP);
            fine_pairs[2u * (size_t)*to + 1u] = pair[1];
            ++*to;
          }
        }
        at[lane] += n[lane];
      }
      fine = next;
    }
  }
  fine_start[t->tiles] = fine;
  return 1;
}

prt_result prt_wavelet_attach_tiles(const prt_context* context, const prt_allocator* allocator,
                                    void* view_memory) {
  prt_wavelet_view* view = (prt_wavelet_view*)view_memory;
  const prt_wavelet_rows* rows = &view->rows;
  const uint32_t vertices = view->info.vertex_count;
  prt_wavelet_tiles header, *t;
  size_t off_mask, off_slab_start, off_scale, off_fine_start, off_fine_count, off_slabs,
      off_fine_pairs;
  uint32_t shift = 0, tile, slabs = 0, fine = 0;
  uint8_t* memory;
  if (prt_internal_simd_isa(context) < PRT_SIMD_ISA_AVX2 || vertices == 0) return PRT_OK;
  memset(&header, 0, sizeof header);
  header.tiles = (vertices + PRT_WAVELET_TILE - 1u) / PRT_WAVELET_TILE;
  header.faces = view->info.faces;
  header.size = view->info.size;
  header.groups = rows->blocks * PRT_WAVELET_GROUPS_PER_BLOCK;
  while ((1u << shift) < header.size) ++shift;
  if (header.faces > PRT_WAVELET_MAX_FACES) return PRT_OK;
  /* Sizes: every row checked, the slabs and fine pairs counted. */
  for (tile = 0; tile < header.tiles; ++tile) {
    uint32_t lane, faces = 0, f;
    for (lane = 0; lane < PRT_WAVELET_TILE && tile * PRT_WAVELET_TILE + lane < vertices; ++lane) {
      const uint32_t v = tile * PRT_WAVELET_TILE + lane;
      const uint8_t* counts = rows->counts + 2u * (size_t)v * rows->blocks;
      uint32_t p, k, i;
      if (!row_ok(rows, v)) return PRT_OK; /* the rows shade, and report it */
      p = prt_le_load_u32(rows->row_start + 4u * (size_t)v);
      for (k = 0; k < rows->blocks; ++k) {
        const uint32_t n = prt_le_load_u16(counts + 2u * k);
        fine += n;
        if (corner_block(shift, k))
          for (i = 0; i < n; ++i)
            if (corner_of(&header, shift, k, rows->pairs[2u * ((size_t)p + i)], &f) >= 0) {
              faces |= 1u << f;
              --fine;
            }
        p += n;
      }
    }
    for (f = 0; f < header.faces; ++f) slabs += (faces >> f) & 1u;
  }
  off_mask = 0;
  off_slab_start = round_up(off_mask + header.tiles);
  off_scale = round_up(off_slab_start + 4u * (size_t)header.tiles);
  off_fine_start = round_up(off_scale + 4u * 3u * PRT_WAVELET_TILE * (size_t)header.tiles);
  off_fine_count = round_up(off_fine_start + 4u * ((size_t)header.tiles + 1u));
  off_slabs = round_up(off_fine_count + PRT_WAVELET_TILE * (size_t)header.tiles * header.groups);
  off_fine_pairs =
      round_up(off_slabs + (size_t)PRT_WAVELET_CORNER_COEFFICIENTS * PRT_WAVELET_TILE * slabs);
  header.bytes = round_up(off_fine_pairs + 2u * (size_t)fine + PRT_WAVELET_FINE_PAD);
  t = (prt_wavelet_tiles*)prt_internal_alloc(allocator, sizeof *t, 16);
  memory = t ? (uint8_t*)prt_internal_alloc(allocator, header.bytes, 32) : NULL;
  if (!memory) {
    if (t) prt_internal_free(allocator, t, sizeof *t);
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  *t = header;
  memset(memory + off_fine_pairs + 2u * (size_t)fine, 0,
         header.bytes - off_fine_pairs - 2u * (size_t)fine);
  t->memory = memory;
  t->face_mask = memory + off_mask;
  t->slab_start = (const uint32_t*)(const void*)(memory + off_slab_start);
  t->scale = (const float*)(const void*)(memory + off_scale);
  t->fine_start = (const uint32_t*)(const void*)(memory + off_fine_start);
  t->fine_count = memory + off_fine_count;
  t->slabs = (const int8_t*)(const void*)(memory + off_slabs);
  t->fine_pairs = memory + off_fine_pairs;
  view->tiles = t;
  if (!fill_tiles(rows, vertices, t, shift)) prt_wavelet_release_tiles(allocator, view);
  return PRT_OK;
}

/* 1 when f is neither infinite nor NaN. */
static int finite_f32(float f) {
  return f - f == 0.0f;
}

int prt_wavelet_tile_light_make(const prt_wavelet_tiles* tiles, const float* light,
                                const uint8_t* skip, prt_wavelet_tile_light* out) {
  const uint32_t face_size = tiles->size * tiles->size;
  uint32_t f, c, ch, g;
  out->light = light;
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
  for (g = 0; g < tiles->groups; ++g) {
    const uint32_t first = g * PRT_WAVELET_GROUP;
    uint32_t j;
    int lit = 0;
    if (!skip[g / PRT_WAVELET_GROUPS_PER_BLOCK])
      for (j = first; j < first + PRT_WAVELET_GROUP && !lit; ++j) {
        const uint32_t within = j % face_size;
        if (within / tiles->size < PRT_WAVELET_CORNER && within % tiles->size < PRT_WAVELET_CORNER)
          continue; /* the dense part's */
        /* NaN counts as lit: the pairs that meet it must reach the sum. */
        lit = light[4u * (size_t)j] != 0.0f || light[4u * (size_t)j + 1u] != 0.0f ||
              light[4u * (size_t)j + 2u] != 0.0f;
      }
    out->group_lit[g] = (uint8_t)lit;
    out->lit_groups += (uint32_t)lit;
  }
  return 1;
}
