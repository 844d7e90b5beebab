/* SPDX-License-Identifier: MIT */
/* The `pose` functions of prt_pose_asset.h on the PSTR view the load checked (pose_section.c):
 * features, coefficients and skin through the shared maths (pose_model.c), and transfer and
 * shading on the scalar reference (summed in double) or the AVX2 kernels (pose_simd.h). Read-only
 * on the asset, no allocation (the largest stack arrays are the skeleton's J matrices and a block
 * of q x 8 coefficients): safe on one asset from several threads at once. */
#include <math.h>
#include <string.h>

#include "pose_internal.h"
#include "pose_simd.h"
#include "techniques.h"

/* The PSTR view the load decoded, NULL without a PSTR section. */
static const prt_pose_view* pose_view(const prt_asset* asset) {
  return (const prt_pose_view*)prt_internal_view(asset, PRT_TECHNIQUE_POSE);
}

static prt_result check_range(const prt_pose_view* view, uint32_t first, uint32_t count) {
  if (first > view->info.vertex_count || count > view->info.vertex_count - first)
    return PRT_ERROR_INVALID_ARGUMENT;
  return PRT_OK;
}

/* The view of an asset and a checked pose: INVALID_ARGUMENT, NOT_FOUND or PRT_OK. */
static prt_result open_pose(const prt_asset* asset, const prt_pose_input* pose,
                            const prt_pose_view** view) {
  if (!asset || !pose) return PRT_ERROR_INVALID_ARGUMENT;
  *view = pose_view(asset);
  if (!*view) return PRT_ERROR_NOT_FOUND;
  return prt_pose_check_input(*view, pose);
}

