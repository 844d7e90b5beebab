// SPDX-License-Identifier: MIT
#include "compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "blob_scene.hpp"

namespace prt::view {
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

}  // namespace

std::vector<glm::vec3> read_npy_vec3(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw ViewerError(path + ": cannot open file");
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)),
                                         std::istreambuf_iterator<char>());
  if (bytes.size() < 10 || std::memcmp(bytes.data(), "\x93NUMPY", 6) != 0) {
    throw ViewerError(path + ": not a NumPy .npy file");
  }
  const int major = bytes[6];
  const int length_bytes = major == 1 ? 2 : 4;
  const std::size_t prefix = 8 + static_cast<std::size_t>(length_bytes);
  if ((major != 1 && major != 2) || bytes.size() < prefix) {
    throw ViewerError(path + ": unsupported .npy version");
  }
  const std::size_t header_size = little_endian(&bytes[8], length_bytes);
  if (bytes.size() < prefix + header_size) throw ViewerError(path + ": truncated .npy header");
  const std::string header(bytes.begin() + static_cast<std::ptrdiff_t>(prefix),
                           bytes.begin() + static_cast<std::ptrdiff_t>(prefix + header_size));
  const std::string descr = header_field(header, "descr");
  const std::string order = header_field(header, "fortran_order");
  const std::string shape = header_field(header, "shape");
  unsigned long long rows = 0;
  int columns = 0;
  if ((descr != "'<f4'" && descr != "'float32'") || order != "False" ||
      std::sscanf(shape.c_str(), "(%llu, %d)", &rows, &columns) != 2 || columns != 3) {
    throw ViewerError(path + ": expected float32 C-order [N, 3] (descr " + descr + ", shape " +
                      shape + ")");
  }
  const std::size_t data = prefix + header_size;
  if ((bytes.size() - data) / 12 < rows) throw ViewerError(path + ": truncated .npy data");
  std::vector<glm::vec3> values(static_cast<std::size_t>(rows));
  for (std::size_t v = 0; v < values.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t bits = little_endian(&bytes[data + 12 * v + 4 * c], 4);
      std::memcpy(&values[v][c], &bits, 4);
    }
  }
  return values;
}

std::vector<float> relative_vertex_error(const std::vector<glm::vec3>& x,
                                         const std::vector<glm::vec3>& ref) {
  double mean = 0.0;
  for (const glm::vec3& r : ref) mean += glm::length(glm::dvec3(r));
  mean = ref.empty() ? 0.0 : mean / static_cast<double>(ref.size());
  std::vector<float> error(std::min(x.size(), ref.size()));
  for (std::size_t v = 0; v < error.size(); ++v) {
    const double e = glm::length(glm::dvec3(x[v]) - glm::dvec3(ref[v]));
    error[v] = static_cast<float>(mean > 0.0 ? e / mean : (e > 0.0 ? INFINITY : 0.0));
  }
  return error;
}

glm::vec3 heat_colour(float error, float scale) {
  static const glm::vec3 kRamp[] = {{0.0f, 0.0f, 0.0f}, {0.15f, 0.1f, 0.6f}, {0.7f, 0.15f, 0.6f},
                                    {1.0f, 0.5f, 0.1f}, {1.0f, 0.9f, 0.2f},  {1.0f, 1.0f, 1.0f}};
  constexpr int kSteps = static_cast<int>(sizeof kRamp / sizeof kRamp[0]) - 1;
  float t = scale > 0.0f ? error / scale : 1.0f;
  if (!(t >= 0.0f)) t = 0.0f;  // NaN
  t = std::min(t, 1.0f) * kSteps;
  const int i = std::min(static_cast<int>(t), kSteps - 1);
  return glm::mix(kRamp[i], kRamp[i + 1], t - static_cast<float>(i));
}

}  // namespace prt::view
