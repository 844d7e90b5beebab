// SPDX-License-Identifier: MIT
// The lobe integrals of cloth's shading (cloth_integrals.c) against brute-force integrals of the
// exact model's fibre scattering (cloth_model.c) over the domain, on a grid adapted to the lobe:
// the method converges as segments and nodes grow, and its default settings stay within a
// stated error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

extern "C" {
#include "cloth_model.h"
#include "cloth_shade_internal.h"
}

namespace {

const double kPi = 3.14159265358979323846;

struct Config {
  double lambda, theta_k, phi_k, theta_o, phi_o, tau;
};

prt_cloth_thread thread_of(double eta, double gs_deg, double gv_deg) {
  prt_cloth_thread t{};
  t.eta = static_cast<float>(eta);
  t.albedo[0] = t.albedo[1] = t.albedo[2] = 1.0f;
  t.kd = 0.0f;
  t.gamma_s = static_cast<float>(gs_deg * kPi / 180.0);
  t.gamma_v = static_cast<float>(gv_deg * kPi / 180.0);
  t.coverage = 1.0f;
  return t;
}

// A unit vector from fibre angles (theta, phi) in the frame (t, n', b).
void from_angles(const prt_cloth_fibre& f, double theta, double phi, double out[3]) {
  for (int i = 0; i < 3; ++i)
    out[i] = std::sin(theta) * f.t[i] +
             std::cos(theta) * (std::cos(phi) * f.n[i] + std::sin(phi) * f.b[i]);
}

// The three parts of f_s cos(theta_i) at wi, by differences of the exact model's scattering.
void parts(const prt_cloth_thread& th, const prt_cloth_fibre& f, const double wi[3],
           const double wo[3], double out[3]) {
  double rgb[3], m, p;
  prt_cloth_thread t = th;
  t.albedo[0] = t.albedo[1] = t.albedo[2] = 0.0f;
  prt_cloth_fibre_scatter(&t, &f, wi, wo, rgb, &m, &p);
  const double surface = rgb[0];
  t = th;
  t.kd = 0.0f;
  prt_cloth_fibre_scatter(&t, &f, wi, wo, rgb, &m, &p);
  const double lobed = rgb[0] - surface;
  t.kd = 1.0f;
  prt_cloth_fibre_scatter(&t, &f, wi, wo, rgb, &m, &p);
  out[0] = surface;
  out[1] = lobed;
  out[2] = rgb[0] - surface;
}

// Brute force over a grid uniform in the lobe's own measure: s = 1 - cos(angle to the axis)
// through the Gaussian's inverse CDF, and the azimuth around the axis.
void brute(const Config& c, const prt_cloth_thread& th, int n, double out[3]) {
  prt_cloth_frame frame{};
  frame.n[1] = 1.0, frame.u[0] = 1.0, frame.v[2] = -1.0;  // n = +Y, u = +X, v = n x u = -Z
  prt_cloth_fibre f;
  prt_cloth_fibre_frame(&frame, 0, c.tau, &f);
  double axis[3], wo[3];
  from_angles(f, c.theta_k, c.phi_k, axis);
  from_angles(f, c.theta_o, c.phi_o, wo);
  double e1[3], e2[3];
  const double pick[3] = {std::fabs(axis[0]) < 0.9 ? 1.0 : 0.0,
                          std::fabs(axis[0]) < 0.9 ? 0.0 : 1.0, 0.0};
  e1[0] = axis[1] * pick[2] - axis[2] * pick[1];
  e1[1] = axis[2] * pick[0] - axis[0] * pick[2];
  e1[2] = axis[0] * pick[1] - axis[1] * pick[0];
  const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (double& x : e1) x /= l1;
  e2[0] = axis[1] * e1[2] - axis[2] * e1[1];
  e2[1] = axis[2] * e1[0] - axis[0] * e1[2];
  e2[2] = axis[0] * e1[1] - axis[1] * e1[0];
  const double mass = -std::expm1(-2.0 * c.lambda) / c.lambda;  // integral of exp(-lambda s) ds
  out[0] = out[1] = out[2] = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) / n;
    const double s = -std::log1p(-x * -std::expm1(-2.0 * c.lambda)) / c.lambda;
    const double ca = 1.0 - s, sa = std::sqrt(std::fmax(0.0, 1.0 - ca * ca));
    for (int j = 0; j < 4 * n; ++j) {
      const double b = (j + 0.5) / (4 * n) * 2.0 * kPi;
      double w[3];
      for (int k = 0; k < 3; ++k)
        w[k] = ca * axis[k] + sa * (std::cos(b) * e1[k] + std::sin(b) * e2[k]);
      const double wn = w[0] * f.n[0] + w[1] * f.n[1] + w[2] * f.n[2];
      if (w[1] <= 0.0 || wn <= 0.0) continue;  // cloth hemisphere (n = +Y) and fibre front
      double p[3];
      parts(th, f, w, wo, p);
      for (int k = 0; k < 3; ++k) out[k] += p[k];
    }
  }
  for (int k = 0; k < 3; ++k) out[k] *= mass * 2.0 * kPi / (static_cast<double>(n) * 4 * n);
}

