// SPDX-License-Identifier: MIT
// Shared by the `pose` GL tests (pose_gl_test.cpp) and its conformance cases
// (pose_conformance.cpp): sections whose t_00 is bounded by construction over a training range,
// the poses at rest, inside it and at twice it, and the float-rounding bound a backend's radiance
// is held to against the scalar reference, computed here from the SPEC's maths restated in
// double (pose/pose_blob.hpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include <prt/prt.hpp>

// pose_blob.hpp and sh/sh_blob_test_util.hpp (through support/gl_test_util.hpp) both define
// prt_test::put_f32; the GL tests need both, so pose_blob.hpp's copy is renamed here.
#define put_f32 pose_blob_put_f32
#include "pose/pose_blob.hpp"
#undef put_f32

namespace prt_test {

constexpr double kPoseU = 0x1p-24;  // float unit roundoff
constexpr double kPosePi = 3.14159265358979323846;
// t_00 of the unoccluded cosine lobe for albedo 1: A_0 / pi * y_00 = 1 / (2 sqrt(pi)).
const double kUnoccludedT00 = 0.5 / std::sqrt(kPosePi);

inline double gamma_n(double n) {
  return n * kPoseU / (1.0 - n * kPoseU);
}

// Joint rotations: each joint's bind rotation turned by its own rotation vector a_j (radians),
// b_j exp(a_j), so that the features are the a_j (the model joint's are 0 whatever it does).
inline std::vector<float> pose_at(const PoseSection& s, const std::vector<double>& a) {
  std::vector<float> r;
  for (uint32_t j = 0; j < s.joint_count(); ++j) {
    const double x = a[3 * j], y = a[3 * j + 1], z = a[3 * j + 2];
    const double angle = std::sqrt(x * x + y * y + z * z);
    const Quat turn = angle > 0 ? axis_angle(x, y, z, angle) : Quat{0, 0, 0, 1};
    const auto& b = s.joints[j].bind;
    for (float c : to_float4(quat_mul({b[0], b[1], b[2], b[3]}, turn))) r.push_back(c);
  }
  return r;
}

// The poses a shading test visits: at rest (the bind pose), one inside the training range, and
// the training poses' first one with every rotation angle doubled (2x outside the range).
struct PoseSet {
  std::vector<float> rest, mid, twice;
};

// A section with a training range and a t_00 guaranteed in [0, its unoccluded value] over it.
struct BoundedSection {
  PoseSection section;
  PoseSet poses;
  double t00_max = 0;  // the unoccluded t_00: 1/(2 sqrt(pi)) (model 0), albedo times it (model 1)
};

// random_section's section (chain skeleton, random PCA, regression, basis and skin) made so that
// t_00 is bounded: the pose range is the box of the coordinates of 12 training poses (rotations
// of up to 0.6 rad from bind) and clamping is on, so every pose's coordinates z lie in it; the
// basis values are fractions (offset 0, scale 1/top: U in [0, 1]); and each y[k][0] over the
// box stays in [0, m/q] (model 0) or [-m/q, 0] (model 1, whose exact t_00 is m at any unit
// normal), m the unoccluded t_00: its bias row is +-m/(2q) and its pose rows are scaled so that
// their largest reach over the box is 0.9 of that. Then t_00 = (exact) + sum_k U_k y[k][0] is in
// [0, m] at every pose.
inline BoundedSection bounded_section(uint32_t order, uint32_t vertices, uint32_t basis_dims,
                                      uint32_t bits, uint32_t model, uint32_t seed) {
  const uint32_t joints = 6, pose_dims = 5;
  BoundedSection out;
  PoseSection& s = out.section;
  s = random_section(order, vertices, joints, pose_dims, basis_dims, bits, model, seed);
  std::mt19937 rng(seed + 1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Training poses and the box of their coordinates (computed with clamping off).
  std::vector<std::vector<double>> training;
  for (int t = 0; t < 12; ++t) {
    std::vector<double> a(3 * joints);
    for (double& x : a) x = 0.6 / std::sqrt(3.0) * unit(rng);
    training.push_back(a);
  }
  s.flags = 0;
  for (uint32_t i = 0; i < pose_dims; ++i)
    s.pose_range[2 * i] = 1e30f, s.pose_range[2 * i + 1] = -1e30f;
  for (const auto& a : training) {
    const std::vector<double> z = coordinates(s, pose_at(s, a));
    for (uint32_t i = 0; i < pose_dims; ++i) {
      s.pose_range[2 * i] = std::min(s.pose_range[2 * i], float(z[i]));
      s.pose_range[2 * i + 1] = std::max(s.pose_range[2 * i + 1], float(z[i]));
    }
  }
  s.flags = PRT_BLOB_PSTR_FLAG_CLAMP;
  const double top = bits == 8 ? 255.0 : 65535.0;
  for (uint32_t k = 0; k < basis_dims; ++k)
    s.basis_params[2 * k] = 0.0f, s.basis_params[2 * k + 1] = float(1.0 / top);
  out.t00_max = model == 1 ? s.albedo * kUnoccludedT00 : kUnoccludedT00;
  const double share = out.t00_max / basis_dims;
  for (uint32_t k = 0; k < basis_dims; ++k) {
    double reach = 0;
    for (uint32_t i = 0; i < pose_dims; ++i)
      reach += std::max(std::fabs(s.pose_range[2 * i]), std::fabs(s.pose_range[2 * i + 1])) *
               std::fabs(s.x(i + 1, k, 0));
    const double scale = reach > 0 ? 0.9 * 0.5 * share / reach : 0.0;
    for (uint32_t i = 0; i < pose_dims; ++i) s.x(i + 1, k, 0) = float(s.x(i + 1, k, 0) * scale);
    s.x(0, k, 0) = float((model == 1 ? -0.5 : 0.5) * share);
  }
  out.poses.rest = pose_at(s, std::vector<double>(3 * joints, 0.0));
  std::vector<double> mid(3 * joints);
  for (double& x : mid) x = 0.3 / std::sqrt(3.0) * unit(rng);
  out.poses.mid = pose_at(s, mid);
  std::vector<double> twice = training[0];
  for (double& x : twice) x *= 2.0;
  out.poses.twice = pose_at(s, twice);
  return out;
}

// Whether the pose's unclamped coordinates leave the section's training range (so that a test at
// that pose is about extrapolation).
inline bool outside_training_range(PoseSection s, const std::vector<float>& rotations) {
  s.flags = 0;
  const std::vector<double> z = coordinates(s, rotations);
  for (uint32_t i = 0; i < s.pose_dims; ++i)
    if (z[i] < s.pose_range[2 * i] || z[i] > s.pose_range[2 * i + 1]) return true;
  return false;
}

// Row-major rotation of angle t about an axis.
inline std::vector<float> axis_rotation(double x, double y, double z, double t) {
  const double len = std::sqrt(x * x + y * y + z * z);
  x /= len, y /= len, z /= len;
  const double c = std::cos(t), s = std::sin(t), k = 1 - c;
  return {float(c + x * x * k),     float(x * y * k - z * s), float(x * z * k + y * s),
          float(y * x * k + z * s), float(c + y * y * k),     float(y * z * k - x * s),
          float(z * x * k - y * s), float(z * y * k + x * s), float(c + z * z * k)};
}

// L' = rotate(L, (W R_m)^T), R_m from the restated skeleton's model frame.
inline std::vector<float> model_frame_light(const PoseSection& s, const std::vector<float>& r,
                                            const std::vector<float>& light, const float* world) {
  const std::vector<Affine> g = globals(s, r);
  const Affine m = model_frame(g[s.model_joint]);
  float rt[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double wr = 0;
      for (int k = 0; k < 3; ++k) wr += (world ? world[3 * j + k] : double(j == k)) * m[4 * k + i];
      rt[3 * i + j] = float(wr);
    }
  std::vector<float> out(light.size());
  EXPECT_EQ(prt_sh_rotate(s.order, rt, light.data(), out.data(), 3), PRT_OK);
  return out;
}

// The bound on |backend - scalar reference| for each vertex and channel of a shade at one pose,
// from float arithmetic (Higham, Accuracy and Stability of Numerical Algorithms, §3.1: a dot
// product of n terms errs by at most gamma_n times the sum of their magnitudes), doubled so that
// it holds between two float evaluations, plus one rounding of the reference's own result.
//
// Learned part: the weights scale_k w_k and the bias are rounded once each, then q products and
// q additions: gamma_(q+3) M, M = sum_k (|offset_k w_k| + |scale_k U_k w_k|).
//
// Exact part (model 1), sum_c y_c(n) e_c with e_c = factor_c L'[c]: e_c rounded once and C
// products and additions give gamma_(C+2) sum_c |y_c| |e_c|, bounded with |y_lm| <=
// sqrt((2l+1)/(4 pi)) (the addition theorem); the SH recurrence in float adds at most
// gamma_(4l+8) sqrt((2l+1)/(4 pi)) per value (a three-term recurrence of l steps, each a few
// roundings; the stable direction of the normalised recurrence keeps growth linear in l); and
// an error dn in the normal's direction moves the sum by at most G dn (pi/2 for arc against
// chord), G = sum_l sqrt(l(l+1)) sqrt((2l+1)/(4 pi)) |e_l| the largest gradient of a band-l sum
// on the sphere. dn comes from skinning in float: K = sum_k a_k K_j errs per entry by
// gamma_6 |K| (with |K| = sum_k a_k |K_j|: K_j and a_k rounded, 4 products and sums), each
// cofactor (2 products, 1 subtraction) by gamma_15 of the products' magnitudes, cof(K) n by
// gamma_18 |cof|(|K|) |n|, and normalising a vector v perturbed by dv turns it by at most
// 2 |dv| / |v|, plus gamma_10 for the two normalisations (skin, then the SH frame). The
// caller's normals skip the skinning term.
//
// The bound is a worst case, linear in the counts, while rounding errors mostly cancel; so the
// error is also measured against `magnitude`, the same sum without the gamma factors (M, the
// exact part's magnitude and G |dv| / |v|), in units of u: the tests cap the worst of that over
// their fixed seeds, which catches a systematic error far inside the bound.
struct PoseBound {
  std::vector<double> tolerance;  // 3 V: per vertex and channel
  std::vector<double> magnitude;  // 3 V: the bound's magnitudes without the gamma factors
};

inline PoseBound pose_bound(const PoseSection& s, const std::vector<float>& r,
                            const std::vector<float>& light, const float* world,
                            const std::vector<double>& reference, bool given_normals = false) {
  const uint32_t n2 = s.coefficients(), q = s.basis_dims, order = s.order;
  const std::vector<double> y = coefficients(s, r);
  const std::vector<float> lp = model_frame_light(s, r, light, world);
  // w_k[ch] in double.
  std::vector<double> w(3 * size_t(q));
  for (uint32_t k = 0; k < q; ++k)
    for (int ch = 0; ch < 3; ++ch) {
      double sum = 0;
      for (uint32_t c = 0; c < n2; ++c) sum += y[size_t(k) * n2 + c] * lp[3 * c + ch];
      w[3 * k + ch] = sum;
    }
  // The exact part's per-channel magnitudes, independent of the vertex but for dn.
  double exact_sum[3] = {0, 0, 0}, exact_eval[3] = {0, 0, 0}, gradient[3] = {0, 0, 0};
  if (s.model == 1)
    for (uint32_t l = 0; l < order; ++l) {
      const double ylm = std::sqrt((2.0 * l + 1.0) / (4 * kPosePi));
      const double band_factor = s.albedo * prt_sh_cosine_band_factor(l) / kPosePi;
      for (int ch = 0; ch < 3; ++ch) {
        double abs_sum = 0, norm2 = 0;
        for (uint32_t c = l * l; c < (l + 1) * (l + 1); ++c) {
          const double e = band_factor * lp[3 * c + ch];
          abs_sum += std::fabs(e);
          norm2 += e * e;
        }
        exact_sum[ch] += ylm * abs_sum;
        exact_eval[ch] += gamma_n(4.0 * l + 8.0) * ylm * abs_sum;
        gradient[ch] += std::sqrt(double(l) * (l + 1)) * ylm * std::sqrt(norm2);
      }
    }
  // Skinning matrices K_j restated.
  const std::vector<Affine> g = globals(s, r);
  const Affine m_inv = affine_inverse(model_frame(g[s.model_joint]));
  std::vector<Affine> kj(s.joint_count());
  for (uint32_t j = 0; j < s.joint_count(); ++j)
    kj[j] = affine_mul(m_inv, affine_mul(g[j], from_float12(s.joints[j].inverse_bind)));
  PoseBound out;
  out.tolerance.resize(3 * size_t(s.vertices));
  out.magnitude.resize(3 * size_t(s.vertices));
  for (uint32_t v = 0; v < s.vertices; ++v) {
    double dn = gamma_n(10), dn_magnitude = 1.0;
    if (s.model == 1 && !given_normals) {
      const PoseSkin& skin = s.skin[v];
      // SPEC §7.3's blend: joints at or past J weigh 0, the identity when no weight is left.
      double total = 0, k3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, kabs[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      for (int i = 0; i < 4; ++i)
        if (skin.joints[i] < s.joint_count()) total += skin.weights[i];
      if (total > 0)
        for (int e = 0; e < 9; ++e) k3[e] = kabs[e] = 0;
      for (int i = 0; i < 4; ++i) {
        if (skin.weights[i] == 0 || skin.joints[i] >= s.joint_count()) continue;
        const Affine& m = kj[skin.joints[i]];
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) {
            k3[3 * a + b] += skin.weights[i] / total * m[4 * a + b];
            kabs[3 * a + b] += skin.weights[i] / total * std::fabs(m[4 * a + b]);
          }
      }
      double vv[3], vabs[3];
      for (int a = 0; a < 3; ++a) {
        vv[a] = vabs[a] = 0;
        const int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
        for (int b = 0; b < 3; ++b) {
          const int b1 = (b + 1) % 3, b2 = (b + 2) % 3;
          const double cof = k3[3 * a1 + b1] * k3[3 * a2 + b2] - k3[3 * a1 + b2] * k3[3 * a2 + b1];
          const double cof_abs =
              kabs[3 * a1 + b1] * kabs[3 * a2 + b2] + kabs[3 * a1 + b2] * kabs[3 * a2 + b1];
          vv[a] += cof * skin.normal[b];
          vabs[a] += cof_abs * std::fabs(skin.normal[b]);
        }
      }
      const double len = std::sqrt(vv[0] * vv[0] + vv[1] * vv[1] + vv[2] * vv[2]);
      const double dlen = std::sqrt(vabs[0] * vabs[0] + vabs[1] * vabs[1] + vabs[2] * vabs[2]);
      dn += 2.0 * gamma_n(18) * dlen / len;
      dn_magnitude += dlen / len;
    }
    for (int ch = 0; ch < 3; ++ch) {
      double m = 0;
      for (uint32_t k = 0; k < q; ++k)
        m += std::fabs(s.basis_params[2 * k] * w[3 * k + ch]) +
             std::fabs(s.basis_params[2 * k + 1] * s.values[size_t(v) * q + k] * w[3 * k + ch]);
      double bound = gamma_n(q + 3.0) * m, magnitude = m;
      if (s.model == 1) {
        bound +=
            gamma_n(n2 + 2.0) * exact_sum[ch] + exact_eval[ch] + 0.5 * kPosePi * gradient[ch] * dn;
        magnitude += exact_sum[ch] + gradient[ch] * dn_magnitude;
      }
      out.magnitude[3 * size_t(v) + ch] = magnitude + 1e-30;
      out.tolerance[3 * size_t(v) + ch] =
          2.0 * bound + kPoseU * std::fabs(reference[3 * size_t(v) + ch]) + 1e-30;
    }
  }
  return out;
}

// The largest |got - reference| / tolerance over vertices [first, first + count) (got holds
// just those), adding a failure for each of the first few values beyond their tolerance; and in
// *worst_in_u (when given) the largest |got - reference| / (u magnitude) seen so far.
inline double compare_to_reference(const char* what, const std::vector<double>& reference,
                                   const PoseBound& bound, const float* got, uint32_t first,
                                   uint32_t count, double* worst_in_u = nullptr) {
  double worst = 0;
  int failures = 0;
  for (size_t i = 0; i < 3 * size_t(count); ++i) {
    const size_t at = 3 * size_t(first) + i;
    const double error = std::fabs(double(got[i]) - reference[at]);
    const double tol = bound.tolerance[at];
    worst = std::max(worst, std::isfinite(error) ? error / tol : INFINITY);
    if (worst_in_u)
      *worst_in_u = std::max(
          *worst_in_u, std::isfinite(error) ? error / (kPoseU * bound.magnitude[at]) : INFINITY);
    if (!(error <= tol) && failures++ < 5)
      ADD_FAILURE() << what << ": vertex " << at / 3 << " channel " << at % 3 << " gives " << got[i]
                    << ", reference " << reference[at] << " (tolerance " << tol << ")";
  }
  return worst;
}

}  // namespace prt_test
