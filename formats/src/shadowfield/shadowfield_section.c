/* SPDX-License-Identifier: MIT */
/* The SFLD header check (shared with the runtime's load) and content check (formats/SPEC.md
 * §7.5, full validation). */
#include "shadowfield_section.h"

#include <float.h>
#include <inttypes.h>

#include <prt/format/shadowfield_layout.h>

#include "../reader_internal.h"

#define FAIL(...) prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'SFLD': " __VA_ARGS__)

/* Order, terms, glossy flag and BRDF grid: the material and the SH. */
static prt_blob_status check_material(const prt_blob_sfld_header* h, char* msg, size_t cap) {
  if (h->order < PRT_BLOB_SFLD_MIN_ORDER || h->order > PRT_BLOB_SFLD_MAX_ORDER)
    return FAIL("order %" PRIu32 " is not in 2..6", h->order);
  if (h->terms < 1u || h->terms > PRT_BLOB_SFLD_MAX_TERMS)
    return FAIL("terms %" PRIu32 " is not in 1..8", h->terms);
  if (h->glossy > 1u) return FAIL("glossy flag %" PRIu32 " is not 0 or 1", h->glossy);
  if (!h->glossy && h->terms != 1u)
    return FAIL("terms %" PRIu32 " for a diffuse surface (must be 1)", h->terms);
  return PRT_BLOB_OK;
}

/* Vertices and basis size. */
static prt_blob_status check_counts(const prt_blob_sfld_header* h, uint64_t vertex_count, char* msg,
                                    size_t cap) {
  if (h->vertices < 1u) return FAIL("vertices 0 (an object has at least one)");
  if (vertex_count != UINT64_MAX && (uint64_t)h->vertices != vertex_count)
    return FAIL("vertices %" PRIu32 ", 'VPOS' has %" PRIu64, h->vertices, vertex_count);
  if (h->basis_size < 1u || h->basis_size > PRT_BLOB_SFLD_MAX_BASIS)
    return FAIL("basis size %" PRIu32 " is not in 1..64", h->basis_size);
  if (h->basis_size > h->vertices)
    return FAIL("basis size %" PRIu32 " exceeds the %" PRIu32 " vertices", h->basis_size,
                h->vertices);
  return PRT_BLOB_OK;
}

/* BRDF grid, bits and flags. */
static prt_blob_status check_storage(const prt_blob_sfld_header* h, char* msg, size_t cap) {
  if (h->glossy &&
      (h->brdf_grid < PRT_BLOB_SFLD_MIN_BRDF_GRID || h->brdf_grid > PRT_BLOB_SFLD_MAX_BRDF_GRID))
    return FAIL("BRDF grid %" PRIu32 " is not in 4..64", h->brdf_grid);
  if (!h->glossy && h->brdf_grid != 0u)
    return FAIL("BRDF grid %" PRIu32 " for a diffuse surface (must be 0)", h->brdf_grid);
  if (h->bits != 8u && h->bits != 16u) return FAIL("%" PRIu32 " bits (must be 8 or 16)", h->bits);
  if (h->flags != 0u) return FAIL("flags 0x%" PRIx32 " (layout 1 defines none)", h->flags);
  return PRT_BLOB_OK;
}

static prt_blob_status not_finite(const char* grid, const char* field, char* msg, size_t cap) {
  return prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap, "'SFLD': %s shells' %s is not finite", grid,
                       field);
}

/* One shell grid: finite floats, radius > 0, 0 < inner <= outer (= when one shell, < with more),
 * r outer finite, shells and face size in 1..64. */
