/* SPDX-License-Identifier: MIT */
/* The `wavelet` transfer section (WVLT, formats/SPEC.md §7.2) read through the view the load
 * decoded (wavelet_section.c): dense decoding of rows, light preparation, scalar shading and the
 * dispatch to the SIMD kernels (wavelet_shade_simd.h). Read-only on the asset, no allocation:
 * safe on one asset from several threads at once. */
#include <string.h>

#include "internal.h"
#include "techniques.h"
#include "wavelet_internal.h"

/* The WVLT view the load decoded (wavelet_section.c), NULL without a WVLT section. */
static const prt_wavelet_view* wavelet_view(const prt_asset* asset) {
  return (const prt_wavelet_view*)prt_internal_view(asset, PRT_TECHNIQUE_WAVELET);
}

prt_result prt_wavelet_get_info(const prt_asset* asset, prt_wavelet_info* out) {
  const prt_wavelet_view* view;
  if (!asset || !out || !prt_internal_struct_size_ok(out, PRT_WAVELET_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  view = wavelet_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  prt_internal_write_struct(out, &view->info, sizeof view->info);
  return PRT_OK;
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
  const prt_wavelet_view* view;
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

prt_result prt_wavelet_decode_transfer(const prt_asset* asset, uint32_t first_vertex,
                                       uint32_t vertex_count, float* out_rgb) {
  const prt_wavelet_view* view;
  uint32_t v, c;
  if (!asset || (!out_rgb && vertex_count > 0)) return PRT_ERROR_INVALID_ARGUMENT;
  view = wavelet_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  if (first_vertex > view->info.vertex_count ||
      vertex_count > view->info.vertex_count - first_vertex)
    return PRT_ERROR_INVALID_ARGUMENT;
  for (v = 0; v < vertex_count; ++v) {
    const size_t row_floats = 3u * (size_t)view->info.coefficient_count;
    decode_context d;
    prt_result r;
    d.view = view;
    d.out_rgb = out_rgb + row_floats * v;
    memset(d.out_rgb, 0, row_floats * sizeof(float));
    for (c = 0; c < 3; ++c) d.scale[c] = prt_wavelet_vertex_scale(&view->rows, first_vertex + v, c);
    r = walk_row(&view->rows, first_vertex + v, decode_pair, &d);
    if (r != PRT_OK) return r;
  }
  return PRT_OK;
}

/* The band scale of each coefficient of face `face` by max(x, y) (its level's band, as
 * prt_wavelet_band numbers them). */
static void tabulate_band_scales(const prt_wavelet_view* view, uint32_t face, float* by_extent) {
  const uint32_t size = view->info.size;
  uint32_t k, log2_size = 0u;
  while ((1u << log2_size) < size) ++log2_size;
  for (k = 0; k < size; ++k) {
    const uint32_t band = face * (log2_size + 1u) + (uint32_t)(prt_haar_level(size, k, 0u) + 1);
    by_extent[k] = prt_wavelet_load_f32(view->band_scale + 4u * (size_t)band);
  }
}

/* A face row (at most PRT_WAVELET_MAX_SIZE coefficients, a power of two) never straddles two
 * blocks, so the zero-block mask can be written at row ends. */
typedef char prt_wavelet_rows_within_blocks[PRT_WAVELET_MAX_SIZE <= PRT_BLOB_WVLT_BLOCK ? 1 : -1];

/* Band scales folded in, face by face and row by row (a coefficient's scale is that of
 * max(x, y)); the zero-block mask in the same pass. */
prt_result prt_wavelet_prepare_light(const prt_asset* asset, const float* light_rgba,
                                     float* out_rgba, uint8_t* out_zero_blocks) {
  const prt_wavelet_view* view;
  float by_extent[PRT_WAVELET_MAX_SIZE];
  uint32_t face, faces, size, x, y;
  size_t j = 0;
  int lit = 0;
  if (!asset || !light_rgba || !out_rgba) return PRT_ERROR_INVALID_ARGUMENT;
  view = wavelet_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  size = view->info.size;
  faces = prt_wavelet_face_count(view->info.param);
  for (face = 0; face < faces; ++face) {
    tabulate_band_scales(view, face, by_extent);
    for (y = 0; y < size; ++y) {
      for (x = 0; x < size; ++x, ++j) {
        const float bs = by_extent[x > y ? x : y];
        const float* in = light_rgba + 4u * j;
        float* out = out_rgba + 4u * j;
        out[0] = in[0] * bs;
        out[1] = in[1] * bs;
        out[2] = in[2] * bs;
        out[3] = 0.0f;
        /* NaN counts as lit: it must reach the sum. Bitwise ors: no branch per channel. */
        lit |= (out[0] != 0.0f) | (out[1] != 0.0f) | (out[2] != 0.0f);
      }
      if (j % PRT_BLOB_WVLT_BLOCK == 0u) {
        if (out_zero_blocks) out_zero_blocks[j / PRT_BLOB_WVLT_BLOCK - 1u] = (uint8_t)!lit;
        lit = 0;
      }
    }
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

/* No block skipped: what shading reads when the caller passes no mask. */
static const uint8_t kSkipNothing[PRT_WAVELET_MAX_BLOCKS];

/* The kernel for the context's SIMD ISA, or NULL when the SIMD backend is not usable there
 * (prt_internal_simd_isa applies the CPU, the ISA limit and the backend limit). */
static prt_wavelet_kernel simd_kernel(const prt_context* context) {
#if defined(PRT_HAS_X86_SIMD)
  const prt_simd_isa isa = prt_internal_simd_isa(context);
  if (isa >= PRT_SIMD_ISA_AVX2) return prt_wavelet_shade_avx2; /* AVX-512 contexts too */
  if (isa == PRT_SIMD_ISA_SSE41) return prt_wavelet_shade_sse41;
#else
  (void)context; /* compiled out, or not an x86 build */
#endif
  return NULL;
}

#if defined(PRT_HAS_X86_SIMD)
/* How many times the row kernel's cost per kept quarter block the tiled kernel pays per lit
 * group. */
#define TILED_GROUP_COST 3u

/* Whether the tiled kernel is the quicker for this light. Each kernel's time follows what the
 * light touches: the row kernel's the blocks the mask keeps, the tiled kernel's its lit groups
 * (plus the dense corners), at a higher cost per group than the row kernel pays per quarter
 * block (short runs per lane); the weight is that ratio, measured on the bench's bake-shaped
 * asset. A choice made from the light alone keeps every vertex's result independent of the
 * range it is shaded in. */
static int tiles_pay(const prt_wavelet_tiles* tiles, const prt_wavelet_rows* rows,
                     const prt_wavelet_tile_light* light) {
  uint32_t k, kept = 0;
  for (k = 0; k < rows->blocks; ++k) kept += !rows->skip[k];
  return (uint64_t)TILED_GROUP_COST * light->lit_groups * rows->blocks <=
         (uint64_t)kept * (tiles->units / (PRT_WAVELET_GROUP / PRT_WAVELET_UNIT));
}
#endif

prt_result prt_wavelet_shade(const prt_asset* asset, prt_backend backend,
                             const float* prepared_rgba, const uint8_t* zero_blocks,
                             uint32_t first_vertex, uint32_t vertex_count, float* out_rgb) {
  const prt_wavelet_view* view;
  prt_wavelet_rows rows;
  prt_wavelet_kernel kernel;
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  if (backend == PRT_BACKEND_AUTO) backend = prt_context_backend(asset->context);
  switch (backend) {
    case PRT_BACKEND_CPU:
      kernel = shade_scalar;
      break;
    case PRT_BACKEND_SIMD:
      kernel = simd_kernel(asset->context);
      if (!kernel) return PRT_ERROR_UNSUPPORTED_BACKEND;
      break;
    case PRT_BACKEND_GL: /* needs the game's GL context: prt_gl_wavelet_create */
      return PRT_ERROR_UNSUPPORTED_BACKEND;
    default:
      return PRT_ERROR_INVALID_ARGUMENT;
  }
  if (!prepared_rgba || (!out_rgb && vertex_count > 0)) return PRT_ERROR_INVALID_ARGUMENT;
  view = wavelet_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  if (first_vertex > view->info.vertex_count ||
      vertex_count > view->info.vertex_count - first_vertex)
    return PRT_ERROR_INVALID_ARGUMENT;
  if (vertex_count == 0) return PRT_OK;
  rows = view->rows;
  rows.light = prepared_rgba;
  rows.skip = zero_blocks ? zero_blocks : kSkipNothing;
#if defined(PRT_HAS_X86_SIMD)
  /* The load's repack, made only for contexts whose SIMD ISA is AVX2 or above (wavelet_tiles.c). */
  if (kernel == prt_wavelet_shade_avx2 && view->tiles) {
    prt_wavelet_tile_light light;
    if (prt_wavelet_tile_light_make(view->tiles, prepared_rgba, rows.skip, &light) &&
        tiles_pay(view->tiles, &rows, &light)) {
      prt_wavelet_shade_tiles_avx2(view->tiles, &light, first_vertex, vertex_count, out_rgb);
      return PRT_OK;
    }
  }
#endif
  return kernel(&rows, first_vertex, vertex_count, out_rgb);
}
