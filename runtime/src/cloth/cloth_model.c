/* SPDX-License-Identifier: MIT */
/* The exact microcylinder model of docs/cloth/model.md in double, term by term: frames, angles,
 * Fresnel, one fibre's scattering, shadowing/masking and projected length, and the kernel of the
 * whole cloth. Safe at the extremes: every degenerate angle is defined, every division guarded. */
#include <math.h>

#include "cloth_model.h"

#define CLOTH_PI 3.14159265358979323846
/* The unit height of u(x) = exp(-x^2 / (2 beta^2)): 20 degrees. */
#define CLOTH_BETA (20.0 * CLOTH_PI / 180.0)
/* cos(theta_d) vanishes only when one direction runs along t and the other along -t; f_s cos
 * theta_i grows without bound towards there, and this floor keeps it finite within a fraction of
 * a float's resolution of that pair of directions. */
#define CLOTH_MIN_COS_THETA_D 1e-8
/* A warp whose part orthogonal to the normal is below this fraction of its length is taken as
 * parallel to it: float input leaves no usable direction there. */
#define CLOTH_MIN_WARP_SINE 1e-6

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* ---- Frames ---------------------------------------------------------------------------------- */

static int finite_vector(const float v[3], double out[3], double* out_length) {
  int i;
  for (i = 0; i < 3; ++i) {
    if (!isfinite(v[i])) return 0;
    out[i] = v[i];
  }
  *out_length = sqrt(dot3(out, out));
  return *out_length > 0.0;
}

int prt_cloth_unit_direction(const float in[3], double out[3]) {
  double length;
  int i;
  if (!finite_vector(in, out, &length)) return 0;
  for (i = 0; i < 3; ++i) out[i] /= length;
  return 1;
}

int prt_cloth_make_frame(const float normal[3], const float warp[3], prt_cloth_frame* out) {
  double w[3], w_length, along, u_length;
  int i;
  if (!prt_cloth_unit_direction(normal, out->n) || !finite_vector(warp, w, &w_length)) return 0;
  along = dot3(w, out->n);
  for (i = 0; i < 3; ++i) out->u[i] = w[i] - along * out->n[i];
  u_length = sqrt(dot3(out->u, out->u));
  if (!(u_length > CLOTH_MIN_WARP_SINE * w_length)) return 0;
  for (i = 0; i < 3; ++i) out->u[i] /= u_length;
  out->v[0] = out->n[1] * out->u[2] - out->n[2] * out->u[1];
  out->v[1] = out->n[2] * out->u[0] - out->n[0] * out->u[2];
  out->v[2] = out->n[0] * out->u[1] - out->n[1] * out->u[0];
  return 1;
}

/* Thread 1: x = u, y = v; thread 2: x = v, y = -u. */
static void thread_axes(const prt_cloth_frame* frame, int thread, double x[3], double y[3]) {
  int i;
  for (i = 0; i < 3; ++i) {
    x[i] = thread == 0 ? frame->u[i] : frame->v[i];
    y[i] = thread == 0 ? frame->v[i] : -frame->u[i];
  }
}

void prt_cloth_fibre_frame(const prt_cloth_frame* frame, int thread, double tau,
                           prt_cloth_fibre* out) {
  double x[3], y[3];
  const double c = cos(tau), s = sin(tau);
  int i;
  thread_axes(frame, thread, x, y);
  for (i = 0; i < 3; ++i) {
    out->t[i] = c * x[i] + s * frame->n[i];
    out->n[i] = -s * x[i] + c * frame->n[i];
    out->b[i] = y[i];
  }
}

/* ---- Angles ---------------------------------------------------------------------------------- */

/* psi and p from w's components along t and n'. */
static void projected_angle(double wt, double wn, double* psi, double* p) {
  const double r = sqrt(wt * wt + wn * wn);
  if (r > 0.0) {
    *psi = atan2(wt, wn);
    *p = wn > 0.0 ? fmin(wn / r, 1.0) : 0.0;
  } else {
    *psi = 0.0;
    *p = 1.0;
  }
}

/* theta, phi and m from w's components along t, n' and b. */
static void azimuth_elevation(double wt, double wn, double wb, prt_cloth_angles* a) {
  const double r = sqrt(wn * wn + wb * wb);
  a->cos_theta = r;
  a->theta = atan2(wt, r);
  if (r > 0.0) {
    a->phi = atan2(wb, wn);
    a->m = wn > 0.0 ? fmin(wn / r, 1.0) : 0.0;
  } else {
    a->phi = 0.0;
    a->m = 1.0;
  }
}

static void fibre_angles(double wt, double wn, double wb, prt_cloth_angles* a) {
  projected_angle(wt, wn, &a->psi, &a->p);
  azimuth_elevation(wt, wn, wb, a);
}

/* ---- One fibre ------------------------------------------------------------------------------- */

