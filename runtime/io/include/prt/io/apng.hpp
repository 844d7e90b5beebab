// SPDX-License-Identifier: MIT
// 8-bit RGB pictures for the tools' outputs: read, tiled, labelled (stb_easy_font) and written
// as PNG or as an animated PNG (APNG 1.0): frames of one size, each compressed by
// stb_image_write's PNG encoder, stored as acTL/fcTL/fdAT chunks. The first frame is also the
// file's default image, so a viewer without APNG support shows it as a still.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace prt::io {

// 8-bit RGB display colours, row-major from the top row, width*height*3 bytes.
struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

// Reads a PNG (or anything stb_image reads) as RGB. Throws Error naming the file on failure.
Rgb8Image read_rgb8(const std::string& path);

// Writes `image` as an RGB PNG. Throws Error naming the file on failure.
void write_rgb8_png(const std::string& path, const Rgb8Image& image);

// Draws `text` (printable ASCII, '\n' starts a line) with stb_easy_font's segment glyphs, each
// font pixel a scale x scale block, its top left at (x, y); clipped to the image.
void draw_text(Rgb8Image& image, int x, int y, int scale, const std::string& text,
               const std::uint8_t (&colour)[3]);
// The size draw_text covers for `text` at `scale`.
int text_width(const std::string& text, int scale);
int text_height(const std::string& text, int scale);

// Tiles `tiles` (one size, row-major, `columns` per row) with `gap` black pixels between them.
// Throws Error if there are none or their sizes differ.
Rgb8Image tile_rgb8(const std::vector<Rgb8Image>& tiles, int columns, int gap);

// The bytes of an APNG showing `frames` (at least one, all of one size) for `frame_ms`
// milliseconds each, looping forever. Throws Error on an empty list, differing sizes or a
// frame the encoder rejects.
std::vector<std::uint8_t> encode_apng(const std::vector<Rgb8Image>& frames, int frame_ms);

// encode_apng written to `path`. Throws Error naming the file on failure.
void write_apng(const std::string& path, const std::vector<Rgb8Image>& frames, int frame_ms);

// CRC-32 of PNG chunks (ISO 3309, as the PNG specification's sample code computes it).
std::uint32_t png_crc32(const std::uint8_t* bytes, std::size_t size, std::uint32_t crc = 0);

}  // namespace prt::io
