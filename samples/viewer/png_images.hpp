// SPDX-License-Identifier: MIT
// PNG helpers that are not tone mapping (that is prt/io/image_io.hpp): writing an image whose
// values are already display colours (the error heat map), and tiling PNGs into one montage.
#pragma once

#include <string>
#include <vector>

#include "prt/io/image_io.hpp"

namespace prt::view {

// Writes `image` as an 8-bit RGB PNG, its values taken as sRGB-encoded colours in [0,1]
// (clamped). Throws ViewerError naming the file on failure.
void write_display_png(const std::string& path, const prt::io::LinearImage& image);

// Tiles `inputs` (PNG files of one size, row-major, `columns` per row) with `gap` black pixels
// between tiles into `output` (PNG). Throws ViewerError naming the file that cannot be read or
// whose size differs from the first.
void write_montage(const std::string& output, const std::vector<std::string>& inputs, int columns,
                   int gap);

}  // namespace prt::view
