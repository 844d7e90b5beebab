// SPDX-License-Identifier: MIT
// What the extremes tests of technique `cloth` share: an asset baked once per test binary on a
// small grid (linen and satin), a flat patch seen from chosen views, a spherical-Gaussian lobe
// tessellated into the reference's texels, and the runtime's shading and brute-force reference
// of the same samples.
#pragma once

#include <prt/prt_cloth.h>
#include <prt/prt_cloth_asset.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "prt/baker/cloth/cloth_blob.hpp"
#include "prt/baker/cloth/cloth_tables.hpp"
#include "prt/baker/cloth/fabrics.hpp"
#include "support/mesh_blob.hpp"

namespace prt_test {

constexpr double kExtremesPi = 3.14159265358979323846;

inline double degrees(double d) {
  return d * kExtremesPi / 180.0;
}

// The fabrics the tests shade, in fabric order: linen (wide lobes, tilted tangents only) and satin
// charmeuse (narrow surface lobes, flat tangents in both threads).
inline const std::vector<prt::bake::ClothPreset>& extremes_presets() {
  static const std::vector<prt::bake::ClothPreset> presets = {
      prt::bake::cloth_fabric("linen_plain"), prt::bake::cloth_fabric("polyester_satin_charmeuse")};
  return presets;
}

// Their blob, baked on a small grid.
inline Bytes bake_extremes_blob() {
  std::vector<prt::bake::ClothFabricSource> fabrics;
  for (const prt::bake::ClothPreset& p : extremes_presets())
    fabrics.push_back({p.name, p.params, p.weave});
  prt::bake::ClothTablesOptions options;
  options.grid.xi_size = 12;
  options.grid.lambda_levels = 6;
  options.grid.view_theta = 6;
  options.grid.view_phi = 6;
  options.sampling.map_size = 64;
  const prt::bake::ClothTablesBake bake =
      prt::bake::bake_cloth_tables(fabrics, options, prt::bake::Context{});
  return prt::bake::write_cloth_blob(bake.section, 16, nullptr, "");
}

// Under ctest every test is a process of its own: the blob is baked once by a fixture into the
// file PRT_CLOTH_EXTREMES_BLOB names (tests/cloth/extremes/CMakeLists.txt), and each test loads
// it. Run by hand without it (or with no blob there), the binary bakes once for all its tests.
constexpr const char* kExtremesBlobVariable = "PRT_CLOTH_EXTREMES_BLOB";

// The blob loaded by the runtime, with its fabrics.
struct BakedCloth {
  Context context;
  std::unique_ptr<LoadedAsset> asset;
  std::vector<prt::bake::ClothPreset> presets;  // in fabric order

