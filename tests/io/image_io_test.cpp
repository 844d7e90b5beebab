// SPDX-License-Identifier: MIT
// Output files: the .npy array, the tone-mapped PNG, the linear .hdr, the display-colour PNG and
// the montage, read back as written.
#include <gtest/gtest.h>

#include <stb_image.h>
#include <stb_image_write.h>

#include <cmath>
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

// Display colours are stored as they are: v -> round(255 v), clamped, non-finite as white.
TEST(ImageIo, DisplayPngStoresColoursAsTheyAre) {
  LinearImage image;
  image.width = 3;
  image.height = 2;
  image.pixels = {{0.0f, 0.5f, 1.0f},          {-1.0f, 2.0f, 0.2f},
                  {0.4f, 0.8f, 0.75f},         {std::nanf(""), INFINITY, 0.0f},
                  {1.0f / 255.0f, 0.0f, 0.0f}, {0.25f, 0.25f, 0.25f}};
  const std::string path = output_path("display.png");
  write_display_png(path, image);
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
  ASSERT_NE(data, nullptr);
  ASSERT_EQ(w, 3);
  ASSERT_EQ(h, 2);
  const unsigned char expected[18] = {0,   128, 255, 0, 255, 51, 102, 204, 191,
                                      255, 255, 0,   1, 0,   0,  64,  64,  64};
  for (int i = 0; i < 18; ++i) EXPECT_EQ(data[i], expected[i]) << "byte " << i;
  stbi_image_free(data);
}

// A montage of 2 x 1 tiles in 2 columns with a gap of 1 black pixel: each tile lands at its
// offset, the gap stays black; tiles of another size and missing files are errors naming them.
TEST(ImageIo, MontageTilesPngsRowMajorWithBlackGaps) {
  const unsigned char red[2 * 1 * 3] = {200, 0, 0, 100, 0, 0};
  const unsigned char green[2 * 1 * 3] = {0, 200, 0, 0, 100, 0};
  const unsigned char blue[2 * 1 * 3] = {0, 0, 200, 0, 0, 100};
  const std::string a = output_path("tile_a.png"), b = output_path("tile_b.png"),
                    c = output_path("tile_c.png"), odd = output_path("tile_odd.png");
  ASSERT_NE(stbi_write_png(a.c_str(), 2, 1, 3, red, 6), 0);
  ASSERT_NE(stbi_write_png(b.c_str(), 2, 1, 3, green, 6), 0);
  ASSERT_NE(stbi_write_png(c.c_str(), 2, 1, 3, blue, 6), 0);
  const std::string out = output_path("montage.png");
  write_montage(out, {a, b, c}, 2, 1);
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(out.c_str(), &w, &h, &channels, 3);
  ASSERT_NE(data, nullptr);
  ASSERT_EQ(w, 2 + 1 + 2);  // two tiles and a gap per row
  ASSERT_EQ(h, 1 + 1 + 1);  // two rows and a gap
  const auto pixel = [&](int x, int y) {
    const unsigned char* p = data + (y * w + x) * 3;
    return glm::ivec3(p[0], p[1], p[2]);
  };
  EXPECT_EQ(pixel(0, 0), glm::ivec3(200, 0, 0));
  EXPECT_EQ(pixel(1, 0), glm::ivec3(100, 0, 0));
  EXPECT_EQ(pixel(2, 0), glm::ivec3(0));  // the gap
  EXPECT_EQ(pixel(3, 0), glm::ivec3(0, 200, 0));
  EXPECT_EQ(pixel(4, 0), glm::ivec3(0, 100, 0));
  for (int x = 0; x < w; ++x) EXPECT_EQ(pixel(x, 1), glm::ivec3(0)) << x;
  EXPECT_EQ(pixel(0, 2), glm::ivec3(0, 0, 200));
  EXPECT_EQ(pixel(1, 2), glm::ivec3(0, 0, 100));
  EXPECT_EQ(pixel(3, 2), glm::ivec3(0));  // no fourth tile
  stbi_image_free(data);

  const unsigned char wide[3 * 1 * 3] = {};
  ASSERT_NE(stbi_write_png(odd.c_str(), 3, 1, 3, wide, 9), 0);
  const auto message_of = [&](const std::vector<std::string>& inputs) {
    try {
      write_montage(out, inputs, 2, 1);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message_of({a, odd}).find(odd + ": 3x1 differs"), std::string::npos)
      << message_of({a, odd});
  const std::string absent = output_path("absent.png");
  EXPECT_NE(message_of({a, absent}).find(absent + ": cannot read"), std::string::npos)
      << message_of({a, absent});
  EXPECT_THROW(write_montage(out, {}, 2, 1), Error);
}

}  // namespace
}  // namespace prt::io
