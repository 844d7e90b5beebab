// SPDX-License-Identifier: MIT
// Interreflection in the wavelet domain against the reference renderer (independent: path
// tracing, no wavelets) and the sphere-cavity law, in a hemispherical bowl under a constant sky
// (smooth and seamless, so vertex interpolation of the hit's transfer is not what is measured).
#include <gtest/gtest.h>

#include <prt/prt_wavelet.h>

#include <cmath>
#include <vector>

#include "prt/baker/reference.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"
#include "prt/io/radiance_error.hpp"
#include "sh/sh_test_scenes.hpp"
#include "support/render_test_scenes.hpp"
#include "wavelet/wavelet_test_util.hpp"

namespace prt::bake {
namespace {

std::vector<glm::vec3> wavelet_radiance(const Scene& scene, int bounces) {
  WaveletTransferSettings s;
  s.size = 16;
  s.samples = 4;
  s.keep = 0;
  s.bounces = bounces;
  s.override_albedo = true;
  s.albedo = glm::vec3(0.8f);
  Context ctx;
  const WaveletTransfer t = compute_wavelet_transfer(scene, nullptr, s, ctx);
  // Radiance 1 everywhere, through the runtime's light pipeline (texel powers, SPEC §14).
  const std::vector<float> light =
      test::runtime_light(io::constant_envmap(glm::vec3(1.0f)), PRT_WAVELET_PARAM_CUBE, 16);
  return shade_wavelet_transfer(t, light);
}

std::vector<glm::vec3> reference_radiance(const Scene& scene, const io::EnvMap& env, int bounces,
                                          double* noise) {
  ReferenceSettings r;
  r.bounces = bounces;
  r.spp = 2048;
  r.override_albedo = true;
  r.albedo = glm::vec3(0.8f);
  Context ctx;
  const ReferenceRenderer renderer(scene, env, r, ctx);
  const VertexRadiance out = renderer.render_vertices(ctx);
  *noise = out.relative_rmse;
  return out.radiance;
}

TEST(WaveletBounce, BowlUnderAConstantSkyFollowsTheSphereCavityLaw) {
  // Inside a sphere every surface element sees every other with view factor dA / (4 pi R^2), so
  // a hemispherical bowl's opening and its own surface each take half of every point's cosine-
  // weighted hemisphere: under a constant sky of radiance 1 with uniform albedo rho every point
  // has rho/2 directly and each bounce multiplies that by rho/2.
  const Scene scene = test::scene_of({test::make_bowl(16, 48)});
  const double rho = 0.8;
  for (int bounces = 0; bounces <= 2; ++bounces) {
    const std::vector<glm::vec3> radiance = wavelet_radiance(scene, bounces);
    double expected = 0.0, mean = 0.0;
    for (int i = 0; i <= bounces; ++i) expected += rho / 2.0 * std::pow(rho / 2.0, i);
    for (const glm::vec3& l : radiance) mean += l.g / radiance.size();
    EXPECT_NEAR(mean, expected, 0.015 * expected) << "bounces " << bounces;
  }
}

TEST(WaveletBounce, OneBounceMatchesThePathTracer) {
  const Scene scene = test::scene_of({test::make_bowl(16, 48)});
  const io::EnvMap sky = io::constant_envmap(glm::vec3(1.0f));
  double noise = 0.0;
  const std::vector<glm::vec3> reference = reference_radiance(scene, sky, 1, &noise);
  const std::vector<glm::vec3> direct = wavelet_radiance(scene, 0);
  const std::vector<glm::vec3> bounced = wavelet_radiance(scene, 1);
  // The RMS difference is the reference's noise (within 1.25 of it over the bowl's hundreds of
  // vertices) and 0.6 % of the bake's own error (the hit's transfer interpolated across the
  // facets, and the texels' jitter), added in quadrature: a bounce 10 % off fails.
  const double error = io::relative_rmse(bounced, reference);
  EXPECT_LT(error, std::hypot(1.25 * noise, 0.006)) << "noise " << noise;
  EXPECT_GT(io::relative_rmse(direct, reference), 5.0 * error);  // the bounce is needed
}

}  // namespace
}  // namespace prt::bake
