// SPDX-License-Identifier: MIT
// Random shading inputs for cloth's backend tests: samples (normals, warps, views with grazing and
// below-the-surface views, runs of samples that share a frame), random lights, and the comparison
// of two backends' outputs.
#pragma once

#include <prt/prt_cloth.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace prt_test {

struct ClothSamples {
  std::vector<float> normals, warps, views;
  std::size_t size() const { return normals.size() / 3; }
  prt_cloth_pixels pixels() const {
    prt_cloth_pixels p{};
    p.struct_size = sizeof p;
    p.normals = normals.data();
    p.warps = warps.data();
    p.views = views.data();
    return p;
  }
  void add(const float n[3], const float w[3], const float v[3]) {
    normals.insert(normals.end(), n, n + 3);
    warps.insert(warps.end(), w, w + 3);
    views.insert(views.end(), v, v + 3);
  }
};

inline void random_unit(std::mt19937& rng, float out[3]) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  float len = 0.0f;
  do {
    for (int i = 0; i < 3; ++i) out[i] = g(rng);
    len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  } while (len < 1e-3f);
  for (int i = 0; i < 3; ++i) out[i] /= len;
}

// A view at cosine `c` from n (c < 0: below the surface), in a random azimuth.
inline void view_at(std::mt19937& rng, const float n[3], float c, float out[3]) {
  float t[3];
  random_unit(rng, t);
  const float along = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
  for (int i = 0; i < 3; ++i) t[i] -= along * n[i];
  const float len = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  for (int i = 0; i < 3; ++i) out[i] = c * n[i] + s * t[i] / len;
}

// A view: mostly over the hemisphere, some grazing (cos 1e-4 .. 0.02), some below the surface.
inline void random_view(std::mt19937& rng, const float n[3], float out[3]) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float pick = u(rng);
  float c;
  if (pick < 0.15f)
    c = 1e-4f + 0.02f * u(rng);  // grazing
  else if (pick < 0.25f)
    c = -u(rng);  // below
  else
    c = std::sqrt(u(rng));
  view_at(rng, n, c, out);
}

// `count` samples: each a random frame, except runs of `run` samples sharing one frame (with
// their own views) every 5 runs, so that batches of one frame occur at every alignment.
inline ClothSamples random_samples(std::size_t count, unsigned seed, std::size_t run = 21) {
  std::mt19937 rng(seed);
  ClothSamples s;
  float n[3], w[3], v[3];
  std::size_t left_in_run = 0, k = 0;
  while (s.size() < count) {
    if (left_in_run == 0) {
      random_unit(rng, n);
      do random_unit(rng, w);
      while (std::fabs(w[0] * n[0] + w[1] * n[1] + w[2] * n[2]) > 0.95f);
      left_in_run = (k++ % 5 == 4) ? run : 1;
    }
    random_view(rng, n, v);
    s.add(n, w, v);
    --left_in_run;
  }
  return s;
}

// K lobes with sharpness log-uniform in [lo, hi], random axes and colours.
inline std::vector<prt_cloth_lobe> random_lobes(unsigned count, float lo, float hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<prt_cloth_lobe> lobes(count);
  for (prt_cloth_lobe& l : lobes) {
    random_unit(rng, l.axis);
    l.sharpness = lo * std::pow(hi / lo, u(rng));
    for (float& c : l.rgb) c = 0.1f + u(rng);
  }
  return lobes;
}

inline prt_cloth_light light_of(const std::vector<prt_cloth_lobe>& lobes) {
  prt_cloth_light l{};
  l.struct_size = sizeof l;
  l.lobe_count = std::uint32_t(lobes.size());
  l.lobes = lobes.data();
  return l;
}

// How far `got` is from `ref`: the largest |got - ref| / (|ref| + floor max|ref|) over the
// values, with the largest |ref| and where the worst value is.
struct Deviation {
  double worst = 0.0, peak = 0.0;
  std::size_t at = 0;
};

inline Deviation deviation(const std::vector<float>& got, const std::vector<float>& ref,
                           double floor) {
  Deviation d;
  for (float r : ref) d.peak = std::max(d.peak, double(std::fabs(r)));
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const double e = std::fabs(double(got[i]) - ref[i]) / (std::fabs(ref[i]) + floor * d.peak);
    if (!(e <= d.worst)) d.worst = e, d.at = i;  // NaN counts as worst
  }
  return d;
}

}  // namespace prt_test
