// SPDX-License-Identifier: MIT
// APNG from stb_image_write's single-frame PNGs: every frame is encoded as a whole PNG, its IDAT
// payloads are kept and the rest dropped; the first frame's stay IDAT (the default image), later
// ones become fdAT with a sequence number. Frames are full-size and replace the previous one
// (dispose none, blend source), so each decodes on its own.
#include "prt/io/apng.hpp"

#include <stb_easy_font.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <memory>

#include "prt/io/error.hpp"

namespace prt::io {
namespace {

constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

void put_u16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}

std::uint32_t get_u32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}

// Appends length, type, data and the CRC over type and data.
void put_chunk(std::vector<std::uint8_t>& out, const char (&type)[5],
               const std::vector<std::uint8_t>& data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_u32(out, png_crc32(out.data() + start, out.size() - start));
}

struct EncodedFrame {
  std::vector<std::uint8_t> ihdr;                // the IHDR payload
  std::vector<std::vector<std::uint8_t>> idats;  // the IDAT payloads, in order
};

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

// The frame as stb_image_write encodes it, split into its chunks.
EncodedFrame encode_frame(const Rgb8Image& frame) {
  std::vector<std::uint8_t> png;
  if (!stbi_write_png_to_func(append_bytes, &png, frame.width, frame.height, 3, frame.rgb.data(),
                              frame.width * 3) ||
      png.size() < sizeof kSignature) {
    throw Error("APNG: the PNG encoder rejected a frame");
  }
  EncodedFrame encoded;
  std::size_t at = sizeof kSignature;
  while (at + 12 <= png.size()) {
    const std::uint32_t length = get_u32(&png[at]);
    if (length > png.size() - at - 12) throw Error("APNG: the PNG encoder wrote a short chunk");
    const std::uint8_t* type = &png[at + 4];
    std::vector<std::uint8_t> data(type + 4, type + 4 + length);
    if (std::memcmp(type, "IHDR", 4) == 0) encoded.ihdr = std::move(data);
    if (std::memcmp(type, "IDAT", 4) == 0) encoded.idats.push_back(std::move(data));
    at += 12 + length;
  }
  if (encoded.ihdr.empty() || encoded.idats.empty())
    throw Error("APNG: the PNG encoder wrote no image data");
  return encoded;
}

// fcTL: the frame covers the whole canvas for frame_ms and replaces what was there.
std::vector<std::uint8_t> frame_control(std::uint32_t sequence, const Rgb8Image& frame,
                                        int frame_ms) {
  std::vector<std::uint8_t> data;
  put_u32(data, sequence);
  put_u32(data, static_cast<std::uint32_t>(frame.width));
  put_u32(data, static_cast<std::uint32_t>(frame.height));
  put_u32(data, 0);  // x offset
  put_u32(data, 0);  // y offset
  put_u16(data, static_cast<std::uint16_t>(frame_ms));
  put_u16(data, 1000);  // delay = frame_ms / 1000 s
  data.push_back(0);    // dispose: none
  data.push_back(0);    // blend: source
  return data;
}

void check_frames(const std::vector<Rgb8Image>& frames, int frame_ms) {
  if (frames.empty()) throw Error("APNG: no frames");
  if (frame_ms < 1 || frame_ms > 65535)
    throw Error("APNG: frame time " + std::to_string(frame_ms) + " ms is outside 1..65535");
  for (const Rgb8Image& frame : frames) {
    if (frame.width != frames[0].width || frame.height != frames[0].height ||
        frame.rgb.size() != static_cast<std::size_t>(frame.width) * frame.height * 3 ||
        frame.width < 1 || frame.height < 1) {
      throw Error("APNG: frames differ in size from the first (" + std::to_string(frames[0].width) +
                  "x" + std::to_string(frames[0].height) + ")");
    }
  }
}

}  // namespace

std::uint32_t png_crc32(const std::uint8_t* bytes, std::size_t size, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ bytes[i]) & 0xffu] ^ (crc >> 8);
  return ~crc;
}

