// SPDX-License-Identifier: MIT
#include "prt/io/image_io.hpp"

#include <stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "prt/io/error.hpp"
#include "prt/io/file.hpp"

namespace prt::io {
namespace {

std::uint32_t little_endian(const unsigned char* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// Value of `key` in the .npy header dictionary (the text after "'key':"), trimmed.
std::string header_field(const std::string& header, const std::string& key) {
  const std::size_t at = header.find("'" + key + "'");
  if (at == std::string::npos) return "";
  std::size_t start = header.find(':', at);
  if (start == std::string::npos) return "";
  ++start;
  while (start < header.size() && header[start] == ' ') ++start;
  std::size_t end = start;
  if (header[start] == '(') {
    end = header.find(')', start);
    if (end != std::string::npos) ++end;
  } else {
    end = header.find(',', start);
  }
  return end == std::string::npos ? "" : header.substr(start, end - start);
}

std::string lower_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

float luminance(const glm::vec3& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

float aces_filmic(float x) {
  const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  return std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
}

std::uint8_t srgb8(float linear) {
  const float v =
      linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

void put_u32_le(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

}  // namespace

void write_npy_vec3(const std::string& path, const std::vector<glm::vec3>& values) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                       std::to_string(values.size()) + ", 3), }";
  // Magic (6) + version (2) + length (2) + header, padded with spaces to a multiple of 64 and
  // ended by a newline, as NumPy writes it.
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header.push_back('\n');
  std::string bytes("\x93NUMPY\x01\x00", 8);
  bytes.push_back(static_cast<char>(header.size() & 0xffu));
  bytes.push_back(static_cast<char>(header.size() >> 8));
  bytes += header;
  bytes.reserve(bytes.size() + values.size() * 12);
  for (const glm::vec3& v : values) {
    for (int c = 0; c < 3; ++c) {
      std::uint32_t bits;
      std::memcpy(&bits, &v[c], 4);
      put_u32_le(bytes, bits);
    }
  }
  std::ofstream file(path, std::ios::binary);
  if (!file || !file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    throw Error(path + ": cannot write the .npy file");
  }
}

namespace {

// Log-average luminance of the pixels `use` accepts; false if none has a positive luminance.
template <typename Use>
bool log_average_luminance(const LinearImage& image, Use use, double* log_average) {
  double log_sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const float y = luminance(image.pixels[i]);
    if (!use(i) || !(y > 0.0f) || !std::isfinite(y)) continue;
    log_sum += std::log(static_cast<double>(y));
    ++count;
  }
  if (count == 0) return false;
  *log_average = log_sum / static_cast<double>(count);
  return true;
}

}  // namespace

float auto_exposure_ev(const LinearImage& image) {
  constexpr double kSubjectKey = 0.35, kSceneKey = 0.18;
  double log_average = 0.0;
  const bool has_coverage = image.coverage.size() == image.pixels.size();
  auto covered = [&](std::size_t i) { return has_coverage && image.coverage[i] >= 0.5f; };
  if (log_average_luminance(image, covered, &log_average)) {
    return static_cast<float>(std::log2(kSubjectKey) - log_average / std::log(2.0));
  }
  if (log_average_luminance(
          image, [](std::size_t) { return true; }, &log_average)) {
    return static_cast<float>(std::log2(kSceneKey) - log_average / std::log(2.0));
  }
  return 0.0f;
}

std::vector<std::uint8_t> tone_map_srgb8(const LinearImage& image, float exposure_ev) {
  const float scale = std::exp2(exposure_ev);
  std::vector<std::uint8_t> out(image.pixels.size() * 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      float v = image.pixels[i][c] * scale;
      if (!std::isfinite(v)) v = 0.0f;
      out[3 * i + c] = srgb8(aces_filmic(std::max(v, 0.0f)));
    }
  }
  return out;
}

void write_image(const std::string& path, const LinearImage& image, float exposure_ev) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
    throw Error(path + ": image has no pixels or an inconsistent size");
  }
  const std::string ext = lower_extension(path);
  int ok = 0;
  if (ext == ".png") {
    const std::vector<std::uint8_t> rgb = tone_map_srgb8(image, exposure_ev);
    ok = stbi_write_png(path.c_str(), image.width, image.height, 3, rgb.data(), image.width * 3);
  } else if (ext == ".hdr") {
    ok = stbi_write_hdr(path.c_str(), image.width, image.height, 3, &image.pixels[0].x);
  } else {
    throw Error(path + ": unknown image extension (use .png or .hdr)");
  }
  if (!ok) throw Error(path + ": cannot write the image");
}

std::vector<glm::vec3> read_npy_vec3(const std::string& path) {
  const std::vector<unsigned char> bytes = read_file(path);
  if (bytes.size() < 10 || std::memcmp(bytes.data(), "\x93NUMPY", 6) != 0) {
    throw Error(path + ": not a NumPy .npy file");
  }
  const int major = bytes[6];
  const int length_bytes = major == 1 ? 2 : 4;
  const std::size_t prefix = 8 + static_cast<std::size_t>(length_bytes);
  if ((major != 1 && major != 2) || bytes.size() < prefix) {
    throw Error(path + ": unsupported .npy version");
  }
  const std::size_t header_size = little_endian(&bytes[8], length_bytes);
  if (bytes.size() < prefix + header_size) throw Error(path + ": truncated .npy header");
  const std::string header(bytes.begin() + static_cast<std::ptrdiff_t>(prefix),
                           bytes.begin() + static_cast<std::ptrdiff_t>(prefix + header_size));
  const std::string descr = header_field(header, "descr");
  const std::string order = header_field(header, "fortran_order");
  const std::string shape = header_field(header, "shape");
  unsigned long long rows = 0;
  int columns = 0;
  if ((descr != "'<f4'" && descr != "'float32'") || order != "False" ||
      std::sscanf(shape.c_str(), "(%llu, %d)", &rows, &columns) != 2 || columns != 3) {
    throw Error(path + ": expected float32 C-order [N, 3] (descr " + descr + ", shape " + shape +
                ")");
  }
  const std::size_t data = prefix + header_size;
  if ((bytes.size() - data) / 12 < rows) throw Error(path + ": truncated .npy data");
  std::vector<glm::vec3> values(static_cast<std::size_t>(rows));
  for (std::size_t v = 0; v < values.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t bits = little_endian(&bytes[data + 12 * v + 4 * c], 4);
      std::memcpy(&values[v][c], &bits, 4);
    }
  }
  return values;
}

}  // namespace prt::io
