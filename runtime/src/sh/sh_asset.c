/* SPDX-License-Identifier: MIT */
/* The `sh` transfer section (SHTR, formats/SPEC.md) read through the view the load decoded
 * (sh_section.c): dequantisation, scalar shading and the dispatch to the SIMD kernels
 * (sh_shade_simd.h). Read-only on the asset, no allocation: safe on one asset from several
 * threads at once. */
#include <math.h>
#include <string.h>

#include "internal.h"
#include "sh_internal.h"
#include "sh_shade_simd.h"
#include "techniques.h"

static float load_f32(const uint8_t* p) {
  uint32_t bits = prt_le_load_u32(p);
  float f;
  memcpy(&f, &bits, sizeof f);
  return f;
}

/* The SHTR view the load decoded (sh_section.c), NULL without an SHTR section. */
static const prt_sh_view* sh_view(const prt_asset* asset) {
  return (const prt_sh_view*)prt_internal_view(asset, PRT_TECHNIQUE_SH);
}

static prt_result check_range(const prt_sh_view* view, uint32_t first, uint32_t count) {
  if (first > view->info.vertex_count || count > view->info.vertex_count - first)
    return PRT_ERROR_INVALID_ARGUMENT;
  return PRT_OK;
}

/* Dequantised coefficient j of vertex v. */
static float transfer_at(const prt_sh_view* view, uint32_t v, uint32_t j) {
  size_t index = (size_t)v * view->coefficients + j;
  uint32_t q = view->info.bits == 8 ? view->values[index]
                                    : (uint32_t)prt_le_load_u16(view->values + 2u * index);
  return load_f32(view->params + 8u * j) + load_f32(view->params + 8u * j + 4u) * (float)q;
}