std::vector<std::uint8_t> encode_apng(const std::vector<Rgb8Image>& frames, int frame_ms) {
  check_frames(frames, frame_ms);
  std::vector<std::uint8_t> out(std::begin(kSignature), std::end(kSignature));
  std::uint32_t sequence = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    EncodedFrame encoded = encode_frame(frames[f]);
    if (f == 0) {
      put_chunk(out, "IHDR", encoded.ihdr);
      std::vector<std::uint8_t> animation;
      put_u32(animation, static_cast<std::uint32_t>(frames.size()));
      put_u32(animation, 0);  // plays: forever
      put_chunk(out, "acTL", animation);
    }
    put_chunk(out, "fcTL", frame_control(sequence++, frames[f], frame_ms));
    for (std::vector<std::uint8_t>& idat : encoded.idats) {
      if (f == 0) {
        put_chunk(out, "IDAT", idat);
        continue;
      }
      std::vector<std::uint8_t> fdat;
      put_u32(fdat, sequence++);
      fdat.insert(fdat.end(), idat.begin(), idat.end());
      put_chunk(out, "fdAT", fdat);
    }
  }
  put_chunk(out, "IEND", {});
  return out;
}

void write_apng(const std::string& path, const std::vector<Rgb8Image>& frames, int frame_ms) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = encode_apng(frames, frame_ms);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  if (!file.flush()) throw Error(path + ": cannot write the file");
}

void write_rgb8_png(const std::string& path, const Rgb8Image& image) {
  if (!stbi_write_png(path.c_str(), image.width, image.height, 3, image.rgb.data(),
                      image.width * 3)) {
    throw Error(path + ": cannot write the PNG file");
  }
}

void draw_text(Rgb8Image& image, int x, int y, int scale, const std::string& text,
               const std::uint8_t (&colour)[3]) {
  // stb_easy_font writes 4 vertices of 16 bytes (x, y, z, colour) per quad, in font pixels.
  std::vector<char> quads(text.size() * 270 + 1024);
  std::string copy = text;
  const int count = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, quads.data(),
                                        static_cast<int>(quads.size()));
  for (int q = 0; q < count; ++q) {
    float corner[2][2];  // top left and bottom right vertices
    std::memcpy(corner[0], quads.data() + q * 64, 8);
    std::memcpy(corner[1], quads.data() + q * 64 + 32, 8);
    const int x0 = std::max(0, x + static_cast<int>(corner[0][0] * scale));
    const int y0 = std::max(0, y + static_cast<int>(corner[0][1] * scale));
    const int x1 = std::min(image.width, x + static_cast<int>(corner[1][0] * scale));
    const int y1 = std::min(image.height, y + static_cast<int>(corner[1][1] * scale));
    for (int py = y0; py < y1; ++py) {
      for (int px = x0; px < x1; ++px) {
        std::memcpy(&image.rgb[(static_cast<std::size_t>(py) * image.width + px) * 3], colour, 3);
      }
    }
  }
}

int text_width(const std::string& text, int scale) {
  std::string copy = text;
  return stb_easy_font_width(copy.data()) * scale;
}

int text_height(const std::string& text, int scale) {
  std::string copy = text;
  return stb_easy_font_height(copy.data()) * scale;
}

Rgb8Image read_rgb8(const std::string& path) {
  struct Free {
    void operator()(unsigned char* p) const { stbi_image_free(p); }
  };
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, Free> pixels(stbi_load(path.c_str(), &w, &h, &channels, 3));
  if (!pixels)
    throw Error(path + ": cannot read the image (" +
                (stbi_failure_reason() ? stbi_failure_reason() : "?") + ")");
  Rgb8Image image;
  image.width = w;
  image.height = h;
  image.rgb.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(w) * h * 3);
  return image;
}

Rgb8Image tile_rgb8(const std::vector<Rgb8Image>& tiles, int columns, int gap) {
  if (tiles.empty() || columns < 1) throw Error("a montage needs at least one image");
  const int width = tiles[0].width, height = tiles[0].height;
  for (const Rgb8Image& tile : tiles) {
    if (tile.width != width || tile.height != height)
      throw Error(std::to_string(tile.width) + "x" + std::to_string(tile.height) +
                  " differs from the first image's " + std::to_string(width) + "x" +
                  std::to_string(height));
  }
  const int count = static_cast<int>(tiles.size());
  const int rows = (count + columns - 1) / columns;
  const int cols = std::min(columns, count);
  Rgb8Image out;
  out.width = cols * width + (cols - 1) * gap;
  out.height = rows * height + (rows - 1) * gap;
  out.rgb.assign(static_cast<std::size_t>(out.width) * out.height * 3, 0);
  for (int k = 0; k < count; ++k) {
    const int ox = (k % columns) * (width + gap), oy = (k / columns) * (height + gap);
    for (int y = 0; y < height; ++y) {
      std::memcpy(&out.rgb[(static_cast<std::size_t>(oy + y) * out.width + ox) * 3],
                  tiles[k].rgb.data() + static_cast<std::size_t>(y) * width * 3,
                  static_cast<std::size_t>(width) * 3);
    }
  }
  return out;
}

}  // namespace prt::io