prt_result prt_pose_get_info(const prt_asset* asset, prt_pose_info* out) {
  const prt_pose_view* view;
  if (!asset || !out || !prt_internal_struct_size_ok(out, PRT_POSE_INFO_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  view = pose_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  prt_internal_write_struct(out, &view->info, sizeof view->info);
  return PRT_OK;
}

/* n floats of joint j's record at `offset` into out + n j (when out is given). */
static void copy_joint_floats(const prt_pose_view* view, uint32_t j, uint32_t offset, uint32_t n,
                              float* out) {
  const uint64_t at = view->layout.joints + (uint64_t)PRT_BLOB_PSTR_JOINT_SIZE * j + offset;
  uint32_t i;
  if (!out) return;
  for (i = 0; i < n; ++i) out[n * j + i] = prt_blob_pstr_load_f32(view->data + at + 4u * i);
}

prt_result prt_pose_bind_pose(const prt_asset* asset, float* out_rotations, float* out_translations,
                              float* out_scales) {
  const prt_pose_view* view;
  uint32_t j;
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  view = pose_view(asset);
  if (!view) return PRT_ERROR_NOT_FOUND;
  for (j = 0; j < view->info.joint_count; ++j) {
    copy_joint_floats(view, j, PRT_BLOB_PSTR_JOINT_OFF_BIND_ROTATION, 4, out_rotations);
    copy_joint_floats(view, j, PRT_BLOB_PSTR_JOINT_OFF_TRANSLATION, 3, out_translations);
    copy_joint_floats(view, j, PRT_BLOB_PSTR_JOINT_OFF_SCALE, 3, out_scales);
  }
  return PRT_OK;
}

prt_result prt_pose_features(const prt_asset* asset, const prt_pose_input* pose,
                             float* out_features) {
  double features[PRT_POSE_MAX_FEATURES];
  const prt_pose_view* view;
  uint32_t f;
  prt_result r = open_pose(asset, pose, &view);
  if (r != PRT_OK) return r;
  if (!out_features) return PRT_ERROR_INVALID_ARGUMENT;
  prt_pose_features_d(view, pose, features);
  for (f = 0; f < view->info.feature_count; ++f) out_features[f] = (float)features[f];
  return PRT_OK;
}

/* The pose coordinates of a checked pose. */
static void coordinates_of(const prt_pose_view* view, const prt_pose_input* pose, double* z) {
  double features[PRT_POSE_MAX_FEATURES];
  prt_pose_features_d(view, pose, features);
  prt_pose_coordinates_d(view, features, z);
}

prt_result prt_pose_coefficients(const prt_asset* asset, const prt_pose_input* pose,
                                 float* out_coordinates, float* out_coefficients) {
  double z[PRT_POSE_MAX_FEATURES], row[PRT_POSE_MAX_COEFFICIENTS];
  const prt_pose_view* view;
  uint32_t i, k, c;
  prt_result r = open_pose(asset, pose, &view);
  if (r != PRT_OK) return r;
  coordinates_of(view, pose, z);
  if (out_coordinates)
    for (i = 0; i < view->info.pose_dims; ++i) out_coordinates[i] = prt_pose_to_float(z[i]);
  if (!out_coefficients) return PRT_OK;
  for (k = 0; k < view->info.basis_dims; ++k) {
    const uint32_t n2 = view->layout.coefficients;
    prt_pose_coefficients_d(view, z, k, 0, n2, row);
    for (c = 0; c < n2; ++c) out_coefficients[(size_t)k * n2 + c] = prt_pose_to_float(row[c]);
  }
  return PRT_OK;
}

prt_result prt_pose_skin(const prt_asset* asset, const prt_pose_input* pose, uint32_t first_vertex,
                         uint32_t vertex_count, float* out_positions, float* out_normals,
                         float* out_model_frame) {
  prt_pose_skeleton skeleton;
  const prt_pose_view* view;
  uint32_t v;
  int i, j;
  prt_result r = open_pose(asset, pose, &view);
  if (r != PRT_OK) return r;
  r = check_range(view, first_vertex, vertex_count);
  if (r != PRT_OK) return r;
  prt_pose_skeleton_of(view, pose, &skeleton);
  if (out_model_frame)
    for (i = 0; i < 3; ++i)
      for (j = 0; j < 4; ++j) out_model_frame[4 * i + j] = (float)skeleton.model_frame.m[i][j];
  for (v = 0; v < vertex_count && (out_positions || out_normals); ++v) {
    double position[3], normal[3];
    prt_pose_skin_vertex(view, &skeleton, first_vertex + v, position, normal);
    for (i = 0; i < 3; ++i) {
      if (out_positions) out_positions[3u * (size_t)v + i] = prt_pose_to_float(position[i]);
      if (out_normals) out_normals[3u * (size_t)v + i] = (float)normal[i];
    }
  }
  return PRT_OK;
}

/* ---- transfer and shading ---- */

/* What a transfer or shading call has worked out before its vertex loop. */
typedef struct pose_frame {
  const prt_pose_view* view;
  double z[PRT_POSE_MAX_FEATURES];
  prt_pose_skeleton skeleton; /* skinned only where a normal or the model frame is needed */
  const float* normals;       /* the caller's normals of the range, or NULL: skinned here */
  prt_pose_dc dc;             /* the learned t_00's clamp (SPEC §7.3) */
  double factor[PRT_POSE_MAX_COEFFICIENTS]; /* rho A_l / pi (model 1) */
} pose_frame;

/* U[v][k]'s stored value. */
static double value_at(const prt_pose_view* view, uint32_t v, uint32_t k) {
  const size_t index = (size_t)v * view->info.basis_dims + k;
  const uint8_t* values = view->data + view->layout.basis_values;
  return view->info.bits == 8 ? values[index] : prt_le_load_u16(values + 2u * index);
}

/* The model-frame normal of vertex first + i (model 1). */
static void normal_of(const pose_frame* frame, uint32_t first, uint32_t i, double normal[3]) {
  int a;
  if (frame->normals) {
    for (a = 0; a < 3; ++a) normal[a] = frame->normals[3u * (size_t)i + a];
    return;
  }
  prt_pose_skin_vertex(frame->view, &frame->skeleton, first + i, NULL, normal);
}

/* The residual model's exact basis terms of vertex first + i: factor_c y_c(n), C values. */
static void exact_terms(const pose_frame* frame, uint32_t first, uint32_t i, double* out) {
  double normal[3];
  uint32_t c;
  normal_of(frame, first, i, normal);
  prt_pose_basis_at_normal(frame->view->info.order, normal, out);
  for (c = 0; c < frame->view->layout.coefficients; ++c) out[c] *= frame->factor[c];
}

static int residual(const prt_pose_view* view) {
  return view->info.model == PRT_POSE_MODEL_RESIDUAL;
}

/* Features, coordinates, the skeleton when the model frame or the normals need it, factors. */
static void open_frame(const prt_pose_view* view, const prt_pose_input* pose, const float* normals,
                       int needs_model_frame, pose_frame* frame) {
  frame->view = view;
  frame->normals = normals;
  coordinates_of(view, pose, frame->z);
  if (needs_model_frame || (residual(view) && !normals))
    prt_pose_skeleton_of(view, pose, &frame->skeleton);
  if (residual(view)) prt_pose_exact_factors(view, frame->factor);
  prt_pose_dc_of(view, frame->z, &frame->dc);
}

void prt_pose_dc_of(const prt_pose_view* view, const double* z, prt_pose_dc* out) {
  const double unoccluded = (double)view->info.albedo * 0.28209479177387814; /* 1/(2 sqrt(pi)) */
  const uint64_t params = view->layout.basis_params;
  uint32_t k;
  out->base = 0.0;
  for (k = 0; k < view->info.basis_dims; ++k) {
    double y;
    prt_pose_coefficients_d(view, z, k, 0, 1, &y);
    out->base += prt_pose_f32(view, params + 8u * k) * y;
    out->weight[k] = prt_pose_f32(view, params + 8u * k + 4u) * y;
  }
  out->lo = view->info.model == PRT_POSE_MODEL_RESIDUAL ? -unoccluded : 0.0;
  out->hi = view->info.model == PRT_POSE_MODEL_RESIDUAL ? 0.0 : unoccluded;
}

double prt_pose_dc_correction(const prt_pose_view* view, const prt_pose_dc* dc, uint32_t v) {
  double t = dc->base;
  uint32_t k;
  for (k = 0; k < view->info.basis_dims; ++k) t += dc->weight[k] * value_at(view, v, k);
  return t < dc->lo ? dc->lo - t : t > dc->hi ? dc->hi - t : 0.0;
}

/* SPEC §7.3's clamp of t_00 after any backend's sums: transfer (rgb NULL) or radiance. */
static void clamp_dc(const pose_frame* frame, const float* light_rgb, uint32_t first,
                     uint32_t count, float* out) {
  const uint32_t n2 = frame->view->layout.coefficients;
  uint32_t v, ch;
  for (v = 0; v < count; ++v) {
    const double d = prt_pose_dc_correction(frame->view, &frame->dc, first + v);
    if (d == 0.0) continue;
    if (!light_rgb) {
      out[(size_t)v * n2] = prt_pose_to_float(out[(size_t)v * n2] + d);
    } else {
      for (ch = 0; ch < 3; ++ch)
        out[3u * (size_t)v + ch] = prt_pose_to_float(out[3u * (size_t)v + ch] + d * light_rgb[ch]);
    }
  }
}

/* y[k][c0 .. c0 + width) for every k, in double, PRT_POSE_SIMD_BLOCK per row. */
static void coefficient_block(const pose_frame* frame, uint32_t c0, uint32_t width,
                              double (*block)[PRT_POSE_SIMD_BLOCK]) {
  uint32_t k;
  for (k = 0; k < frame->view->info.basis_dims; ++k)
    prt_pose_coefficients_d(frame->view, frame->z, k, c0, width, block[k]);
}

/* The scalar reference: t[v][c] = sum_k U[v][k] y[k][c] (+ the exact part), summed in double. */
static void transfer_scalar(const pose_frame* frame, uint32_t first, uint32_t count, float* out) {
  double block[PRT_POSE_MAX_BASIS_DIMS][PRT_POSE_SIMD_BLOCK];
  double basis[PRT_POSE_MAX_COEFFICIENTS];
  const prt_pose_view* view = frame->view;
  const uint32_t n2 = view->layout.coefficients, q = view->info.basis_dims;
  const uint64_t params = view->layout.basis_params;
  uint32_t c0, v, k, c;
  for (c0 = 0; c0 < n2; c0 += PRT_POSE_SIMD_BLOCK) {
    const uint32_t width = n2 - c0 < PRT_POSE_SIMD_BLOCK ? n2 - c0 : PRT_POSE_SIMD_BLOCK;
    coefficient_block(frame, c0, width, block);
    for (v = 0; v < count; ++v) {
      double sum[PRT_POSE_SIMD_BLOCK] = {0};
      if (residual(view)) {
        exact_terms(frame, first, v, basis);
        for (c = 0; c < width; ++c) sum[c] = basis[c0 + c];
      }
      for (k = 0; k < q; ++k) {
        const double u = prt_pose_f32(view, params + 8u * k) +
                         prt_pose_f32(view, params + 8u * k + 4u) * value_at(view, first + v, k);
        for (c = 0; c < width; ++c) sum[c] += u * block[k][c];
      }
      for (c = 0; c < width; ++c) out[(size_t)v * n2 + c0 + c] = prt_pose_to_float(sum[c]);
    }
  }
}

/* The light in the model frame, L' = rotate(L, (W R_m)^T), and the folded weights
 * w_k[ch] = sum_c y[k][c] L'[c][ch]; exact[c][ch] = factor_c L'[c][ch] for model 1. */
static prt_result fold_light(const pose_frame* frame, const prt_pose_light* light, double (*w)[3],
                             double (*exact)[3]) {
  float rotation[9], model_light[3u * PRT_POSE_MAX_COEFFICIENTS];
  double row[PRT_POSE_MAX_COEFFICIENTS];
  const prt_pose_view* view = frame->view;
  const uint32_t n2 = view->layout.coefficients;
  uint32_t i, j, k, c, ch;
  prt_result r;
  for (i = 0; i < 3; ++i)
    for (j = 0; j < 3; ++j) {
      double wr = 0.0; /* (W R_m)[j][i], stored at [i][j]: the transpose */
      for (k = 0; k < 3; ++k) {
        const double wjk = light->world_from_character ? light->world_from_character[3 * j + k]
                                                       : (j == k ? 1.0 : 0.0);
        wr += wjk * frame->skeleton.model_frame.m[k][i];
      }
      rotation[3 * i + j] = (float)wr;
    }
  r = prt_sh_rotate(view->info.order, rotation, light->light_rgb, model_light, 3);
  if (r != PRT_OK) return r;
  for (k = 0; k < view->info.basis_dims; ++k) {
    prt_pose_coefficients_d(view, frame->z, k, 0, n2, row);
    for (ch = 0; ch < 3; ++ch) {
      double sum = 0.0;
      for (c = 0; c < n2; ++c) sum += row[c] * (double)model_light[3u * c + ch];
      w[k][ch] = sum;
    }
  }
  if (residual(view))
    for (c = 0; c < n2; ++c)
      for (ch = 0; ch < 3; ++ch) exact[c][ch] = frame->factor[c] * (double)model_light[3u * c + ch];
  return PRT_OK;
}

/* The exact part's radiance of vertex first + i (model 1). */
static void exact_radiance(const pose_frame* frame, const double (*exact)[3], uint32_t first,
                           uint32_t i, double rgb[3]) {
  double basis[PRT_POSE_MAX_COEFFICIENTS], normal[3];
  uint32_t c, ch;
  normal_of(frame, first, i, normal);
  prt_pose_basis_at_normal(frame->view->info.order, normal, basis);
  for (ch = 0; ch < 3; ++ch) {
    rgb[ch] = 0.0;
    for (c = 0; c < frame->view->layout.coefficients; ++c) rgb[ch] += basis[c] * exact[c][ch];
  }
}

static void shade_scalar(const pose_frame* frame, const double (*w)[3], const double (*exact)[3],
                         uint32_t first, uint32_t count, float* out_rgb) {
  const prt_pose_view* view = frame->view;
  const uint64_t params = view->layout.basis_params;
  uint32_t v, k, ch;
  for (v = 0; v < count; ++v) {
    double rgb[3] = {0.0, 0.0, 0.0};
    if (residual(view)) exact_radiance(frame, exact, first, v, rgb);
    for (k = 0; k < view->info.basis_dims; ++k) {
      const double u = prt_pose_f32(view, params + 8u * k) +
                       prt_pose_f32(view, params + 8u * k + 4u) * value_at(view, first + v, k);
      for (ch = 0; ch < 3; ++ch) rgb[ch] += u * w[k][ch];
    }
    for (ch = 0; ch < 3; ++ch) out_rgb[3u * (size_t)v + ch] = prt_pose_to_float(rgb[ch]);
  }
}

#if defined(PRT_HAS_X86_SIMD)

static int simd_usable(const prt_asset* asset) {
  return prt_internal_simd_isa(asset->context) >= PRT_SIMD_ISA_AVX2;
}

static const uint8_t* values_of(const prt_pose_view* view, uint32_t first) {
  return view->data + view->layout.basis_values +
         (size_t)first * view->info.basis_dims * (view->info.bits / 8u);
}

/* The exact part's float inputs (model 1): the joints' 3x3 skinning parts when the normals are
 * skinned, the factors, and the light folded with them when `exact` is given (shading). */
typedef struct pose_exact_inputs {
  float joint[(PRT_POSE_MAX_JOINTS + 1u) * 12u];
  float factor[PRT_POSE_MAX_COEFFICIENTS];
  float light[PRT_POSE_MAX_COEFFICIENTS * 3];
} pose_exact_inputs;

static void exact_job_of(const pose_frame* frame, const double (*exact)[3], uint32_t first,
                         pose_exact_inputs* in, prt_pose_exact_job* job) {
  const prt_pose_view* view = frame->view;
  uint32_t j, r, c, ch;
  job->order = view->info.order;
  job->skin = view->data + view->layout.skin + (uint64_t)PRT_BLOB_PSTR_SKIN_SIZE * first;
  job->normals = frame->normals;
  job->joint = in->joint;
  job->joint_count = view->info.joint_count;
  job->factor = in->factor;
  job->light = in->light;
  if (!frame->normals)
    for (j = 0; j <= view->info.joint_count; ++j)
      for (r = 0; r < 3; ++r)
        for (c = 0; c < 4; ++c)
          in->joint[12u * j + 4u * r + c] = c == 3 ? 0.0f
                                            : j < view->info.joint_count
                                                ? prt_pose_to_float(frame->skeleton.skin[j].m[r][c])
                                                : (r == c ? 1.0f : 0.0f);
  for (c = 0; c < view->layout.coefficients; ++c) {
    in->factor[c] = (float)frame->factor[c];
    for (ch = 0; ch < 3; ++ch)
      in->light[3u * c + ch] = exact ? prt_pose_to_float(exact[c][ch]) : 0.0f;
  }
}

static void transfer_simd(const pose_frame* frame, uint32_t first, uint32_t count, float* out) {
  double block[PRT_POSE_MAX_BASIS_DIMS][PRT_POSE_SIMD_BLOCK];
  float column[PRT_POSE_MAX_BASIS_DIMS * PRT_POSE_SIMD_BLOCK];
  pose_exact_inputs exact_in;
  prt_pose_exact_job exact_job;
  const prt_pose_view* view = frame->view;
  const uint32_t n2 = view->layout.coefficients, q = view->info.basis_dims;
  const uint64_t params = view->layout.basis_params;
  prt_pose_transfer_job job;
  uint32_t c0, k, c;
  job.values = values_of(view, first);
  job.bits = view->info.bits;
  job.stride = (size_t)q * (view->info.bits / 8u);
  job.basis_dims = q;
  job.column = column;
  job.out_stride = n2;
  for (c0 = 0; c0 < n2; c0 += PRT_POSE_SIMD_BLOCK) {
    job.width = n2 - c0 < PRT_POSE_SIMD_BLOCK ? n2 - c0 : PRT_POSE_SIMD_BLOCK;
    coefficient_block(frame, c0, job.width, block);
    for (c = 0; c < PRT_POSE_SIMD_BLOCK; ++c) {
      double bias = 0.0;
      for (k = 0; k < q; ++k) {
        const double y = c < job.width ? block[k][c] : 0.0;
        bias += prt_pose_f32(view, params + 8u * k) * y;
        column[PRT_POSE_SIMD_BLOCK * k + c] =
            prt_pose_to_float(prt_pose_f32(view, params + 8u * k + 4u) * y);
      }
      job.bias[c] = prt_pose_to_float(bias);
    }
    prt_pose_transfer_avx2(&job, count, out + c0);
  }
  if (!residual(view)) return;
  exact_job_of(frame, NULL, first, &exact_in, &exact_job);
  prt_pose_exact_transfer_avx2(&exact_job, count, out, n2);
}

static void shade_simd(const pose_frame* frame, const double (*w)[3], const double (*exact)[3],
                       uint32_t first, uint32_t count, float* out_rgb) {
  float weight[3][PRT_POSE_MAX_BASIS_DIMS];
  pose_exact_inputs exact_in;
  prt_pose_exact_job exact_job;
  const prt_pose_view* view = frame->view;
  const uint32_t q = view->info.basis_dims, padded = (q + 7u) / 8u * 8u;
  const uint64_t params = view->layout.basis_params;
  prt_pose_shade_job job;
  uint32_t k, ch;
  for (ch = 0; ch < 3; ++ch) {
    double bias = 0.0;
    for (k = 0; k < q; ++k) {
      bias += prt_pose_f32(view, params + 8u * k) * w[k][ch];
      weight[ch][k] = prt_pose_to_float(prt_pose_f32(view, params + 8u * k + 4u) * w[k][ch]);
    }
    for (; k < padded; ++k) weight[ch][k] = 0.0f;
    job.bias[ch] = prt_pose_to_float(bias);
    job.weight[ch] = weight[ch];
  }
  job.values = values_of(view, first);
  job.bits = view->info.bits;
  job.stride = (size_t)q * (view->info.bits / 8u);
  job.basis_dims = q;
  prt_pose_shade_avx2(&job, count, out_rgb);
  if (!residual(view)) return;
  exact_job_of(frame, exact, first, &exact_in, &exact_job);
  prt_pose_exact_shade_avx2(&exact_job, count, out_rgb);
}

#else

static int simd_usable(const prt_asset* asset) {
  (void)asset;
  return 0; /* compiled out, or not an x86 build */
}

static void transfer_simd(const pose_frame* frame, uint32_t first, uint32_t count, float* out) {
  transfer_scalar(frame, first, count, out); /* unreachable: simd_usable is 0 */
}

static void shade_simd(const pose_frame* frame, const double (*w)[3], const double (*exact)[3],
                       uint32_t first, uint32_t count, float* out_rgb) {
  shade_scalar(frame, w, exact, first, count, out_rgb); /* unreachable: simd_usable is 0 */
}

#endif

/* The backend a call runs on: PRT_BACKEND_CPU or PRT_BACKEND_SIMD in *out, or the error. AUTO
 * takes the context's backend, and the scalar one where the SIMD ISA lacks AVX2 (there is no
 * SSE4.1 kernel); SIMD asked for explicitly without AVX2 is unsupported. */
static prt_result resolve_backend(const prt_asset* asset, prt_backend backend, prt_backend* out) {
  const int automatic = backend == PRT_BACKEND_AUTO;
  if (automatic) backend = prt_context_backend(asset->context);
  switch (backend) {
    case PRT_BACKEND_CPU:
      *out = PRT_BACKEND_CPU;
      return PRT_OK;
    case PRT_BACKEND_SIMD:
      if (simd_usable(asset)) {
        *out = PRT_BACKEND_SIMD;
        return PRT_OK;
      }
      *out = PRT_BACKEND_CPU;
      return automatic ? PRT_OK : PRT_ERROR_UNSUPPORTED_BACKEND;
    case PRT_BACKEND_GL: /* no GL backend for `pose` */
      return PRT_ERROR_UNSUPPORTED_BACKEND;
    case PRT_BACKEND_AUTO:
      break;
  }
  return PRT_ERROR_INVALID_ARGUMENT;
}

prt_result prt_pose_transfer(const prt_asset* asset, prt_backend backend,
                             const prt_pose_input* pose, const float* normals,
                             uint32_t first_vertex, uint32_t vertex_count, float* out) {
  pose_frame frame;
  const prt_pose_view* view;
  prt_backend run;
  prt_result r;
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  r = resolve_backend(asset, backend, &run);
  if (r != PRT_OK) return r;
  r = open_pose(asset, pose, &view);
  if (r != PRT_OK) return r;
  if (!out && vertex_count > 0) return PRT_ERROR_INVALID_ARGUMENT;
  r = check_range(view, first_vertex, vertex_count);
  if (r != PRT_OK || vertex_count == 0) return r;
  open_frame(view, pose, normals, 0, &frame);
  if (run == PRT_BACKEND_SIMD)
    transfer_simd(&frame, first_vertex, vertex_count, out);
  else
    transfer_scalar(&frame, first_vertex, vertex_count, out);
  clamp_dc(&frame, NULL, first_vertex, vertex_count, out);
  return PRT_OK;
}

prt_result prt_pose_shade(const prt_asset* asset, prt_backend backend, const prt_pose_input* pose,
                          const prt_pose_light* light, uint32_t first_vertex, uint32_t vertex_count,
                          float* out_rgb) {
  double w[PRT_POSE_MAX_BASIS_DIMS][3], exact[PRT_POSE_MAX_COEFFICIENTS][3];
  pose_frame frame;
  const prt_pose_view* view;
  prt_backend run;
  prt_result r;
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  r = resolve_backend(asset, backend, &run);
  if (r != PRT_OK) return r;
  r = open_pose(asset, pose, &view);
  if (r != PRT_OK) return r;
  if (!light || !prt_internal_struct_size_ok(light, PRT_POSE_LIGHT_SIZE_1_0) || !light->light_rgb ||
      (!out_rgb && vertex_count > 0))
    return PRT_ERROR_INVALID_ARGUMENT;
  r = check_range(view, first_vertex, vertex_count);
  if (r != PRT_OK) return r;
  open_frame(view, pose, light->normals, 1, &frame);
  r = fold_light(&frame, light, w, exact);
  if (r != PRT_OK || vertex_count == 0) return r;
  if (run == PRT_BACKEND_SIMD)
    shade_simd(&frame, (const double(*)[3])w, (const double(*)[3])exact, first_vertex, vertex_count,
               out_rgb);
  else
    shade_scalar(&frame, (const double(*)[3])w, (const double(*)[3])exact, first_vertex,
                 vertex_count, out_rgb);
  /* L_00 is the same in every frame: the clamp needs no rotated light. */
  clamp_dc(&frame, light->light_rgb, first_vertex, vertex_count, out_rgb);
  return PRT_OK;
}

prt_result prt_pose_fold_shading(const prt_pose_view* view, const prt_pose_input* pose,
                                 const prt_pose_light* light, prt_pose_folded* out) {
  pose_frame frame;
  open_frame(view, pose, NULL, 1, &frame);
  out->skeleton = frame.skeleton;
  out->dc = frame.dc;
  out->light_dc[0] = light->light_rgb[0];
  out->light_dc[1] = light->light_rgb[1];
  out->light_dc[2] = light->light_rgb[2];
  return fold_light(&frame, light, out->weight, out->exact);
}