void method(const Config& c, const prt_cloth_thread& th, uint32_t segments, uint32_t nodes,
            double out[3]) {
  prt_cloth_lobe_fibre lf{};
  lf.lambda = c.lambda;
  lf.theta_k = c.theta_k, lf.phi_k = c.phi_k;
  lf.theta_o = c.theta_o, lf.phi_o = c.phi_o;
  lf.sin_tau = std::sin(c.tau), lf.cos_tau = std::cos(c.tau);
  prt_cloth_method m{};
  m.theta_segments = segments;
  m.phi_nodes = nodes;
  prt_cloth_lobe_integrals(&lf, &th, &m, out);
}

std::vector<Config> configs(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Config> out;
  const double taus[] = {0.0, 25.0, -25.0, 32.0, -18.0};
  for (int i = 0; i < count; ++i) {
    Config c;
    c.lambda = std::exp(std::log(0.25) + u(rng) * (std::log(1e4) - std::log(0.25)));
    c.theta_k = (u(rng) * 2.0 - 1.0) * 1.4;
    c.phi_k = (u(rng) * 2.0 - 1.0) * 1.4;
    c.theta_o = (u(rng) * 2.0 - 1.0) * 1.3;
    c.phi_o = (u(rng) * 2.0 - 1.0) * 1.4;
    c.tau = taus[i % 5] * kPi / 180.0;
    out.push_back(c);
  }
  return out;
}

TEST(ClothIntegrals, ConvergeToTheBruteForceIntegrals) {
  const prt_cloth_thread threads[] = {thread_of(1.46, 12, 24), thread_of(1.539, 2.5, 5)};
  double worst_fine = 0.0, worst_default = 0.0, sum_default = 0.0, sum_ref = 0.0;
  for (const Config& c : configs(24, 7)) {
    for (const prt_cloth_thread& th : threads) {
      double ref[3], fine[3], def[3];
      brute(c, th, c.lambda > 300 ? 600 : 300, ref);
      method(c, th, 6, 6, fine);
      method(c, th, PRT_CLOTH_DEFAULT_THETA_SEGMENTS, PRT_CLOTH_DEFAULT_PHI_NODES, def);
      const double scale = ref[0] + ref[1] + ref[2];
      if (scale < 1e-9) continue;
      for (int k = 0; k < 3; ++k) {
        worst_fine = std::fmax(worst_fine, std::fabs(fine[k] - ref[k]) / scale);
        worst_default = std::fmax(worst_default, std::fabs(def[k] - ref[k]) / scale);
        sum_default += std::fabs(def[k] - ref[k]);
        sum_ref += ref[k];
      }
    }
  }
  std::printf("worst relative error: fine %.5f, default %.5f; mean %.5f\n", worst_fine,
              worst_default, sum_default / sum_ref);
  // Bounds about twice the errors measured when the defaults were chosen.
  EXPECT_LT(worst_fine, 0.01);
  EXPECT_LT(worst_default, 0.1);
  EXPECT_LT(sum_default / sum_ref, 0.02);
}

}  // namespace
