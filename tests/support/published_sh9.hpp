// SPDX-License-Identifier: MIT
// The real SH basis of Ramamoorthi & Hanrahan's published irradiance table
// (tables/sh9_irradiance_envmaps.json, its "basis" field), in the table's own frame and order:
// L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22. The table's axes (x', y', z') are world
// (X, Y, -Z): the centre of its probe is z', image right x', image up y' (formats/SPEC.md §12:
// centre -Z, right +X, up +Y). Written out from the table so tests check our projection against
// it, not against our own basis code.
#pragma once

#include <array>

namespace prt_test {

// The basis at the unit direction (x, y, z) given in the table's frame.
inline std::array<double, 9> published_sh9_basis(double x, double y, double z) {
  return {0.282095,
          0.488603 * y,
          0.488603 * z,
          0.488603 * x,
          1.092548 * x * y,
          1.092548 * y * z,
          0.315392 * (3 * z * z - 1),
          1.092548 * x * z,
          0.546274 * (x * x - y * y)};
}

// The same at a world direction (X, Y, Z): the table's frame is (X, Y, -Z).
inline std::array<double, 9> published_sh9_basis_world(double wx, double wy, double wz) {
  return published_sh9_basis(wx, wy, -wz);
}

}  // namespace prt_test
