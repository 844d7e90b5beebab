// SPDX-License-Identifier: MIT
// Output files: the .npy array, the tone-mapped PNG and the linear .hdr read back as written.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "prt/io/image_io.hpp"

namespace prt::io {
namespace {

std::string output_path(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(PRT_TEST_OUTPUT_DIR) / "image_io";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

std::string read_all(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

TEST(ImageIo, NpyHasVersion1HeaderShapeAndLittleEndianFloats) {
  const std::vector<glm::vec3> values = {{1.0f, -2.5f, 3.25f}, {0.0f, 1e-3f, 7.0f}, {4, 5, 6}};
  const std::string path = output_path("values.npy");
  write_npy_vec3(path, values);
  const std::string bytes = read_all(path);
  ASSERT_GE(bytes.size(), 10u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t header_len =
      static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
  EXPECT_EQ((10 + header_len) % 64, 0u);  // data aligned as NumPy aligns it
  const std::string header = bytes.substr(10, header_len);
  EXPECT_NE(header.find("'descr': '<f4'"), std::string::npos) << header;
  EXPECT_NE(header.find("'fortran_order': False"), std::string::npos) << header;
  EXPECT_NE(header.find("'shape': (3, 3)"), std::string::npos) << header;
  EXPECT_EQ(header.back(), '\n');
  ASSERT_EQ(bytes.size(), 10 + header_len + values.size() * 12);
  // Little-endian IEEE floats (checked through the bytes of 1.0f = 0x3f800000).
  EXPECT_EQ(static_cast<unsigned char>(bytes[10 + header_len + 3]), 0x3fu);
  EXPECT_EQ(static_cast<unsigned char>(bytes[10 + header_len + 2]), 0x80u);
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      float f;
      std::memcpy(&f, bytes.data() + 10 + header_len + 12 * i + 4 * c, 4);
      EXPECT_EQ(f, values[i][c]);
    }
  }
}

LinearImage gradient_image(int width, int height) {
  LinearImage image;
  image.width = width;
  image.height = height;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.pixels.emplace_back(0.01f * (x + 1), 0.5f * (y + 1), 3.0f);
    }
  }
  return image;
}

TEST(ImageIo, PngIsToneMappedSrgbOfTheRightSize) {
  const LinearImage image = gradient_image(7, 5);
  const std::string path = output_path("image.png");
  write_image(path, image, 0.0f);
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(w, 7);
  EXPECT_EQ(h, 5);
  // Brighter radiance never maps darker, and the tone map keeps everything in range: red grows
  // along x, green along y.
  for (int y = 0; y < 5; ++y) {
    for (int x = 1; x < 7; ++x) EXPECT_GE(data[(y * 7 + x) * 3], data[(y * 7 + x - 1) * 3]);
  }
  EXPECT_GT(data[(4 * 7) * 3 + 1], data[1]);
  stbi_image_free(data);
}

TEST(ImageIo, HdrKeepsLinearRadiance) {
  const LinearImage image = gradient_image(6, 4);
  const std::string path = output_path("image.hdr");
  write_image(path, image, 5.0f);  // exposure does not apply to linear output
  int w = 0, h = 0, channels = 0;
  float* data = stbi_loadf(path.c_str(), &w, &h, &channels, 3);
  ASSERT_NE(data, nullptr);
  ASSERT_EQ(w, 6);
  ASSERT_EQ(h, 4);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const glm::vec3 p = image.pixels[i];
    const float largest = std::max({p.r, p.g, p.b});
    // RGBE: a shared exponent, so each channel is exact to 2^-7 of the largest one.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(data[3 * i + c], p[c], largest / 128.0f) << i;
  }
  stbi_image_free(data);
}

TEST(ImageIo, AutoExposureMetersTheSubjectOrTheWholeImage) {
  LinearImage image;
  image.width = 2;
  image.height = 1;
  image.pixels = {glm::vec3(0.5f), glm::vec3(2.0f)};  // log-average luminance 1
  EXPECT_NEAR(auto_exposure_ev(image), std::log2(0.18f), 1e-5f);
  // With coverage, only the pixels mostly covered by surfaces are metered, against 0.35.
  image.coverage = {0.0f, 1.0f};
  EXPECT_NEAR(auto_exposure_ev(image), std::log2(0.35f / 2.0f), 1e-5f);
  image.coverage = {0.0f, 0.25f};  // no covered pixel: back to the whole image
  EXPECT_NEAR(auto_exposure_ev(image), std::log2(0.18f), 1e-5f);
}

TEST(ImageIo, UnknownExtensionIsAnError) {
  EXPECT_THROW(write_image(output_path("image.bmp"), gradient_image(2, 2), 0.0f), Error);
}

}  // namespace
}  // namespace prt::io
