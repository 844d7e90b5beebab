// SPDX-License-Identifier: MIT
// docs/cloth/model.md restated by hand for the tests, written from the angles: the textbook s/p
// Fresnel, one fibre's f_s cos(theta_i), M, P and the kernel of a weave in the frame n = +Z,
// u = +X (so v = +Y), with the angles of a direction read off its components with asin and
// atan2. A second implementation, independent of the runtime's vector code, and the fabric
// structs the tests build.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <utility>

#include <prt/prt.hpp>

namespace cloth_test {

constexpr double kPi = 3.14159265358979323846;
constexpr double kBeta = 20.0 * kPi / 180.0;

using Vec3 = std::array<double, 3>;
using Rgb = std::array<double, 3>;

inline std::array<float, 3> to_float(const Vec3& v) {
  return {float(v[0]), float(v[1]), float(v[2])};
}

// x rounded to float and back. Through a volatile: GCC 12's SLP vectoriser at -O2 and above
// drops the rounding of two of three such components written in a row.
inline double float_rounded(double x) {
  volatile float f = float(x);
  return f;
}

// Unpolarised reflectance from air into index eta at incidence cosine cos_i: the mean of the s
// and p amplitudes squared, through Snell's law.
inline double fresnel_sp(double eta, double cos_i) {
  const double sin_t2 = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin_t2 >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t2);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

inline double gaussian(double x, double width) {
  return std::exp(-x * x / (2.0 * width * width)) / (width * std::sqrt(2.0 * kPi));
}

inline double wrapped(double a) {
  while (a > kPi) a -= 2.0 * kPi;
  while (a <= -kPi) a += 2.0 * kPi;
  return a;
}

// M or P from the two angles (phi or psi) of light and view.
inline double shadowing(double angle_i, double angle_o) {
  const double d = wrapped(angle_i - angle_o);
  const double u = std::exp(-d * d / (2.0 * kBeta * kBeta));
  const double ci = std::max(std::cos(angle_i), 0.0), co = std::max(std::cos(angle_o), 0.0);
  return (1.0 - u) * ci * co + u * std::min(ci, co);
}

struct Angles {
  double theta, phi, psi;
};

// The angles of a direction given as its components along t, n' and b.
inline Angles angles_of(double along_t, double along_n, double along_b) {
  return {std::asin(std::clamp(along_t, -1.0, 1.0)), std::atan2(along_b, along_n),
          std::atan2(along_t, along_n)};
}

// The direction of angles (theta, phi) in a fibre frame, as components along t, n' and b.
inline Vec3 fibre_components(double theta, double phi) {
  return {std::sin(theta), std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi)};
}

// f_s cos(theta_i) of one fibre, term by term.
inline Rgb fibre_fs_cos(const prt_cloth_thread& p, const Angles& in, const Angles& out) {
  const double theta_h = 0.5 * (in.theta + out.theta);
  const double theta_d = 0.5 * (in.theta - out.theta);
  const double half_phi = 0.5 * wrapped(in.phi - out.phi);
  const double c = std::cos(theta_d) * std::cos(half_phi);
  const double fr = fresnel_sp(p.eta, c);
  const double surface = fr * std::cos(half_phi) * gaussian(theta_h, p.gamma_s);
  const double volume = (1.0 - fr) * (1.0 - fr) *
                        ((1.0 - p.kd) * gaussian(theta_h, p.gamma_v) + p.kd) /
                        (std::cos(in.theta) + std::cos(out.theta));
  const double scale = std::cos(in.theta) / (std::cos(theta_d) * std::cos(theta_d));
  Rgb rgb;
  for (int c3 = 0; c3 < 3; ++c3) rgb[c3] = (surface + volume * p.albedo[c3]) * scale;
  return rgb;
}

// The angles of world direction w (normalised here) at offset tau of thread j, frame n = Z,
// u = X, v = Y.
inline Angles thread_angles(int j, double tau, const Vec3& w) {
  const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  const double along_x = (j == 0 ? w[0] : w[1]) / len;
  const double along_y = (j == 0 ? w[1] : -w[0]) / len;
  const double along_n = w[2] / len;
  return angles_of(std::cos(tau) * along_x + std::sin(tau) * along_n,
                   -std::sin(tau) * along_x + std::cos(tau) * along_n, along_y);
}

// The world direction of angles (theta, phi) at offset tau of thread j (frame as above).
inline Vec3 thread_direction(int j, double tau, double theta, double phi) {
  const Vec3 f = fibre_components(theta, phi);  // along t, n', b
  const double along_x = std::cos(tau) * f[0] - std::sin(tau) * f[1];
  const double along_n = std::sin(tau) * f[0] + std::cos(tau) * f[1];
  return j == 0 ? Vec3{along_x, f[2], along_n} : Vec3{-f[2], along_x, along_n};
}

