// SPDX-License-Identifier: MIT
// The learned model of technique `pose` (prt/baker/pose/pose_model.hpp): pose PCA, one
// uncentred vertex basis for every coefficient (randomised range finder), least-squares
// coefficients per frame on the quantised basis, ridge regression with an unpenalised bias and
// alpha by cross-validation (leave one clip, block or frame out).
#include "prt/baker/pose/pose_model.hpp"

#include <prt/prt_sh.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "pose_model_detail.hpp"

namespace prt::bake {
namespace {

// t_00 of an unoccluded surface of albedo 1: (A_0 / pi) y_00 = 1 / (2 sqrt(pi)).
constexpr double kUnoccludedT00 = 0.28209479177387814;

using pose_detail::Matrix;
using pose_detail::Vector;

// Pose PCA of the frames' features: mean, basis (F x p) and the coordinates (frames x p).
struct PosePca {
  Vector mean;
  Matrix basis;
};

PosePca fit_pose_pca(const Matrix& features, const PoseModelSettings& s) {
  PosePca pca;
  pca.mean = features.colwise().mean().transpose();
  const Matrix centred = features.rowwise() - pca.mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Matrix> eig(centred.transpose() * centred);
  const Vector values = eig.eigenvalues().reverse().cwiseMax(0.0);
  const Matrix vectors = eig.eigenvectors().rowwise().reverse();
  const double total = values.sum();
  Eigen::Index p = s.pose_dims;
  if (s.pose_dims == 0) {
    p = 0;
    double kept = 0.0;
    // Dimensions without variance carry nothing a regression could use.
    while (p < values.size() && total > 0.0 && values(p) > 1e-12 * total &&
           kept < s.pose_variance * total) {
      kept += values(p++);
    }
  }
  p = std::min<Eigen::Index>(p, features.cols());
  pca.basis = vectors.leftCols(p);
  pose_detail::fix_signs(pca.basis);
  return pca;
}

// The learned target of every frame, vertex-major per frame: V x (frames * C).
Matrix learned_target(const PoseTrainingSet& t, const std::vector<std::size_t>& frames,
                      PoseModelKind kind) {
  const std::size_t V = t.vertex_count, C = t.coefficient_count();
  Matrix target(V, frames.size() * C);
  std::vector<float> exact(C);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const float* transfer = t.frame_transfer(frames[i]);
    const float* normals = t.frame_normals(frames[i]);
    for (std::size_t v = 0; v < V; ++v) {
      std::fill(exact.begin(), exact.end(), 0.0f);
      if (kind == PoseModelKind::Residual) {
        unshadowed_transfer(t.order, t.albedo, normals + 3 * v, exact.data());
      }
      for (std::size_t c = 0; c < C; ++c) {
        target(Eigen::Index(v), Eigen::Index(i * C + c)) =
            double(transfer[v * C + c]) - double(exact[c]);
      }
    }
  }
  return target;
}

// Quantises each basis column as SPEC §7.3 stores it; returns the dequantised basis.
Matrix quantize_basis(const Matrix& basis, int bits, PoseModel& m) {
  const double levels = std::ldexp(1.0, bits) - 1.0;
  const Eigen::Index V = basis.rows(), q = basis.cols();
  m.basis_offset.assign(q, 0.0f);
  m.basis_scale.assign(q, 0.0f);
  m.basis_values.assign(std::size_t(V * q), 0);
  Matrix dequantized(V, q);
  for (Eigen::Index k = 0; k < q; ++k) {
    const float lo = float(basis.col(k).minCoeff()), hi = float(basis.col(k).maxCoeff());
    const float scale = hi > lo ? float((double(hi) - double(lo)) / levels) : 0.0f;
    m.basis_offset[k] = lo;
    m.basis_scale[k] = scale;
    for (Eigen::Index v = 0; v < V; ++v) {
      double value = 0.0;
      if (scale > 0.0f) {
        value = std::floor((basis(v, k) - double(lo)) / double(scale) + 0.5);
        value = std::clamp(value, 0.0, levels);
      }
      m.basis_values[std::size_t(v * q + k)] = static_cast<std::uint16_t>(value);
      dequantized(v, k) = double(lo) + double(scale) * value;
    }
  }
  return dequantized;
}

std::size_t model_bytes(const PoseModel& m) {
  const std::size_t F = m.feature_count, p = m.pose_dims, q = m.basis_dims;
  const std::size_t C = std::size_t(m.order) * m.order;
  const std::size_t values = m.vertex_count * q * std::size_t(m.bits / 8);
  return 4 * F + 4 * F * p + 8 * p + 4 * (p + 1) * q * C + 8 * q + ((values + 3) & ~std::size_t(3));
}

void store(const Matrix& m, std::vector<float>& out) {
  out.resize(std::size_t(m.size()));
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) out[std::size_t(r * m.cols() + c)] = float(m(r, c));
}

}  // namespace