double prt_cloth_fresnel(double eta, double c) {
  double g2, g, a, b;
  if (!(c > 0.0)) c = 0.0;
  if (c > 1.0) c = 1.0;
  if (eta == 1.0) return 0.0; /* no interface */
  g2 = eta * eta - 1.0 + c * c;
  if (g2 <= 0.0) return 1.0; /* total internal reflection (eta < 1 only) */
  g = sqrt(g2);
  a = (g - c) / (g + c);
  b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

/* d wrapped into (-pi, pi] from (-2 pi, 2 pi). */
static double wrap_angle(double d) {
  if (d > CLOTH_PI) return d - 2.0 * CLOTH_PI;
  if (d <= -CLOTH_PI) return d + 2.0 * CLOTH_PI;
  return d;
}

/* M or P: (1 - u(d)) a b + u(d) min(a, b). */
static double shadowing(double d, double a, double b) {
  const double x = wrap_angle(d);
  const double u = exp(-x * x / (2.0 * CLOTH_BETA * CLOTH_BETA));
  return (1.0 - u) * a * b + u * fmin(a, b);
}

void prt_cloth_material_of(const prt_cloth_thread* thread, prt_cloth_material* out) {
  const double root_two_pi = sqrt(2.0 * CLOTH_PI);
  const double gs = thread->gamma_s, gv = thread->gamma_v;
  int c;
  out->coverage = thread->coverage;
  out->eta = thread->eta;
  out->kd = thread->kd;
  for (c = 0; c < 3; ++c) out->albedo[c] = thread->albedo[c];
  out->surface_scale = 1.0 / (2.0 * gs * gs);
  out->surface_norm = 1.0 / (gs * root_two_pi);
  out->volume_scale = 1.0 / (2.0 * gv * gv);
  out->volume_norm = 1.0 / (gv * root_two_pi);
}

/* f_s cos(theta_i) (RGB). The volume term's 1 / (cos theta_i + cos theta_o) is taken with the
 * cos theta_i beside it as a share in [0, 1] (0 when both vanish). */
static void fibre_scatter(const prt_cloth_material* mat, const prt_cloth_angles* in,
                          const prt_cloth_angles* out, double rgb[3]) {
  const double theta_h = 0.5 * (in->theta + out->theta);
  const double cos_d = cos(0.5 * (in->theta - out->theta));
  const double cos_half_phi = cos(0.5 * wrap_angle(in->phi - out->phi));
  const double fr = prt_cloth_fresnel(mat->eta, cos_d * cos_half_phi);
  const double ft = (1.0 - fr) * (1.0 - fr);
  const double h2 = theta_h * theta_h;
  const double gs = mat->surface_norm * exp(-h2 * mat->surface_scale);
  const double gv = mat->volume_norm * exp(-h2 * mat->volume_scale);
  const double cos_sum = in->cos_theta + out->cos_theta;
  const double share = cos_sum > 0.0 ? in->cos_theta / cos_sum : 0.0;
  const double floor_d = fmax(cos_d, CLOTH_MIN_COS_THETA_D);
  const double inv_cos2_d = 1.0 / (floor_d * floor_d);
  const double surface = fr * cos_half_phi * gs * in->cos_theta * inv_cos2_d;
  const double volume = ft * ((1.0 - mat->kd) * gv + mat->kd) * share * inv_cos2_d;
  int c;
  for (c = 0; c < 3; ++c) rgb[c] = surface + volume * mat->albedo[c];
}

void prt_cloth_fibre_scatter(const prt_cloth_thread* thread, const prt_cloth_fibre* fibre,
                             const double wi[3], const double wo[3], double out_rgb[3],
                             double* out_m, double* out_p) {
  prt_cloth_material mat;
  prt_cloth_angles in, out;
  prt_cloth_material_of(thread, &mat);
  fibre_angles(dot3(wi, fibre->t), dot3(wi, fibre->n), dot3(wi, fibre->b), &in);
  fibre_angles(dot3(wo, fibre->t), dot3(wo, fibre->n), dot3(wo, fibre->b), &out);
  fibre_scatter(&mat, &in, &out, out_rgb);
  *out_m = shadowing(in.phi - out.phi, in.m, out.m);
  *out_p = shadowing(in.psi - out.psi, in.p, out.p);
}

/* ---- The cloth ------------------------------------------------------------------------------- */

/* w's components along the tilted t and n' of an offset, from those along x_j and n. */
static void tilt(const prt_cloth_tangent_out* tangent, double dx, double dn, double* wt,
                 double* wn) {
  *wt = tangent->cos_tau * dx + tangent->sin_tau * dn;
  *wn = -tangent->sin_tau * dx + tangent->cos_tau * dn;
}

void prt_cloth_outgoing_of(const prt_cloth_weave* weave, const prt_cloth_frame* frame,
                           const double wo[3], prt_cloth_outgoing* out) {
  int j, i;
  for (i = 0; i < 3; ++i) out->n[i] = frame->n[i];
  out->above = dot3(wo, frame->n) > 0.0;
  for (j = 0; j < 2; ++j) {
    prt_cloth_thread_out* thread = &out->threads[j];
    double ox, oy, on;
    uint32_t k;
    thread_axes(frame, j, thread->x, thread->y);
    ox = dot3(wo, thread->x);
    oy = dot3(wo, thread->y);
    on = dot3(wo, frame->n);
    thread->count = weave->tangent_count[j];
    for (k = 0; k < thread->count; ++k) {
      prt_cloth_tangent_out* tangent = &thread->tangents[k];
      double wt, wn;
      tangent->cos_tau = cos(weave->offsets[j][k]);
      tangent->sin_tau = sin(weave->offsets[j][k]);
      tangent->multiplicity = weave->multiplicity[j][k];
      tilt(tangent, ox, on, &wt, &wn);
      fibre_angles(wt, wn, oy, &tangent->view);
    }
  }
}

/* For a unit wi above the surface: each offset's M P (0 where either vanishes) and, where it
 * does not, wi's angles; returns the sum of P over the thread's multiset. */
static double thread_terms(const prt_cloth_thread_out* thread, const double wi[3], double dn,
                           double mp[], prt_cloth_angles in[]) {
  const double dx = dot3(wi, thread->x), dy = dot3(wi, thread->y);
  double sum_p = 0.0;
  uint32_t k;
  for (k = 0; k < thread->count; ++k) {
    const prt_cloth_tangent_out* tangent = &thread->tangents[k];
    double wt, wn, p, m;
    mp[k] = 0.0;
    if (!(tangent->view.p > 0.0)) continue; /* then P = 0 for every light */
    tilt(tangent, dx, dn, &wt, &wn);
    projected_angle(wt, wn, &in[k].psi, &in[k].p);
    p = shadowing(in[k].psi - tangent->view.psi, in[k].p, tangent->view.p);
    sum_p += tangent->multiplicity * p;
    if (!(p > 0.0) || !(tangent->view.m > 0.0)) continue;
    azimuth_elevation(wt, wn, dy, &in[k]);
    m = shadowing(in[k].phi - tangent->view.phi, in[k].m, tangent->view.m);
    mp[k] = m * p;
  }
  return sum_p;
}

void prt_cloth_outgoing_kernel(const prt_cloth_material materials[2],
                               const prt_cloth_outgoing* outgoing, const double wi[3],
                               double out_rgb[3]) {
  const double dn = dot3(wi, outgoing->n);
  int j, c;
  out_rgb[0] = out_rgb[1] = out_rgb[2] = 0.0;
  if (!outgoing->above || !(dn > 0.0)) return;
  for (j = 0; j < 2; ++j) {
    const prt_cloth_thread_out* thread = &outgoing->threads[j];
    double mp[PRT_CLOTH_MAX_THREAD_TANGENTS], sum[3] = {0.0, 0.0, 0.0}, sum_p;
    prt_cloth_angles in[PRT_CLOTH_MAX_THREAD_TANGENTS];
    uint32_t k;
    if (!(materials[j].coverage > 0.0)) continue;
    sum_p = thread_terms(thread, wi, dn, mp, in);
    if (!(sum_p > 0.0)) continue;
    for (k = 0; k < thread->count; ++k) {
      double fs[3];
      if (!(mp[k] > 0.0)) continue;
      fibre_scatter(&materials[j], &in[k], &thread->tangents[k].view, fs);
      for (c = 0; c < 3; ++c) sum[c] += thread->tangents[k].multiplicity * mp[k] * fs[c];
    }
    for (c = 0; c < 3; ++c) out_rgb[c] += materials[j].coverage * sum[c] / sum_p;
  }
}

void prt_cloth_outgoing_weights(const prt_cloth_outgoing* outgoing, int thread, const double wi[3],
                                double* out_weights) {
  const prt_cloth_thread_out* th = &outgoing->threads[thread];
  const double dn = dot3(wi, outgoing->n);
  double mp[PRT_CLOTH_MAX_THREAD_TANGENTS], sum_p = 0.0;
  prt_cloth_angles in[PRT_CLOTH_MAX_THREAD_TANGENTS];
  uint32_t k;
  if (outgoing->above && dn > 0.0) sum_p = thread_terms(th, wi, dn, mp, in);
  for (k = 0; k < th->count; ++k) out_weights[k] = sum_p > 0.0 ? mp[k] / sum_p : 0.0;
}

void prt_cloth_kernel_d(const prt_cloth_params* params, const prt_cloth_weave* weave,
                        const prt_cloth_frame* frame, const double wi[3], const double wo[3],
                        double out_rgb[3]) {
  prt_cloth_material materials[2];
  prt_cloth_outgoing outgoing;
  prt_cloth_material_of(&params->threads[0], &materials[0]);
  prt_cloth_material_of(&params->threads[1], &materials[1]);
  prt_cloth_outgoing_of(weave, frame, wo, &outgoing);
  prt_cloth_outgoing_kernel(materials, &outgoing, wi, out_rgb);
}
