// SPDX-License-Identifier: MIT
// The numerical parts of the pose model's fit (private to baker/src/pose/): the vertex basis,
// the cross-validation folds, ridge regression and the choice of alpha.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "prt/baker/pose/pose_model.hpp"

namespace prt::bake::pose_detail {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// Sign convention of basis columns: each one's largest entry in magnitude is positive, so
// that the same data give the same basis.
void fix_signs(Matrix& basis);

// Progress through ctx; Error("cancelled") when the callback says stop.
void progress(const Context& ctx, double fraction, const std::string& stage);

// Error for frames or settings the fit cannot use (none, out of range, bits).
void check_settings(const PoseTrainingSet& training, const std::vector<std::size_t>& frames,
                    const PoseModelSettings& settings);

// The leading left singular vectors of `target` (V x n C, uncentred) by a randomised range
// finder with power iterations (deterministic: a fixed pseudo-random test matrix): q columns
// when settings.basis_dims > 0, else the fewest whose truncation leaves at most
// (1 - settings.basis_energy) of `transfer_energy` (the whole transfer's squared norm, so that
// a residual model's basis is cut where its error matters for the transfer); at most 256.
Matrix vertex_basis(const Matrix& target, double transfer_energy,
                    const PoseModelSettings& settings);

// Held-out sets of rows (indices into the fit's frames), one per fold.
using Folds = std::vector<std::vector<Eigen::Index>>;
// Clip: one fold per clip among the frames (Block when they hold one clip); Block: cv_blocks
// contiguous runs; Frame: one fold per frame (solved in closed form by choose_alpha).
Folds folds_of(const PoseTrainingSet& training, const std::vector<std::size_t>& frames,
               const PoseModelSettings& settings);

// X = argmin |y - [1 z] X|^2 + alpha^2 |X without its bias row|^2: (p + 1) x outputs.
Matrix ridge(const Matrix& z, const Matrix& y, double alpha);

// The alpha of a log grid with the least held-out error |dy|^2 / |y|^2 over the folds (the
// larger alpha on a tie); the grid and its errors in *curve_alpha and *curve_error. With fewer
// than two folds or no pose dimension, 0 and an empty curve.
double choose_alpha(const Matrix& z, const Matrix& y, const Folds& folds,
                    std::vector<double>& curve_alpha, std::vector<double>& curve_error);

}  // namespace prt::bake::pose_detail
