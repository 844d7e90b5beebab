/* SPDX-License-Identifier: MIT */
/* `cloth` shading (prt_cloth_shade, docs/cloth/method.md): the per-call preparation of the light
 * and the fabric, and the scalar reference of the method in double. For each sample, each
 * distinct tangent of each thread and each lobe that survives culling:
 *   L += a_j m_tau rgb_k (T_s I_s + T_v (1 - k_d) A I_v + T k_d A I_k)
 * with I_* the lobe integrals of cloth_integrals.c and T_* the shadowing/masking weight read from
 * the fabric's table: T for the isotropic part, and for the two lobed parts a blend of T and its
 * specular-cone restriction T_c by how much narrower the part's lobe is than the light's. */
#include <math.h>
#include <string.h>

#include "../techniques.h"
#include "cloth_shade_internal.h"
#include "cloth_shade_simd.h"

#define PRT_CLOTH_KNOWN_FLAGS                                                          \
  (PRT_CLOTH_KEEP_HIDDEN_LOBES | PRT_CLOTH_KEEP_WEAK_LOBES | PRT_CLOTH_NO_CONE_TABLE | \
   PRT_CLOTH_NO_FRAME_CACHE | PRT_CLOTH_TANGENT_COPIES | PRT_CLOTH_NO_LOBE_SHARING |   \
   PRT_CLOTH_PAPER_FLAGS)

prt_result prt_cloth_method_of(const prt_cloth_settings* settings, prt_cloth_method* out) {
  prt_cloth_settings s;
  memset(&s, 0, sizeof s);
  if (settings) {
    if (!prt_internal_struct_size_ok(settings, PRT_CLOTH_SETTINGS_SIZE_1_0))
      return PRT_ERROR_INVALID_ARGUMENT;
    s = *settings;
  }
  if ((s.flags & ~PRT_CLOTH_KNOWN_FLAGS) != 0 || !(s.weak_lobe >= 0.0f && s.weak_lobe < 1.0f) ||
      s.theta_segments > PRT_CLOTH_MAX_THETA_SEGMENTS || s.phi_nodes > PRT_CLOTH_MAX_PHI_NODES)
    return PRT_ERROR_INVALID_ARGUMENT;
  out->flags = s.flags;
  out->weak_lobe = s.weak_lobe > 0.0f ? s.weak_lobe : PRT_CLOTH_DEFAULT_WEAK_LOBE;
  out->theta_segments = s.theta_segments ? s.theta_segments : PRT_CLOTH_DEFAULT_THETA_SEGMENTS;
  out->phi_nodes = s.phi_nodes ? s.phi_nodes : PRT_CLOTH_DEFAULT_PHI_NODES;
  return PRT_OK;
}

/* A lobe's power: its integral over the sphere times its mean amplitude. */
static double lobe_power(const prt_cloth_lobe* lobe) {
  const double lambda = lobe->sharpness;
  const double mean = ((double)lobe->rgb[0] + lobe->rgb[1] + lobe->rgb[2]) / 3.0;
  return mean * 2.0 * 3.14159265358979323846 / lambda * -expm1(-2.0 * lambda);
}

void prt_cloth_prepare_light(const prt_cloth_view* view, const prt_cloth_light* light,
                             const prt_cloth_method* method, prt_cloth_light_prep* out) {
  const double lmin = view->header.lambda_min, lmax = view->header.lambda_max;
  const uint32_t levels = view->header.levels;
  double total = 0.0;
  uint32_t k;
  for (k = 0; k < light->lobe_count; ++k) total += lobe_power(&light->lobes[k]);
  out->count = 0;
  for (k = 0; k < light->lobe_count; ++k) {
    const prt_cloth_lobe* lobe = &light->lobes[k];
    prt_cloth_lobe_prep* p = &out->lobes[out->count];
    const double power = lobe_power(lobe);
    double norm, level = 0.0;
    if (power <= 0.0) continue;
    if (!(method->flags & PRT_CLOTH_KEEP_WEAK_LOBES) && power < method->weak_lobe * total) continue;
    norm = sqrt((double)lobe->axis[0] * lobe->axis[0] + (double)lobe->axis[1] * lobe->axis[1] +
                (double)lobe->axis[2] * lobe->axis[2]);
    p->axis[0] = lobe->axis[0] / norm;
    p->axis[1] = lobe->axis[1] / norm;
    p->axis[2] = lobe->axis[2] / norm;
    p->lambda = lobe->sharpness;
    p->rgb[0] = lobe->rgb[0];
    p->rgb[1] = lobe->rgb[1];
    p->rgb[2] = lobe->rgb[2];
    if (levels > 1 && lmax > lmin) level = log(p->lambda / lmin) / log(lmax / lmin) * (levels - 1);
    p->level = fmin(fmax(level, 0.0), (double)(levels - 1));
    ++out->count;
  }
}

