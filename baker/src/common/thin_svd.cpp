// SPDX-License-Identifier: MIT
// The thin SVD (thin_svd.hpp): Eigen's BDCSVD, instantiated here only.
#include "thin_svd.hpp"

#include <Eigen/SVD>

namespace prt::bake {

ThinSvd thin_svd(const Eigen::MatrixXd& a, bool with_u) {
  const unsigned int wanted =
      with_u ? unsigned(Eigen::ComputeThinU | Eigen::ComputeThinV) : unsigned(Eigen::ComputeThinV);
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(a, wanted);
  ThinSvd result{svd.singularValues(), with_u ? svd.matrixU() : Eigen::MatrixXd(), svd.matrixV()};
  for (Eigen::Index k = 0; k < result.v.cols(); ++k) {
    Eigen::Index at = 0;
    result.v.col(k).cwiseAbs().maxCoeff(&at);
    if (result.v(at, k) >= 0.0) continue;
    result.v.col(k) = -result.v.col(k);
    if (with_u) result.u.col(k) = -result.u.col(k);
  }
  return result;
}

}  // namespace prt::bake