static prt_blob_status check_shells(const prt_sf_shells* s, const char* grid, char* msg,
                                    size_t cap) {
  int i;
  for (i = 0; i < 3; ++i)
    if (!prt_blob_f32_is_finite(s->centre[i])) return not_finite(grid, "centre", msg, cap);
  if (!prt_blob_f32_is_finite(s->radius)) return not_finite(grid, "radius", msg, cap);
  if (!prt_blob_f32_is_finite(s->inner)) return not_finite(grid, "inner", msg, cap);
  if (!prt_blob_f32_is_finite(s->outer)) return not_finite(grid, "outer", msg, cap);
  if (!(s->radius > 0.0f)) return FAIL("%s shells' radius %g is not > 0", grid, s->radius);
  if (!(s->inner > 0.0f)) return FAIL("%s shells' inner %g is not > 0", grid, s->inner);
  if (s->shells < 1u || s->shells > PRT_BLOB_SFLD_MAX_SHELLS)
    return FAIL("%s shells' count %" PRIu32 " is not in 1..64", grid, s->shells);
  if (s->shells == 1u ? s->outer != s->inner : !(s->outer > s->inner))
    return FAIL("%s shells' outer %g against inner %g (= with one shell, > with more)", grid,
                s->outer, s->inner);
  if ((double)s->radius * s->outer > FLT_MAX)
    return FAIL("%s shells' radius x outer overflows f32", grid);
  if (s->face_size < 1u || s->face_size > PRT_BLOB_SFLD_MAX_FACE_SIZE)
    return FAIL("%s shells' face size %" PRIu32 " is not in 1..64", grid, s->face_size);
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_sfld_check_header(const uint8_t* p, size_t size, uint64_t element_count,
                                           uint64_t vertex_count, prt_blob_sfld_layout* layout,
                                           char* msg, size_t cap) {
  prt_blob_sfld_header h;
  prt_blob_sfld_layout l;
  prt_blob_status st;
  if (!p || size < PRT_BLOB_SFLD_HEADER_SIZE)
    return FAIL("%zu bytes cannot hold the 128-byte header", size);
  prt_blob_sfld_read_header(p, &h);
  st = check_material(&h, msg, cap);
  if (st == PRT_BLOB_OK) st = check_counts(&h, vertex_count, msg, cap);
  if (st == PRT_BLOB_OK) st = check_storage(&h, msg, cap);
  if (st == PRT_BLOB_OK) st = check_shells(&h.oof_shells, "OOF", msg, cap);
  if (st == PRT_BLOB_OK) st = check_shells(&h.srf_shells, "SRF", msg, cap);
  if (st != PRT_BLOB_OK) return st;
  if (!prt_blob_bytes_are_zero(p + PRT_BLOB_SFLD_OFF_RESERVED, PRT_BLOB_SFLD_RESERVED_SIZE))
    return FAIL("reserved header fields are not zero");
  if (element_count != 1u)
    return FAIL("element count %" PRIu64 " (one object per section)", element_count);
  prt_blob_sfld_layout_of(&h, &l); /* valid fields */
  if ((uint64_t)size != l.raw_size)
    return FAIL("%zu raw bytes, the header implies %" PRIu64, size, l.raw_size);
  if (layout) *layout = l;
  return PRT_BLOB_OK;
}

/* `count` f32 at p: finite, and within [lo, hi]. */
static prt_blob_status check_floats(const uint8_t* p, uint64_t count, float lo, float hi,
                                    const char* what, char* msg, size_t cap) {
  uint64_t i;
  for (i = 0; i < count; ++i) {
    const float f = prt_blob_load_f32(p + 4u * i);
    if (!prt_blob_f32_is_finite(f))
      return prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap,
                           "'SFLD': %s value %" PRIu64 " is not finite", what, i);
    if (f < lo || f > hi)
      return FAIL("%s value %" PRIu64 " (%g) is not in [%g, %g]", what, i, f, lo, hi);
  }
  return PRT_BLOB_OK;
}

/* A quantised block's (offset, scale) rows and its padding. */
static prt_blob_status check_block(const uint8_t* p, const prt_blob_sfld_block* b, const char* what,
                                   char* msg, size_t cap) {
  uint64_t r;
  for (r = 0; r < b->rows; ++r) {
    const uint8_t* pair = p + b->params + PRT_BLOB_SFLD_PARAM_SIZE * r;
    const float offset = prt_blob_load_f32(pair), scale = prt_blob_load_f32(pair + 4u);
    if (!prt_blob_f32_is_finite(offset) || !prt_blob_f32_is_finite(scale))
      return prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap,
                           "'SFLD': %s offset or scale of row %" PRIu64 " is not finite", what, r);
    if (scale < 0.0f) return FAIL("%s scale of row %" PRIu64 " is negative", what, r);
  }
  if (!prt_blob_bytes_are_zero(p + b->payload_end, (size_t)(b->end - b->payload_end)))
    return FAIL("%s padding is not zero", what);
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_sfld(const prt_blob_content* content, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  const float inf = FLT_MAX;
  prt_blob_sfld_layout l;
  prt_blob_status st;
  uint64_t v, n;
  st = prt_blob_sfld_check_header(p, content->size, content->section->element_count,
                                  content->vertex_count, &l, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  v = l.vertices;
  n = l.basis_size;
  st = check_floats(p + l.albedo, 3u * v, 0.0f, 1.0f, "albedo", msg, cap);
  if (st == PRT_BLOB_OK)
    st = check_floats(p + l.g_table, l.g_values, -inf, inf, "g table", msg, cap);
  if (st == PRT_BLOB_OK) st = check_block(p, &l.transfer, "transfer", msg, cap);
  if (st == PRT_BLOB_OK) st = check_block(p, &l.oof, "OOF", msg, cap);
  if (st == PRT_BLOB_OK) st = check_block(p, &l.basis, "basis", msg, cap);
  if (st == PRT_BLOB_OK)
    st = check_floats(p + l.vertex_weights, v, 0.0f, inf, "vertex weight", msg, cap);
  if (st == PRT_BLOB_OK)
    st = check_floats(p + l.basis_inverse, n * n, -inf, inf, "inverse normal matrix", msg, cap);
  if (st == PRT_BLOB_OK) st = check_block(p, &l.srf, "SRF", msg, cap);
  return st;
}
