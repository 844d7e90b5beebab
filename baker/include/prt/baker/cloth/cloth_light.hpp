// SPDX-License-Identifier: MIT
// The spherical-Gaussian light of technique `cloth` for lights that do not change at run time:
// the runtime's per-frame fit (prt_cloth_fit_light) refined offline against what cloth sees of
// the environment, the map smoothed by Gaussian kernels a few degrees wide and wider. Also the
// light's radiance in a direction, its errors against a map, and its JSON file, which apps and
// the trade load. A lobe is prt_cloth_lobe (prt/prt_cloth.h): L(w) = rgb exp(sharpness (w . axis
// - 1)), world frame.
#pragma once

#include <prt/prt_cloth.h>

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake {

struct SgLightOptions {
  std::uint32_t lobe_count = 10;  // K, 1..PRT_CLOTH_MAX_LOBES
  // R: the fits and the errors use a lat-long grid of 2R x R cells (the runtime's resolution).
  std::uint32_t resolution = 64;
  // Standard deviations (degrees) of the smoothing kernels of the refinement's error: cloth
  // reflects the environment through lobes this wide or wider. Each in (0, 90].
  std::vector<double> smoothing_degrees{3.0, 10.0, 30.0};
  // Refinement steps at most (0: the runtime's fit as it is); it stops earlier once a step
  // gains little.
  std::uint32_t max_steps = 100;
};

// How far a light is from a map, on the grid of SgLightOptions::resolution.
struct SgLightError {
  // RMS over the grid's cells (solid-angle weighted, RGB) of the light's mean radiance in the
  // cell minus the map's, over the map's RMS radiance: prt_cloth_fit_report's relative_error.
  double relative = 0.0;
  // The same for the map and the light each smoothed by the kernel of smoothing_degrees[i]
  // (a normalised von Mises-Fisher kernel of sharpness 1 / sigma^2), at the centres of a grid
  // spaced about two thirds of the kernel's width (no finer than the grid above). The light is
  // smoothed exactly; the map from a grid of twice the rows, each block of cells at most half
  // the kernel wide taken as the vMF lobe with its power, mean direction and spread.
  std::vector<double> smoothed;
  // |the light's power - the map's power| / the map's power (RGB summed; 0 for a black map).
  double power = 0.0;
};

struct SgLightFit {
  std::vector<prt_cloth_lobe> lobes;  // the lit lobes (at most lobe_count)
  std::uint32_t lobe_count = 0;       // K asked for
  std::uint32_t resolution = 0;
  std::vector<double> smoothing_degrees;
  SgLightError fast;   // the runtime's fit it started from (its lit lobes)
  SgLightError error;  // this light's
  // Lobes kept as the runtime's fit made them: those at least as sharp as the finest kernel
  // (the smoothed error sees them as points), which includes every compact source (a sun), so
  // their power stays exact. The others' axes, sharpness and amplitudes are refined.
  std::uint32_t fixed_lobes = 0;
  std::uint32_t steps = 0;  // refinement steps taken, each of which lowered the objective
};

// The runtime's fit (prt_cloth_fit_light) of the map: a lat-long map as it is (its rotation
// given as the env's), a cross or probe resampled to a cube (prt::io::resample_to_cube; a
// cross at its own face size, a probe at a quarter of its width). `report` may be null.
// Throws Error for invalid options or when the runtime fails.
std::vector<prt_cloth_lobe> fast_sg_light(const io::EnvMap& map, const SgLightOptions& options,
                                          prt_cloth_fit_report* report = nullptr);

// The static fit: the runtime's fit refined (Levenberg-Marquardt on the free lobes' axes and
// log sharpness, non-negative least squares for their amplitudes at each step) to lower the sum
// over kernels of (smoothed error / the runtime fit's)^2. The result is the best step that
// raised no smoothed error above the runtime fit's (the runtime's fit itself when none did), so
// no smoothed error is ever larger. Deterministic (any thread count). Throws Error for invalid
// options.
SgLightFit fit_sg_light(const io::EnvMap& map, const SgLightOptions& options = {},
                        const Context& ctx = {});

// The errors of any light against the map (SgLightError), on options' grid and kernels.
SgLightError measure_sg_light(const io::EnvMap& map, const std::vector<prt_cloth_lobe>& lobes,
                              const SgLightOptions& options, const Context& ctx = {});

// The light's radiance arriving from unit direction `direction` (world frame).
glm::vec3 sg_radiance(const std::vector<prt_cloth_lobe>& lobes, const glm::vec3& direction);

// The light as JSON: {"lobes": [{"axis": [x, y, z], "sharpness": s, "rgb": [r, g, b]}, ...],
// "fit": {"lobe_count", "resolution", "smoothing_degrees", "fixed_lobes", "steps",
// "error": {"relative", "smoothed", "power"}, "fast": {...}}}; floats printed so that they read
// back to the same bits.
std::string sg_light_json(const SgLightFit& fit);
// Writes sg_light_json(fit) to path; Error naming the file when it cannot be written.
void write_sg_light(const std::string& path, const SgLightFit& fit);
// Reads a light file. Error naming the file for unreadable JSON, a missing member or a lobe
// prt_cloth_light_validate would reject (an axis off unit length by more than 1e-3, a sharpness
// outside [PRT_CLOTH_MIN_SHARPNESS, PRT_CLOTH_MAX_SHARPNESS], a negative or non-finite rgb), or
// more than PRT_CLOTH_MAX_LOBES lobes. "fit" is optional (then left default).
SgLightFit read_sg_light(const std::string& path);

}  // namespace prt::bake
