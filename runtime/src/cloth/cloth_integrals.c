/* SPDX-License-Identifier: MIT */
/* The integral of one spherical-Gaussian lobe against one fibre's scattering over the cloth's
 * upper hemisphere and the fibre's front (docs/cloth/method.md, "The lobe integrals"), in
 * double: the scalar reference the SIMD and GL backends follow step by step.
 *
 * In the fibre's angles the lobe factors exactly into exp(lambda (cos(theta - theta_k) - 1))
 * times a von Mises profile in phi of concentration lambda cos(theta) cos(theta_k). Each part of
 * f_s has a Gaussian in theta (the surface and volume lobes in theta_h) or none (the isotropic
 * volume term), so each part is integrated over its own theta window: the product of the lobe's
 * and the part's Gaussians, clipped to where the domain is not empty and split where the horizon
 * starts to cut the fibre's front (theta = 0 for a tilted fibre). The window is cut into
 * segments; the integrand divided by that Gaussian is taken linear on each segment and the
 * Gaussian's moments over it are exact (erf). At each segment end the phi integral runs over the
 * part of the front above the horizon with Gauss-Legendre nodes placed through the Gaussian
 * approximation of the von Mises profile (its inverse CDF), so a sharp lobe gets its nodes where
 * it is, and a clipped one where it is left.
 *
 * The PRT_CLOTH_PAPER_* study switches put back paper 003's printed rules (the phi domain, the
 * theta segments, Eq. 13's Fresnel expansion) for measuring what each fix gains. */
#include <math.h>

#include "cloth_shade_internal.h"

#define PI 3.14159265358979323846
#define HALF_PI 1.57079632679489661923
#define SQRT_2PI 2.50662827463100050242
#define WINDOW_SIGMAS 4.0 /* theta windows: the product Gaussian's mean +- this many sd */
#define PHI_SIGMAS 6.0    /* phi windows of a sharp von Mises profile */
#define PAPER_SEGMENTS 6  /* paper 003's theta segments over [-pi/2, pi/2] */

/* Gauss-Legendre nodes and weights on [-1, 1] for n = 1..8 (row n - 1). */
static const double kNodes[PRT_CLOTH_MAX_PHI_NODES][PRT_CLOTH_MAX_PHI_NODES] = {
    {0.0},
    {-0.5773502691896257, 0.5773502691896257},
    {-0.7745966692414834, 0.0, 0.7745966692414834},
    {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526},
    {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640},
    {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969, 0.2386191860831969,
     0.6612093864662645, 0.9324695142031521},
    {-0.9491079123427585, -0.7415311855993945, -0.4058451513773972, 0.0, 0.4058451513773972,
     0.7415311855993945, 0.9491079123427585},
    {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
     0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363},
};
static const double kWeights[PRT_CLOTH_MAX_PHI_NODES][PRT_CLOTH_MAX_PHI_NODES] = {
    {2.0},
    {1.0, 1.0},
    {0.5555555555555556, 0.8888888888888888, 0.5555555555555556},
    {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538},
    {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
     0.2369268850561891},
    {0.1713244923791704, 0.3607615730481386, 0.4679139345726910, 0.4679139345726910,
     0.3607615730481386, 0.1713244923791704},
    {0.1294849661688697, 0.2797053914892766, 0.3818300505051189, 0.4179591836734694,
     0.3818300505051189, 0.2797053914892766, 0.1294849661688697},
    {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
     0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763},
};

static double normal_cdf(double z) {
  return 0.5 * erfc(-z * 0.70710678118654752440);
}

