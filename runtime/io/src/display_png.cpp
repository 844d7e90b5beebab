// SPDX-License-Identifier: MIT
// PNGs that are not tone mapped: display colours as they are, and montages of PNG files.
#include "prt/io/image_io.hpp"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "prt/io/apng.hpp"
#include "prt/io/error.hpp"

namespace prt::io {
namespace {

void write_png(const std::string& path, int width, int height, const std::uint8_t* rgb) {
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb, width * 3)) {
    throw Error(path + ": cannot write the PNG file");
  }
}

}  // namespace

void write_display_png(const std::string& path, const LinearImage& image) {
  std::vector<std::uint8_t> rgb(image.pixels.size() * 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const float v = image.pixels[i][c];
      rgb[3 * i + c] = static_cast<std::uint8_t>(
          std::lround(std::clamp(std::isfinite(v) ? v : 1.0f, 0.0f, 1.0f) * 255.0f));
    }
  }
  write_png(path, image.width, image.height, rgb.data());
}

void write_montage(const std::string& output, const std::vector<std::string>& inputs, int columns,
                   int gap) {
  if (inputs.empty() || columns < 1)
    throw Error(output + ": a montage needs at least one input image");
  std::vector<Rgb8Image> tiles;
  for (const std::string& path : inputs) {
    tiles.push_back(read_rgb8(path));
    const Rgb8Image& tile = tiles.back();
    if (tile.width != tiles[0].width || tile.height != tiles[0].height) {
      throw Error(path + ": " + std::to_string(tile.width) + "x" + std::to_string(tile.height) +
                  " differs from the first image's " + std::to_string(tiles[0].width) + "x" +
                  std::to_string(tiles[0].height));
    }
  }
  const Rgb8Image montage = tile_rgb8(tiles, columns, gap);
  write_png(output, montage.width, montage.height, montage.rgb.data());
}

}  // namespace prt::io
