// SPDX-License-Identifier: MIT
// Paper 003's printed rules as the lobe integrals' study switches (PRT_CLOTH_PAPER_*), each
// against what the paper prints, restated here: Eq. 13's polynomial at one point worked by hand,
// the phi domain's leak from below the horizon, and the theta rule (6 straight segments times the
// Gaussian) by brute force over the same piecewise-linear integrand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

extern "C" {
#include "cloth_model.h"
#include "cloth_shade_internal.h"
}

namespace {

const double kPi = 3.14159265358979323846;

prt_cloth_thread thread_of(double eta, double gs, double gv) {
  prt_cloth_thread t{};
  t.eta = static_cast<float>(eta);
  t.albedo[0] = t.albedo[1] = t.albedo[2] = 1.0f;
  t.gamma_s = static_cast<float>(gs);
  t.gamma_v = static_cast<float>(gv);
  t.coverage = 1.0f;
  return t;
}

prt_cloth_lobe_fibre lobe_fibre(double lambda, double theta_k, double phi_k, double theta_o,
                                double phi_o, double tau) {
  prt_cloth_lobe_fibre lf{};
  lf.lambda = lambda;
  lf.theta_k = theta_k, lf.phi_k = phi_k;
  lf.theta_o = theta_o, lf.phi_o = phi_o;
  lf.sin_tau = std::sin(tau), lf.cos_tau = std::cos(tau);
  return lf;
}

void integrals(const prt_cloth_lobe_fibre& lf, const prt_cloth_thread& th, uint32_t flags,
               uint32_t phi_nodes, double out[3]) {
  prt_cloth_method m{};
  m.flags = flags;
  m.theta_segments = 2;
  m.phi_nodes = phi_nodes;
  prt_cloth_lobe_integrals(&lf, &th, &m, out);
}

// Eq. 13 as printed: F_0 + (1 - F_0) times the binomial sum of (1 - x)^5 to l = 3, x =
// cos(theta_d) cos(phi_d). At eta 1.5 (F_0 = 0.25^2 = 0.04), cos(theta_d) 0.8 and phi_d 60 degrees
// (x = 0.4): 1 - 5 (0.4) + 10 (0.16) - 10 (0.064) = -0.04, so F = 0.04 + 0.96 (-0.04) = 0.0016;
// the whole sum is 0.6^5 = 0.07776, F = 0.04 + 0.96 (0.07776) = 0.1146496. Schlick's term meets
// the exact Fresnel term at normal and grazing incidence.
TEST(ClothPaper, SchlickIsEq13WholeOrCutAsPrinted) {
  EXPECT_NEAR(prt_cloth_fresnel_schlick(1.5, 0.8 * std::cos(kPi / 3.0), 1), 0.0016, 1e-15);
  EXPECT_NEAR(prt_cloth_fresnel_schlick(1.5, 0.4, 0), 0.1146496, 1e-15);
  EXPECT_NEAR(prt_cloth_fresnel_schlick(1.5, 1.0, 0), prt_cloth_fresnel(1.5, 1.0), 1e-15);
  EXPECT_NEAR(prt_cloth_fresnel_schlick(1.5, 0.0, 0), prt_cloth_fresnel(1.5, 0.0), 1e-15);
  // and each switch changes what replaces the exact term, in every part that has F
  const prt_cloth_lobe_fibre lf = lobe_fibre(20.0, 0.3, 0.2, -0.2, 0.5, 0.0);
  const prt_cloth_thread th = thread_of(1.46, 0.2, 0.4);
  const uint32_t kinds[] = {
      0u, PRT_CLOTH_PAPER_SCHLICK, PRT_CLOTH_PAPER_SCHLICK | PRT_CLOTH_PAPER_SCHLICK_ANGLE,
      PRT_CLOTH_PAPER_SCHLICK | PRT_CLOTH_PAPER_SCHLICK_CUBE, PRT_CLOTH_PAPER_FRESNEL};
  double out[5][3];
  for (int k = 0; k < 5; ++k) integrals(lf, th, kinds[k], 3, out[k]);
  // each against the one it adds to: Schlick against exact, the angle and the cut against
  // Schlick, and the cut on top of the angle
  const int base[5] = {0, 0, 1, 1, 2};
  for (int k = 1; k < 5; ++k)
    for (int part = 0; part < 3; ++part) EXPECT_NE(out[k][part], out[base[k]][part]) << k << part;
}

// The fibre's front below a tilted fibre's horizon: a lobe wholly below the horizon (and on the
// front) gives nothing over the hemisphere but leaks through the paper's domain; an untilted
// fibre's front is all above the horizon (phi_c = pi/2), where the two agree bit for bit.
TEST(ClothPaper, PhiDomainLeaksFromBelowTheHorizonOfATiltedFibre) {
  const prt_cloth_thread th = thread_of(1.46, 0.2, 0.4);
  const double tau = 30.0 * kPi / 180.0, theta_k = -70.0 * kPi / 180.0;
  // the lobe's axis below the horizon: sin(tau) sin(theta_k) + cos(tau) cos(theta_k) < 0
  ASSERT_LT(std::sin(tau) * std::sin(theta_k) + std::cos(tau) * std::cos(theta_k), -0.1);
  const prt_cloth_lobe_fibre below = lobe_fibre(1000.0, theta_k, 0.0, 0.3, 0.2, tau);
  double clipped[3], front[3];
  integrals(below, th, 0u, 3, clipped);
  integrals(below, th, PRT_CLOTH_PAPER_PHI_DOMAIN, 3, front);
  for (int part = 0; part < 3; ++part) {
    EXPECT_EQ(clipped[part], 0.0) << part;
    EXPECT_GT(front[part], 0.0) << part;
  }
  const double lambdas[] = {0.5, 8.0, 300.0};
  for (const double lambda : lambdas)
    for (double theta_k0 = -1.4; theta_k0 < 1.5; theta_k0 += 0.35) {
      const prt_cloth_lobe_fibre flat = lobe_fibre(lambda, theta_k0, 0.4, -0.5, -0.3, 0.0);
      double a[3], b[3];
      integrals(flat, th, 0u, 3, a);
      integrals(flat, th, PRT_CLOTH_PAPER_PHI_DOMAIN, 3, b);
      EXPECT_EQ(std::memcmp(a, b, sizeof a), 0) << "lambda " << lambda << " theta_k " << theta_k0;
    }
}

// The paper's theta rule restated: nodes at -pi/2 + s pi/6, s = 0..6; each part's integrand
// without its theta profile, h(theta) = cos^2(theta) / cos^2(theta_d) Phi_p(theta) (over
// cos(theta) + cos(theta_o) for the volume parts), linear between them; times the profile's
// Gaussian: exp(-lambda (theta - theta_k)^2 / 2), times the part's N(theta_h; 0, gamma) for the
// lobed parts. Phi_p is the phi integral over the front (an untilted fibre) of the von Mises
// profile times F_r cos(phi_d / 2) (surface) or (1 - F_r)^2 (volume), here by a fine midpoint
// rule, and the theta integral too.
void brute_paper_theta(const prt_cloth_lobe_fibre& lf, const prt_cloth_thread& th, double out[3]) {
  auto phi_integrals = [&](double theta, double phi[2]) {
    const double kappa = lf.lambda * std::cos(theta) * std::cos(lf.theta_k);
    const double cos_d = std::cos(0.5 * (theta - lf.theta_o));
    const int n = 4000;
    phi[0] = phi[1] = 0.0;
    for (int i = 0; i < n; ++i) {
      const double p = -kPi / 2 + (i + 0.5) * kPi / n;
      const double w = std::exp(kappa * (std::cos(p - lf.phi_k) - 1.0)) * kPi / n;
      const double y = std::cos(0.5 * (p - lf.phi_o));
      const double f = prt_cloth_fresnel(th.eta, cos_d * y);
      phi[0] += w * f * y;
      phi[1] += w * (1.0 - f) * (1.0 - f);
    }
  };
  double node[7], h[7][3];
  for (int s = 0; s <= 6; ++s) {
    const double t = -kPi / 2 + s * kPi / 6;
    const double ct = std::cos(t), cd = std::cos(0.5 * (t - lf.theta_o));
    double phi[2];
    phi_integrals(t, phi);
    node[s] = t;
    h[s][0] = ct * ct / (cd * cd) * phi[0];
    h[s][1] = h[s][2] = ct * ct / (cd * cd) * phi[1] / (ct + std::cos(lf.theta_o));
  }
  const double gammas[3] = {th.gamma_s, th.gamma_v, 0.0};
  const int n = 200000;
  out[0] = out[1] = out[2] = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = -kPi / 2 + (i + 0.5) * kPi / n;
    const int s = std::min(5, static_cast<int>((t + kPi / 2) / (kPi / 6)));
    const double u = (t - node[s]) / (node[s + 1] - node[s]);
    const double lobe = std::exp(-0.5 * lf.lambda * (t - lf.theta_k) * (t - lf.theta_k));
    const double half = 0.5 * (t + lf.theta_o);
    for (int part = 0; part < 3; ++part) {
      double g = lobe;
      if (gammas[part] > 0.0)
        g *= std::exp(-half * half / (2.0 * gammas[part] * gammas[part])) /
             (gammas[part] * std::sqrt(2.0 * kPi));
      out[part] += ((1.0 - u) * h[s][part] + u * h[s + 1][part]) * g * (kPi / n);
    }
  }
}