void prt_cloth_prepare_fabric(const prt_cloth_view* view, uint32_t fabric,
                              const prt_cloth_params* params, prt_cloth_fabric_prep* out) {
  prt_cloth_fabric_record record;
  int thread;
  prt_cloth_read_fabric(view, fabric, &record);
  out->params = params ? *params : record.params;
  out->tangent_count = 0;
  for (thread = 0; thread < 2; ++thread) {
    uint32_t i;
    for (i = 0; i < record.tangent_count[thread]; ++i) {
      prt_cloth_tangent_record t;
      prt_cloth_tangent_prep* p = &out->tangents[out->tangent_count++];
      prt_cloth_read_tangent(view, record.first_tangent[thread] + i, &t);
      p->thread = thread;
      p->tau = t.offset;
      p->sin_tau = sin(p->tau);
      p->cos_tau = cos(p->tau);
      p->weight = (double)out->params.threads[thread].coverage * t.multiplicity;
      p->mirror = t.mirror != 0;
      prt_cloth_read_factor(view, t.table, 0, &p->full);
      prt_cloth_read_factor(view, t.table, 1, &p->cone);
    }
  }
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double dot_rank(const double* a, const double* b, uint32_t rank) {
  double s = 0.0;
  uint32_t r;
  for (r = 0; r < rank; ++r) s += a[r] * b[r];
  return fmin(1.0, fmax(0.0, s)); /* a weight: quantisation must not push it outside [0, 1] */
}

/* Whether lobe k contributes to a sample of this normal at all (with the paper's phi domain, a
 * lobe below the horizon does). */
static int lobe_visible(const prt_cloth_lobe_prep* lobe, const double n[3], uint32_t flags) {
  const double d = dot3(lobe->axis, n);
  if ((flags & (PRT_CLOTH_KEEP_HIDDEN_LOBES | PRT_CLOTH_PAPER_PHI_DOMAIN)) || d >= 0.0) return 1;
  return exp(lobe->lambda * (sqrt(1.0 - d * d) - 1.0)) >= PRT_CLOTH_HIDDEN_LOBE;
}

/* The blend of T and T_c for a part whose lobe in theta_h has width gamma. */
static double part_weight(double t, double t_cone, double lambda, double gamma, uint32_t flags) {
  const double lobe = 1.0 / lambda, band = 4.0 * gamma * gamma;
  if (flags & PRT_CLOTH_NO_CONE_TABLE) return t;
  return (lobe * t_cone + band * t) / (lobe + band);
}

/* The fibre's angles of a unit direction. */
static void fibre_angles(const prt_cloth_fibre* f, const double w[3], double* theta, double* phi) {
  *theta = asin(fmin(1.0, fmax(-1.0, dot3(w, f->t))));
  *phi = atan2(dot3(w, f->b), dot3(w, f->n));
}

/* One tangent's contribution to one sample. */
static void shade_tangent(const prt_cloth_view* view, const prt_cloth_fabric_prep* fabric,
                          const prt_cloth_tangent_prep* tp, const prt_cloth_light_prep* light,
                          const prt_cloth_method* method, const prt_cloth_frame* frame,
                          const double wo[3], double rgb[3]) {
  const prt_cloth_thread* thread = &fabric->params.threads[tp->thread];
  double cv[3], v_full[PRT_BLOB_CLTH_MAX_RANK], v_cone[PRT_BLOB_CLTH_MAX_RANK];
  double u_full[PRT_BLOB_CLTH_MAX_RANK], u_cone[PRT_BLOB_CLTH_MAX_RANK];
  prt_cloth_fibre fibre;
  prt_cloth_lobe_fibre lf;
  int flip;
  uint32_t k;
  prt_cloth_fibre_frame(frame, tp->thread, tp->tau, &fibre);
  fibre_angles(&fibre, wo, &lf.theta_o, &lf.phi_o);
  lf.sin_tau = tp->sin_tau;
  lf.cos_tau = tp->cos_tau;
  prt_cloth_canonical(frame, tp->thread, tp->mirror, wo, cv);
  flip = cv[1] < 0.0;
  cv[1] = fabs(cv[1]);
  prt_cloth_view_factor(view, &tp->full, cv, v_full);
  prt_cloth_view_factor(view, &tp->cone, cv, v_cone);
  for (k = 0; k < light->count; ++k) {
    const prt_cloth_lobe_prep* lobe = &light->lobes[k];
    double cl[3], integrals[3], t, t_cone, ws, wv, c;
    int i;
    if (!lobe_visible(lobe, frame->n, method->flags)) continue;
    prt_cloth_canonical(frame, tp->thread, tp->mirror, lobe->axis, cl);
    if (flip) cl[1] = -cl[1];
    prt_cloth_lobe_factor(view, &tp->full, cl, lobe->level, u_full);
    prt_cloth_lobe_factor(view, &tp->cone, cl, lobe->level, u_cone);
    t = dot_rank(u_full, v_full, tp->full.rank);
    t_cone = dot_rank(u_cone, v_cone, tp->cone.rank);
    lf.lambda = lobe->lambda;
    fibre_angles(&fibre, lobe->axis, &lf.theta_k, &lf.phi_k);
    prt_cloth_lobe_integrals(&lf, thread, method, integrals);
    ws = part_weight(t, t_cone, lobe->lambda, thread->gamma_s, method->flags);
    wv = part_weight(t, t_cone, lobe->lambda, thread->gamma_v, method->flags);
    for (i = 0; i < 3; ++i) {
      c = ws * integrals[0] + thread->albedo[i] * ((1.0 - thread->kd) * wv * integrals[1] +
                                                   thread->kd * t * integrals[2]);
      rgb[i] += tp->weight * lobe->rgb[i] * c;
    }
  }
}

/* The scalar reference: samples [first, first + count). */
static void shade_scalar(const prt_cloth_view* view, const prt_cloth_fabric_prep* fabric,
                         const prt_cloth_light_prep* light, const prt_cloth_method* method,
                         const prt_cloth_pixels* pixels, uint32_t first, uint32_t count,
                         float* out_rgb) {
  uint32_t s, i;
  for (s = 0; s < count; ++s) {
    const size_t at = 3u * ((size_t)first + s);
    double rgb[3] = {0.0, 0.0, 0.0}, wo[3], len;
    prt_cloth_frame frame;
    if (prt_cloth_make_frame(pixels->normals + at, pixels->warps + at, &frame)) {
      wo[0] = pixels->views[at], wo[1] = pixels->views[at + 1], wo[2] = pixels->views[at + 2];
      len = sqrt(dot3(wo, wo));
      if (len > 0.0 && isfinite(len)) {
        wo[0] /= len, wo[1] /= len, wo[2] /= len;
        if (dot3(wo, frame.n) > 0.0)
          for (i = 0; i < fabric->tangent_count; ++i)
            shade_tangent(view, fabric, &fabric->tangents[i], light, method, &frame, wo, rgb);
      }
    }
    for (i = 0; i < 3; ++i) out_rgb[3u * (size_t)s + i] = (float)rgb[i];
  }
}

/* Eq. 4's g_u as printed, exp(-x^2 / gamma^2) / (sqrt(pi) gamma), is a Gaussian of standard
 * deviation gamma / sqrt 2: the fabric's lobed parts with their gammas so narrowed. */
static void narrow_gu(prt_cloth_params* params) {
  int j;
  for (j = 0; j < 2; ++j) {
    params->threads[j].gamma_s = (float)(params->threads[j].gamma_s / sqrt(2.0));
    params->threads[j].gamma_v = (float)(params->threads[j].gamma_v / sqrt(2.0));
  }
}

#if defined(PRT_HAS_X86_SIMD)
static int simd_usable(const prt_asset* asset) {
  return prt_internal_simd_isa(asset->context) >= PRT_SIMD_ISA_AVX2;
}
#else
static int simd_usable(const prt_asset* asset) {
  (void)asset;
  return 0; /* compiled out, or not an x86 build */
}
#endif

/* The backend a call runs on: PRT_BACKEND_CPU or PRT_BACKEND_SIMD in *out, or the error. AUTO
 * takes the context's backend, and the scalar reference where the SIMD ISA lacks AVX2 (there is
 * no SSE4.1 kernel) or the settings ask for the paper's study switches (scalar only); SIMD asked
 * for explicitly in either case is unsupported. */
static prt_result resolve_backend(const prt_asset* asset, prt_backend backend, uint32_t flags,
                                  prt_backend* out) {
  const int automatic = backend == PRT_BACKEND_AUTO;
  if (automatic) backend = prt_context_backend(asset->context);
  switch (backend) {
    case PRT_BACKEND_CPU:
      *out = PRT_BACKEND_CPU;
      return PRT_OK;
    case PRT_BACKEND_SIMD:
      if (simd_usable(asset) && !(flags & PRT_CLOTH_PAPER_FLAGS)) {
        *out = PRT_BACKEND_SIMD;
        return PRT_OK;
      }
      *out = PRT_BACKEND_CPU;
      return automatic ? PRT_OK : PRT_ERROR_UNSUPPORTED_BACKEND;
    case PRT_BACKEND_GL: /* a prt_gl_cloth_shader shades on GL */
      return PRT_ERROR_UNSUPPORTED_BACKEND;
    case PRT_BACKEND_AUTO:
      break;
  }
  return PRT_ERROR_INVALID_ARGUMENT;
}

prt_result prt_cloth_shade(const prt_asset* asset, prt_backend backend, uint32_t fabric,
                           const prt_cloth_params* params, const prt_cloth_light* light,
                           const prt_cloth_settings* settings, const prt_cloth_pixels* pixels,
                           uint32_t first, uint32_t count, float* out_rgb) {
  const prt_cloth_view* view;
  prt_cloth_method method;
  prt_cloth_light_prep light_prep;
  prt_cloth_fabric_prep fabric_prep;
  prt_backend run;
  prt_result r;
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  view = (const prt_cloth_view*)prt_internal_view(asset, PRT_TECHNIQUE_CLOTH);
  if (!view) return PRT_ERROR_NOT_FOUND;
  if (fabric >= view->header.fabrics) return PRT_ERROR_NOT_FOUND;
  if (!pixels || !prt_internal_struct_size_ok(pixels, PRT_CLOTH_PIXELS_SIZE_1_0) ||
      (count > 0 && (!out_rgb || !pixels->normals || !pixels->warps || !pixels->views)))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (count > UINT32_MAX - first) return PRT_ERROR_INVALID_ARGUMENT;
  if (params && prt_cloth_params_validate(params) != PRT_OK) return PRT_ERROR_INVALID_ARGUMENT;
  if (prt_cloth_light_validate(light) != PRT_OK) return PRT_ERROR_INVALID_ARGUMENT;
  r = prt_cloth_method_of(settings, &method);
  if (r != PRT_OK) return r;
  r = resolve_backend(asset, backend, method.flags, &run);
  if (r != PRT_OK) return r;
  prt_cloth_prepare_light(view, light, &method, &light_prep);
  prt_cloth_prepare_fabric(view, fabric, params, &fabric_prep);
#if defined(PRT_HAS_X86_SIMD)
  if (run == PRT_BACKEND_SIMD) {
    prt_cloth_shade_avx2(view, &fabric_prep, &light_prep, &method, pixels, first, count, out_rgb);
    return PRT_OK;
  }
#endif
  if (method.flags & PRT_CLOTH_PAPER_NARROW_GU) narrow_gu(&fabric_prep.params);
  shade_scalar(view, &fabric_prep, &light_prep, &method, pixels, first, count, out_rgb);
  return PRT_OK;
}
