// SPDX-License-Identifier: MIT
// The PSTR section bytes (formats/SPEC.md §7.3, formats/include/prt/format/pose_layout.h).
#include "prt/baker/pose/pose_blob.hpp"

#include <prt/format/pose_layout.h>
#include <prt/format/sh_layout.h>

#include <cstring>
#include <string>

namespace prt::bake {
namespace {

class SectionBytes {
 public:
  explicit SectionBytes(std::size_t size) : bytes_(size, 0) {}
  void u32(std::uint64_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes_[at + i] = std::uint8_t(v >> (8 * i));
  }
  void f32(std::uint64_t at, float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    u32(at, bits);
  }
  void u16(std::uint64_t at, std::uint16_t v) {
    bytes_[at] = std::uint8_t(v);
    bytes_[at + 1] = std::uint8_t(v >> 8);
  }
  void u8(std::uint64_t at, std::uint8_t v) { bytes_[at] = v; }
  // A glm (column-major) affine matrix as SPEC's 3x4 row-major [R | t].
  void affine(std::uint64_t at, const glm::mat4& m) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) f32(at + 4u * (4 * r + c), m[c][r]);
  }
  void floats(std::uint64_t at, const std::vector<float>& values) {
    for (std::size_t i = 0; i < values.size(); ++i) f32(at + 4 * i, values[i]);
  }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
};

std::uint32_t pose_kind_code(ShTransferKind kind) {
  switch (kind) {
    case ShTransferKind::Unshadowed:
      return PRT_BLOB_SHTR_KIND_UNSHADOWED;
    case ShTransferKind::Shadowed:
      return PRT_BLOB_SHTR_KIND_SHADOWED;
    case ShTransferKind::Interreflected:
      return PRT_BLOB_SHTR_KIND_INTERREFLECTED;
  }
  return PRT_BLOB_SHTR_KIND_SHADOWED;
}

void check_sizes(const PoseSkeleton& s, const PoseModel& m, std::size_t C) {
  const std::size_t J = s.joints.size(), V = m.vertex_count, p = m.pose_dims, q = m.basis_dims;
  const bool ok =
      m.feature_count == 3 * J && s.eval_order.size() == J && s.local_positions.size() == V &&
      s.local_normals.size() == V && s.skin_joints.size() == V && s.skin_weights.size() == V &&
      m.pose_mean.size() == 3 * J && m.pose_basis.size() == 3 * J * p && m.pose_min.size() == p &&
      m.pose_max.size() == p && m.regression.size() == (p + 1) * q * C &&
      m.basis_offset.size() == q && m.basis_scale.size() == q && m.basis_values.size() == V * q;
  if (!ok) throw Error("pose blob: the skeleton and the model do not match");
}

void write_header(SectionBytes& out, const PoseSkeleton& s, const PoseModel& m, ShTransferKind kind,
                  int bounces) {
  out.u32(PRT_BLOB_PSTR_OFF_ORDER, m.order);
  out.u32(PRT_BLOB_PSTR_OFF_VERTICES, std::uint32_t(m.vertex_count));
  out.u32(PRT_BLOB_PSTR_OFF_JOINTS, std::uint32_t(s.joints.size()));
  out.u32(PRT_BLOB_PSTR_OFF_POSE_DIMS, m.pose_dims);
  out.u32(PRT_BLOB_PSTR_OFF_BASIS_DIMS, m.basis_dims);
  out.u32(PRT_BLOB_PSTR_OFF_MODEL, m.kind == PoseModelKind::Direct ? PRT_BLOB_PSTR_MODEL_DIRECT
                                                                   : PRT_BLOB_PSTR_MODEL_RESIDUAL);
  out.u32(PRT_BLOB_PSTR_OFF_BITS, std::uint32_t(m.bits));
  out.u32(PRT_BLOB_PSTR_OFF_MODEL_JOINT, s.model_joint);
  out.u32(PRT_BLOB_PSTR_OFF_KIND, pose_kind_code(kind));
  out.u32(PRT_BLOB_PSTR_OFF_BOUNCES, std::uint32_t(bounces > 0 ? bounces : 0));
  out.f32(PRT_BLOB_PSTR_OFF_ALBEDO, m.albedo);
  out.u32(PRT_BLOB_PSTR_OFF_FLAGS, m.clamp ? PRT_BLOB_PSTR_FLAG_CLAMP : 0u);
}