prt_result prt_sh_get_info(const prt_asset* asset, prt_sh_info* out) {
  const prt_sh_view* view;
  if (!asset || !out || !prt_internal_struct_size_ok(out, PRT_SH_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  view = sh_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  prt_internal_write_struct(out, &view->info, sizeof view->info);
  return PRT_OK;
}

prt_result prt_sh_decode_transfer(const prt_asset* asset, uint32_t first_vertex,
                                  uint32_t vertex_count, float* out) {
  const prt_sh_view* view;
  uint32_t v, j;
  prt_result r;
  if (!asset || (!out && vertex_count > 0)) return PRT_ERROR_INVALID_ARGUMENT;
  view = sh_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  r = check_range(view, first_vertex, vertex_count);
  if (r != PRT_OK) return r;
  for (v = 0; v < vertex_count; ++v)
    for (j = 0; j < view->coefficients; ++j)
      out[(size_t)v * view->coefficients + j] = transfer_at(view, first_vertex + v, j);
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
static void shade_vertex(const prt_sh_view* view, const float* light_rgb, uint32_t v, float* rgb) {
  uint32_t n2 = view->info.order * view->info.order, ch, k;
  for (ch = 0; ch < 3; ++ch) {
    uint32_t base = (view->info.channels == 3 ? ch : 0u) * n2;
    double sum = 0.0;
    for (k = 0; k < n2; ++k)
      sum += (double)transfer_at(view, v, base + k) * (double)light_rgb[3u * k + ch];
    rgb[ch] = to_float(sum);
  }
}

/* Argument checks shared by every shading backend. */
static prt_result open_shading(const prt_asset* asset, const float* light_rgb,
                               uint32_t first_vertex, uint32_t vertex_count, const float* out_rgb,
                               const prt_sh_view** view) {
  if (!light_rgb || (!out_rgb && vertex_count > 0)) return PRT_ERROR_INVALID_ARGUMENT;
  *view = sh_view(asset);
  if (!*view) return PRT_ERROR_NOT_FOUND;
  return check_range(*view, first_vertex, vertex_count);
}

static prt_result shade_scalar(const prt_asset* asset, const float* light_rgb, uint32_t first,
                               uint32_t count, float* out_rgb) {
  const prt_sh_view* view;
  uint32_t v;
  prt_result r = open_shading(asset, light_rgb, first, count, out_rgb, &view);
  if (r != PRT_OK) return r;
  for (v = 0; v < count; ++v) shade_vertex(view, light_rgb, first + v, out_rgb + 3u * (size_t)v);
  return PRT_OK;
}

#if defined(PRT_HAS_X86_SIMD)

#define PRT_SH_MAX_COEFFICIENTS (PRT_BLOB_SHTR_MAX_ORDER * PRT_BLOB_SHTR_MAX_ORDER)

/* The kernel for the context's SIMD ISA, or NULL when the SIMD backend is not usable there
 * (prt_backend_get_info applies the CPU, the ISA limit and the backend limit). */
static prt_sh_simd_kernel simd_kernel(const prt_context* context) {
  const prt_simd_isa isa = prt_internal_simd_isa(context);
  if (isa == PRT_SIMD_ISA_AVX512) return prt_sh_shade_avx512; /* 8-bit RGB: shade_simd */
  if (isa == PRT_SIMD_ISA_AVX2) return prt_sh_shade_avx2;
  if (isa == PRT_SIMD_ISA_SSE41) return prt_sh_shade_sse41;
  return NULL;
}

/* The light folded into the quantisation, once per call (prt_sh_fold_light). */
static void fold_light(const prt_sh_view* view, const float* light_rgb,
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
static void run_in_bounds(prt_sh_simd_kernel kernel, prt_sh_simd_job* job, const prt_sh_view* view,
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

/* sum_k |offset_j L_k| of each output channel: the part of the conformance bound's magnitude
 * that does not depend on the vertex (prt_sh_fix_weights). */
static void offset_magnitude(const prt_sh_view* view, const float* light_rgb, double out[3]) {
  const uint32_t n2 = view->info.order * view->info.order;
  uint32_t ch, k;
  for (ch = 0; ch < 3; ++ch) {
    const uint8_t* param = view->params + 8u * (size_t)((view->info.channels == 3 ? ch : 0u) * n2);
    out[ch] = 0.0;
    for (k = 0; k < n2; ++k)
      out[ch] += fabs((double)load_f32(param + 8u * k) * (double)light_rgb[3u * k + ch]);
  }
}

static prt_result shade_simd(const prt_asset* asset, const float* light_rgb, uint32_t first,
                             uint32_t count, float* out_rgb) {
  float weight[3][PRT_SH_MAX_COEFFICIENTS + PRT_SH_SIMD_BLOCK];
  prt_sh_fixed_weights fixed;
  prt_sh_simd_job job;
  const prt_sh_view* view;
  prt_sh_simd_kernel kernel = simd_kernel(asset->context);
  prt_result r;
  if (!kernel) return PRT_ERROR_UNSUPPORTED_BACKEND;
  r = open_shading(asset, light_rgb, first, count, out_rgb, &view);
  if (r != PRT_OK || count == 0) return r;
  fold_light(view, light_rgb, weight, &job);
  job.bits = view->info.bits;
  job.stride = (size_t)view->coefficients * (view->info.bits / 8u);
  job.fixed = NULL;
  if (kernel == prt_sh_shade_avx512) {
    /* The fixed-point kernel takes 8-bit RGB values (grey transfer, whose one value serves three
     * channels, is quicker on the float kernel), and only a light whose weights it rounds within
     * the bound; the rest goes to the AVX2 kernel. The choice depends on the asset and the light
     * alone, never on the range. */
    double magnitude[3];
    offset_magnitude(view, light_rgb, magnitude);
    if (job.bits == 8 && view->info.channels == 3 &&
        prt_sh_fix_weights(&job, view->info.order * view->info.order, magnitude, &fixed))
      job.fixed = &fixed;
    else
      kernel = prt_sh_shade_avx2;
  }
  run_in_bounds(kernel, &job, view, first, count, out_rgb);
  return PRT_OK;
}

#else

static prt_result shade_simd(const prt_asset* asset, const float* light_rgb, uint32_t first,
                             uint32_t count, float* out_rgb) {
  (void)asset, (void)light_rgb, (void)first, (void)count, (void)out_rgb;
  return PRT_ERROR_UNSUPPORTED_BACKEND; /* compiled out, or not an x86 build */
}

#endif

prt_result prt_sh_shade(const prt_asset* asset, prt_backend backend, const float* light_rgb,
                        uint32_t first_vertex, uint32_t vertex_count, float* out_rgb) {
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  if (backend == PRT_BACKEND_AUTO) backend = prt_context_backend(asset->context);
  switch (backend) {
    case PRT_BACKEND_CPU:
      return shade_scalar(asset, light_rgb, first_vertex, vertex_count, out_rgb);
    case PRT_BACKEND_SIMD:
      return shade_simd(asset, light_rgb, first_vertex, vertex_count, out_rgb);
    case PRT_BACKEND_GL: /* needs the game's GL context: prt_gl_sh_create */
      return PRT_ERROR_UNSUPPORTED_BACKEND;
    case PRT_BACKEND_AUTO:
      break;
  }
  return PRT_ERROR_INVALID_ARGUMENT;
}
