// SPDX-License-Identifier: MIT
// The runtime reads what the baker wrote as the baker reads it: the concentric map, the g table's
// bilinear read (SeparableBrdf::outgoing_at) and the tangent frame (sampling.hpp's Frame), each
// against the baker's own function.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "prt/baker/sampling.hpp"
#include "prt/baker/shadowfield/shadowfield_brdf.hpp"
#include "shadowfield/runtime/shadowfield_synthetic.hpp"

extern "C" {
#include "shadowfield_scene.h"
}

namespace prt::test {
namespace {

// Directions over the whole sphere (so below the horizon too), and the axes and diagonals where
// the concentric map changes sector.
std::vector<glm::dvec3> test_directions() {
  std::vector<glm::dvec3> out = {{0, 0, 1},   {1, 0, 0}, {0, 1, 0},  {-1, 0, 0},
                                 {0, -1, 0},  {1, 1, 1}, {-1, 1, 1}, {1, -1, 1},
                                 {-1, -1, 1}, {1, 1, 0}, {1, 0, -1}, {0.3, 0.2, -0.9}};
  std::mt19937 random(11);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 2000; ++i) out.emplace_back(normal(random), normal(random), normal(random));
  return out;
}

TEST(ShadowfieldBakerRead, TheConcentricMapIsTheBakers) {
  double worst = 0.0;
  for (const glm::dvec3& d : test_directions()) {
    double a = 0, b = 0, ea = 0, eb = 0;
    const double direction[3] = {d.x, d.y, d.z};
    prt_sf_square_from_hemisphere(direction, &a, &b);
    bake::square_from_hemisphere(d, &ea, &eb);
    worst = std::max({worst, std::fabs(a - ea), std::fabs(b - eb)});
  }
  EXPECT_LT(worst, 1e-14);
}

TEST(ShadowfieldBakerRead, TheGTableReadIsTheBakers) {
  bake::SeparableBrdf brdf =
      bake::separate_brdf(bake::brdf_function(bake::PhongBrdf{10.0, 1.0, 0.0}), {8, 4});
  // The blob stores floats: the baker's read of the same floats is the reference.
  for (double& value : brdf.outgoing) value = double(float(value));
  SyntheticObject object = make_patch(4, 1);
  object.glossy = 1;
  object.terms = brdf.terms;
  object.brdf_grid = brdf.grid.size;
  object.g_table.assign(brdf.outgoing.begin(), brdf.outgoing.end());
  const prt_sf_object* view = object.view();
  double worst = 0.0, scale = 0.0;
  for (const glm::dvec3& d : test_directions()) {
    const double wo[3] = {d.x, d.y, d.z};
    for (uint32_t k = 0; k < brdf.terms; ++k) {
      const double expected = brdf.outgoing_at(k, d);
      worst = std::max(worst, std::fabs(prt_sf_outgoing_at(view, k, wo) - expected));
      scale = std::max(scale, std::fabs(expected));
    }
  }
  std::printf("g read: max difference %.2e of %.2f\n", worst, scale);
  EXPECT_LT(worst, 3e-7 * scale);  // the result's rounding to float
}

TEST(ShadowfieldBakerRead, TheTangentFrameIsTheBakers) {
  double worst = 0.0;
  for (const glm::dvec3& d : test_directions()) {
    const glm::vec3 n = glm::normalize(glm::vec3(d));
    const bake::Frame frame(n);
    const float normal[3] = {n.x, n.y, n.z};
    float t[3], b[3];
    prt_sf_tangent_frame(normal, t, b);
    for (int c = 0; c < 3; ++c)
      worst = std::max(
          {worst, double(std::fabs(t[c] - frame.t[c])), double(std::fabs(b[c] - frame.b[c]))});
  }
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace prt::test
