// SPDX-License-Identifier: MIT
// Environment maps for the SG light's tests, built from prt_env.h's conventions restated here
// (texel centre directions and exact solid angles of lat-long and cube images), and the sums
// the tests compare the fits with (a map's power, a light's power and radiance), in double.
#pragma once

#include <prt/prt_cloth.h>
#include <prt/prt.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace prt_test {

constexpr double kSgPi = 3.14159265358979323846;

using Vec3 = std::array<double, 3>;

inline Vec3 normalised(Vec3 v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline Vec3 axis_of(const prt_cloth_lobe& lobe) {
  return {lobe.axis[0], lobe.axis[1], lobe.axis[2]};
}

// The angle between two directions, in degrees (atan2 of |a x b| and a . b: exact near 0).
inline double degrees_between(const Vec3& a, const Vec3& b) {
  const Vec3 cross{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return std::atan2(std::sqrt(dot(cross, cross)), dot(a, b)) * 180.0 / kSgPi;
}

// A lobe in double: L(w) = rgb exp(sharpness (w . axis - 1)).
struct TrueLobe {
  Vec3 axis;
  double sharpness;
  Vec3 rgb;
};

// The integral of exp(l (w . axis - 1)) over the sphere.
inline double sg_integral(double l) {
  return 2.0 * kSgPi / l * (1.0 - std::exp(-2.0 * l));
}

inline Vec3 radiance_of(const std::vector<TrueLobe>& lobes, const Vec3& w) {
  Vec3 sum{0.0, 0.0, 0.0};
  for (const TrueLobe& l : lobes) {
    const double e = std::exp(l.sharpness * (dot(l.axis, w) - 1.0));
    for (int c = 0; c < 3; ++c) sum[c] += l.rgb[c] * e;
  }
  return sum;
}

// Sum over lobes of rgb x integral, RGB summed.
inline double power_of(const std::vector<prt_cloth_lobe>& lobes) {
  double sum = 0.0;
  for (const prt_cloth_lobe& l : lobes)
    sum += (double(l.rgb[0]) + l.rgb[1] + l.rgb[2]) * sg_integral(l.sharpness);
  return sum;
}

// An RGB image as the runtime takes it (a lat-long map, or six cube faces one after another).
struct EnvImage {
  prt_env_layout layout = PRT_ENV_LATLONG;
  std::uint32_t width = 0, height = 0;
  std::vector<float> rgb;

  prt_env_image image() const {
    prt_env_image env = prt::sized<prt_env_image>();
    env.layout = layout;
    env.width = width;
    env.height = height;
    env.channels = 3;
    env.texels = rgb.data();
    return env;
  }
  std::size_t texels() const { return rgb.size() / 3; }
};

// prt_env.h, lat-long: texel (x, y) has direction (sin t sin f, cos t, -sin t cos f) at its
// centre, f = 2 pi (u - 1/2), t = pi v, and solid angle (2 pi / W)(cos t0 - cos t1).
inline Vec3 latlong_direction(std::uint32_t w, std::uint32_t h, std::uint32_t x, std::uint32_t y) {
  const double f = 2.0 * kSgPi * ((x + 0.5) / w - 0.5), t = kSgPi * (y + 0.5) / h;
  return {std::sin(t) * std::sin(f), std::cos(t), -std::sin(t) * std::cos(f)};
}

inline double latlong_solid_angle(std::uint32_t w, std::uint32_t h, std::uint32_t y) {
  return 2.0 * kSgPi / w * (std::cos(kSgPi * y / h) - std::cos(kSgPi * (y + 1.0) / h));
}

// prt_env.h, cube: face f's texel (i, j) at s = 2 (i + 0.5) / F - 1, t = 2 (j + 0.5) / F - 1.
inline Vec3 cube_direction(std::uint32_t f, double s, double t) {
  switch (f) {
    case 0:
      return normalised({1.0, -t, -s});
    case 1:
      return normalised({-1.0, -t, s});
    case 2:
      return normalised({s, 1.0, t});
    case 3:
      return normalised({s, -1.0, -t});
    case 4:
      return normalised({s, -t, 1.0});
    default:
      return normalised({-s, -t, -1.0});
  }
}

// The exact solid angle of face rectangle [s0, s1] x [t0, t1]: the signed sum over its corners
// of atan(s t / sqrt(s^2 + t^2 + 1)).
inline double cube_rect_solid_angle(double s0, double s1, double t0, double t1) {
  const auto corner = [](double s, double t) {
    return std::atan2(s * t, std::sqrt(s * s + t * t + 1.0));
  };
  return std::fabs(corner(s1, t1) - corner(s0, t1) - corner(s1, t0) + corner(s0, t0));
}

// Calls visit(texel index, direction, solid angle) for every texel of the image.
template <typename Visit>
void for_each_texel(const EnvImage& env, const Visit& visit) {
  if (env.layout == PRT_ENV_LATLONG) {
    for (std::uint32_t y = 0; y < env.height; ++y)
      for (std::uint32_t x = 0; x < env.width; ++x)
        visit(std::size_t(y) * env.width + x, latlong_direction(env.width, env.height, x, y),
              latlong_solid_angle(env.width, env.height, y));
    return;
  }
  const std::uint32_t n = env.width;
  const double step = 2.0 / n;
  for (std::uint32_t f = 0; f < 6; ++f)
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i) {
        const double s0 = step * i - 1.0, t0 = step * j - 1.0;
        visit((std::size_t(f) * n + j) * n + i, cube_direction(f, s0 + 0.5 * step, t0 + 0.5 * step),
              cube_rect_solid_angle(s0, s0 + step, t0, t0 + step));
      }
}

inline EnvImage latlong_image(std::uint32_t w, std::uint32_t h) {
  EnvImage env;
  env.layout = PRT_ENV_LATLONG;
  env.width = w;
  env.height = h;
  env.rgb.assign(std::size_t(w) * h * 3, 0.0f);
  return env;
}

inline EnvImage cube_image(std::uint32_t face) {
  EnvImage env;
  env.layout = PRT_ENV_CUBE;
  env.width = env.height = face;
  env.rgb.assign(std::size_t(face) * face * 18, 0.0f);
  return env;
}

// The image whose texels are the lobes' radiance at their centres.
inline EnvImage with_lobes(EnvImage env, const std::vector<TrueLobe>& lobes) {
  for_each_texel(env, [&](std::size_t k, const Vec3& d, double) {
    const Vec3 l = radiance_of(lobes, d);
    for (int c = 0; c < 3; ++c) env.rgb[3 * k + c] = static_cast<float>(l[c]);
  });
  return env;
}

// Radiance drawn uniformly in [0, top) per channel from a fixed seed.
inline EnvImage with_noise(EnvImage env, float top, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> value(0.0f, top);
  for (float& v : env.rgb) v = value(random);
  return env;
}

// The image's power (sum of radiance x solid angle; RGB summed), counting NaN, infinite or
// negative values as 0.
inline double map_power(const EnvImage& env) {
  double sum = 0.0;
  for_each_texel(env, [&](std::size_t k, const Vec3&, double solid_angle) {
    for (int c = 0; c < 3; ++c) {
      const float v = env.rgb[3 * k + c];
      if (std::isfinite(v) && v > 0.0f) sum += v * solid_angle;
    }
  });
  return sum;
}

// The three well separated lobes the recovery tests synthesise (more than 80 degrees apart, so
// each one's tail is below 1e-5 of its peak where another's begins).
inline std::vector<TrueLobe> three_lobes() {
  return {{normalised({0.5, 0.6, -0.62}), 40.0, {3.0, 2.0, 1.0}},
          {normalised({-0.7, 0.05, 0.7}), 150.0, {10.0, 12.0, 8.0}},
          {normalised({0.2, -0.85, 0.45}), 600.0, {40.0, 30.0, 50.0}}};
}

}  // namespace prt_test
