// SPDX-License-Identifier: MIT
// 8-bit RGB pictures read back with stb for tests that check what a program drew.
#pragma once

#include <gtest/gtest.h>
#include <stb_image.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace prt_test {

struct Picture {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // row-major, top row first, 3 bytes per pixel
  std::array<int, 3> at(int x, int y) const {
    const unsigned char* p = &rgb[(std::size_t(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
  }
  // Rec. 709 weights on the encoded bytes: enough to tell lit from shadowed pixels.
  double luminance(int x, int y) const {
    const std::array<int, 3> p = at(x, y);
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
  }
};

// Fails the test and returns an empty picture (width 0) when stb cannot read `path`.
inline Picture read_picture(const std::string& path) {
  Picture picture;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &picture.width, &picture.height, &channels, 3);
  if (!data) {
    ADD_FAILURE() << "cannot read " << path << ": " << stbi_failure_reason();
    return Picture{};
  }
  picture.rgb.assign(data, data + std::size_t(picture.width) * picture.height * 3);
  stbi_image_free(data);
  return picture;
}

}  // namespace prt_test
