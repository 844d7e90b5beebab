/* SPDX-License-Identifier: MIT */
/* The `wavelet` transfer section (WVLT, formats/SPEC.md §7.2): header, dense decoding of a row,
 * light preparation, scalar shading and the dispatch to the SIMD kernels
 * (wavelet_shade_simd.h). Read-only on the asset, no allocation: safe on one asset from several
 * threads at once. */
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>
#include <string.h>

#include "internal.h"
#include "wavelet_shade_simd.h"

/* A checked view of the WVLT bytes. */
typedef struct wvlt_view {
  prt_wavelet_info info;
  prt_blob_wvlt_layout layout;
  const uint8_t* band_scale; /* f32[bands] */
  prt_wavelet_rows rows;     /* light left NULL */
} wvlt_view;

/* Finds WVLT and checks what every later read relies on: the header fields, the exact size and
 * rs[V] = P (SPEC §7.2's quick checks), so reads stay inside the section even for an asset loaded
 * with quick validation. Row contents are checked as the rows are walked. */
static prt_result open_wvlt(const prt_asset* asset, wvlt_view* view) {
  const void* data;
  size_t size;
  uint32_t index;
  const uint8_t* p;
  prt_wavelet_info* info = &view->info;
  prt_blob_wvlt_layout* l = &view->layout;
  prt_result r = prt_asset_section_data(asset, PRT_SECTION_WVLT, &data, &size);
  if (r != PRT_OK) return r;
  p = (const uint8_t*)data;
  if (!p || size < PRT_BLOB_WVLT_HEADER_SIZE) return PRT_ERROR_CORRUPT;
  memset(info, 0, sizeof *info);
  info->param = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_PARAM);
  info->size = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_SIZE);
  info->vertex_count = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_VERTICES);
  info->quantizer = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_QUANTIZER);
  info->keep = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_KEEP);
  info->bounces = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_BOUNCES);
  info->pair_count = prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_PAIR_COUNT);
  if (!prt_blob_wvlt_layout_of(info->param, info->size, info->vertex_count, info->pair_count, l) ||
      info->quantizer > 1u || prt_le_load_u32(p + PRT_BLOB_WVLT_OFF_RESERVED) != 0 ||
      l->raw_size != (uint64_t)size)
    return PRT_ERROR_CORRUPT;
  /* Quick validation tied element_count to VPOS; the header must agree with both. */
  if (prt_asset_find_section(asset, PRT_SECTION_WVLT, &index) != PRT_OK ||
      asset->sections[index].entry.element_count != (uint64_t)info->vertex_count)
    return PRT_ERROR_CORRUPT;
  if (prt_le_load_u32(p + l->row_start + 4u * (uint64_t)info->vertex_count) != info->pair_count)
    return PRT_ERROR_CORRUPT;
  info->faces = l->faces;
  info->coefficient_count = l->coefficients;
  info->block_count = l->blocks;
  view->band_scale = p + l->band_scale;
  view->rows.vertex_scale = p + l->vertex_scale;
  view->rows.row_start = p + l->row_start;
  view->rows.counts = p + l->counts;
  view->rows.pairs = p + l->pairs;
  view->rows.light = NULL;
  view->rows.skip = NULL;
  view->rows.blocks = l->blocks;
  view->rows.pair_count = info->pair_count;
  return PRT_OK;
}

prt_result prt_wavelet_get_info(const prt_asset* asset, prt_wavelet_info* out) {
  wvlt_view view;
  prt_result r;
  if (!asset || !out) return PRT_ERROR_INVALID_ARGUMENT;
  r = open_wvlt(asset, &view);
  if (r == PRT_OK) *out = view.info;
  return r;
}

/* Calls visit(context, j, q) for each pair of row v in stored order, checking every block count
 * (at most 256) against the row's pair range; PRT_ERROR_CORRUPT when they disagree. */
typedef void (*pair_visitor)(void* context, uint32_t j, int q);
static prt_result walk_row(const prt_wavelet_rows* rows, uint32_t v, pair_visitor visit,
                           void* context) {
  const uint8_t* counts = rows->counts + 2u * (size_t)v * rows->blocks;
  uint32_t start, end, at, k, i;
  if (!prt_wavelet_row_range(rows, v, &start, &end)) return PRT_ERROR_CORRUPT;
  at = start;
  for (k = 0; k < rows->blocks; ++k) {
    const uint32_t count = prt_le_load_u16(counts + 2u * k);
    const uint8_t* pair = rows->pairs + 2u * (size_t)at;
    if (count > PRT_BLOB_WVLT_BLOCK || count > end - at) return PRT_ERROR_CORRUPT;
    for (i = 0; i < count; ++i, pair += 2)
      visit(context, PRT_BLOB_WVLT_BLOCK * k + pair[0], (int)(int8_t)pair[1]);
    at += count;
  }
  return at == end ? PRT_OK : PRT_ERROR_CORRUPT;
}