  static constexpr std::uint32_t kLinen = 0, kSatin = 1;
};

inline const BakedCloth& baked_cloth() {
  static const BakedCloth* baked = [] {
    auto* b = new BakedCloth;
    b->presets = extremes_presets();
    const char* path = std::getenv(kExtremesBlobVariable);
    if (path) b->asset = std::make_unique<LoadedAsset>(b->context.ctx, read_file(path));
    if (!b->asset || b->asset->result != PRT_OK)
      b->asset = std::make_unique<LoadedAsset>(b->context.ctx, bake_extremes_blob());
    return b;
  }();
  return *baked;
}

using Vec3d = std::array<double, 3>;

inline Vec3d unit(Vec3d v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

// A direction at `elevation` above the plane z = 0 and `azimuth` from +x towards +y (radians).
inline Vec3d from_angles(double elevation, double azimuth) {
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

// A flat patch (normal +z, warp +x) seen from each of `views`.
struct Patch {
  std::vector<float> normals, warps, views;

  explicit Patch(const std::vector<Vec3d>& directions) {
    for (const Vec3d& d : directions) {
      normals.insert(normals.end(), {0.0f, 0.0f, 1.0f});
      warps.insert(warps.end(), {1.0f, 0.0f, 0.0f});
      views.insert(views.end(), {float(d[0]), float(d[1]), float(d[2])});
    }
  }
  std::uint32_t count() const { return std::uint32_t(views.size() / 3); }
  prt_cloth_pixels pixels() const {
    prt_cloth_pixels p = prt::sized<prt_cloth_pixels>();
    p.normals = normals.data();
    p.warps = warps.data();
    p.views = views.data();
    return p;
  }
};

// Views over the upper hemisphere at several elevations and azimuths (none grazing).
inline std::vector<Vec3d> spread_views() {
  std::vector<Vec3d> views;
  for (const double elevation : {20.0, 45.0, 75.0})
    for (const double azimuth : {10.0, 70.0, 130.0, 200.0, 290.0})
      views.push_back(from_angles(degrees(elevation), degrees(azimuth)));
  return views;
}

inline prt_cloth_lobe make_lobe(const Vec3d& axis, double sharpness, Vec3d rgb = {1, 1, 1}) {
  prt_cloth_lobe lobe{};
  for (int c = 0; c < 3; ++c) {
    lobe.axis[c] = float(axis[c]);
    lobe.rgb[c] = float(rgb[c]);
  }
  lobe.sharpness = float(sharpness);
  return lobe;
}

// An environment as the reference takes it.
struct Texels {
  std::vector<float> directions, power;

  void add(const Vec3d& d, const Vec3d& p) {
    directions.insert(directions.end(), {float(d[0]), float(d[1]), float(d[2])});
    power.insert(power.end(), {float(p[0]), float(p[1]), float(p[2])});
  }
  void append(const Texels& other) {
    directions.insert(directions.end(), other.directions.begin(), other.directions.end());
    power.insert(power.end(), other.power.begin(), other.power.end());
  }
  prt_cloth_env_texels env() const {
    prt_cloth_env_texels e = prt::sized<prt_cloth_env_texels>();
    e.count = std::uint32_t(directions.size() / 3);
    e.directions = directions.data();
    e.power = power.data();
    return e;
  }
};

// A lobe over the cloth's upper hemisphere (normal +z) as lat-long texels: rows of elevation from
// the horizon up, each cut into azimuth steps over the arc where the lobe is above exp(-20) of its
// peak; a texel carries the lobe's radiance at its centre times its exact solid angle. Rows start
// at the horizon, so the hemisphere's edge is exact; texels are at most `step` radians wide and a
// tenth of the lobe's width, so the kernel's and the lobe's variation across one stays small.
inline Texels hemisphere_texels(const prt_cloth_lobe& lobe, double step) {
  const double lambda = lobe.sharpness;
  const Vec3d axis = unit({lobe.axis[0], lobe.axis[1], lobe.axis[2]});
  const double h = std::min(step, 0.1 / std::sqrt(lambda));
  const double cos_reach = std::max(-1.0, 1.0 - 20.0 / lambda);  // the lobe's extent
  const double e_axis = std::asin(std::clamp(axis[2], -1.0, 1.0));
  const double a_axis = std::atan2(axis[1], axis[0]);
  const double reach = std::acos(cos_reach);
  const double e_lo = std::max(0.0, e_axis - reach),
               e_hi = std::min(kExtremesPi / 2, e_axis + reach);
  Texels texels;
  if (e_hi <= e_lo) return texels;
  const int rows = std::max(1, int(std::ceil((e_hi - e_lo) / h)));
  for (int r = 0; r < rows; ++r) {
    const double e0 = e_lo + (e_hi - e_lo) * r / rows, e1 = e_lo + (e_hi - e_lo) * (r + 1) / rows;
    const double e = 0.5 * (e0 + e1);
    // The azimuths within reach of the axis on this row: cos(distance) >= cos_reach.
    const double denominator = std::cos(e) * std::cos(e_axis);
    double half = kExtremesPi;
    if (denominator > 1e-12) {
      const double c = (cos_reach - std::sin(e) * std::sin(e_axis)) / denominator;
      if (c > 1.0) continue;
      if (c > -1.0) half = std::acos(c);
    }
    // Widen by a step either side so the row's ends are covered.
    const double width =
        std::min(2.0 * kExtremesPi, 2.0 * half + 2.0 * h / std::max(std::cos(e1), 1e-3));
    const int segments = std::max(4, int(std::ceil(width * std::cos(e0) / h)));
    const double d_a = width / segments, solid = d_a * (std::sin(e1) - std::sin(e0));
    for (int k = 0; k < segments; ++k) {
      const Vec3d d = from_angles(e, a_axis - 0.5 * width + (k + 0.5) * d_a);
      const double g = std::exp(lambda * (d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2] - 1.0));
      texels.add(d, {lobe.rgb[0] * g * solid, lobe.rgb[1] * g * solid, lobe.rgb[2] * g * solid});
    }
  }
  return texels;
}

inline prt_cloth_light light_of(const std::vector<prt_cloth_lobe>& lobes) {
  prt_cloth_light light = prt::sized<prt_cloth_light>();
  light.lobe_count = std::uint32_t(lobes.size());
  light.lobes = lobes.data();
  return light;
}

// prt_cloth_shade on the CPU backend; the fabric's own parameters when `params` is null.
inline std::vector<float> shade(std::uint32_t fabric, const prt_cloth_params* params,
                                const std::vector<prt_cloth_lobe>& lobes, const Patch& patch,
                                const prt_cloth_settings* settings = nullptr) {
  std::vector<float> out(3 * std::size_t(patch.count()), -1.0f);
  const prt_cloth_light light = light_of(lobes);
  const prt_cloth_pixels pixels = patch.pixels();
  const prt_result r = prt_cloth_shade(baked_cloth().asset->asset, PRT_BACKEND_CPU, fabric, params,
                                       &light, settings, &pixels, 0, patch.count(), out.data());
  if (r != PRT_OK) out.assign(out.size(), std::nanf(""));
  return out;
}

inline std::vector<float> reference(std::uint32_t fabric, const prt_cloth_params& params,
                                    const Texels& texels, const Patch& patch) {
  std::vector<float> out(3 * std::size_t(patch.count()), -1.0f);
  const prt_cloth_env_texels env = texels.env();
  const prt_cloth_pixels pixels = patch.pixels();
  const prt_result r = prt_cloth_reference(&params, &baked_cloth().presets[fabric].weave, &env,
                                           &pixels, 0, patch.count(), out.data());
  if (r != PRT_OK) out.assign(out.size(), std::nanf(""));
  return out;
}

// sqrt(sum (a - b)^2 / sum b^2) over every sample and channel.
inline double relative_rms(const std::vector<float>& a, const std::vector<float>& b) {
  double error = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    error += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    norm += double(b[i]) * b[i];
  }
  return std::sqrt(error / norm);
}

// The reference's texels are at most this wide (and a tenth of the lobe's width): the reference
// then moves by far less than the method's error when they are halved.
inline double reference_step() {
  return degrees(2);
}

// The error against the reference of one white lobe on `axis` of sharpness `lambda`, over
// spread_views().
inline double lobe_error(std::uint32_t fabric, const Vec3d& axis, double lambda) {
  const Patch patch(spread_views());
  const prt_cloth_lobe lobe = make_lobe(axis, lambda);
  return relative_rms(shade(fabric, nullptr, {lobe}, patch),
                      reference(fabric, baked_cloth().presets[fabric].params,
                                hemisphere_texels(lobe, reference_step()), patch));
}

// How far beyond the moderate error an extreme may go (a small multiple of it), and the moderate
// error's own bound per fabric (linen, satin): both measured on this asset, rounded up.
constexpr double kSlack = 1.5;
constexpr double kModerateErrorBound[2] = {0.065, 0.115};
// The same for a view grazing the cloth (see GrazingViewAsCloseToTheReferenceAsAModerateView).
constexpr double kGrazingSlack = 3.0;
// How far the fitted light's power may be from the map's, relative: a few roundings of the
// lobes' float amplitudes.
constexpr double kPowerTolerance = 2e-7;
// How far the shading may move when eta goes from 1 to just above it.
constexpr double kEtaContinuity = 1e-3;

// A lobe high in the sky, away from every grid line of the tables.
inline Vec3d high_axis() {
  return from_angles(degrees(40), degrees(30));
}

// The bar the extremes are held to: the asset's error at moderate sharpness (lobes a few to tens
// of degrees wide) for a lobe on `axis`; on this small grid its tables dominate it.
// Computed once per fabric and axis.
inline double moderate_error(std::uint32_t fabric, const Vec3d& axis = high_axis()) {
  static std::map<std::pair<std::uint32_t, Vec3d>, double> known;
  const auto key = std::make_pair(fabric, axis);
  auto it = known.find(key);
  if (it == known.end())
    it =
        known
            .emplace(key, std::max(lobe_error(fabric, axis, 10.0), lobe_error(fabric, axis, 100.0)))
            .first;
  return it->second;
}

inline bool all_finite_non_negative(const std::vector<float>& v) {
  return std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x) && x >= 0.0f; });
}

}  // namespace prt_test
