// SPDX-License-Identifier: MIT
// What technique `cloth`'s trade measures with (private to baker/src/cloth/): the surface
// samples (frames of the scene seen from a fixed set of views), the environment as texels for
// the brute-force reference, the reference cached on disk, the method's shading through the
// runtime, and the error figures.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/cloth/cloth_blob.hpp"
#include "prt/baker/cloth/fabrics.hpp"
#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake::cloth_trade {

// A surface frame: unit normal and unit warp orthogonal to it.
struct SurfaceFrame {
  glm::vec3 normal, warp;
};

// The scene's distinct vertex frames (warps as the bake writes them), in vertex order, at most
// `limit`. Throws Error for a scene without vertices.
std::vector<SurfaceFrame> surface_frames(const Scene& scene, std::uint32_t limit);

// The views of each frame: elevations 15, 35, 55 and 75 degrees over the frame's plane, 8
// azimuths each from the warp, every other elevation turned by half a step (32 views).
std::vector<glm::vec3> frame_views(const SurfaceFrame& frame);

// Every frame seen from every one of its views, as prt_cloth_pixels takes them.
struct Samples {
  std::vector<float> normals, warps, views;
  std::uint32_t count() const { return static_cast<std::uint32_t>(views.size() / 3); }
  prt_cloth_pixels pixels() const;
};
Samples make_samples(const std::vector<SurfaceFrame>& frames);

// The map's texels as the reference integrates them (direction, radiance x solid angle), each
// block x block square of texels merged into one (power summed, direction the power-weighted
// mean): block 1 is the map itself, block 2 shows the reference's own discretisation error.
struct EnvTexels {
  std::vector<float> directions, power;
  std::vector<float> solid_angles;
  prt_cloth_env_texels view() const;
};
EnvTexels env_texels(const io::EnvMap& map, int block);
// A spherical-Gaussian light as texels (the light's error alone, without the method's): each
// lobe cut into rings of equal mass about its axis (exact for the lobe, however sharp), each ring
// into equal azimuth steps.
EnvTexels sg_texels(const std::vector<prt_cloth_lobe>& lobes);

// The brute-force reference of one fabric at the samples, read from
// cache_dir/<key>.f32 when a run with the same inputs wrote it (the key hashes the fabric, the
// samples, the map's file name, rotation and block), else computed and written there.
std::vector<float> cached_reference(const ClothPreset& fabric, const Samples& samples,
                                    const io::EnvMap& map, const std::string& map_name, int block,
                                    const std::string& cache_dir, const Context& ctx);
// The reference under explicit texels (not cached).
std::vector<float> reference(const ClothPreset& fabric, const Samples& samples,
                             const EnvTexels& texels, const Context& ctx);

// The method's shading of fabric 0 of a blob (loaded at full validation) on `backend`.
struct Shading {
  std::vector<float> rgb;
  double microseconds_per_sample = -1.0;  // median of `frames` timed calls; -1: not available
};
Shading shade(const std::vector<std::uint8_t>& blob, prt_backend backend, const Samples& samples,
              const std::vector<prt_cloth_lobe>& lobes, const prt_cloth_settings& settings,
              int frames, const Context& ctx);

// RMS error over every sample and channel / the reference's mean, and the mean's bias
// (sum of x / sum of reference - 1).
double nrmse(const std::vector<float>& x, const std::vector<float>& reference);
double bias(const std::vector<float>& x, const std::vector<float>& reference);

// A section with every table truncated to the smallest rank leaving at most `energy` of its
// squared norm (ranks from singular values, descending, per table: full then cone).
ClothSection truncated_section(const ClothSection& section,
                               const std::vector<std::vector<double>>& full_singular_values,
                               const std::vector<std::vector<double>>& cone_singular_values,
                               double energy);

}  // namespace prt::bake::cloth_trade
