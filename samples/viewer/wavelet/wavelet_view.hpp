// SPDX-License-Identifier: MIT
// prt-view's `wavelet` technique: the map resampled onto the blob's parameterisation with the
// turn, Haar-transformed, cut to --light-coefficients and prepared by the runtime, shaded with
// prt_wavelet_shade (skipping dark blocks) or prt_gl_wavelet_*.
#pragma once

#include <memory>

#include "view_technique.hpp"

namespace prt::view {

std::unique_ptr<ViewTechnique> make_wavelet_view();

}  // namespace prt::view
