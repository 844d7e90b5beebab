// SPDX-License-Identifier: MIT
// Constants and small measures every part of the baker uses, defined once so that files stay free
// of private copies (and can share a unity build's translation unit).
#pragma once

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>

#include <glm/vec3.hpp>

namespace prt::bake {

inline constexpr double kPi = 3.14159265358979323846;

// Wall-clock seconds since `start`, for bake reports and progress.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The double nearest the shortest decimal that reads back as f, for reports and JSON: they show
// 0.001, not the float's exact binary value 0.0010000000474974513, and still read back to f.
inline double shortest(float f) {
  char text[32];
  const std::to_chars_result end = std::to_chars(text, text + sizeof text - 1, f);
  *end.ptr = '\0';
  return std::strtod(text, nullptr);
}

}  // namespace prt::bake
