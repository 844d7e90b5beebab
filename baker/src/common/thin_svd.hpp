// SPDX-License-Identifier: MIT
// The thin singular value decomposition the techniques factor their tables with. Eigen's BDCSVD
// is slow to compile, so the whole baker instantiates it once, in thin_svd.cpp.
#pragma once

#include <Eigen/Core>

namespace prt::bake {

struct ThinSvd {
  Eigen::VectorXd singular_values;  // descending, min(rows, columns) of them
  Eigen::MatrixXd u;                // rows x min(rows, columns); empty unless asked for
  Eigen::MatrixXd v;                // columns x min(rows, columns)
};

// a = U diag(S) V^T, each pair of singular vectors signed so that V's entry of largest magnitude
// is positive: the SVD's signs are arbitrary, factors stored from it need not be.
ThinSvd thin_svd(const Eigen::MatrixXd& a, bool with_u);

}  // namespace prt::bake