TEST(ClothPaper, ThetaSegmentsAreSixStraightSegmentsTimesTheGaussian) {
  const prt_cloth_thread threads[] = {thread_of(1.46, 0.2, 0.4), thread_of(1.539, 0.05, 0.1)};
  struct Case {
    double lambda, theta_k, phi_k, theta_o, phi_o;
  };
  // lobes wide enough in phi (4 sd >= pi/2 at every theta) that the runtime's phi rule is plain
  // Gauss-Legendre over the front, whose 8 nodes all but match the brute force; the lobed parts'
  // narrow Gaussians (gamma 0.05) make narrow products in theta all the same
  const Case cases[] = {
      {0.5, 0.2, -0.3, 0.4, 0.3}, {2.0, -0.5, 0.4, 0.7, -0.2}, {1.0, 0.9, -0.2, -0.3, 0.6}};
  for (const prt_cloth_thread& th : threads)
    for (const Case& c : cases) {
      const prt_cloth_lobe_fibre lf =
          lobe_fibre(c.lambda, c.theta_k, c.phi_k, c.theta_o, c.phi_o, 0.0);
      double method[3], brute[3], ours[3];
      integrals(lf, th, PRT_CLOTH_PAPER_THETA_SEGMENTS, 8, method);
      integrals(lf, th, 0u, 8, ours);
      brute_paper_theta(lf, th, brute);
      for (int part = 0; part < 3; ++part) {
        EXPECT_NEAR(method[part], brute[part], 2e-6 * std::fabs(brute[part]))
            << "lambda " << c.lambda << " part " << part;
        EXPECT_NE(method[part], ours[part]) << "lambda " << c.lambda << " part " << part;
      }
    }
}

}  // namespace