PoseModel fit_pose_model(const PoseTrainingSet& training, const PoseModelSettings& settings,
                         const Context& ctx) {
  std::vector<std::size_t> all(training.frames.size());
  std::iota(all.begin(), all.end(), std::size_t(0));
  return fit_pose_model(training, all, settings, ctx);
}

PoseModel fit_pose_model(const PoseTrainingSet& t, const std::vector<std::size_t>& frames,
                         const PoseModelSettings& s, const Context& ctx) {
  pose_detail::check_settings(t, frames, s);
  PoseModel m;
  m.kind = s.kind;
  m.order = t.order;
  m.vertex_count = t.vertex_count;
  m.feature_count = 3 * t.joint_count();
  m.albedo = t.albedo;
  m.clamp = s.clamp;
  m.bits = s.bits;
  const std::size_t C = t.coefficient_count();

  Matrix features(Eigen::Index(frames.size()), Eigen::Index(m.feature_count));
  for (std::size_t i = 0; i < frames.size(); ++i)
    for (std::size_t f = 0; f < m.feature_count; ++f)
      features(Eigen::Index(i), Eigen::Index(f)) = t.frames[frames[i]].features[f];
  const PosePca pca = fit_pose_pca(features, s);
  m.pose_dims = std::uint32_t(pca.basis.cols());
  const Matrix z = (features.rowwise() - pca.mean.transpose()) * pca.basis;
  pose_detail::progress(ctx, 0.2, "pose model: vertex basis");

  const Matrix target = learned_target(t, frames, s.kind);
  double transfer_energy = 0.0;
  for (std::size_t f : frames) {
    const float* transfer = t.frame_transfer(f);
    for (std::size_t i = 0; i < t.vertex_count * C; ++i)
      transfer_energy += double(transfer[i]) * double(transfer[i]);
  }
  const Matrix basis = pose_detail::vertex_basis(target, transfer_energy, s);
  m.basis_dims = std::uint32_t(basis.cols());
  store(basis, m.basis);
  const Matrix dequantized = quantize_basis(basis, s.bits, m);
  pose_detail::progress(ctx, 0.6, "pose model: regression");

  // Each frame's coefficients: least squares on the stored (quantised) basis, frames x (q C).
  const Matrix gram = dequantized.transpose() * dequantized;
  const Matrix projected = gram.ldlt().solve(dequantized.transpose() * target);  // q x (n C)
  Matrix y(Eigen::Index(frames.size()), Eigen::Index(m.basis_dims * C));
  for (std::size_t i = 0; i < frames.size(); ++i)
    for (Eigen::Index k = 0; k < projected.rows(); ++k)
      for (std::size_t c = 0; c < C; ++c)
        y(Eigen::Index(i), Eigen::Index(k * Eigen::Index(C) + Eigen::Index(c))) =
            projected(k, Eigen::Index(i * C + c));

  const pose_detail::Folds folds = pose_detail::folds_of(t, frames, s);
  m.alpha = s.alpha >= 0.0
                ? s.alpha
                : pose_detail::choose_alpha(z, y, folds, m.alpha_curve_alpha, m.alpha_curve_error);
  const Matrix x = pose_detail::ridge(z, y, m.alpha);  // (p + 1) x (q C)
  store(x, m.regression);
  store(pca.mean.transpose(), m.pose_mean);
  store(pca.basis, m.pose_basis);
  m.pose_min.resize(m.pose_dims);
  m.pose_max.resize(m.pose_dims);
  for (std::uint32_t i = 0; i < m.pose_dims; ++i) {
    m.pose_min[i] = float(z.col(i).minCoeff());
    m.pose_max[i] = float(z.col(i).maxCoeff());
  }
  m.model_bytes = model_bytes(m);
  pose_detail::progress(ctx, 1.0, "pose model: done");
  return m;
}

