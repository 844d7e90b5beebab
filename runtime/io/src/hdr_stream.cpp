// SPDX-License-Identifier: MIT
#include "hdr_stream.hpp"

#include <cstdlib>
#include <cstring>

#include "prt/io/error.hpp"

namespace prt::io::detail {
namespace {

class ByteReader {
 public:
  ByteReader(const std::string& path, const std::vector<unsigned char>& bytes)
      : path_(path), bytes_(bytes) {}

  bool at_end() const { return pos_ >= bytes_.size(); }
  std::size_t remaining() const { return bytes_.size() - pos_; }

  // One header line without its '\n' (stb reads tokens the same way).
  std::string line() {
    std::string text;
    while (pos_ < bytes_.size() && bytes_[pos_] != '\n') text += static_cast<char>(bytes_[pos_++]);
    if (pos_ < bytes_.size()) ++pos_;
    return text;
  }
  unsigned byte(const char* what, long scanline) {
    if (pos_ >= bytes_.size()) {
      throw Error(path_ + ": truncated .hdr: the pixel data ends in scanline " +
                  std::to_string(scanline) + " (" + what + ")");
    }
    return bytes_[pos_++];
  }
  // The next n bytes (skipped over).
  const unsigned char* take(std::size_t n, const char* what, long scanline) {
    if (n > remaining()) {
      throw Error(path_ + ": truncated .hdr: the pixel data ends in scanline " +
                  std::to_string(scanline) + " (" + what + ")");
    }
    const unsigned char* start = bytes_.data() + pos_;
    pos_ += n;
    return start;
  }

 private:
  const std::string& path_;
  const std::vector<unsigned char>& bytes_;
  std::size_t pos_ = 0;
};

constexpr unsigned kTopExponent = 255;

// Flat RGBE from the current position: texels x 4 bytes. Returns how many have the top exponent.
std::size_t check_flat(ByteReader& in, std::size_t texels, long width) {
  const long scanline = static_cast<long>(in.remaining() / 4 / width);
  const unsigned char* rgbe = in.take(texels * 4, "flat RGBE texels", scanline);
  std::size_t top = 0;
  for (std::size_t i = 0; i < texels; ++i) top += rgbe[4 * i + 3] == kTopExponent ? 1 : 0;
  return top;
}

}  // namespace

bool has_radiance_signature(const std::vector<unsigned char>& bytes) {
  auto starts = [&](const char* sig) {
    const std::size_t n = std::strlen(sig);
    return bytes.size() >= n && std::memcmp(bytes.data(), sig, n) == 0 &&
           (bytes.size() == n || bytes[n] == '\n' || bytes[n] == '\r');
  };
  return starts("#?RADIANCE") || starts("#?RGBE");
}

RadianceStreamSummary check_radiance_stream(const std::string& path,
                                            const std::vector<unsigned char>& bytes) {
  ByteReader in(path, bytes);
  in.line();  // signature, checked by has_radiance_signature
  bool rgbe = false;
  for (;;) {
    if (in.at_end()) throw Error(path + ": truncated .hdr: the header does not end");
    const std::string line = in.line();
    if (line.empty()) break;
    if (line == "FORMAT=32-bit_rle_rgbe") rgbe = true;
  }
  if (!rgbe) throw Error(path + ": unsupported .hdr format (expected FORMAT=32-bit_rle_rgbe)");
  const std::string size = in.line();
  const char* p = size.c_str();
  char* end = nullptr;
  if (std::strncmp(p, "-Y ", 3) != 0) {
    throw Error(path + ": unsupported .hdr layout '" + size + "' (expected '-Y H +X W')");
  }
  const long height = std::strtol(p + 3, &end, 10);
  while (*end == ' ') ++end;
  if (std::strncmp(end, "+X ", 3) != 0) {
    throw Error(path + ": unsupported .hdr layout '" + size + "' (expected '-Y H +X W')");
  }
  const long width = std::strtol(end + 3, nullptr, 10);
  if (width <= 0 || height <= 0 || width > (1L << 24) || height > (1L << 24)) {
    throw Error(path + ": .hdr image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is invalid");
  }
  const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  RadianceStreamSummary summary;
  if (width < 8 || width >= 32768) {
    summary.top_exponent_texels = check_flat(in, texels, width);
    return summary;
  }
  for (long y = 0; y < height; ++y) {
    const unsigned c1 = in.byte("scanline header", y), c2 = in.byte("scanline header", y);
    unsigned length = in.byte("scanline header", y);
    if (c1 != 2 || c2 != 2 || (length & 0x80)) {
      // Not run-length encoded: stb reads the whole image as flat texels from here, the
      // three bytes just read being the first texel's.
      const unsigned exponent = in.byte("flat RGBE texel", y);
      summary.top_exponent_texels +=
          (exponent == kTopExponent ? 1 : 0) + check_flat(in, texels - 1, width);
      return summary;
    }
    length = (length << 8) | in.byte("scanline header", y);
    if (static_cast<long>(length) != width) {
      throw Error(path + ": corrupt .hdr: scanline " + std::to_string(y) + " has length " +
                  std::to_string(length) + ", the image is " + std::to_string(width) + " wide");
    }
    for (int channel = 0; channel < 4; ++channel) {
      long x = 0;
      while (x < width) {
        unsigned count = in.byte("run length", y);
        std::size_t top = 0;
        if (count > 128) {
          count -= 128;
          top = in.byte("run value", y) == kTopExponent ? count : 0;
        } else {
          const unsigned char* literal = in.take(count, "literal run", y);
          for (unsigned i = 0; i < count; ++i) top += literal[i] == kTopExponent ? 1 : 0;
        }
        if (static_cast<long>(count) > width - x) {
          throw Error(path + ": corrupt .hdr: a run in scanline " + std::to_string(y) +
                      " is longer than the scanline");
        }
        if (channel == 3) summary.top_exponent_texels += top;
        x += count;
      }
    }
  }
  return summary;
}

}  // namespace prt::io::detail
