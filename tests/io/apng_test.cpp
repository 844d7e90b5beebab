// SPDX-License-Identifier: MIT
// The animated PNG writer, read back chunk by chunk: the chunk order APNG 1.0 requires, the frame
// count, consecutive sequence numbers, every CRC (checked with zlib's crc32, an independent
// implementation), the first frame as the default image stb_image decodes, and every later frame
// decoded from its fdAT data.
#include <gtest/gtest.h>
#include <stb_image.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "prt/io/apng.hpp"
#include "prt/io/error.hpp"

namespace prt::io {
namespace {

using Bytes = std::vector<std::uint8_t>;

struct Chunk {
  std::string type;
  Bytes data;
  std::uint32_t crc = 0;
};

std::uint32_t be32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}

std::vector<Chunk> chunks_of(const Bytes& png) {
  std::vector<Chunk> chunks;
  EXPECT_GE(png.size(), 8u);
  EXPECT_EQ(std::memcmp(png.data(), "\x89PNG\r\n\x1a\n", 8), 0);
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length = be32(&png[at]);
    EXPECT_LE(at + 12 + length, png.size());
    if (at + 12 + length > png.size()) break;
    Chunk chunk;
    chunk.type.assign(reinterpret_cast<const char*>(&png[at + 4]), 4);
    chunk.data.assign(png.begin() + at + 8, png.begin() + at + 8 + length);
    chunk.crc = be32(&png[at + 8 + length]);
    chunks.push_back(chunk);
    at += 12 + length;
  }
  return chunks;
}

std::uint32_t zlib_crc(const Chunk& chunk) {
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, reinterpret_cast<const Bytef*>(chunk.type.data()), 4);
  // crc32(crc, NULL, 0) answers its initial value, not crc: an empty chunk adds nothing.
  if (!chunk.data.empty()) crc = crc32(crc, chunk.data.data(), chunk.data.size());
  return static_cast<std::uint32_t>(crc);
}

void put_chunk(Bytes& out, const std::string& type, const Bytes& data) {
  Chunk chunk{type, data, 0};
  for (std::uint32_t v : {static_cast<std::uint32_t>(data.size())})
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
  out.insert(out.end(), type.begin(), type.end());
  out.insert(out.end(), data.begin(), data.end());
  const std::uint32_t crc = zlib_crc(chunk);
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(crc >> s));
}

// Decodes a PNG held in memory with stb_image as RGB.
Rgb8Image decode(const Bytes& png) {
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &channels, 3);
  Rgb8Image image;
  if (!pixels) return image;
  image.width = w;
  image.height = h;
  image.rgb.assign(pixels, pixels + static_cast<std::size_t>(w) * h * 3);
  stbi_image_free(pixels);
  return image;
}

// Three 7x5 frames that differ everywhere: a gradient shifted per frame.
std::vector<Rgb8Image> test_frames() {
  std::vector<Rgb8Image> frames(3);
  for (int f = 0; f < 3; ++f) {
    frames[f].width = 7;
    frames[f].height = 5;
    for (int y = 0; y < 5; ++y) {
      for (int x = 0; x < 7; ++x) {
        frames[f].rgb.push_back(static_cast<std::uint8_t>(30 * x + 80 * f));
        frames[f].rgb.push_back(static_cast<std::uint8_t>(40 * y + 7 * f));
        frames[f].rgb.push_back(static_cast<std::uint8_t>(255 - 60 * f - x * y));
      }
    }
  }
  return frames;
}

TEST(Apng, Crc32MatchesThePublishedCheckValue) {
  const char* text = "123456789";  // the CRC-32/ISO-HDLC check value
  EXPECT_EQ(png_crc32(reinterpret_cast<const std::uint8_t*>(text), 9), 0xCBF43926u);
}

TEST(Apng, ChunksFrameCountSequenceAndCrcs) {
  const std::vector<Rgb8Image> frames = test_frames();
  const std::vector<Chunk> chunks = chunks_of(encode_apng(frames, 80));
  ASSERT_GE(chunks.size(), 8u);
  EXPECT_EQ(chunks.front().type, "IHDR");
  EXPECT_EQ(chunks[1].type, "acTL");  // before any image data
  EXPECT_EQ(chunks.back().type, "IEND");
  ASSERT_EQ(chunks[1].data.size(), 8u);
  EXPECT_EQ(be32(&chunks[1].data[0]), 3u);  // frames
  EXPECT_EQ(be32(&chunks[1].data[4]), 0u);  // plays forever
  std::uint32_t expected_sequence = 0, frame_controls = 0;
  bool idat_seen = false, fdat_seen = false;
  for (const Chunk& chunk : chunks) {
    EXPECT_EQ(chunk.crc, zlib_crc(chunk)) << chunk.type;
    if (chunk.type == "fcTL") {
      ASSERT_EQ(chunk.data.size(), 26u);
      EXPECT_EQ(be32(&chunk.data[0]), expected_sequence++);
      EXPECT_EQ(be32(&chunk.data[4]), 7u);
      EXPECT_EQ(be32(&chunk.data[8]), 5u);
      EXPECT_EQ(chunk.data[20] << 8 | chunk.data[21], 80);    // delay numerator
      EXPECT_EQ(chunk.data[22] << 8 | chunk.data[23], 1000);  // delay denominator
      ++frame_controls;
    } else if (chunk.type == "fdAT") {
      EXPECT_EQ(be32(&chunk.data[0]), expected_sequence++);
      EXPECT_TRUE(idat_seen);
      fdat_seen = true;
    } else if (chunk.type == "IDAT") {
      EXPECT_EQ(frame_controls, 1u) << "the default image is the first frame";
      EXPECT_FALSE(fdat_seen);
      idat_seen = true;
    }
  }
  EXPECT_EQ(frame_controls, 3u);
  EXPECT_TRUE(idat_seen);
  EXPECT_TRUE(fdat_seen);
}

