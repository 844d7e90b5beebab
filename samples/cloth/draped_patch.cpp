// SPDX-License-Identifier: MIT
#include "draped_patch.hpp"

#include <cmath>

namespace prt::cloth_app {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kBar = 0.12;                // the bar's radius
constexpr double kFront = 1.3, kBack = 1.0;  // hanging lengths below the bar's middle
constexpr double kFold = 0.11;               // the folds' depth at the hem
constexpr double kFoldStart = 0.25;          // the folds reach half their depth this far down
constexpr double kTurn = 0.6;                // the sheet turned about +Y (radians)

// The sheet's middle line in the (y, z) plane by arc length s (s = 0 on top of the bar, s > 0
// towards the front): around the bar, then straight down. `point`, its derivative `along`
// (unit), the outward normal `out` (unit) and the normal's derivative `out_s`.
struct Profile {
  double point[2], along[2], out[2], out_s[2];  // (y, z)
  double hang;                                  // 0 on the bar, growing to 1 at the hem
  double hang_s;                                // d hang / ds
};

Profile profile(double s) {
  const double arc = 0.5 * kPi * kBar;
  Profile p{};
  if (std::abs(s) <= arc) {
    const double a = s / kBar;
    p.point[0] = kBar * std::cos(a), p.point[1] = kBar * std::sin(a);
    p.along[0] = -std::sin(a), p.along[1] = std::cos(a);
    p.out[0] = std::cos(a), p.out[1] = std::sin(a);
    p.out_s[0] = -std::sin(a) / kBar, p.out_s[1] = std::cos(a) / kBar;
    return p;
  }
  const double side = s > 0.0 ? 1.0 : -1.0, below = std::abs(s) - arc;
  const double length = s > 0.0 ? kFront : kBack;
  p.point[0] = -below, p.point[1] = side * kBar;
  p.along[0] = -side, p.along[1] = 0.0;
  p.out[0] = 0.0, p.out[1] = side;
  p.hang = below / length;
  p.hang_s = side / length;
  return p;
}

// The folds across the sheet, and their derivative in x: two waves, so they do not repeat.
double folds(double x) {
  return std::sin(7.5 * x + 0.4) + 0.45 * std::sin(17.0 * x + 1.3);
}
double folds_x(double x) {
  return 7.5 * std::cos(7.5 * x + 0.4) + 0.45 * 17.0 * std::cos(17.0 * x + 1.3);
}

// v (times scale) turned by kTurn about +Y.
void push(std::vector<float>& out, const double v[3], double scale = 1.0) {
  const double c = std::cos(kTurn), s = std::sin(kTurn);
  out.insert(out.end(), {float((c * v[0] + s * v[2]) * scale), float(v[1] * scale),
                         float((-s * v[0] + c * v[2]) * scale)});
}

}  // namespace

FramedMesh draped_patch(int columns, int rows) {
  FramedMesh mesh;
  const double arc = 0.5 * kPi * kBar, s0 = -(kBack + arc), s1 = kFront + arc;
  for (int j = 0; j < rows; ++j) {
    const double s = s0 + (s1 - s0) * j / (rows - 1);
    const Profile p = profile(s);
    // The folds deepen quickly below the bar, h^2 / (h^2 + c^2), and smoothly (no crease where
    // they start).
    const double h = p.hang, c2 = kFoldStart * kFoldStart, q = h * h + c2;
    const double depth = kFold * (1.0 + c2) * h * h / q;
    const double depth_s = kFold * (1.0 + c2) * 2.0 * h * c2 / (q * q) * p.hang_s;
    for (int i = 0; i < columns; ++i) {
      const double x = -1.0 + 2.0 * i / (columns - 1);
      const double d = depth * folds(x), d_x = depth * folds_x(x), d_s = depth_s * folds(x);
      // P(x, s) = (x, middle(s)) + d(x, s) out(s): its partials in x and s.
      const double point[3] = {x, p.point[0] + d * p.out[0], p.point[1] + d * p.out[1]};
      const double px[3] = {1.0, d_x * p.out[0], d_x * p.out[1]};
      const double ps[3] = {0.0, p.along[0] + d_s * p.out[0] + d * p.out_s[0],
                            p.along[1] + d_s * p.out[1] + d * p.out_s[1]};
      // The outward normal is P_s x P_x; the warp runs along x.
      const double n[3] = {ps[1] * px[2] - ps[2] * px[1], ps[2] * px[0] - ps[0] * px[2],
                           ps[0] * px[1] - ps[1] * px[0]};
      const double n_length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double x_length = std::sqrt(px[0] * px[0] + px[1] * px[1] + px[2] * px[2]);
      push(mesh.positions, point);
      push(mesh.normals, n, 1.0 / n_length);
      push(mesh.warps, px, 1.0 / x_length);
    }
  }
  // Counter-clockwise seen from the outward side: (i, j), (i, j + 1), (i + 1, j).
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < columns; ++i) {
      const std::uint32_t a = std::uint32_t(j * columns + i), b = a + 1,
                          c = a + std::uint32_t(columns), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  return mesh;
}

}  // namespace prt::cloth_app
