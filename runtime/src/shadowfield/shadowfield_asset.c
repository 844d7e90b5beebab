/* SPDX-License-Identifier: MIT */
/* The `shadowfield` object decoded at load (the attach hook) from SFLD, VPOS and VNRM into one
 * allocation of floats the asset owns, and the queries on it. The header was checked at open, so
 * every block lies inside the section; nothing here reads past it. */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>

#include "shadowfield_asset_internal.h"
#include "techniques.h"

#define PRT_SHADOWFIELD_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_shadowfield_info, decoded_bytes)

static const prt_sf_view* sf_view(const prt_asset* asset) {
  return (const prt_sf_view*)prt_internal_view(asset, PRT_TECHNIQUE_SHADOWFIELD);
}

const prt_sf_object* prt_internal_sf_object(const prt_asset* asset) {
  const prt_sf_view* view = asset ? sf_view(asset) : NULL;
  return view && view->floats ? &view->object : NULL;
}

prt_result prt_shadowfield_get_info(const prt_asset* asset, prt_shadowfield_info* out) {
  const prt_sf_view* view;
  if (!asset || !out || !prt_internal_struct_size_ok(out, PRT_SHADOWFIELD_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  view = sf_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  prt_internal_write_struct(out, &view->info, sizeof view->info);
  return PRT_OK;
}

/* The decoded section with this tag, NULL when there is none. */
static const prt_asset_section* find(const prt_asset_section* sections, uint32_t count,
                                     uint32_t tag) {
  uint32_t i;
  for (i = 0; i < count; ++i)
    if (sections[i].entry.tag == tag && sections[i].decoded) return &sections[i];
  return NULL;
}

static void decode_f32(const uint8_t* p, uint64_t count, float* out) {
  uint64_t i;
  for (i = 0; i < count; ++i) out[i] = prt_blob_sfld_load_f32(p + 4u * i);
}

/* A quantised block whose values are [groups][repeat][width], value (g, m, c) in row g width + c:
 * transfer (1, V, K n^2), OOF (1, P, n^2), basis (N, V, 1), SRF (N K, P, n^2). */
static void decode_block(const uint8_t* p, const prt_blob_sfld_block* b, uint32_t value_size,
                         uint64_t groups, uint64_t repeat, uint64_t width, float* out) {
  const uint8_t* values = p + b->values;
  uint64_t g, m, c, x = 0;
  for (g = 0; g < groups; ++g)
    for (m = 0; m < repeat; ++m)
      for (c = 0; c < width; ++c, ++x) {
        const uint8_t* pair = p + b->params + PRT_BLOB_SFLD_PARAM_SIZE * (g * width + c);
        const uint32_t q = value_size == 1u ? values[x] : prt_le_load_u16(values + 2u * x);
        out[x] = prt_blob_sfld_load_f32(pair) + prt_blob_sfld_load_f32(pair + 4u) * (float)q;
      }
}

/* The next `count` floats from *at. */
static float* take(float** at, uint64_t count) {
  float* p = *at;
  *at += count;
  return p;
}

/* Points the object's arrays into `f` (float_count floats) in a fixed order. */
static void lay_out(prt_sf_view* view, float* f) {
  const prt_blob_sfld_layout* l = &view->layout;
  const uint64_t v = l->vertices;
  prt_sf_object* o = &view->object;
  float* at = f;
  o->positions = take(&at, 3u * v);
  o->normals = take(&at, 3u * v);
  o->albedo = take(&at, 3u * v);
  o->g_table = l->g_values ? take(&at, l->g_values) : NULL;
  o->transfer = take(&at, l->transfer.count);
  o->oof = take(&at, l->oof.count);
  o->basis = take(&at, l->basis.count);
  o->vertex_weights = take(&at, v);
  o->basis_inverse = take(&at, (uint64_t)l->basis_size * l->basis_size);
  o->srf = take(&at, l->srf.count);
}

/* Floats of the decoded object (positions, normals, albedo and weights: 10 per vertex); 0 when they
 * would not fit a size_t of bytes. */
static size_t float_count(const prt_blob_sfld_layout* l) {
  const uint64_t n = 10u * (uint64_t)l->vertices + l->g_values + l->transfer.count + l->oof.count +
                     l->basis.count + (uint64_t)l->basis_size * l->basis_size + l->srf.count;
  return n <= SIZE_MAX / sizeof(float) ? (size_t)n : 0u;
}

static prt_result mesh_mismatch(const char* tag, uint64_t count, uint32_t vertices, char* msg,
                                size_t capacity) {
  snprintf(msg, capacity, "'SFLD': header says %" PRIu32 " vertices, '%s' has %" PRIu64, vertices,
           tag, count);
  return PRT_ERROR_CORRUPT;
}

static void decode_object(prt_sf_view* view, const uint8_t* positions, const uint8_t* normals) {
  const prt_blob_sfld_layout* l = &view->layout;
  const uint8_t* p = view->data;
  const uint64_t v = l->vertices, n2 = l->coefficients, k = l->terms, n = l->basis_size;
  prt_sf_object* o = &view->object;
  float* f = view->floats;
  lay_out(view, f);
  decode_f32(positions, 3u * v, (float*)o->positions);
  decode_f32(normals, 3u * v, (float*)o->normals);
  decode_f32(p + l->albedo, 3u * v, (float*)o->albedo);
  if (o->g_table) decode_f32(p + l->g_table, l->g_values, (float*)o->g_table);
  decode_block(p, &l->transfer, l->value_size, 1u, v, k * n2, (float*)o->transfer);
  decode_block(p, &l->oof, l->value_size, 1u, l->oof_points, n2, (float*)o->oof);
  decode_block(p, &l->basis, l->value_size, n, v, 1u, (float*)o->basis);
  decode_f32(p + l->vertex_weights, v, (float*)o->vertex_weights);
  decode_f32(p + l->basis_inverse, n * n, (float*)o->basis_inverse);
  decode_block(p, &l->srf, l->value_size, n * k, l->srf_points, n2, (float*)o->srf);
}

static void fill_header(prt_sf_view* view) {
  const prt_shadowfield_info* info = &view->info;
  prt_sf_object* o = &view->object;
  o->order = info->order;
  o->terms = info->terms;
  o->glossy = info->glossy;
  o->vertex_count = info->vertex_count;
  o->basis_size = info->basis_size;
  o->brdf_grid = info->brdf_grid;
  memcpy(&o->oof_shells, &info->oof_shells, sizeof o->oof_shells);
  memcpy(&o->srf_shells, &info->srf_shells, sizeof o->srf_shells);
}

prt_result prt_sf_attach(const prt_context* context, const prt_allocator* allocator,
                         const prt_asset_section* sections, uint32_t section_count, void* memory,
                         char* msg, size_t capacity) {
  prt_sf_view* view = (prt_sf_view*)memory;
  const prt_asset_section* vpos = find(sections, section_count, PRT_BLOB_TAG_VPOS);
  const prt_asset_section* vnrm = find(sections, section_count, PRT_BLOB_TAG_VNRM);
  const uint32_t vertices = view->info.vertex_count;
  size_t count;
  (void)context;
  /* The kind relations made both present; only the vertex count is left to compare. */
  if (!vpos || vpos->entry.element_count != vertices)
    return mesh_mismatch("VPOS", vpos ? vpos->entry.element_count : 0u, vertices, msg, capacity);
  if (!vnrm || vnrm->entry.element_count != vertices)
    return mesh_mismatch("VNRM", vnrm ? vnrm->entry.element_count : 0u, vertices, msg, capacity);
  count = float_count(&view->layout);
  view->floats = count ? (float*)prt_internal_alloc(allocator, count * sizeof(float), 16) : NULL;
  if (!view->floats) return PRT_ERROR_OUT_OF_MEMORY;
  view->float_count = count;
  view->info.decoded_bytes = (uint64_t)count * sizeof(float);
  fill_header(view);
  decode_object(view, vpos->data, vnrm->data);
  return PRT_OK;
}

void prt_sf_release(const prt_allocator* allocator, void* memory) {
  prt_sf_view* view = (prt_sf_view*)memory;
  prt_internal_free(allocator, view->floats, view->float_count * sizeof(float));
  view->floats = NULL;
  view->float_count = 0;
}
