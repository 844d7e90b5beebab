/* SPDX-License-Identifier: MIT */
/* The `sh` transfer section (SHTR, formats/SPEC.md): header, dequantisation, scalar shading.
 * Read-only on the asset, no allocation: safe on one asset from several threads at once. */
#include <string.h>

#include "internal.h"

/* A checked view of the SHTR bytes. */
typedef struct shtr_view {
  prt_sh_transfer_info info;
  uint32_t coefficients; /* channels * order^2 per vertex */
  const uint8_t* params; /* (offset, scale) f32 pairs, `coefficients` of them */
  const uint8_t* values; /* u8 or u16 [vertex_count][coefficients] */
} shtr_view;

static float load_f32(const uint8_t* p) {
  uint32_t bits = prt_le_load_u32(p);
  float f;
  memcpy(&f, &bits, sizeof f);
  return f;
}

/* Finds SHTR and checks its header against its size, so that reads stay inside the section even
 * for an asset loaded with quick validation (full validation also checks the floats). */
static prt_result open_shtr(const prt_asset* asset, shtr_view* view) {
  const void* data;
  size_t size;
  const uint8_t* p;
  uint64_t payload, expected;
  prt_sh_transfer_info* info = &view->info;
  prt_result r = prt_asset_section_data(asset, PRT_SECTION_SHTR, &data, &size);
  if (r != PRT_OK) return r;
  p = (const uint8_t*)data;
  if (!p || size < PRT_BLOB_SHTR_HEADER_SIZE) return PRT_ERROR_CORRUPT;
  info->order = prt_le_load_u32(p);
  info->vertex_count = prt_le_load_u32(p + 4);
  info->channels = prt_le_load_u32(p + 8);
  info->bits = prt_le_load_u32(p + 12);
  info->kind = prt_le_load_u32(p + 16);
  info->bounces = prt_le_load_u32(p + 20);
  if (info->order < 1 || info->order > PRT_BLOB_SHTR_MAX_ORDER ||
      (info->channels != 1 && info->channels != 3) || (info->bits != 8 && info->bits != 16))
    return PRT_ERROR_CORRUPT;
  view->coefficients = info->channels * info->order * info->order;
  payload = PRT_BLOB_SHTR_HEADER_SIZE + 8u * (uint64_t)view->coefficients +
            (uint64_t)info->vertex_count * view->coefficients * (info->bits / 8u);
  expected = (payload + 3u) & ~(uint64_t)3u;
  if (expected != (uint64_t)size) return PRT_ERROR_CORRUPT;
  view->params = p + PRT_BLOB_SHTR_HEADER_SIZE;
  view->values = view->params + 8u * (size_t)view->coefficients;
  return PRT_OK;
}

static prt_result check_range(const shtr_view* view, uint32_t first, uint32_t count) {
  if (first > view->info.vertex_count || count > view->info.vertex_count - first)
    return PRT_ERROR_INVALID_ARGUMENT;
  return PRT_OK;
}

/* Dequantised coefficient j of vertex v. */
static float transfer_at(const shtr_view* view, uint32_t v, uint32_t j) {
  size_t index = (size_t)v * view->coefficients + j;
  uint32_t q = view->info.bits == 8 ? view->values[index]
                                    : (uint32_t)prt_le_load_u16(view->values + 2u * index);
  return load_f32(view->params + 8u * j) + load_f32(view->params + 8u * j + 4u) * (float)q;
}

prt_result prt_sh_get_transfer_info(const prt_asset* asset, prt_sh_transfer_info* out) {
  shtr_view view;
  prt_result r;
  if (!asset || !out) return PRT_ERROR_INVALID_ARGUMENT;
  r = open_shtr(asset, &view);
  if (r == PRT_OK) *out = view.info;
  return r;
}

prt_result prt_sh_decode_transfer(const prt_asset* asset, uint32_t first_vertex,
                                  uint32_t vertex_count, float* out) {
  shtr_view view;
  uint32_t v, j;
  prt_result r;
  if (!asset || (!out && vertex_count > 0)) return PRT_ERROR_INVALID_ARGUMENT;
  r = open_shtr(asset, &view);
  if (r == PRT_OK) r = check_range(&view, first_vertex, vertex_count);
  if (r != PRT_OK) return r;
  for (v = 0; v < vertex_count; ++v)
    for (j = 0; j < view.coefficients; ++j)
      out[(size_t)v * view.coefficients + j] = transfer_at(&view, first_vertex + v, j);
  return PRT_OK;
}

/* radiance[ch] = sum_k t[c(ch)][k] L[k][ch], c(ch) = ch for RGB transfer, 0 for grey; summed in
 * double since this is the reference the other backends are compared with. */
static void shade_vertex(const shtr_view* view, const float* light_rgb, uint32_t v, float* rgb) {
  uint32_t n2 = view->info.order * view->info.order, ch, k;
  for (ch = 0; ch < 3; ++ch) {
    uint32_t base = (view->info.channels == 3 ? ch : 0u) * n2;
    double sum = 0.0;
    for (k = 0; k < n2; ++k)
      sum += (double)transfer_at(view, v, base + k) * (double)light_rgb[3u * k + ch];
    rgb[ch] = (float)sum;
  }
}

prt_result prt_sh_shade(const prt_asset* asset, const float* light_rgb, uint32_t first_vertex,
                        uint32_t vertex_count, float* out_rgb) {
  shtr_view view;
  uint32_t v;
  prt_result r;
  if (!asset || !light_rgb || (!out_rgb && vertex_count > 0)) return PRT_ERROR_INVALID_ARGUMENT;
  r = open_shtr(asset, &view);
  if (r == PRT_OK) r = check_range(&view, first_vertex, vertex_count);
  if (r != PRT_OK) return r;
  for (v = 0; v < vertex_count; ++v)
    shade_vertex(&view, light_rgb, first_vertex + v, out_rgb + 3u * (size_t)v);
  return PRT_OK;
}

prt_result prt_sh_shade_on(const prt_asset* asset, prt_backend backend, const float* light_rgb,
                           uint32_t first_vertex, uint32_t vertex_count, float* out_rgb) {
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  if (backend == PRT_BACKEND_AUTO) backend = prt_context_backend(asset->context);
  switch (backend) {
    case PRT_BACKEND_CPU:
      return prt_sh_shade(asset, light_rgb, first_vertex, vertex_count, out_rgb);
    case PRT_BACKEND_SIMD: /* SIMD kernels: see sh_shade_simd.c (in progress) */
    case PRT_BACKEND_GL:
      return PRT_ERROR_UNSUPPORTED_BACKEND;
    case PRT_BACKEND_AUTO:
      break;
  }
  return PRT_ERROR_INVALID_ARGUMENT;
}