/* The inverse of normal_cdf on (0, 1): Acklam's rational approximation and one Halley step. */
static double normal_quantile(double p) {
  static const double a[6] = {-3.969683028665376e+01, 2.209460984245205e+02,
                              -2.759285104469687e+02, 1.383577518672690e+02,
                              -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[5] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                              6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[6] = {-7.784894002430293e-03, -3.223964580411365e-01,
                              -2.400758277161838e+00, -2.549732539343734e+00,
                              4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[4] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                              3.754408661907416e+00};
  double q, r, x, e, u;
  if (p <= 0.0) return -40.0;
  if (p >= 1.0) return 40.0;
  if (p < 0.02425) {
    q = sqrt(-2.0 * log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  } else if (p > 1.0 - 0.02425) {
    q = sqrt(-2.0 * log(1.0 - p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  } else {
    q = p - 0.5;
    r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  }
  e = normal_cdf(x) - p;
  u = e * SQRT_2PI * exp(0.5 * x * x);
  return x - u / (1.0 + 0.5 * x * u);
}

/* The theta range where the domain is not empty, and the half-width of its phi range at theta:
 * the front |phi| < pi/2 intersected with the hemisphere
 * sin(tau) sin(theta) + cos(tau) cos(theta) cos(phi) > 0 (the paper's domain: the front alone). */
static void theta_support(const prt_cloth_lobe_fibre* lf, uint32_t flags, double* lo, double* hi) {
  const double tilt = asin(fmin(1.0, fabs(lf->sin_tau)));
  if (flags & PRT_CLOTH_PAPER_PHI_DOMAIN) {
    *lo = -HALF_PI, *hi = HALF_PI;
    return;
  }
  *lo = lf->sin_tau > 0.0 ? -(HALF_PI - tilt) : -HALF_PI;
  *hi = lf->sin_tau < 0.0 ? HALF_PI - tilt : HALF_PI;
}

static double phi_half_width(const prt_cloth_lobe_fibre* lf, uint32_t flags, double theta) {
  double c;
  if (flags & PRT_CLOTH_PAPER_PHI_DOMAIN) return HALF_PI;
  if (lf->cos_tau < 1e-9) return lf->sin_tau * sin(theta) > 0.0 ? HALF_PI : 0.0;
  c = -lf->sin_tau * tan(theta) / lf->cos_tau;
  if (c <= 0.0) return HALF_PI;
  return c >= 1.0 ? 0.0 : acos(c);
}

double prt_cloth_fresnel_schlick(double eta, double c, int cube) {
  const double f0 = (1.0 - eta) * (1.0 - eta) / ((1.0 + eta) * (1.0 + eta));
  const double m = 1.0 - c;
  /* (1 - c)^5 = sum_l C(5, l) (-c)^l, printed to l = 3 */
  const double power = cube ? 1.0 - c * (5.0 - c * (10.0 - 10.0 * c)) : m * m * m * m * m;
  return f0 + (1.0 - f0) * power;
}

/* The Fresnel term at a phi node: exact, or Schlick's as paper 003's switches ask. `y` is
 * cos(phi_d / 2), `cos_phi_d` cos(phi_d). */
static double fresnel_at(const prt_cloth_thread* thread, uint32_t flags, double cos_d, double y,
                         double cos_phi_d) {
  if (!(flags & PRT_CLOTH_PAPER_FRESNEL)) return prt_cloth_fresnel(thread->eta, cos_d * y);
  return prt_cloth_fresnel_schlick(thread->eta,
                                   cos_d * (flags & PRT_CLOTH_PAPER_SCHLICK_ANGLE ? cos_phi_d : y),
                                   (flags & PRT_CLOTH_PAPER_SCHLICK_CUBE) != 0);
}

/* The phi integrals at theta of the lobe's von Mises profile times the surface part's
 * F_r(c) cos(phi_d/2) (out[0]) and the volume parts' (1 - F_r(c))^2 (out[1]). */
static void phi_integrals(const prt_cloth_lobe_fibre* lf, const prt_cloth_thread* thread,
                          const prt_cloth_method* method, double theta, double out[2]) {
  const uint32_t nodes = method->phi_nodes;
  const double kappa = lf->lambda * cos(theta) * cos(lf->theta_k);
  const double half = phi_half_width(lf, method->flags, theta);
  const double cos_d = cos(0.5 * (theta - lf->theta_o));
  const double* x = kNodes[nodes - 1];
  const double* w = kWeights[nodes - 1];
  double sd, a, b, ua, ub;
  uint32_t q;
  out[0] = out[1] = 0.0;
  if (half <= 0.0) return;
  sd = kappa > 0.0 ? 1.0 / sqrt(kappa) : INFINITY;
  if (4.0 * sd >= HALF_PI) {
    a = -half, b = half, ua = ub = 0.0; /* wide: plain nodes over the whole range */
  } else {
    a = fmax(-half, lf->phi_k - PHI_SIGMAS * sd);
    b = fmin(half, lf->phi_k + PHI_SIGMAS * sd);
    if (b <= a) return;
    ua = normal_cdf((a - lf->phi_k) / sd);
    ub = normal_cdf((b - lf->phi_k) / sd);
  }
  for (q = 0; q < nodes; ++q) {
    double phi, weight, cos_phi_d, y, f;
    if (ua == ub) {
      phi = 0.5 * (a + b) + 0.5 * (b - a) * x[q];
      weight = 0.5 * (b - a) * w[q];
    } else {
      const double z = normal_quantile(ua + 0.5 * (ub - ua) * (x[q] + 1.0));
      phi = lf->phi_k + sd * z;
      weight = 0.5 * (ub - ua) * w[q] * sd * SQRT_2PI * exp(0.5 * z * z);
    }
    weight *= exp(kappa * (cos(phi - lf->phi_k) - 1.0));
    cos_phi_d = cos(phi - lf->phi_o);
    y = sqrt(fmax(0.0, 0.5 * (1.0 + cos_phi_d))); /* cos(phi_d / 2), |phi_d| <= pi */
    f = fresnel_at(thread, method->flags, cos_d, y, cos_phi_d);
    out[0] += weight * f * y;
    out[1] += weight * (1.0 - f) * (1.0 - f);
  }
}

/* log of the part's exact theta profile: the lobe's, times the unit-area Gaussian of theta_h
 * for the surface (part 0) and volume (part 1) lobes. */
static double log_theta_profile(const prt_cloth_lobe_fibre* lf, double gamma, double theta) {
  double v = lf->lambda * (cos(theta - lf->theta_k) - 1.0);
  if (gamma > 0.0) {
    const double h = 0.5 * (theta + lf->theta_o);
    v += -h * h / (2.0 * gamma * gamma) - log(gamma * SQRT_2PI);
  }
  return v;
}

/* The integrands of the parts in `mask` (bit p: part p) at theta, each divided by the Gaussian
 * N(mu, sd) the window integrates against, into h[p]. */
static void integrands_over_gaussian(const prt_cloth_lobe_fibre* lf, const prt_cloth_thread* thread,
                                     const prt_cloth_method* method, unsigned mask, double mu,
                                     double sd, double theta, double h[3]) {
  const double z = (theta - mu) / sd;
  const double log_n = -0.5 * z * z - log(sd * SQRT_2PI);
  const double ct = cos(theta), cd = cos(0.5 * (theta - lf->theta_o));
  double phi[2], base;
  int part;
  h[0] = h[1] = h[2] = 0.0;
  if (ct <= 0.0 || cd <= 1e-12) return; /* grazing: the measure vanishes */
  phi_integrals(lf, thread, method, theta, phi);
  base = ct * ct / (cd * cd);
  for (part = 0; part < 3; ++part) {
    const double gamma = part == 0 ? thread->gamma_s : part == 1 ? thread->gamma_v : 0.0;
    if (!(mask & (1u << part))) continue;
    h[part] = exp(log_theta_profile(lf, gamma, theta) - log_n) * base * phi[part == 0 ? 0 : 1];
    if (part > 0) h[part] /= ct + cos(lf->theta_o);
  }
}

/* The end of piece [lo, hi] where the domain pinches: towards the end of the support on the
 * side the tilt lowers, the phi range closes like the square root of the distance to it, which
 * segments of equal length follow badly; boundaries graded quadratically towards that end make it
 * linear in the segment index. -1: lo pinches, +1: hi, 0: neither. */
static int pinched_end(const prt_cloth_lobe_fibre* lf, double support_lo, double support_hi,
                       double lo, double hi) {
  if (lf->sin_tau > 0.0 && lo <= support_lo) return -1;
  if (lf->sin_tau < 0.0 && hi >= support_hi) return 1;
  return 0;
}

static double boundary(double lo, double hi, uint32_t s, uint32_t segments, int pinch) {
  const double f = (double)s / segments;
  if (pinch < 0) return lo + (hi - lo) * f * f;
  if (pinch > 0) return hi - (hi - lo) * (1.0 - f) * (1.0 - f);
  return lo + (hi - lo) * f;
}

/* Moments of the Gaussian N(mu, sd) over [a, b] about c: out[k] = integral of N (theta - c)^k,
 * k = 0, 1, 2, from its CDF and density at the ends (za, zb in sd units from mu). */
static void gaussian_moments(double mu, double sd, double c, double cdf_a, double cdf_b, double za,
                             double pdf_a, double zb, double pdf_b, double out[3]) {
  const double d = mu - c;
  const double m0 = cdf_b - cdf_a;
  const double m1 = sd * (pdf_a - pdf_b);                       /* about mu */
  const double m2 = sd * sd * (m0 - (zb * pdf_b - za * pdf_a)); /* about mu */
  out[0] = m0;
  out[1] = m1 + d * m0;
  out[2] = m2 + 2.0 * d * m1 + d * d * m0;
}

/* The integrals of the parts in `mask` over [lo, hi] (inside the support and on one side of the
 * split), added to out: `theta_segments` panels of three nodes each; on each panel a part's
 * integrand over the Gaussian is the parabola through its nodes, integrated against the
 * Gaussian's exact moments. */
static void integrate_piece(const prt_cloth_lobe_fibre* lf, const prt_cloth_thread* thread,
                            const prt_cloth_method* method, unsigned mask, double mu, double sd,
                            double lo, double hi, int pinch, double out[3]) {
  enum { MAX_NODES = 2 * PRT_CLOTH_MAX_THETA_SEGMENTS + 1 };
  const uint32_t nodes = 2u * method->theta_segments;
  double theta[MAX_NODES], h[MAX_NODES][3], z[MAX_NODES], cdf[MAX_NODES], pdf[MAX_NODES];
  uint32_t s;
  int part;
  for (s = 0; s <= nodes; ++s) {
    theta[s] = s == 0 ? lo : s == nodes ? hi : boundary(lo, hi, s, nodes, pinch);
    integrands_over_gaussian(lf, thread, method, mask, mu, sd, theta[s], h[s]);
    z[s] = (theta[s] - mu) / sd;
    cdf[s] = normal_cdf(z[s]);
    pdf[s] = exp(-0.5 * z[s] * z[s]) / SQRT_2PI;
  }
  for (s = 0; s < nodes; s += 2) {
    const double x0 = theta[s] - theta[s + 1], x2 = theta[s + 2] - theta[s + 1];
    double m[3];
    gaussian_moments(mu, sd, theta[s + 1], cdf[s], cdf[s + 2], z[s], pdf[s], z[s + 2], pdf[s + 2],
                     m);
    for (part = 0; part < 3; ++part) {
      /* the parabola through the three nodes, in powers of (theta - theta_mid) */
      const double d0 = (h[s][part] - h[s + 1][part]) / x0;
      const double d2 = (h[s + 2][part] - h[s + 1][part]) / x2;
      const double c2 = (d2 - d0) / (x2 - x0), c1 = d0 - c2 * x0;
      if (mask & (1u << part)) out[part] += h[s + 1][part] * m[0] + c1 * m[1] + c2 * m[2];
    }
  }
}

/* The integrals of the parts in `mask` over the window mu +- WINDOW_SIGMAS sd clipped to the
 * support, in two pieces where a tilted fibre's horizon starts cutting its front (theta = 0). */
static void integrate_window(const prt_cloth_lobe_fibre* lf, const prt_cloth_thread* thread,
                             const prt_cloth_method* method, unsigned mask, double mu, double sd,
                             double out[3]) {
  double support_lo, support_hi, lo, hi;
  theta_support(lf, method->flags, &support_lo, &support_hi);
  lo = fmax(support_lo, mu - WINDOW_SIGMAS * sd);
  hi = fmin(support_hi, mu + WINDOW_SIGMAS * sd);
  if (hi <= lo) return;
  if (lf->sin_tau != 0.0 && lo < 0.0 && hi > 0.0) {
    integrate_piece(lf, thread, method, mask, mu, sd, lo, 0.0,
                    pinched_end(lf, support_lo, support_hi, lo, 0.0), out);
    integrate_piece(lf, thread, method, mask, mu, sd, 0.0, hi,
                    pinched_end(lf, support_lo, support_hi, 0.0, hi), out);
  } else {
    integrate_piece(lf, thread, method, mask, mu, sd, lo, hi,
                    pinched_end(lf, support_lo, support_hi, lo, hi), out);
  }
}

/* A part whose lobe in theta (sd 2 gamma) is at least this many times wider than the light's lobe
 * (sd 1 / sqrt(lambda)) is smooth across the light's window: it is integrated there, with the
 * isotropic part and on the same nodes, instead of on a window of its own. */
#define MERGE_WIDTH 1.5

/* Paper 003's theta rule (its Eqs. 15-16): the light's lobe in theta, exp(lambda (cos(theta -
 * theta_k) - 1)), taken as the Gaussian exp(-lambda (theta - theta_k)^2 / 2), and its product
 * with a lobed part's Gaussian in theta_h as one Gaussian, alpha N(mu, sd); the rest of each
 * part's integrand, linear on each of PAPER_SEGMENTS equal segments of [-pi/2, pi/2] through its
 * values at their ends, integrated against that Gaussian in closed form. */
static void integrate_paper_segments(const prt_cloth_lobe_fibre* lf, const prt_cloth_thread* thread,
                                     const prt_cloth_method* method, double out[3]) {
  double theta[PAPER_SEGMENTS + 1], smooth[PAPER_SEGMENTS + 1][3];
  uint32_t s;
  int part;
  for (s = 0; s <= PAPER_SEGMENTS; ++s) {
    const double t = -HALF_PI + PI * s / PAPER_SEGMENTS;
    const double ct = cos(t), cd = cos(0.5 * (t - lf->theta_o));
    double phi[2];
    theta[s] = t;
    smooth[s][0] = smooth[s][1] = smooth[s][2] = 0.0;
    if (ct <= 0.0 || cd <= 1e-12) continue; /* grazing: the measure vanishes */
    phi_integrals(lf, thread, method, t, phi);
    smooth[s][0] = ct * ct / (cd * cd) * phi[0];
    smooth[s][1] = ct * ct / (cd * cd) * phi[1] / (ct + cos(lf->theta_o));
    smooth[s][2] = smooth[s][1];
  }
  for (part = 0; part < 3; ++part) {
    const double gamma = part == 0 ? thread->gamma_s : part == 1 ? thread->gamma_v : 0.0;
    double precision = lf->lambda, mu = lf->theta_k, log_alpha, sd;
    if (gamma > 0.0) {
      const double band = 1.0 / (4.0 * gamma * gamma), d = lf->theta_k + lf->theta_o;
      precision = lf->lambda + band;
      mu = (lf->lambda * lf->theta_k - band * lf->theta_o) / precision;
      log_alpha = -0.5 * lf->lambda * band * d * d / precision - log(gamma * SQRT_2PI);
    } else {
      log_alpha = 0.0;
    }
    log_alpha += 0.5 * log(2.0 * PI / precision);
    sd = 1.0 / sqrt(precision);
    for (s = 0; s < PAPER_SEGMENTS; ++s) {
      const double za = (theta[s] - mu) / sd, zb = (theta[s + 1] - mu) / sd;
      const double slope = (smooth[s + 1][part] - smooth[s][part]) / (theta[s + 1] - theta[s]);
      double m[3];
      gaussian_moments(mu, sd, theta[s], normal_cdf(za), normal_cdf(zb), za,
                       exp(-0.5 * za * za) / SQRT_2PI, zb, exp(-0.5 * zb * zb) / SQRT_2PI, m);
      out[part] += exp(log_alpha) * (smooth[s][part] * m[0] + slope * m[1]);
    }
  }
}

void prt_cloth_lobe_integrals(const prt_cloth_lobe_fibre* lf, const prt_cloth_thread* thread,
                              const prt_cloth_method* method, double out[3]) {
  const double lobe_sd = 1.0 / sqrt(lf->lambda);
  unsigned merged = 4u; /* the isotropic part always */
  int part;
  out[0] = out[1] = out[2] = 0.0;
  if (method->flags & PRT_CLOTH_PAPER_THETA_SEGMENTS) {
    integrate_paper_segments(lf, thread, method, out);
    for (part = 0; part < 3; ++part) out[part] = fmax(out[part], 0.0);
    return;
  }
  for (part = 0; part < 2; ++part) {
    const double gamma = part == 0 ? thread->gamma_s : thread->gamma_v;
    const double band = 1.0 / (4.0 * gamma * gamma);
    if (2.0 * gamma >= MERGE_WIDTH * lobe_sd) {
      merged |= 1u << part;
    } else {
      const double precision = lf->lambda + band;
      const double mu = (lf->lambda * lf->theta_k - band * lf->theta_o) / precision;
      integrate_window(lf, thread, method, 1u << part, mu, 1.0 / sqrt(precision), out);
    }
  }
  integrate_window(lf, thread, method, merged, lf->theta_k, lobe_sd, out);
  /* Every integrand is >= 0, but a panel's parabola can dip below 0 where the integrand falls
   * steeply to the support's end (grazing views): no part may subtract light. */
  for (part = 0; part < 3; ++part) out[part] = fmax(out[part], 0.0);
}
