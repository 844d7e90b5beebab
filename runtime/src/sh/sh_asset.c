/* SPDX-License-Identifier: MIT */
/* The `sh` transfer section (SHTR, formats/SPEC.md): header, dequantisation, scalar shading and
 * the dispatch to the SIMD kernels (sh_shade_simd.h). Read-only on the asset, no allocation:
 * safe on one asset from several threads at once. */
#include <math.h>
#include <string.h>

#include "internal.h"
#include "sh_internal.h"
#include "sh_shade_simd.h"

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

/* A double as float, rounded to nearest as the hardware does, including to an infinity from
 * halfway past FLT_MAX on (0x1.ffffffp127), where a C conversion would be undefined. */
static float to_float(double x) {
  if (x >= 0x1.ffffffp127) return INFINITY;
  if (x <= -0x1.ffffffp127) return -INFINITY;
  return (float)x;
}

void prt_sh_fold_light(const uint8_t* params, uint32_t order, uint32_t channels,
                       const float* light_rgb, uint32_t padded, float* weight, size_t weight_stride,
                       float bias[3]) {
  const uint32_t n2 = order * order;
  uint32_t ch, k;
  for (ch = 0; ch < 3; ++ch) {
    const uint8_t* param = params + 8u * (size_t)((channels == 3 ? ch : 0u) * n2);
    float* row = weight + ch * weight_stride;
    double sum = 0.0;
    for (k = 0; k < n2; ++k, param += 8) {
      const float light = light_rgb[3u * k + ch];
      sum += (double)load_f32(param) * (double)light;
      row[k] = load_f32(param + 4u) * light;
    }
    for (; k < padded; ++k) row[k] = 0.0f;
    bias[ch] = to_float(sum);
  }
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
    rgb[ch] = to_float(sum);
  }
}

/* Argument and header checks shared by every shading backend. */
static prt_result open_shading(const prt_asset* asset, const float* light_rgb,
                               uint32_t first_vertex, uint32_t vertex_count, const float* out_rgb,
                               shtr_view* view) {
  prt_result r;
  if (!asset || !light_rgb || (!out_rgb && vertex_count > 0)) return PRT_ERROR_INVALID_ARGUMENT;
  r = open_shtr(asset, view);
  if (r == PRT_OK) r = check_range(view, first_vertex, vertex_count);
  return r;
}

prt_result prt_sh_shade(const prt_asset* asset, const float* light_rgb, uint32_t first_vertex,
                        uint32_t vertex_count, float* out_rgb) {
  shtr_view view;
  uint32_t v;
  prt_result r = open_shading(asset, light_rgb, first_vertex, vertex_count, out_rgb, &view);
  if (r != PRT_OK) return r;
  for (v = 0; v < vertex_count; ++v)
    shade_vertex(&view, light_rgb, first_vertex + v, out_rgb + 3u * (size_t)v);
  return PRT_OK;
}

#if defined(PRT_HAS_X86_SIMD)

#define PRT_SH_MAX_COEFFICIENTS (PRT_BLOB_SHTR_MAX_ORDER * PRT_BLOB_SHTR_MAX_ORDER)

/* The kernel for the context's SIMD ISA, or NULL when the SIMD backend is not usable there
 * (prt_backend_get_info applies the CPU, the ISA limit and the backend limit). */
static prt_sh_simd_kernel simd_kernel(const prt_context* context) {
  prt_backend_info info;
  if (prt_backend_get_info(context, PRT_BACKEND_SIMD, &info) != PRT_OK || !info.usable) return NULL;
  if (info.isa == PRT_SIMD_ISA_AVX2) return prt_sh_shade_avx2;
  if (info.isa == PRT_SIMD_ISA_SSE41) return prt_sh_shade_sse41;
  return NULL;
}

/* The light folded into the quantisation, once per call (prt_sh_fold_light). */
static void fold_light(const shtr_view* view, const float* light_rgb,
                       float weight[3][PRT_SH_MAX_COEFFICIENTS + PRT_SH_SIMD_BLOCK],
                       prt_sh_simd_job* job) {
  const uint32_t n2 = view->info.order * view->info.order;
  uint32_t ch;
  job->padded = (n2 + PRT_SH_SIMD_BLOCK - 1u) / PRT_SH_SIMD_BLOCK * PRT_SH_SIMD_BLOCK;
  prt_sh_fold_light(view->params, view->info.order, view->info.channels, light_rgb, job->padded,
                    &weight[0][0], PRT_SH_MAX_COEFFICIENTS + PRT_SH_SIMD_BLOCK, job->bias);
  for (ch = 0; ch < 3; ++ch) {
    job->segment[ch] = (view->info.channels == 3 ? ch : 0u) * n2;
    job->weight[ch] = weight[ch];
  }
}

