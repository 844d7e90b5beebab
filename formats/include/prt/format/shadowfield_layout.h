/* SPDX-License-Identifier: MIT */
/* The `shadowfield` section SFLD, layout version 1 (formats/SPEC.md §7.5): one rigid object baked
 * alone (docs/shadowfield/design.md), its material, self-shadowed transfer, object occlusion
 * field, surface-radiance basis and source radiance fields. Element = object (one per blob); the
 * section counts the object domain. A 128-byte header, then eight blocks in a fixed order, the
 * big ones quantised with an (offset, scale) pair per row; the size follows from the header
 * (prt_blob_sfld_layout_of). Plain C99; the header check is in the formats library. */
#ifndef PRT_FORMAT_SHADOWFIELD_LAYOUT_H
#define PRT_FORMAT_SHADOWFIELD_LAYOUT_H

#include <stddef.h>

#include <prt/format/blob_layout.h>
#include <prt/format/blob_reader.h>
#include <prt/format/shadowfield_shells.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRT_BLOB_TAG_SFLD PRT_BLOB_TAG('S', 'F', 'L', 'D')

#define PRT_BLOB_SFLD_HEADER_SIZE 128u
#define PRT_BLOB_SFLD_MIN_ORDER 2u
#define PRT_BLOB_SFLD_MAX_ORDER 6u
#define PRT_BLOB_SFLD_MAX_TERMS 8u     /* K, BRDF terms */
#define PRT_BLOB_SFLD_MAX_BASIS 64u    /* N, surface-radiance basis functions */
#define PRT_BLOB_SFLD_MIN_BRDF_GRID 4u /* G of a glossy surface's g table */
#define PRT_BLOB_SFLD_MAX_BRDF_GRID 64u
#define PRT_BLOB_SFLD_MAX_SHELLS 64u    /* S of either grid */
#define PRT_BLOB_SFLD_MAX_FACE_SIZE 64u /* F of either grid */
#define PRT_BLOB_SFLD_PARAM_SIZE 8u     /* f32 offset, f32 scale per row */

/* Header, 128 bytes. */
#define PRT_BLOB_SFLD_OFF_ORDER 0u       /* u32: SH order n, 2..6 */
#define PRT_BLOB_SFLD_OFF_TERMS 4u       /* u32: BRDF terms K, 1..8; 1 when diffuse */
#define PRT_BLOB_SFLD_OFF_GLOSSY 8u      /* u32: 1 glossy (g table stored), 0 diffuse */
#define PRT_BLOB_SFLD_OFF_VERTICES 12u   /* u32: V >= 1, = VPOS element count */
#define PRT_BLOB_SFLD_OFF_BASIS 16u      /* u32: N, 1..64 and <= V */
#define PRT_BLOB_SFLD_OFF_BRDF_GRID 20u  /* u32: G, 4..64 when glossy, 0 when diffuse */
#define PRT_BLOB_SFLD_OFF_BITS 24u       /* u32: bits per quantised value, 8 or 16 */
#define PRT_BLOB_SFLD_OFF_FLAGS 28u      /* u32: 0 (layout 1 defines none) */
#define PRT_BLOB_SFLD_OFF_OOF_SHELLS 32u /* shell grid of the OOF, 32 bytes */
#define PRT_BLOB_SFLD_OFF_SRF_SHELLS 64u /* shell grid of the SRFs, 32 bytes */
#define PRT_BLOB_SFLD_OFF_RESERVED 96u   /* u32[8], zero */
#define PRT_BLOB_SFLD_RESERVED_SIZE 32u

/* A shell grid, 32 bytes, at one of the two offsets above. */
#define PRT_BLOB_SFLD_SHELLS_SIZE 32u
#define PRT_BLOB_SFLD_SHELL_OFF_CENTRE 0u     /* f32[3], finite */
#define PRT_BLOB_SFLD_SHELL_OFF_RADIUS 12u    /* f32, finite, > 0 */
#define PRT_BLOB_SFLD_SHELL_OFF_INNER 16u     /* f32, finite, > 0 */
#define PRT_BLOB_SFLD_SHELL_OFF_OUTER 20u     /* f32, finite; = inner when S = 1, else > inner */
#define PRT_BLOB_SFLD_SHELL_OFF_SHELLS 24u    /* u32: S, 1..64 */
#define PRT_BLOB_SFLD_SHELL_OFF_FACE_SIZE 28u /* u32: F, 1..64 */

/* The header fields, as stored. */
typedef struct prt_blob_sfld_header {
  uint32_t order;
  uint32_t terms;
  uint32_t glossy;
  uint32_t vertices;
  uint32_t basis_size;
  uint32_t brdf_grid;
  uint32_t bits;
  uint32_t flags;
  prt_sf_shells oof_shells;
  prt_sf_shells srf_shells;
} prt_blob_sfld_header;