typedef struct decode_context {
  const wvlt_view* view;
  float scale[3]; /* vs[v] */
  float* out_rgb;
} decode_context;

static void decode_pair(void* context, uint32_t j, int q) {
  decode_context* d = (decode_context*)context;
  const uint32_t band =
      prt_wavelet_band(d->view->info.param, d->view->info.size, j); /* j < coefficients */
  const float bs = prt_wavelet_load_f32(d->view->band_scale + 4u * (size_t)band);
  uint32_t c;
  for (c = 0; c < 3; ++c) d->out_rgb[3u * (size_t)j + c] = (float)q * bs * d->scale[c];
}

prt_result prt_wavelet_decode_row(const prt_asset* asset, uint32_t vertex, float* out_rgb) {
  wvlt_view view;
  decode_context d;
  uint32_t c;
  prt_result r;
  if (!asset || !out_rgb) return PRT_ERROR_INVALID_ARGUMENT;
  r = open_wvlt(asset, &view);
  if (r != PRT_OK) return r;
  if (vertex >= view.info.vertex_count) return PRT_ERROR_INVALID_ARGUMENT;
  memset(out_rgb, 0, 3u * sizeof(float) * view.info.coefficient_count);
  d.view = &view;
  d.out_rgb = out_rgb;
  for (c = 0; c < 3; ++c) d.scale[c] = prt_wavelet_vertex_scale(&view.rows, vertex, c);
  return walk_row(&view.rows, vertex, decode_pair, &d);
}

/* Band scales folded in, block by block; a block whose prepared RGB is all zero is marked in
 * the 4th float of its first coefficient (prt_wavelet_asset.h), in the same pass. */
prt_result prt_wavelet_prepare_light(const prt_asset* asset, const float* light_rgba,
                                     float* out_rgba) {
  const uint32_t mark = PRT_WAVELET_ZERO_BLOCK_MARK;
  wvlt_view view;
  uint32_t block, j, c;
  prt_result r;
  if (!asset || !light_rgba || !out_rgba) return PRT_ERROR_INVALID_ARGUMENT;
  r = open_wvlt(asset, &view);
  if (r != PRT_OK) return r;
  for (block = 0; block < view.info.block_count; ++block) {
    const uint32_t first = block * PRT_BLOB_WVLT_BLOCK;
    int lit = 0;
    for (j = first; j < first + PRT_BLOB_WVLT_BLOCK; ++j) {
      const uint32_t band = prt_wavelet_band(view.info.param, view.info.size, j);
      const float bs = prt_wavelet_load_f32(view.band_scale + 4u * (size_t)band);
      for (c = 0; c < 3; ++c) {
        const float value = light_rgba[4u * (size_t)j + c] * bs;
        out_rgba[4u * (size_t)j + c] = value;
        lit |= value != 0.0f; /* NaN counts as lit: it must reach the sum */
      }
      out_rgba[4u * (size_t)j + 3] = 0.0f;
    }
    if (!lit) memcpy(out_rgba + 4u * (size_t)first + 3, &mark, sizeof mark);
  }
  return PRT_OK;
}

/* The report's loop: per block and pair, q times the prepared light summed in float in stored
 * order, then times the vertex scale (blocks of zero light skipped: they add exactly 0). */
static prt_result shade_scalar(const prt_wavelet_rows* rows, uint32_t first, uint32_t count,
                               float* out_rgb) {
  uint32_t v, k, i, c;
  for (v = first; v < first + count; ++v) {
    const uint8_t* counts = rows->counts + 2u * (size_t)v * rows->blocks;
    float sum[3] = {0.0f, 0.0f, 0.0f};
    float* out = out_rgb + 3u * (size_t)(v - first);
    uint32_t start, end, at;
    if (!prt_wavelet_row_range(rows, v, &start, &end)) return PRT_ERROR_CORRUPT;
    for (at = start, k = 0; k < rows->blocks; ++k) {
      const uint32_t n = prt_le_load_u16(counts + 2u * k);
      const uint8_t* pair = rows->pairs + 2u * (size_t)at;
      const float* block = rows->light + 4u * PRT_BLOB_WVLT_BLOCK * (size_t)k;
      if (n > PRT_BLOB_WVLT_BLOCK || n > end - at) return PRT_ERROR_CORRUPT;
      at += n;
      if (rows->skip[k]) continue;
      for (i = 0; i < n; ++i, pair += 2) {
        const float q = (float)(int8_t)pair[1];
        const float* light = block + 4u * pair[0];
        sum[0] += q * light[0];
        sum[1] += q * light[1];
        sum[2] += q * light[2];
      }
    }
    if (at != end) return PRT_ERROR_CORRUPT;
    for (c = 0; c < 3; ++c) out[c] = prt_wavelet_vertex_scale(rows, v, c) * sum[c];
  }
  return PRT_OK;
}