// The weights W of thread j's distinct offsets (frame as above).
inline std::array<double, PRT_CLOTH_MAX_THREAD_TANGENTS> thread_weights(const prt_cloth_weave& w,
                                                                        int j, const Vec3& wi,
                                                                        const Vec3& wo) {
  std::array<double, PRT_CLOTH_MAX_THREAD_TANGENTS> mp{}, out{};
  double sum_p = 0.0;
  for (uint32_t k = 0; k < w.tangent_count[j]; ++k) {
    const Angles in = thread_angles(j, w.offsets[j][k], wi);
    const Angles ou = thread_angles(j, w.offsets[j][k], wo);
    const double p = shadowing(in.psi, ou.psi);
    mp[k] = shadowing(in.phi, ou.phi) * p;
    sum_p += w.multiplicity[j][k] * p;
  }
  for (uint32_t k = 0; k < w.tangent_count[j]; ++k) out[k] = sum_p > 0.0 ? mp[k] / sum_p : 0.0;
  return out;
}

// The kernel (frame as above), 0 below the surface.
inline Rgb kernel(const prt_cloth_params& p, const prt_cloth_weave& w, const Vec3& wi,
                  const Vec3& wo) {
  Rgb k{0.0, 0.0, 0.0};
  if (!(wi[2] > 0.0) || !(wo[2] > 0.0)) return k;
  for (int j = 0; j < 2; ++j) {
    const auto weights = thread_weights(w, j, wi, wo);
    for (uint32_t t = 0; t < w.tangent_count[j]; ++t) {
      const Rgb fs = fibre_fs_cos(p.threads[j], thread_angles(j, w.offsets[j][t], wi),
                                  thread_angles(j, w.offsets[j][t], wo));
      for (int c = 0; c < 3; ++c)
        k[c] += p.threads[j].coverage * w.multiplicity[j][t] * fs[c] * weights[t];
    }
  }
  return k;
}

// ---- Fabrics the tests build -----------------------------------------------------------------

inline prt_cloth_thread thread_of(float eta, std::array<float, 3> albedo, float kd, float gamma_s,
                                  float gamma_v, float coverage) {
  return {eta, {albedo[0], albedo[1], albedo[2]}, kd, gamma_s, gamma_v, coverage};
}

inline prt_cloth_params params_of(const prt_cloth_thread& warp, const prt_cloth_thread& weft) {
  prt_cloth_params p = prt::sized<prt_cloth_params>();
  p.threads[0] = warp;
  p.threads[1] = weft;
  return p;
}

// Offsets in degrees with their multiplicities, per thread.
using Tangents = std::initializer_list<std::pair<double, uint32_t>>;

inline prt_cloth_weave weave_of(Tangents warp, Tangents weft) {
  prt_cloth_weave w = prt::sized<prt_cloth_weave>();
  int j = 0;
  for (const Tangents& set : {warp, weft}) {
    for (const auto& [degrees, count] : set) {
      w.offsets[j][w.tangent_count[j]] = float(degrees * kPi / 180.0);
      w.multiplicity[j][w.tangent_count[j]++] = count;
    }
    ++j;
  }
  return w;
}

// Linen plain of the shared table (both tangent sets symmetric).
inline prt_cloth_params linen_params() {
  const prt_cloth_thread t = thread_of(1.46f, {0.06f, 0.24f, 0.3f}, 0.3f, float(12 * kPi / 180),
                                       float(24 * kPi / 180), 0.33f);
  return params_of(t, t);
}
inline prt_cloth_weave linen_weave() {
  return weave_of({{-25, 1}, {25, 1}}, {{-25, 1}, {25, 1}});
}

// Satin charmeuse of the shared table (a sharp lobe, several tangents, a single-tangent weft).
inline prt_cloth_params satin_params() {
  return params_of(thread_of(1.539f, {0.035f, 0.01295f, 0.0105f}, 0.1f, float(2.5 * kPi / 180),
                             float(5 * kPi / 180), 0.9f),
                   thread_of(1.539f, {0.2f, 0.074f, 0.06f}, 0.7f, float(30 * kPi / 180),
                             float(60 * kPi / 180), 0.1f));
}
inline prt_cloth_weave satin_weave() {
  return weave_of({{-32, 2}, {-18, 1}, {0, 2}, {18, 1}, {32, 2}}, {{0, 1}});
}

// Velvet of the shared table: the warp's set {-90, -50} is not symmetric, the weft's is.
inline prt_cloth_params velvet_params() {
  const prt_cloth_thread t = thread_of(1.46f, {0.015f, 0.006f, 0.0f}, 0.1f, float(6 * kPi / 180),
                                       float(12 * kPi / 180), 0.5f);
  return params_of(t, t);
}
inline prt_cloth_weave velvet_weave() {
  return weave_of({{-90, 1}, {-50, 1}}, {{-90, 1}, {-55, 1}, {55, 1}, {90, 1}});
}

}  // namespace cloth_test
