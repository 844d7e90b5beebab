// SPDX-License-Identifier: MIT
#include "pose_model_detail.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

namespace prt::bake::pose_detail {
namespace {

constexpr Eigen::Index kMaxBasisDims = 256;
constexpr Eigen::Index kOversampling = 10;  // extra test vectors of the range finder
constexpr int kPowerIterations = 3;

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Standard normal test matrix (Box-Muller on splitmix64): the same on every platform.
Matrix gaussian(Eigen::Index rows, Eigen::Index cols) {
  std::uint64_t state = 0x5eed;
  Matrix m(rows, cols);
  const double two_pi = 6.28318530717958647692;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    const double u1 = (double(splitmix64(state) >> 11) + 1.0) * 0x1.0p-53;
    const double u2 = double(splitmix64(state) >> 11) * 0x1.0p-53;
    m.data()[i] = std::sqrt(-2.0 * std::log(u1)) * std::cos(two_pi * u2);
  }
  return m;
}

Matrix orthonormal_columns(const Matrix& a) {
  const Eigen::HouseholderQR<Matrix> qr(a);
  return qr.householderQ() * Matrix::Identity(a.rows(), a.cols());
}

// (z^T z + alpha^2 I)^-1 rhs for centred z: LDLT when alpha > 0 (positive definite), else the
// minimum-norm solution (a pose dimension without variance is rank-deficient).
Matrix solve_normal(const Matrix& zc, const Matrix& rhs, double alpha) {
  if (zc.cols() == 0) return Matrix(0, rhs.cols());
  Matrix a = zc.transpose() * zc;
  a.diagonal().array() += alpha * alpha;
  if (alpha > 0.0) return a.ldlt().solve(rhs);
  return a.completeOrthogonalDecomposition().solve(rhs);
}

Matrix design(const Matrix& z) {
  Matrix d(z.rows(), z.cols() + 1);
  d.col(0).setOnes();
  d.rightCols(z.cols()) = z;
  return d;
}

Matrix rows_of(const Matrix& m, const std::vector<Eigen::Index>& rows) {
  Matrix out(Eigen::Index(rows.size()), m.cols());
  for (std::size_t i = 0; i < rows.size(); ++i) out.row(Eigen::Index(i)) = m.row(rows[i]);
  return out;
}

// Held-out error of one alpha over folds of several frames each.
double fold_error(const Matrix& z, const Matrix& y, const Folds& folds, double alpha) {
  double error = 0.0, energy = 0.0;
  for (const std::vector<Eigen::Index>& held : folds) {
    std::vector<Eigen::Index> kept;
    std::size_t h = 0;
    for (Eigen::Index r = 0; r < z.rows(); ++r) {
      if (h < held.size() && held[h] == r) {
        ++h;
      } else {
        kept.push_back(r);
      }
    }
    const Matrix x = ridge(rows_of(z, kept), rows_of(y, kept), alpha);
    const Matrix truth = rows_of(y, held);
    error += (design(rows_of(z, held)) * x - truth).squaredNorm();
    energy += truth.squaredNorm();
  }
  return energy > 0.0 ? error / energy : 0.0;
}

// Leave-one-frame-out error in closed form: residual_i / (1 - H_ii) with H the hat matrix of
// the centred ridge, 1/n + z_c (z_c^T z_c + alpha^2 I)^-1 z_c^T.
double frame_error(const Matrix& z, const Matrix& y, double alpha) {
  const Matrix zc = z.rowwise() - z.colwise().mean();
  const Matrix hat = Matrix::Constant(z.rows(), z.rows(), 1.0 / double(z.rows())) +
                     zc * solve_normal(zc, zc.transpose(), alpha);
  const Matrix residual = y - hat * y;
  double error = 0.0;
  for (Eigen::Index i = 0; i < y.rows(); ++i) {
    const double leverage = 1.0 - hat(i, i);
    error += residual.row(i).squaredNorm() / std::max(leverage * leverage, 1e-24);
  }
  const double energy = y.squaredNorm();
  return energy > 0.0 ? error / energy : 0.0;
}

}  // namespace

void fix_signs(Matrix& basis) {
  for (Eigen::Index k = 0; k < basis.cols(); ++k) {
    Eigen::Index at = 0;
    basis.col(k).cwiseAbs().maxCoeff(&at);
    if (basis(at, k) < 0.0) basis.col(k) *= -1.0;
  }
}

void progress(const Context& ctx, double fraction, const std::string& stage) {
  if (ctx.progress && !ctx.progress(fraction, stage)) throw Error("cancelled");
}

void check_settings(const PoseTrainingSet& t, const std::vector<std::size_t>& frames,
                    const PoseModelSettings& s) {
  const std::size_t C = t.coefficient_count(), V = t.vertex_count;
  if (frames.empty()) throw Error("pose model: no training frames");
  for (std::size_t f : frames) {
    if (f >= t.frames.size()) throw Error("pose model: frame index out of range");
  }
  if (t.transfer.size() != t.frames.size() * V * C || t.normals.size() != t.frames.size() * V * 3)
    throw Error("pose model: the training set's arrays do not match its frames and vertices");
  if (V == 0) throw Error("pose model: the character has no vertices");
  if (s.bits != 8 && s.bits != 16) throw Error("pose model: bits must be 8 or 16");
  if (s.basis_dims > kMaxBasisDims) throw Error("pose model: basis dimensions above 256");
  if (s.pose_dims > 3 * t.joint_count())
    throw Error("pose model: pose dimensions above 3 per joint");
  if (!(s.pose_variance >= 0.0 && s.pose_variance <= 1.0) ||
      !(s.basis_energy >= 0.0 && s.basis_energy <= 1.0))
    throw Error("pose model: variance and energy shares must be in [0, 1]");
}