void unshadowed_transfer(std::uint32_t order, float rho, const float n[3], float* out) {
  const std::uint32_t count = order * order;
  std::fill(out, out + count, 0.0f);
  if (!(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.0f)) return;
  float y[PRT_SH_MAX_ORDER * PRT_SH_MAX_ORDER];
  if (prt_sh_eval(order, n, y) != PRT_OK) throw Error("pose: SH order out of range");
  const double pi = 3.14159265358979323846;
  for (std::uint32_t l = 0; l < order; ++l) {
    const double factor = double(rho) * double(prt_sh_cosine_band_factor(l)) / pi;
    for (std::uint32_t c = l * l; c < (l + 1) * (l + 1); ++c) out[c] = float(factor * y[c]);
  }
}

std::vector<float> predict_pose_transfer(const PoseModel& m, const std::vector<float>& features,
                                         const float* normals) {
  const std::size_t C = std::size_t(m.order) * m.order, p = m.pose_dims, q = m.basis_dims;
  if (features.size() != m.feature_count) throw Error("pose: feature count does not match");
  std::vector<double> z(p, 0.0);
  for (std::size_t i = 0; i < p; ++i) {
    for (std::size_t f = 0; f < m.feature_count; ++f)
      z[i] += double(m.pose_basis[f * p + i]) * (double(features[f]) - double(m.pose_mean[f]));
    if (m.clamp) z[i] = std::clamp(z[i], double(m.pose_min[i]), double(m.pose_max[i]));
  }
  std::vector<double> y(q * C);
  for (std::size_t j = 0; j < q * C; ++j) {
    double sum = m.regression[j];
    for (std::size_t i = 0; i < p; ++i) sum += z[i] * double(m.regression[(i + 1) * q * C + j]);
    y[j] = sum;
  }
  std::vector<float> out(m.vertex_count * C), exact(C, 0.0f);
  for (std::size_t v = 0; v < m.vertex_count; ++v) {
    if (m.kind == PoseModelKind::Residual && normals) {
      unshadowed_transfer(m.order, m.albedo, normals + 3 * v, exact.data());
    }
    for (std::size_t c = 0; c < C; ++c) {
      double learned = 0.0;
      for (std::size_t k = 0; k < q; ++k) {
        const double u = double(m.basis_offset[k]) +
                         double(m.basis_scale[k]) * double(m.basis_values[v * q + k]);
        learned += u * y[k * C + c];
      }
      // SPEC §7.3: the learned t_00 within [0, u] (direct) or [-u, 0] (residual), u the
      // unoccluded t_00, so that t_00 stays in the uniform sky's bounds.
      if (c == 0) {
        const double u = double(m.albedo) * kUnoccludedT00;
        learned = m.kind == PoseModelKind::Residual ? std::clamp(learned, -u, 0.0)
                                                    : std::clamp(learned, 0.0, u);
      }
      const double base = m.kind == PoseModelKind::Residual ? double(exact[c]) : 0.0;
      out[v * C + c] = float(base + learned);
    }
  }
  return out;
}

}  // namespace prt::bake