/* Runs `kernel` on vertices [first, first+count) without reading past the section's values. A
 * kernel reads up to PRT_SH_SIMD_BLOCK - 1 values past a channel's run, so the last vertices of
 * the section, whose reads would pass its end, are shaded one by one from a zero-padded copy. */
static void run_in_bounds(prt_sh_simd_kernel kernel, prt_sh_simd_job* job, const shtr_view* view,
                          uint32_t first, uint32_t count, float* out_rgb) {
  uint8_t padded_vertex[2u * (3u * PRT_SH_MAX_COEFFICIENTS + PRT_SH_SIMD_BLOCK)];
  const size_t value_size = job->bits / 8u, end = (size_t)first + count;
  /* Bytes read from a vertex's start; at least one stride (segment[2] is the last run). */
  const size_t reach = ((size_t)job->segment[2] + job->padded) * value_size;
  const size_t values_end = (size_t)view->info.vertex_count * job->stride;
  const size_t in_place_end = reach <= values_end ? (values_end - reach) / job->stride + 1u : 0u;
  size_t direct_end = in_place_end < first ? first : in_place_end, v;
  if (direct_end > end) direct_end = end;
  if (direct_end > first) {
    job->values = view->values + first * job->stride;
    kernel(job, (uint32_t)(direct_end - first), out_rgb);
  }
  if (direct_end == end) return;
  memset(padded_vertex + job->stride, 0, reach - job->stride);
  for (v = direct_end; v < end; ++v) {
    memcpy(padded_vertex, view->values + v * job->stride, job->stride);
    job->values = padded_vertex;
    kernel(job, 1u, out_rgb + 3u * (v - first));
  }
}

static prt_result shade_simd(const prt_asset* asset, const float* light_rgb, uint32_t first,
                             uint32_t count, float* out_rgb) {
  float weight[3][PRT_SH_MAX_COEFFICIENTS + PRT_SH_SIMD_BLOCK];
  prt_sh_simd_job job;
  shtr_view view;
  const prt_sh_simd_kernel kernel = simd_kernel(asset->context);
  prt_result r;
  if (!kernel) return PRT_ERROR_UNSUPPORTED_BACKEND;
  r = open_shading(asset, light_rgb, first, count, out_rgb, &view);
  if (r != PRT_OK || count == 0) return r;
  fold_light(&view, light_rgb, weight, &job);
  job.bits = view.info.bits;
  job.stride = (size_t)view.coefficients * (view.info.bits / 8u);
  run_in_bounds(kernel, &job, &view, first, count, out_rgb);
  return PRT_OK;
}

#else

static prt_result shade_simd(const prt_asset* asset, const float* light_rgb, uint32_t first,
                             uint32_t count, float* out_rgb) {
  (void)asset, (void)light_rgb, (void)first, (void)count, (void)out_rgb;
  return PRT_ERROR_UNSUPPORTED_BACKEND; /* compiled out, or not an x86 build */
}

#endif

prt_result prt_sh_shade_on(const prt_asset* asset, prt_backend backend, const float* light_rgb,
                           uint32_t first_vertex, uint32_t vertex_count, float* out_rgb) {
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  if (backend == PRT_BACKEND_AUTO) backend = prt_context_backend(asset->context);
  switch (backend) {
    case PRT_BACKEND_CPU:
      return prt_sh_shade(asset, light_rgb, first_vertex, vertex_count, out_rgb);
    case PRT_BACKEND_SIMD:
      return shade_simd(asset, light_rgb, first_vertex, vertex_count, out_rgb);
    case PRT_BACKEND_GL: /* needs the game's GL context: prt_gl.h */
      return PRT_ERROR_UNSUPPORTED_BACKEND;
    case PRT_BACKEND_AUTO:
      break;
  }
  return PRT_ERROR_INVALID_ARGUMENT;
}
