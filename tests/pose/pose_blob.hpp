// SPDX-License-Identifier: MIT
// PSTR sections built by hand for the `pose` runtime tests (formats/SPEC.md §7.3): the fields as
// plain vectors, their bytes, a blob around them (support/mesh_blob.hpp), and the SPEC's maths
// restated here in double, independently of the runtime, for the tests to compare with.
#pragma once

#include <prt/format/pose_layout.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "support/blob_test_util.hpp"
#include "support/mesh_blob.hpp"

namespace prt_test {

using Affine = std::array<double, 12>;  // 3x4 row-major [R | t]
using Quat = std::array<double, 4>;     // x y z w

inline Affine identity_affine() {
  return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
}

struct PoseJoint {
  int32_t parent = -1;
  std::array<float, 4> bind{0, 0, 0, 1};
  std::array<float, 3> translation{0, 0, 0};
  std::array<float, 3> scale{1, 1, 1};
  std::array<float, 12> pre{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  std::array<float, 12> inverse_bind{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
};

struct PoseSkin {
  std::array<float, 3> position{0, 0, 0};
  std::array<float, 3> normal{0, 0, 1};
  std::array<uint8_t, 4> joints{0, 0, 0, 0};
  std::array<uint16_t, 4> weights{65535, 0, 0, 0};
};

struct PoseSection {
  uint32_t order = 2, vertices = 1, model = 0, bits = 8, model_joint = 0, kind = 1, bounces = 0;
  uint32_t pose_dims = 0, basis_dims = 1, flags = 0;
  float albedo = 0.8f;
  std::vector<PoseJoint> joints{PoseJoint{}};
  std::vector<uint32_t> eval_order{0};
  std::vector<float> pose_mean, pose_basis, pose_range, regression, basis_params;
  std::vector<uint16_t> values;  // V x q (u8 or u16 by bits)
  std::vector<PoseSkin> skin;

  uint32_t coefficients() const { return order * order; }
  uint32_t joint_count() const { return uint32_t(joints.size()); }
  uint32_t features() const { return 3 * joint_count(); }
  // Resizes every array to the header's counts (zeros, unit skin) keeping what is there.
  void fit() {
    const uint32_t f = features(), p = pose_dims, q = basis_dims, c = coefficients();
    pose_mean.resize(f);
    pose_basis.resize(size_t(f) * p);
    pose_range.resize(size_t(p) * 2);
    regression.resize(size_t(p + 1) * q * c);
    basis_params.resize(size_t(q) * 2);
    values.resize(size_t(vertices) * q);
    skin.resize(vertices);
  }
  float& x(uint32_t row, uint32_t k, uint32_t c) {
    return regression[(size_t(row) * basis_dims + k) * coefficients() + c];
  }
};

inline void put_f32(Bytes& b, size_t off, float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  put_u32(b, off, u);
}

inline prt_blob_pstr_layout pstr_layout(const PoseSection& s) {
  prt_blob_pstr_layout l{};
  prt_blob_pstr_layout_of(s.order, s.vertices, s.joint_count(), s.pose_dims, s.basis_dims, s.bits,
                          &l);
  return l;
}

inline Bytes encode(const PoseSection& s) {
  const prt_blob_pstr_layout l = pstr_layout(s);
  Bytes b(l.raw_size, 0);
  const uint32_t header[10] = {s.order, s.vertices, s.joint_count(), s.pose_dims, s.basis_dims,
                               s.model, s.bits,     s.model_joint,   s.kind,      s.bounces};
  for (int i = 0; i < 10; ++i) put_u32(b, 4 * i, header[i]);
  put_f32(b, PRT_BLOB_PSTR_OFF_ALBEDO, s.albedo);
  put_u32(b, PRT_BLOB_PSTR_OFF_FLAGS, s.flags);
  for (size_t j = 0; j < s.joints.size(); ++j) {
    const PoseJoint& joint = s.joints[j];
    size_t at = l.joints + PRT_BLOB_PSTR_JOINT_SIZE * j;
    put_u32(b, at, uint32_t(joint.parent));
    at += 4;
    for (float f : joint.bind) put_f32(b, at, f), at += 4;
    for (float f : joint.translation) put_f32(b, at, f), at += 4;
    for (float f : joint.scale) put_f32(b, at, f), at += 4;
    for (float f : joint.pre) put_f32(b, at, f), at += 4;
    for (float f : joint.inverse_bind) put_f32(b, at, f), at += 4;
  }
  for (size_t i = 0; i < s.eval_order.size(); ++i)
    put_u32(b, l.eval_order + 4 * i, s.eval_order[i]);
  auto floats = [&](uint64_t at, const std::vector<float>& v) {
    for (size_t i = 0; i < v.size(); ++i) put_f32(b, at + 4 * i, v[i]);
  };
  floats(l.pose_mean, s.pose_mean);
  floats(l.pose_basis, s.pose_basis);
  floats(l.pose_range, s.pose_range);
  floats(l.regression, s.regression);
  floats(l.basis_params, s.basis_params);
  for (size_t i = 0; i < s.values.size(); ++i) {
    if (s.bits == 8)
      b[l.basis_values + i] = uint8_t(s.values[i]);
    else
      put_u16(b, l.basis_values + 2 * i, s.values[i]);
  }
  for (size_t v = 0; v < s.skin.size(); ++v) {
    const PoseSkin& k = s.skin[v];
    size_t at = l.skin + PRT_BLOB_PSTR_SKIN_SIZE * v;
    for (float f : k.position) put_f32(b, at, f), at += 4;
    for (float f : k.normal) put_f32(b, at, f), at += 4;
    for (uint8_t j : k.joints) b[at++] = j;
    for (uint16_t w : k.weights) put_u16(b, at, w), at += 2;
  }
  return b;
}

inline Bytes pose_blob(const PoseSection& s) {
  return mesh_blob(PRT_BLOB_TAG_PSTR, encode(s), s.vertices);
}

// ---- the SPEC's maths, restated in double ----

inline Quat axis_angle(double x, double y, double z, double angle) {
  const double len = std::sqrt(x * x + y * y + z * z), s = std::sin(angle / 2) / len;
  return {x * s, y * s, z * s, std::cos(angle / 2)};
}

// Hamilton product a b, (x, y, z, w).
inline Quat quat_mul(const Quat& a, const Quat& b) {
  return {a[3] * b[0] + b[3] * a[0] + a[1] * b[2] - a[2] * b[1],
          a[3] * b[1] + b[3] * a[1] + a[2] * b[0] - a[0] * b[2],
          a[3] * b[2] + b[3] * a[2] + a[0] * b[1] - a[1] * b[0],
          a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

inline std::array<float, 4> to_float4(const Quat& q) {
  return {float(q[0]), float(q[1]), float(q[2]), float(q[3])};
}

inline Affine affine_mul(const Affine& a, const Affine& b) {
  Affine out{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      double s = c == 3 ? a[4 * r + 3] : 0.0;
      for (int k = 0; k < 3; ++k) s += a[4 * r + k] * b[4 * k + c];
      out[4 * r + c] = s;
    }
  return out;
}

inline Affine from_float12(const std::array<float, 12>& m) {
  Affine a;
  for (int i = 0; i < 12; ++i) a[i] = m[i];
  return a;
}

// T(t) R(q) S(s).
inline Affine trs(const std::array<double, 3>& t, Quat q, const std::array<double, 3>& s) {
  const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= len;
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                       2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                       2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
  Affine a;
  for (int i = 0; i < 3; ++i) {
    for (int c = 0; c < 3; ++c) a[4 * i + c] = r[3 * i + c] * s[c];
    a[4 * i + 3] = t[i];
  }
  return a;
}

// Every joint's G_j (character space) at the given rotations and the stored rest values.
inline std::vector<Affine> globals(const PoseSection& s, const std::vector<float>& rotations) {
  std::vector<Affine> g(s.joints.size());
  for (uint32_t j : s.eval_order) {
    const PoseJoint& joint = s.joints[j];
    const Quat q{rotations[4 * j], rotations[4 * j + 1], rotations[4 * j + 2],
                 rotations[4 * j + 3]};
    const Affine local = trs({joint.translation[0], joint.translation[1], joint.translation[2]}, q,
                             {joint.scale[0], joint.scale[1], joint.scale[2]});
    const Affine pre_local = affine_mul(from_float12(joint.pre), local);
    g[j] = joint.parent < 0 ? pre_local : affine_mul(g[joint.parent], pre_local);
  }
  return g;
}

// The model frame [R_m | o_m] by Gram-Schmidt of G_m's columns.
inline Affine model_frame(const Affine& gm) {
  double x[3] = {gm[0], gm[4], gm[8]}, y[3] = {gm[1], gm[5], gm[9]}, z[3];
  const double lx = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  for (double& c : x) c /= lx;
  const double d = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  for (int i = 0; i < 3; ++i) y[i] -= d * x[i];
  const double ly = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  for (double& c : y) c /= ly;
  z[0] = x[1] * y[2] - x[2] * y[1];
  z[1] = x[2] * y[0] - x[0] * y[2];
  z[2] = x[0] * y[1] - x[1] * y[0];
  return {x[0], y[0], z[0], gm[3], x[1], y[1], z[1], gm[7], x[2], y[2], z[2], gm[11]};
}

// A general affine inverse (not only rigid), so that it checks the runtime's rigid one.
inline Affine affine_inverse(const Affine& a) {
  const double m[9] = {a[0], a[1], a[2], a[4], a[5], a[6], a[8], a[9], a[10]};
  const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                     m[2] * (m[3] * m[7] - m[4] * m[6]);
  double inv[9] = {(m[4] * m[8] - m[5] * m[7]) / det, (m[2] * m[7] - m[1] * m[8]) / det,
                   (m[1] * m[5] - m[2] * m[4]) / det, (m[5] * m[6] - m[3] * m[8]) / det,
                   (m[0] * m[8] - m[2] * m[6]) / det, (m[2] * m[3] - m[0] * m[5]) / det,
                   (m[3] * m[7] - m[4] * m[6]) / det, (m[1] * m[6] - m[0] * m[7]) / det,
                   (m[0] * m[4] - m[1] * m[3]) / det};
  Affine out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[4 * r + c] = inv[3 * r + c];
    out[4 * r + 3] = -(inv[3 * r] * a[3] + inv[3 * r + 1] * a[7] + inv[3 * r + 2] * a[11]);
  }
  return out;
}

struct SkinnedVertex {
  std::array<double, 3> position, normal;
};

// Vertex v skinned per SPEC §7.3 "Skin": K = sum (w/sum w) K_j; normal by the inverse transpose.
inline SkinnedVertex skin_vertex(const PoseSection& s, const std::vector<float>& rotations,
                                 uint32_t v) {
  const std::vector<Affine> g = globals(s, rotations);
  const Affine m_inv = affine_inverse(model_frame(g[s.model_joint]));
  const PoseSkin& k = s.skin[v];
  double total = 0;
  for (uint16_t w : k.weights) total += w / 65535.0;
  Affine kk = identity_affine();
  if (total > 0) {
    kk.fill(0);
    for (int i = 0; i < 4; ++i) {
      if (k.weights[i] == 0) continue;
      const Affine kj = affine_mul(
          m_inv, affine_mul(g[k.joints[i]], from_float12(s.joints[k.joints[i]].inverse_bind)));
      for (int e = 0; e < 12; ++e) kk[e] += k.weights[i] / 65535.0 / total * kj[e];
    }
  }
  SkinnedVertex out;
  for (int r = 0; r < 3; ++r)
    out.position[r] = kk[4 * r] * k.position[0] + kk[4 * r + 1] * k.position[1] +
                      kk[4 * r + 2] * k.position[2] + kk[4 * r + 3];
  const Affine inv = affine_inverse(kk);  // n' = inv^T n
  double len = 0;
  for (int r = 0; r < 3; ++r) {
    out.normal[r] = inv[r] * k.normal[0] + inv[4 + r] * k.normal[1] + inv[8 + r] * k.normal[2];
    len += out.normal[r] * out.normal[r];
  }
  for (double& c : out.normal) c /= std::sqrt(len);
  return out;
}

// The features a per SPEC §7.3 "Features".
inline std::vector<double> features(const PoseSection& s, const std::vector<float>& rotations) {
  std::vector<double> a(s.features(), 0.0);
  for (uint32_t j = 0; j < s.joint_count(); ++j) {
    if (j == s.model_joint) continue;
    Quat q{rotations[4 * j], rotations[4 * j + 1], rotations[4 * j + 2], rotations[4 * j + 3]};
    const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& c : q) c /= len;
    const auto& b = s.joints[j].bind;
    Quat r = quat_mul({-b[0], -b[1], -b[2], b[3]}, q);
    if (r[3] < 0)
      for (double& c : r) c = -c;
    const double v = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int i = 0; i < 3; ++i)
      a[3 * j + i] = v > 0 ? 2 * std::atan2(v, r[3]) * r[i] / v : 2 * r[i];
  }
  return a;
}

// Pose coordinates z and the coefficients y[k][c] of a pose.
inline std::vector<double> coordinates(const PoseSection& s, const std::vector<float>& rotations) {
  const std::vector<double> a = features(s, rotations);
  std::vector<double> z(s.pose_dims, 0.0);
  for (uint32_t i = 0; i < s.pose_dims; ++i) {
    for (uint32_t f = 0; f < s.features(); ++f)
      z[i] += double(s.pose_basis[size_t(f) * s.pose_dims + i]) * (a[f] - s.pose_mean[f]);
    if (s.flags & PRT_BLOB_PSTR_FLAG_CLAMP)
      z[i] = std::min(std::max(z[i], double(s.pose_range[2 * i])), double(s.pose_range[2 * i + 1]));
  }
  return z;
}

inline std::vector<double> coefficients(const PoseSection& s, const std::vector<float>& rotations) {
  const std::vector<double> z = coordinates(s, rotations);
  const uint32_t n2 = s.coefficients();
  std::vector<double> y(size_t(s.basis_dims) * n2);
  for (uint32_t k = 0; k < s.basis_dims; ++k)
    for (uint32_t c = 0; c < n2; ++c) {
      double sum = s.regression[size_t(k) * n2 + c];
      for (uint32_t i = 0; i < s.pose_dims; ++i)
        sum += z[i] * s.regression[(size_t(i + 1) * s.basis_dims + k) * n2 + c];
      y[size_t(k) * n2 + c] = sum;
    }
  return y;
}

inline double basis_u(const PoseSection& s, uint32_t v, uint32_t k) {
  return double(s.basis_params[2 * k]) +
         double(s.basis_params[2 * k + 1]) * s.values[size_t(v) * s.basis_dims + k];
}

// ---- random sections ----

// A chain skeleton (joint j's parent j - 1; joint 0 the model joint), evaluated in reverse
// storage order where that is valid, with rest poses, pre and inverse-bind matrices, a pose
// PCA, a regression, a basis and skin weights over up to four joints, all from `seed`.
inline PoseSection random_section(uint32_t order, uint32_t vertices, uint32_t joints,
                                  uint32_t pose_dims, uint32_t basis_dims, uint32_t bits,
                                  uint32_t model, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PoseSection s;
  s.order = order, s.vertices = vertices, s.pose_dims = pose_dims, s.basis_dims = basis_dims;
  s.bits = bits, s.model = model, s.albedo = 0.7f;
  s.joints.assign(joints, PoseJoint{});
  s.eval_order.clear();
  for (uint32_t j = 0; j < joints; ++j) {
    PoseJoint& joint = s.joints[j];
    joint.parent = j == 0 ? -1 : int32_t(j - 1);
    joint.bind = to_float4(axis_angle(unit(rng), unit(rng), unit(rng) + 2.0, unit(rng)));
    for (float& t : joint.translation) t = float(unit(rng));
    for (float& c : joint.scale) c = float(1.0 + 0.2 * unit(rng));
    const Affine pre = trs({unit(rng), unit(rng), unit(rng)},
                           axis_angle(unit(rng), 1.0, unit(rng), 0.5 * unit(rng)), {1, 1, 1});
    const Affine ib = trs({unit(rng), unit(rng), unit(rng)},
                          axis_angle(1.0, unit(rng), unit(rng), 0.5 * unit(rng)), {1.1, 0.9, 1.0});
    for (int e = 0; e < 12; ++e) joint.pre[e] = float(pre[e]), joint.inverse_bind[e] = float(ib[e]);
    s.eval_order.push_back(j);
  }
  s.fit();
  for (float& f : s.pose_mean) f = float(0.3 * unit(rng));
  for (float& f : s.pose_basis) f = float(unit(rng));
  for (uint32_t i = 0; i < pose_dims; ++i) s.pose_range[2 * i] = -4, s.pose_range[2 * i + 1] = 4;
  for (float& f : s.regression) f = float(0.5 * unit(rng));
  const double top = bits == 8 ? 255.0 : 65535.0;
  for (uint32_t k = 0; k < basis_dims; ++k) {
    s.basis_params[2 * k] = float(unit(rng));
    s.basis_params[2 * k + 1] = float((1.0 + unit(rng)) / top);
  }
  std::uniform_int_distribution<uint32_t> value(0, uint32_t(top));
  for (uint16_t& q : s.values) q = uint16_t(value(rng));
  std::uniform_int_distribution<uint32_t> joint_of(0, joints - 1), weight(0, 65535);
  for (PoseSkin& k : s.skin) {
    for (float& p : k.position) p = float(unit(rng));
    for (float& n : k.normal) n = float(unit(rng));
    k.normal[2] += 2.0f;
    for (int i = 0; i < 4; ++i) {
      k.joints[i] = uint8_t(joint_of(rng));
      k.weights[i] = uint16_t(i < 2 ? weight(rng) : (weight(rng) < 20000 ? weight(rng) : 0));
    }
  }
  return s;
}

// Random rotations (unnormalised on purpose: the runtime normalises them), J x 4.
inline std::vector<float> random_rotations(uint32_t joints, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<float> r;
  for (uint32_t j = 0; j < joints; ++j) {
    const Quat q = axis_angle(unit(rng), unit(rng), unit(rng), 2.0 * unit(rng));
    const double scale = 1.5 + unit(rng);
    for (double c : q) r.push_back(float(c * scale));
  }
  return r;
}

inline prt_pose_input pose_of(const std::vector<float>& rotations) {
  prt_pose_input in{};
  in.struct_size = sizeof in;
  in.joint_rotations = rotations.data();
  return in;
}

}  // namespace prt_test
