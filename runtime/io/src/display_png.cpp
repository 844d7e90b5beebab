// SPDX-License-Identifier: MIT
// PNGs that are not tone mapped: display colours as they are, and montages of PNG files.
#include "prt/io/image_io.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>

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
  struct Free {
    void operator()(unsigned char* p) const { stbi_image_free(p); }
  };
  std::vector<std::unique_ptr<unsigned char, Free>> tiles;
  int width = 0, height = 0;
  for (const std::string& path : inputs) {
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<unsigned char, Free> pixels(stbi_load(path.c_str(), &w, &h, &channels, 3));
    if (!pixels)
      throw Error(path + ": cannot read the image (" +
                  (stbi_failure_reason() ? stbi_failure_reason() : "?") + ")");
    if (tiles.empty()) {
      width = w;
      height = h;
    } else if (w != width || h != height) {
      throw Error(path + ": " + std::to_string(w) + "x" + std::to_string(h) +
                  " differs from the first image's " + std::to_string(width) + "x" +
                  std::to_string(height));
    }
    tiles.push_back(std::move(pixels));
  }
  const int count = static_cast<int>(tiles.size());
  const int rows = (count + columns - 1) / columns;
  const int cols = std::min(columns, count);
  const int out_width = cols * width + (cols - 1) * gap;
  const int out_height = rows * height + (rows - 1) * gap;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(out_width) * out_height * 3, 0);
  for (int k = 0; k < count; ++k) {
    const int ox = (k % columns) * (width + gap), oy = (k / columns) * (height + gap);
    for (int y = 0; y < height; ++y) {
      std::memcpy(&rgb[(static_cast<std::size_t>(oy + y) * out_width + ox) * 3],
                  tiles[k].get() + static_cast<std::size_t>(y) * width * 3,
                  static_cast<std::size_t>(width) * 3);
    }
  }
  write_png(output, out_width, out_height, rgb.data());
}

}  // namespace prt::io
