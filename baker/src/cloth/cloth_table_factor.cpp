// SPDX-License-Identifier: MIT
// The truncated SVD of a cloth table (formats/SPEC.md §7.4: T ~ U V^T with the singular values
// folded into U) and the size of its stored factorisation.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "prt/baker/cloth/cloth_tables.hpp"

#include "../common/thin_svd.hpp"

namespace prt::bake {
namespace {

constexpr std::uint32_t kMaxRank = 64;

std::uint64_t align4(std::uint64_t bytes) {
  return (bytes + 3) & ~std::uint64_t(3);
}

}  // namespace

std::uint32_t cloth_rank_for_energy(const std::vector<double>& singular_values, double energy,
                                    std::uint32_t max_rank) {
  const std::uint32_t cap = std::max<std::uint32_t>(
      1, std::min<std::uint32_t>({max_rank, kMaxRank, std::uint32_t(singular_values.size())}));
  double total = 0.0;
  for (const double s : singular_values) total += s * s;
  // tail[r]: the squared norm the rank-r truncation leaves, summed from the smallest value.
  std::vector<double> tail(singular_values.size() + 1, 0.0);
  for (std::size_t r = singular_values.size(); r-- > 0;)
    tail[r] = tail[r + 1] + singular_values[r] * singular_values[r];
  for (std::uint32_t r = 1; r < cap; ++r)
    if (tail[r] <= energy * total) return r;
  return cap;
}

std::uint64_t cloth_factor_bytes(const ClothGrid& grid, std::uint32_t rank, int bits) {
  const std::uint64_t value = std::uint64_t(bits / 8);
  return 8 * std::uint64_t(rank) + align4(grid.columns() * rank * value) +
         align4(grid.rows() * rank * value);
}

ClothFactor factor_cloth_table(const std::vector<float>& table, std::uint64_t rows,
                               std::uint64_t columns, const ClothFactorOptions& options,
                               ClothFactorReport* report) {
  if (rows == 0 || columns == 0 || table.size() != rows * columns)
    throw Error("cloth tables: a table's size does not match its rows and columns");
  Eigen::MatrixXd a(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(columns));
  for (std::uint64_t r = 0; r < rows; ++r)
    for (std::uint64_t c = 0; c < columns; ++c)
      a(Eigen::Index(r), Eigen::Index(c)) = table[r * columns + c];
  const ThinSvd svd = thin_svd(a, true);
  const Eigen::VectorXd& sigma = svd.singular_values;
  std::vector<double> values(sigma.data(), sigma.data() + sigma.size());

  std::uint32_t rank = cloth_rank_for_energy(values, options.energy, options.max_rank);
  if (options.fixed_rank > 0)
    rank = std::min<std::uint32_t>({options.fixed_rank, kMaxRank, std::uint32_t(values.size())});
  const Eigen::MatrixXd u = svd.u.leftCols(rank) * sigma.head(rank).asDiagonal();
  const Eigen::MatrixXd v = svd.v.leftCols(rank);

  ClothFactor factor;
  factor.rank = rank;
  factor.u.resize(rows * rank);
  factor.v.resize(columns * rank);
  for (std::uint64_t r = 0; r < rows; ++r)
    for (std::uint32_t k = 0; k < rank; ++k) factor.u[r * rank + k] = float(u(Eigen::Index(r), k));
  for (std::uint64_t c = 0; c < columns; ++c)
    for (std::uint32_t k = 0; k < rank; ++k) factor.v[c * rank + k] = float(v(Eigen::Index(c), k));

  if (report) {
    report->rank = rank;
    report->singular_values = values;
    double total = 0.0, kept = 0.0;
    for (std::size_t r = 0; r < values.size(); ++r) {
      total += values[r] * values[r];
      if (r < rank) kept += values[r] * values[r];
    }
    report->relative_error = total > 0.0 ? std::sqrt(std::max(0.0, total - kept) / total) : 0.0;
    report->max_abs_error = (a - u * v.transpose()).cwiseAbs().maxCoeff();
  }
  return factor;
}

}  // namespace prt::bake