static inline float prt_blob_sfld_load_f32(const uint8_t* p) {
  union {
    uint32_t u;
    float f;
  } v;
  v.u = prt_le_load_u32(p);
  return v.f;
}

static inline void prt_blob_sfld_read_shells(const uint8_t* p, prt_sf_shells* out) {
  int i;
  for (i = 0; i < 3; ++i) out->centre[i] = prt_blob_sfld_load_f32(p + 4 * i);
  out->radius = prt_blob_sfld_load_f32(p + PRT_BLOB_SFLD_SHELL_OFF_RADIUS);
  out->inner = prt_blob_sfld_load_f32(p + PRT_BLOB_SFLD_SHELL_OFF_INNER);
  out->outer = prt_blob_sfld_load_f32(p + PRT_BLOB_SFLD_SHELL_OFF_OUTER);
  out->shells = prt_le_load_u32(p + PRT_BLOB_SFLD_SHELL_OFF_SHELLS);
  out->face_size = prt_le_load_u32(p + PRT_BLOB_SFLD_SHELL_OFF_FACE_SIZE);
}

/* Reads the header from the section's first PRT_BLOB_SFLD_HEADER_SIZE bytes (the caller checks
 * that they are there). The reserved words are not part of it. */
static inline void prt_blob_sfld_read_header(const uint8_t* p, prt_blob_sfld_header* out) {
  out->order = prt_le_load_u32(p + PRT_BLOB_SFLD_OFF_ORDER);
  out->terms = prt_le_load_u32(p + PRT_BLOB_SFLD_OFF_TERMS);
  out->glossy = prt_le_load_u32(p + PRT_BLOB_SFLD_OFF_GLOSSY);
  out->vertices = prt_le_load_u32(p + PRT_BLOB_SFLD_OFF_VERTICES);
  out->basis_size = prt_le_load_u32(p + PRT_BLOB_SFLD_OFF_BASIS);
  out->brdf_grid = prt_le_load_u32(p + PRT_BLOB_SFLD_OFF_BRDF_GRID);
  out->bits = prt_le_load_u32(p + PRT_BLOB_SFLD_OFF_BITS);
  out->flags = prt_le_load_u32(p + PRT_BLOB_SFLD_OFF_FLAGS);
  prt_blob_sfld_read_shells(p + PRT_BLOB_SFLD_OFF_OOF_SHELLS, &out->oof_shells);
  prt_blob_sfld_read_shells(p + PRT_BLOB_SFLD_OFF_SRF_SHELLS, &out->srf_shells);
}

/* One quantised block: `rows` (offset, scale) f32 pairs at `params`, then `count` u8 or u16
 * values at `values`, then zero padding from `payload_end` to `end` (a multiple of 4). */
typedef struct prt_blob_sfld_block {
  uint64_t params;
  uint64_t rows;
  uint64_t values;
  uint64_t count;
  uint64_t payload_end;
  uint64_t end;
} prt_blob_sfld_block;

/* Where the parts of an SFLD section lie, from its header; offsets in bytes from the section's
 * first byte, each a multiple of 4. */
typedef struct prt_blob_sfld_layout {
  uint32_t coefficients;        /* n^2 */
  uint32_t value_size;          /* bits / 8 */
  uint32_t vertices;            /* V */
  uint32_t terms;               /* K */
  uint32_t basis_size;          /* N */
  uint32_t g_values;            /* K G^2 when glossy, else 0 */
  uint64_t oof_points;          /* S 6 F^2 of the OOF grid */
  uint64_t srf_points;          /* of the SRF grid */
  uint64_t albedo;              /* f32[V][3] */
  uint64_t g_table;             /* f32[K][G^2], glossy only (no bytes when diffuse) */
  prt_blob_sfld_block transfer; /* rows K n^2; values [V][K][n^2] */
  prt_blob_sfld_block oof;      /* rows n^2; values [P_oof][n^2] */
  prt_blob_sfld_block basis;    /* rows N; values [N][V] */
  uint64_t vertex_weights;      /* f32[V] */
  uint64_t basis_inverse;       /* f32[N][N], row-major */
  prt_blob_sfld_block srf;      /* rows N K n^2; values [N][K][P_srf][n^2] */
  uint64_t raw_size;            /* srf.end */
} prt_blob_sfld_layout;

static inline uint64_t prt_blob_sfld_block_at(uint64_t at, uint64_t rows, uint64_t count,
                                              uint32_t value_size, prt_blob_sfld_block* out) {
  out->params = at;
  out->rows = rows;
  out->values = at + PRT_BLOB_SFLD_PARAM_SIZE * rows;
  out->count = count;
  out->payload_end = out->values + count * value_size;
  out->end = (out->payload_end + 3u) & ~(uint64_t)3u;
  return out->end;
}