TEST(Apng, FirstFrameIsTheDefaultImageAndEveryFrameDecodes) {
  const std::vector<Rgb8Image> frames = test_frames();
  const Bytes apng = encode_apng(frames, 100);
  const Rgb8Image still = decode(apng);  // stb_image ignores the animation chunks
  ASSERT_EQ(still.width, 7);
  ASSERT_EQ(still.height, 5);
  EXPECT_EQ(still.rgb, frames[0].rgb);

  // Each frame k > 0 as a plain PNG: the IHDR, its fdAT payloads (sequence number dropped) as
  // IDAT, IEND.
  const std::vector<Chunk> chunks = chunks_of(apng);
  std::vector<Bytes> frame_data(frames.size());
  int frame = -1;
  for (const Chunk& chunk : chunks) {
    if (chunk.type == "fcTL") ++frame;
    if (chunk.type == "fdAT")
      frame_data[frame].insert(frame_data[frame].end(), chunk.data.begin() + 4, chunk.data.end());
  }
  for (std::size_t k = 1; k < frames.size(); ++k) {
    Bytes png(apng.begin(), apng.begin() + 8);
    put_chunk(png, "IHDR", chunks.front().data);
    put_chunk(png, "IDAT", frame_data[k]);
    put_chunk(png, "IEND", {});
    EXPECT_EQ(decode(png).rgb, frames[k].rgb) << "frame " << k;
  }
}

TEST(Apng, WritesTheFileAndRefusesBadFrames) {
  const std::filesystem::path dir = std::filesystem::path(PRT_TEST_OUTPUT_DIR) / "apng";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "three.png").string();
  const std::vector<Rgb8Image> frames = test_frames();
  write_apng(path, frames, 50);
  std::ifstream file(path, std::ios::binary);
  const Bytes bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  EXPECT_EQ(bytes, encode_apng(frames, 50));
  EXPECT_EQ(read_rgb8(path).rgb, frames[0].rgb);

  EXPECT_THROW(encode_apng({}, 50), Error);
  std::vector<Rgb8Image> mixed = frames;
  mixed[2].width = 6;
  mixed[2].rgb.resize(6 * 5 * 3);
  EXPECT_THROW(encode_apng(mixed, 50), Error);
  EXPECT_THROW(encode_apng(frames, 0), Error);
}

TEST(Apng, TilesSideBySideWithAGap) {
  const std::vector<Rgb8Image> frames = test_frames();
  const Rgb8Image tiled = tile_rgb8({frames[0], frames[1]}, 2, 3);
  ASSERT_EQ(tiled.width, 7 + 3 + 7);
  ASSERT_EQ(tiled.height, 5);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(tiled.rgb[(y * 17 + x) * 3 + c], frames[0].rgb[(y * 7 + x) * 3 + c]);
        EXPECT_EQ(tiled.rgb[(y * 17 + 10 + x) * 3 + c], frames[1].rgb[(y * 7 + x) * 3 + c]);
      }
    }
    EXPECT_EQ(tiled.rgb[(y * 17 + 8) * 3], 0);  // the gap is black
  }
}

TEST(Rgb8Text, DrawsWithinTheSizeItReportsInTheColourGiven) {
  Rgb8Image image;
  image.width = 200;
  image.height = 60;
  image.rgb.assign(200 * 60 * 3, 0);
  const std::uint8_t colour[3] = {250, 120, 10};
  const int x = 7, y = 9, scale = 3;
  draw_text(image, x, y, scale, "sh 8.2 %", colour);
  const int width = text_width("sh 8.2 %", scale), height = text_height("sh 8.2 %", scale);
  ASSERT_GT(width, 0);
  ASSERT_LT(x + width, image.width);
  int lo_x = image.width, hi_x = -1, lo_y = image.height, hi_y = -1;
  for (int py = 0; py < image.height; ++py) {
    for (int px = 0; px < image.width; ++px) {
      const std::uint8_t* p = &image.rgb[(py * image.width + px) * 3];
      if (p[0] == 0 && p[1] == 0 && p[2] == 0) continue;
      ASSERT_EQ(std::memcmp(p, colour, 3), 0) << px << "," << py;
      lo_x = std::min(lo_x, px), hi_x = std::max(hi_x, px);
      lo_y = std::min(lo_y, py), hi_y = std::max(hi_y, py);
    }
  }
  ASSERT_GE(hi_x, 0) << "nothing drawn";
  EXPECT_GE(lo_x, x);
  EXPECT_LT(hi_x, x + width);
  EXPECT_GE(lo_y, y);
  EXPECT_LT(hi_y, y + height);
  EXPECT_GT(hi_x - lo_x, width / 2) << "the text spans most of its width";
  // Off the image it is clipped, not written out of bounds.
  draw_text(image, 190, 55, 4, "clipped", colour);
}

}  // namespace
}  // namespace prt::io
