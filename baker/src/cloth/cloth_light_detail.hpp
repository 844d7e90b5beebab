// SPDX-License-Identifier: MIT
// Private to the baker's SG light (cloth_light.cpp, cloth_light_refine.cpp): the map on a
// lat-long grid, the maths of spherical Gaussians smoothed by a normalised von Mises-Fisher
// kernel, the smoothed targets the refinement fits and the refinement itself.
#pragma once

#include <prt/prt_cloth.h>

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "../common/numbers.hpp"
#include "prt/baker/context.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake::sg_light {

// A lobe in double while it is fitted.
struct Lobe {
  glm::dvec3 axis{0.0, 1.0, 0.0};
  double sharpness = PRT_CLOTH_MIN_SHARPNESS;
  glm::dvec3 rgb{0.0};
};
std::vector<Lobe> to_lobes(const std::vector<prt_cloth_lobe>& lobes);
std::vector<prt_cloth_lobe> to_cloth_lobes(const std::vector<Lobe>& lobes);

// The map averaged onto a 2R x R lat-long grid (rows from +Y down, columns from azimuth -pi as
// prt_env.h's lat-long): per cell the power (radiance x solid angle) of the texels whose
// centres fall in it, their weight (power summed over RGB), the weighted sum of their
// directions and their solid angle. Built from EnvMap::texel (any mapping, rotation included).
struct MapGrid {
  std::uint32_t rows = 0, cols = 0;
  std::vector<glm::dvec3> power;
  std::vector<double> weight;
  std::vector<glm::dvec3> resultant;
  std::vector<double> solid_angle;
  glm::dvec3 total_power{0.0};
};
MapGrid grid_of(const io::EnvMap& map, std::uint32_t rows);
// The grid of half the rows: each cell the sum of 2 x 2 cells (a texel falls in the cell of the
// coarser grid it would fall in directly: the bins nest exactly).
MapGrid coarser(const MapGrid& fine);

// The cell (row, col)'s centre direction and exact solid angle.
glm::dvec3 cell_centre(std::uint32_t rows, std::uint32_t row, std::uint32_t col);
double cell_solid_angle(std::uint32_t rows, std::uint32_t row);

// The sharpness of a von Mises-Fisher lobe of mean resultant length r (coth l - 1/l = r),
// within [lo, hi]; the integral of exp(l (w . axis - 1)) over the sphere.
double sharpness_of_resultant(double r, double lo, double hi);
double lobe_integral(double sharpness);

// A unit-amplitude SG of sharpness l smoothed by the normalised vMF kernel of sharpness kappa,
// at a direction whose dot product with the lobe's axis is t (exact: the product of two SGs
// integrates to 4 pi sinh(|l a + kappa v|) / |l a + kappa v| e^(-l - kappa)); and its
// derivatives in l and t.
double smoothed_lobe(double l, double kappa, double t);
void smoothed_lobe_derivatives(double l, double kappa, double t, double* value, double* d_l,
                               double* d_t);

// The plain relative error (SgLightError::relative) of lobes against the grid.
double relative_error(const MapGrid& grid, const std::vector<Lobe>& lobes);
// |lobe power - map power| / map power.
double power_error(const MapGrid& grid, const std::vector<Lobe>& lobes);

// One smoothing kernel's evaluation: points (the centres of a 2R' x R' grid with R' fitting the
// kernel's width, at most half the fine grid's rows), their solid angles, and the smoothed map
// there, from the map's grid at twice the error grid's rows.
struct SmoothedTarget {
  double kappa = 0.0;  // 1 / sigma^2
  std::vector<glm::dvec3> points;
  std::vector<double> weights;
  std::vector<glm::dvec3> target;
  double norm = 0.0;  // sum of weights x |target|^2 (RGB)
};
std::vector<SmoothedTarget> smoothed_targets(const MapGrid& fine,
                                             const std::vector<double>& degrees,
                                             const Context& ctx);
// sqrt(sum of weights x |smoothed lobes - target|^2 / norm); 0 for a black target.
double smoothed_error(const SmoothedTarget& target, const std::vector<Lobe>& lobes);

struct Refinement {
  std::vector<Lobe> lobes;
  std::uint32_t fixed = 0;
  std::uint32_t steps = 0;
};
// The refinement of `start` (fit_sg_light's documentation); lobes at least as sharp as
// fixed_sharpness are kept as they are.
Refinement refine(const std::vector<SmoothedTarget>& targets, const std::vector<Lobe>& start,
                  double fixed_sharpness, std::uint32_t max_steps, const Context& ctx);

}  // namespace prt::bake::sg_light