Matrix vertex_basis(const Matrix& target, double transfer_energy, const PoseModelSettings& s) {
  const Eigen::Index wanted = s.basis_dims > 0 ? Eigen::Index(s.basis_dims) : kMaxBasisDims;
  const Eigen::Index k = std::min({wanted + kOversampling, target.rows(), target.cols()});
  Matrix q = orthonormal_columns(target * gaussian(target.cols(), k));
  for (int i = 0; i < kPowerIterations; ++i) {
    q = orthonormal_columns(target * (target.transpose() * q));
  }
  const Matrix b = q.transpose() * target;  // k x n C
  const Eigen::SelfAdjointEigenSolver<Matrix> eig(b * b.transpose());
  const Vector energy = eig.eigenvalues().reverse().cwiseMax(0.0);
  const Matrix basis = q * eig.eigenvectors().rowwise().reverse();
  const double total = target.squaredNorm();
  Eigen::Index dims = std::min(wanted, k);
  if (s.basis_dims == 0) {
    dims = 0;
    double kept = 0.0;
    const double allowed = (1.0 - s.basis_energy) * transfer_energy;
    while (dims < std::min(kMaxBasisDims, k) && total - kept > allowed) kept += energy(dims++);
  }
  dims = std::max<Eigen::Index>(dims, 1);
  Matrix out = basis.leftCols(dims);
  fix_signs(out);
  return out;
}

Folds folds_of(const PoseTrainingSet& t, const std::vector<std::size_t>& frames,
               const PoseModelSettings& s) {
  const auto n = Eigen::Index(frames.size());
  Folds folds;
  if (s.cv == PoseCrossValidation::Clip) {
    std::map<std::uint32_t, std::vector<Eigen::Index>> by_clip;
    for (Eigen::Index r = 0; r < n; ++r)
      by_clip[t.frames[frames[std::size_t(r)]].clip].push_back(r);
    if (by_clip.size() >= 2) {
      for (auto& [clip, rows] : by_clip) folds.push_back(std::move(rows));
      return folds;
    }
  }
  if (s.cv == PoseCrossValidation::Frame) {
    for (Eigen::Index r = 0; r < n; ++r) folds.push_back({r});
    return folds;
  }
  const Eigen::Index blocks = std::min<Eigen::Index>(std::max<std::uint32_t>(s.cv_blocks, 2), n);
  for (Eigen::Index b = 0; b < blocks && n >= 2; ++b) {
    std::vector<Eigen::Index> rows;
    for (Eigen::Index r = b * n / blocks; r < (b + 1) * n / blocks; ++r) rows.push_back(r);
    folds.push_back(std::move(rows));
  }
  return folds;
}

Matrix ridge(const Matrix& z, const Matrix& y, double alpha) {
  // The bias is not penalised, so it is the means' fit: centre, solve, then bias = y - z W.
  const Eigen::RowVectorXd z_mean = z.colwise().mean(), y_mean = y.colwise().mean();
  const Matrix zc = z.rowwise() - z_mean;
  Matrix x(z.cols() + 1, y.cols());
  x.bottomRows(z.cols()) = solve_normal(zc, zc.transpose() * (y.rowwise() - y_mean), alpha);
  x.row(0) = y_mean - z_mean * x.bottomRows(z.cols());
  return x;
}

double choose_alpha(const Matrix& z, const Matrix& y, const Folds& folds,
                    std::vector<double>& curve_alpha, std::vector<double>& curve_error) {
  curve_alpha.clear();
  curve_error.clear();
  if (folds.size() < 2 || z.cols() == 0) return 0.0;
  const bool single_frames =
      std::all_of(folds.begin(), folds.end(), [](const auto& f) { return f.size() == 1; });
  const Eigen::SelfAdjointEigenSolver<Matrix> eig(z.transpose() * z);
  const double largest = eig.eigenvalues().maxCoeff();
  const double scale = largest > 0.0 ? std::sqrt(largest) : 1.0;
  double best_alpha = 0.0, best_error = INFINITY;
  for (int step = -1; step <= 24; ++step) {
    // 0, then scale * 10^-4 .. 10^2 in quarter decades.
    const double alpha = step < 0 ? 0.0 : scale * std::pow(10.0, -4.0 + 0.25 * step);
    const double error = single_frames ? frame_error(z, y, alpha) : fold_error(z, y, folds, alpha);
    curve_alpha.push_back(alpha);
    curve_error.push_back(error);
    if (error <= best_error) best_error = error, best_alpha = alpha;
  }
  return best_alpha;
}

}  // namespace prt::bake::pose_detail