/* Fills *out from header fields within the limits above (the shell counts and face sizes at
 * most 64, V < 2^32) and returns 1; returns 0 (out untouched) for an order, term count, basis
 * size, grid size or bit count out of range. Within the limits every size stays below 2^46, so
 * no product overflows 64 bits. */
static inline int prt_blob_sfld_layout_of(const prt_blob_sfld_header* h,
                                          prt_blob_sfld_layout* out) {
  prt_blob_sfld_layout l;
  uint64_t n2, v, k, g, at;
  if (h->order < PRT_BLOB_SFLD_MIN_ORDER || h->order > PRT_BLOB_SFLD_MAX_ORDER) return 0;
  if (h->terms < 1u || h->terms > PRT_BLOB_SFLD_MAX_TERMS) return 0;
  if (h->basis_size < 1u || h->basis_size > PRT_BLOB_SFLD_MAX_BASIS) return 0;
  if (h->brdf_grid > PRT_BLOB_SFLD_MAX_BRDF_GRID) return 0;
  if (h->bits != 8u && h->bits != 16u) return 0;
  if (h->oof_shells.shells > PRT_BLOB_SFLD_MAX_SHELLS ||
      h->oof_shells.face_size > PRT_BLOB_SFLD_MAX_FACE_SIZE ||
      h->srf_shells.shells > PRT_BLOB_SFLD_MAX_SHELLS ||
      h->srf_shells.face_size > PRT_BLOB_SFLD_MAX_FACE_SIZE)
    return 0;
  n2 = (uint64_t)h->order * h->order;
  v = h->vertices;
  k = h->terms;
  g = h->glossy ? (uint64_t)h->brdf_grid * h->brdf_grid : 0u;
  l.coefficients = (uint32_t)n2;
  l.value_size = h->bits / 8u;
  l.vertices = h->vertices;
  l.terms = h->terms;
  l.basis_size = h->basis_size;
  l.g_values = (uint32_t)(k * g);
  l.oof_points = prt_sf_point_count(&h->oof_shells);
  l.srf_points = prt_sf_point_count(&h->srf_shells);
  l.albedo = PRT_BLOB_SFLD_HEADER_SIZE;
  l.g_table = l.albedo + 12u * v;
  at = l.g_table + 4u * k * g;
  at = prt_blob_sfld_block_at(at, k * n2, v * k * n2, l.value_size, &l.transfer);
  at = prt_blob_sfld_block_at(at, n2, l.oof_points * n2, l.value_size, &l.oof);
  at = prt_blob_sfld_block_at(at, h->basis_size, (uint64_t)h->basis_size * v, l.value_size,
                              &l.basis);
  l.vertex_weights = at;
  l.basis_inverse = l.vertex_weights + 4u * v;
  at = l.basis_inverse + 4u * (uint64_t)h->basis_size * h->basis_size;
  at = prt_blob_sfld_block_at(at, h->basis_size * k * n2, h->basis_size * k * l.srf_points * n2,
                              l.value_size, &l.srf);
  l.raw_size = at;
  *out = l;
  return 1;
}

/* The row of value `index` of each quantised block (SPEC §7.5): transfer per (term, coefficient),
 * OOF per coefficient, basis per function, SRF per (field, coefficient). */
static inline uint64_t prt_blob_sfld_transfer_row(const prt_blob_sfld_layout* l, uint64_t index) {
  return index % l->transfer.rows;
}
static inline uint64_t prt_blob_sfld_oof_row(const prt_blob_sfld_layout* l, uint64_t index) {
  return index % l->coefficients;
}
static inline uint64_t prt_blob_sfld_basis_row(const prt_blob_sfld_layout* l, uint64_t index) {
  return index / (l->basis.count / l->basis.rows);
}
static inline uint64_t prt_blob_sfld_srf_row(const prt_blob_sfld_layout* l, uint64_t index) {
  const uint64_t per_field = l->srf_points * l->coefficients;
  return (index / per_field) * l->coefficients + index % l->coefficients;
}

/* Checks every header field of an SFLD section of `size` bytes and `element_count` elements, in
 * the order of SPEC §7.5's header table, then the element count (1), then the exact size; on
 * success fills *layout (may be NULL). `vertex_count` is VPOS's (the caller's, or the header's
 * own when the caller has none: pass UINT64_MAX to skip that comparison). Failures: CORRUPT, or
 * NON_FINITE for a non-finite shell float, with a message naming the field. O(1). */
prt_blob_status prt_blob_sfld_check_header(const uint8_t* bytes, size_t size,
                                           uint64_t element_count, uint64_t vertex_count,
                                           prt_blob_sfld_layout* layout, char* msg,
                                           size_t capacity);

#ifdef __cplusplus
}
#endif

#endif /* PRT_FORMAT_SHADOWFIELD_LAYOUT_H */