/* Argument and header checks shared by every shading backend. */
static prt_result open_shading(const prt_asset* asset, const float* prepared_rgba,
                               uint32_t first_vertex, uint32_t vertex_count, const float* out_rgb,
                               wvlt_view* view) {
  prt_result r;
  if (!asset || !prepared_rgba || (!out_rgb && vertex_count > 0)) return PRT_ERROR_INVALID_ARGUMENT;
  r = open_wvlt(asset, view);
  if (r != PRT_OK) return r;
  if (first_vertex > view->info.vertex_count ||
      vertex_count > view->info.vertex_count - first_vertex)
    return PRT_ERROR_INVALID_ARGUMENT;
  view->rows.light = prepared_rgba;
  return PRT_OK;
}

static prt_result shade_with(prt_wavelet_kernel kernel, const prt_asset* asset,
                             const float* prepared_rgba, uint32_t first, uint32_t count,
                             float* out_rgb) {
  wvlt_view view;
  uint8_t skip[PRT_WAVELET_MAX_BLOCKS];
  uint32_t k;
  prt_result r = open_shading(asset, prepared_rgba, first, count, out_rgb, &view);
  if (r != PRT_OK || count == 0) return r;
  for (k = 0; k < view.rows.blocks; ++k)
    skip[k] = (uint8_t)prt_wavelet_block_marked_zero(prepared_rgba +
                                                     4u * PRT_BLOB_WVLT_BLOCK * (size_t)k);
  view.rows.skip = skip;
  return kernel(&view.rows, first, count, out_rgb);
}

prt_result prt_wavelet_shade(const prt_asset* asset, const float* prepared_rgba,
                             uint32_t first_vertex, uint32_t vertex_count, float* out_rgb) {
  return shade_with(shade_scalar, asset, prepared_rgba, first_vertex, vertex_count, out_rgb);
}

/* The kernel for the context's SIMD ISA, or NULL when the SIMD backend is not usable there
 * (prt_backend_get_info applies the CPU, the ISA limit and the backend limit). */
static prt_wavelet_kernel simd_kernel(const prt_context* context) {
#if defined(PRT_HAS_X86_SIMD)
  prt_backend_info info;
  if (prt_backend_get_info(context, PRT_BACKEND_SIMD, &info) != PRT_OK || !info.usable) return NULL;
  if (info.isa == PRT_SIMD_ISA_AVX2) return prt_wavelet_shade_avx2;
  if (info.isa == PRT_SIMD_ISA_SSE41) return prt_wavelet_shade_sse41;
#else
  (void)context; /* compiled out, or not an x86 build */
#endif
  return NULL;
}

prt_result prt_wavelet_shade_on(const prt_asset* asset, prt_backend backend,
                                const float* prepared_rgba, uint32_t first_vertex,
                                uint32_t vertex_count, float* out_rgb) {
  prt_wavelet_kernel kernel;
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  if (backend == PRT_BACKEND_AUTO) backend = prt_context_backend(asset->context);
  switch (backend) {
    case PRT_BACKEND_CPU:
      return prt_wavelet_shade(asset, prepared_rgba, first_vertex, vertex_count, out_rgb);
    case PRT_BACKEND_SIMD:
      kernel = simd_kernel(asset->context);
      if (!kernel) return PRT_ERROR_UNSUPPORTED_BACKEND;
      return shade_with(kernel, asset, prepared_rgba, first_vertex, vertex_count, out_rgb);
    case PRT_BACKEND_GL: /* needs the game's GL context: prt_gl.h */
      return PRT_ERROR_UNSUPPORTED_BACKEND;
    case PRT_BACKEND_AUTO:
      break;
  }
  return PRT_ERROR_INVALID_ARGUMENT;
}
