// SPDX-License-Identifier: MIT
#include "baked_frames.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace prt::character {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what);
}

// The value of `key` in the header dict, up to the next comma or closing brace outside
// parentheses.
std::string header_value(const std::string& header, const std::string& key,
                         const std::string& path) {
  const std::size_t at = header.find("'" + key + "'");
  if (at == std::string::npos) fail(path, "the .npy header has no '" + key + "'");
  std::size_t i = header.find(':', at);
  if (i == std::string::npos) fail(path, "bad .npy header");
  ++i;
  int depth = 0;
  std::string value;
  for (; i < header.size(); ++i) {
    const char c = header[i];
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (depth == 0 && (c == ',' || c == '}')) break;
    value += c;
  }
  value.erase(0, value.find_first_not_of(' '));
  value.erase(value.find_last_not_of(' ') + 1);
  return value;
}

}  // namespace

NpyArray read_npy(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) fail(path, "not a .npy file");
  const int major = static_cast<unsigned char>(bytes[6]);
  std::size_t length = 0, start = 0;
  if (major == 1) {
    length = static_cast<unsigned char>(bytes[8]) |
             std::size_t(static_cast<unsigned char>(bytes[9])) << 8;
    start = 10;
  } else if (major == 2 && bytes.size() >= 12) {
    for (int i = 0; i < 4; ++i)
      length |= std::size_t(static_cast<unsigned char>(bytes[8 + i])) << (8 * i);
    start = 12;
  } else {
    fail(path, "unsupported .npy version");
  }
  if (start + length > bytes.size()) fail(path, "truncated .npy header");
  const std::string header = bytes.substr(start, length);
  if (header_value(header, "descr", path) != "'<f4'") fail(path, "not float32 little-endian");
  if (header_value(header, "fortran_order", path) != "False") fail(path, "not C order");
  const std::string shape = header_value(header, "shape", path);
  NpyArray array;
  std::size_t count = 1;
  for (std::size_t i = 0; i < shape.size();) {
    if (!std::isdigit(static_cast<unsigned char>(shape[i]))) {
      ++i;
      continue;
    }
    std::size_t used = 0;
    const unsigned long long d = std::stoull(shape.substr(i), &used);
    array.shape.push_back(static_cast<std::size_t>(d));
    count *= static_cast<std::size_t>(d);
    i += used;
  }
  const std::size_t data = start + length;
  if (bytes.size() - data != count * sizeof(float))
    fail(path, "holds " + std::to_string(bytes.size() - data) + " data bytes, its shape says " +
                   std::to_string(count * sizeof(float)));
  array.values.resize(count);
  if (count) std::memcpy(array.values.data(), bytes.data() + data, count * sizeof(float));
  return array;
}

void BakedFrames::clip_frames(std::uint32_t c, std::uint32_t* first, std::uint32_t* last) const {
  const auto lo = std::lower_bound(clip.begin(), clip.end(), c);
  const auto hi = std::upper_bound(clip.begin(), clip.end(), c);
  *first = static_cast<std::uint32_t>(lo - clip.begin());
  *last = static_cast<std::uint32_t>(std::max<std::ptrdiff_t>(hi - clip.begin() - 1, *first));
}

BakedFrames read_baked_frames(const std::string& prefix, std::uint32_t vertices,
                              std::uint32_t coefficients, std::uint32_t joints) {
  const std::string transfer_path = prefix + ".transfer.npy",
                    rotations_path = prefix + ".rotations.npy", times_path = prefix + ".times.npy";
  NpyArray transfer = read_npy(transfer_path), rotations = read_npy(rotations_path),
           times = read_npy(times_path);
  const auto shape = [](const NpyArray& a) {
    std::string text;
    for (std::size_t d : a.shape) text += (text.empty() ? "" : " x ") + std::to_string(d);
    return "[" + text + "]";
  };
  if (transfer.shape.size() != 3 || transfer.shape[0] == 0 || transfer.shape[1] != vertices ||
      transfer.shape[2] != coefficients)
    fail(transfer_path, "is " + shape(transfer) + ", the blob needs [frames x " +
                            std::to_string(vertices) + " x " + std::to_string(coefficients) + "]");
  const std::size_t frames = transfer.shape[0];
  if (rotations.shape != std::vector<std::size_t>{frames, joints, 4})
    fail(rotations_path, "is " + shape(rotations) + ", needs [" + std::to_string(frames) + " x " +
                             std::to_string(joints) + " x 4]");
  if (times.shape != std::vector<std::size_t>{frames, 2})
    fail(times_path, "is " + shape(times) + ", needs [" + std::to_string(frames) + " x 2]");
  BakedFrames baked;
  baked.frames = static_cast<std::uint32_t>(frames);
  baked.vertices = vertices, baked.coefficients = coefficients, baked.joints = joints;
  baked.transfer = std::move(transfer.values);
  baked.rotations = std::move(rotations.values);
  for (std::size_t f = 0; f < frames; ++f) {
    const float c = times.values[2 * f], t = times.values[2 * f + 1];
    if (!(c >= 0.0f) || c != std::floor(c) || !std::isfinite(t) ||
        (f > 0 && (c < float(baked.clip.back()) ||
                   (c == float(baked.clip.back()) && t < baked.time.back()))))
      fail(times_path, "frame " + std::to_string(f) + " is out of clip and time order");
    baked.clip.push_back(static_cast<std::uint32_t>(c));
    baked.time.push_back(t);
  }
  return baked;
}

std::uint32_t clip_pose(const BakedFrames& baked, std::uint32_t c, double time, float* out) {
  std::uint32_t first = 0, last = 0;
  baked.clip_frames(c, &first, &last);
  std::uint32_t a = first;
  while (a < last && baked.time[a + 1] <= time) ++a;
  const std::uint32_t b = std::min(a + 1, last);
  const double span = baked.time[b] - baked.time[a];
  const double s = span > 0.0 ? std::clamp((time - baked.time[a]) / span, 0.0, 1.0) : 0.0;
  const float* qa = baked.frame_rotations(a);
  const float* qb = baked.frame_rotations(b);
  for (std::uint32_t j = 0; j < baked.joints; ++j) {
    const float* p = qa + 4 * j;
    float q[4] = {qb[4 * j], qb[4 * j + 1], qb[4 * j + 2], qb[4 * j + 3]};
    double dot = 0.0;
    for (int k = 0; k < 4; ++k) dot += double(p[k]) * q[k];
    if (dot < 0.0) {  // the shorter way round
      for (float& v : q) v = -v;
      dot = -dot;
    }
    double wa = 1.0 - s, wb = s;
    if (dot < 0.9995) {
      const double angle = std::acos(std::min(dot, 1.0));
      wa = std::sin((1.0 - s) * angle) / std::sin(angle);
      wb = std::sin(s * angle) / std::sin(angle);
    }
    for (int k = 0; k < 4; ++k) out[4 * j + k] = float(wa * p[k] + wb * q[k]);
  }
  return s < 0.5 ? a : b;
}

}  // namespace prt::character