void write_joints(SectionBytes& out, const PoseSkeleton& s, const prt_blob_pstr_layout& layout) {
  for (std::size_t j = 0; j < s.joints.size(); ++j) {
    const PoseSkeleton::Joint& joint = s.joints[j];
    const std::uint64_t at = layout.joints + PRT_BLOB_PSTR_JOINT_SIZE * j;
    out.u32(at + PRT_BLOB_PSTR_JOINT_OFF_PARENT, std::uint32_t(std::int32_t(joint.parent)));
    const glm::quat& b = joint.bind_rotation;
    out.floats(at + PRT_BLOB_PSTR_JOINT_OFF_BIND_ROTATION, {b.x, b.y, b.z, b.w});
    const glm::vec3& t = joint.rest_translation;
    const glm::vec3& sc = joint.rest_scale;
    out.floats(at + PRT_BLOB_PSTR_JOINT_OFF_TRANSLATION, {t.x, t.y, t.z});
    out.floats(at + PRT_BLOB_PSTR_JOINT_OFF_SCALE, {sc.x, sc.y, sc.z});
    out.affine(at + PRT_BLOB_PSTR_JOINT_OFF_PRE, joint.pre);
    out.affine(at + PRT_BLOB_PSTR_JOINT_OFF_INVERSE_BIND, joint.inverse_bind);
    out.u32(layout.eval_order + 4 * j, s.eval_order[j]);
  }
}

void write_skin(SectionBytes& out, const PoseSkeleton& s, const prt_blob_pstr_layout& layout) {
  for (std::size_t v = 0; v < s.local_positions.size(); ++v) {
    const std::uint64_t at = layout.skin + PRT_BLOB_PSTR_SKIN_SIZE * v;
    const glm::vec3& p = s.local_positions[v];
    const glm::vec3& n = s.local_normals[v];
    out.floats(at + PRT_BLOB_PSTR_SKIN_OFF_POSITION, {p.x, p.y, p.z});
    out.floats(at + PRT_BLOB_PSTR_SKIN_OFF_NORMAL, {n.x, n.y, n.z});
    for (int k = 0; k < 4; ++k) {
      out.u8(at + PRT_BLOB_PSTR_SKIN_OFF_JOINTS + k, s.skin_joints[v][k]);
      out.u16(at + PRT_BLOB_PSTR_SKIN_OFF_WEIGHTS + 2 * k, s.skin_weights[v][k]);
    }
  }
}

}  // namespace

std::vector<std::uint8_t> encode_pstr_section(const PoseSkeleton& s, const PoseModel& m,
                                              ShTransferKind kind, int bounces) {
  prt_blob_pstr_layout layout;
  if (m.vertex_count > 0xffffffffu ||
      !prt_blob_pstr_layout_of(m.order, std::uint32_t(m.vertex_count),
                               std::uint32_t(s.joints.size()), m.pose_dims, m.basis_dims,
                               std::uint32_t(m.bits), &layout)) {
    throw Error("pose blob: the layout cannot hold order " + std::to_string(m.order) + ", " +
                std::to_string(s.joints.size()) + " joints, PCA(" + std::to_string(m.pose_dims) +
                ", " + std::to_string(m.basis_dims) + "), " + std::to_string(m.bits) + " bits");
  }
  const std::size_t C = layout.coefficients;
  check_sizes(s, m, C);
  SectionBytes out(layout.raw_size);
  write_header(out, s, m, kind, bounces);
  write_joints(out, s, layout);
  out.floats(layout.pose_mean, m.pose_mean);
  out.floats(layout.pose_basis, m.pose_basis);
  for (std::uint32_t i = 0; i < m.pose_dims; ++i) {
    out.f32(layout.pose_range + 8u * i, m.pose_min[i]);
    out.f32(layout.pose_range + 8u * i + 4, m.pose_max[i]);
  }
  out.floats(layout.regression, m.regression);
  for (std::uint32_t k = 0; k < m.basis_dims; ++k) {
    out.f32(layout.basis_params + 8u * k, m.basis_offset[k]);
    out.f32(layout.basis_params + 8u * k + 4, m.basis_scale[k]);
  }
  for (std::size_t i = 0; i < m.basis_values.size(); ++i) {
    if (m.bits == 8) {
      out.u8(layout.basis_values + i, std::uint8_t(m.basis_values[i]));
    } else {
      out.u16(layout.basis_values + 2 * i, m.basis_values[i]);
    }
  }
  write_skin(out, s, layout);
  return out.take();
}

}  // namespace prt::bake
