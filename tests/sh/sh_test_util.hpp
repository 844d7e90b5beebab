// Shared helpers of the SH tests: lat-long projection, indexing, random directions,
// Gauss-Legendre nodes.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <prt/prt.hpp>

namespace prt_sh_test {

// prt_sh_project of a lat-long RGB image of w x h texels whose rows start row_stride floats apart
// (0: tight).
inline prt_result ProjectLatLong(uint32_t order, uint32_t w, uint32_t h, const float* rgb,
                                 size_t row_stride, float* out) {
  prt_env_image env = prt::latlong_env(w, h, rgb);
  env.row_stride = row_stride;
  return prt_sh_project(order, &env, out);
}

constexpr double kPi = 3.14159265358979323846;

inline uint32_t ShIndex(uint32_t l, int m) {
  return static_cast<uint32_t>(static_cast<int>(l * (l + 1)) + m);
}

inline std::array<float, 3> RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  for (;;) {
    const double x = n(rng), y = n(rng), z = n(rng);
    const double len = std::sqrt(x * x + y * y + z * z);
    if (len > 1e-6)
      return {static_cast<float>(x / len), static_cast<float>(y / len),
              static_cast<float>(z / len)};
  }
}

struct Quadrature {
  std::vector<double> nodes;
  std::vector<double> weights;
};

// Gauss-Legendre nodes and weights on [-1, 1] by Newton iteration on P_n (Golub-Welsch
// alternative; standard textbook algorithm, e.g. Numerical Recipes gauleg).
inline Quadrature GaussLegendre(uint32_t n) {
  Quadrature q;
  q.nodes.resize(n);
  q.weights.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (uint32_t k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-15) break;
    }
    q.nodes[i] = x;
    q.weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return q;
}

}  // namespace prt_sh_test
