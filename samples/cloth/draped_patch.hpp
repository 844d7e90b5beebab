// SPDX-License-Identifier: MIT
// prt-cloth's built-in cloth: a sheet hung over a horizontal bar (like a towel over a rail),
// its two sides falling in vertical folds that deepen towards the hem. Positions, normals and
// the warp (thread 1, across the sheet along the bar) are analytic, from the surface's partial
// derivatives, so the highlights the threads make run smoothly along the folds.
#pragma once

#include "cloth_blob.hpp"

namespace prt::cloth_app {

// The sheet: 2 wide, over a bar of radius 0.12 through the origin, 1.3 long in front and 1.0
// behind, pleated with folds up to 0.11 deep; the bar runs along X turned 34 degrees about +Y,
// so that the first view (from +Z) sees the folds obliquely. `columns` x `rows` vertices
// (across, along the sheet).
FramedMesh draped_patch(int columns = 161, int rows = 321);

}  // namespace prt::cloth_app
