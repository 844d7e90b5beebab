// SPDX-License-Identifier: MIT
// Maps for the rotation tests: an asymmetric lat-long map turned about +Y, and the independent
// construction it must equal at 90 degrees, the same map with its columns shifted by a quarter
// of the width.
//
// The sign, derived from the conventions (not fitted): with R = [[c,0,s],[0,1,0],[-s,0,c]] at 90
// degrees (c = 0, s = 1), light from d = (sin t sin p, cos t, -sin t cos p) (formats/SPEC.md §12)
// comes from R d = (-sin t cos p, cos t, -sin t sin p), which is the direction of azimuth
// p - 90 degrees. Since u = 0.5 + p / 2pi, light seen in column x of the original is seen in
// column x - W/4 of the turned map: turned(x, y) = original((x + W/4) mod W, y).
#pragma once

#include <cmath>
#include <vector>

#include "prt/io/envmap.hpp"

namespace prt::io::test {

constexpr int kWidth = 64, kHeight = 32;

// An environment with no symmetry about +Y: a smooth colour pattern and a small bright patch.
inline std::vector<float> asymmetric_pixels() {
  std::vector<float> rgb(kWidth * kHeight * 3);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      float* t = &rgb[(y * kWidth + x) * 3];
      const float u = (x + 0.5f) / kWidth, v = (y + 0.5f) / kHeight;
      t[0] = 0.2f + 0.8f * u * (1.0f - v);
      t[1] = 0.3f + 0.5f * std::sin(3.0f * u + 1.0f) * std::sin(3.14159f * v);
      t[2] = 0.1f + 0.6f * v * v;
      if (x >= 10 && x < 13 && y >= 8 && y < 10) t[0] += 40.0f, t[1] += 30.0f, t[2] += 20.0f;
    }
  }
  return rgb;
}

inline std::vector<float> shifted_by_quarter(const std::vector<float>& rgb) {
  std::vector<float> out(rgb.size());
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const int from = (x + kWidth / 4) % kWidth;
      for (int c = 0; c < 3; ++c) out[(y * kWidth + x) * 3 + c] = rgb[(y * kWidth + from) * 3 + c];
    }
  }
  return out;
}

inline EnvMap turned_map(double degrees) {
  EnvMap map(kWidth, kHeight, asymmetric_pixels(), EnvMapping::LatLong, "turned");
  map.set_rotation(rotation_about_y(degrees));
  return map;
}

inline EnvMap shifted_map() {
  return EnvMap(kWidth, kHeight, shifted_by_quarter(asymmetric_pixels()), EnvMapping::LatLong,
                "shifted");
}

}  // namespace prt::io::test
