// SPDX-License-Identifier: MIT
// Backend conformance of `sh` (tests/gl/conformance.hpp): random SHTR blobs of several orders,
// channel counts and bit depths shaded under a light with a realistic spread on every backend,
// each within prt_test::tolerance (gl_test_util.hpp: the float dot product error bound
// gamma_(order²+8) * sum_j (|offset_j| + |scale_j q_j|) |L_j|, doubled) of the reference.
#include <algorithm>
#include <string>
#include <vector>

#include "gl/conformance.hpp"

namespace prt_conformance {
namespace {

using prt_test::ContextPtr;
using prt_test::LoadedAsset;
using prt_test::ShaderPtr;
using prt_test::Transfer;

Truth exact(const Transfer& t, const std::vector<float>& light) {
  Truth truth;
  for (uint32_t v = 0; v < t.vertices; ++v)
    for (uint32_t c = 0; c < 3; ++c) {
      const prt_test::Expected e = prt_test::expected_radiance(t, light, v, c);
      truth.value.push_back(e.value);
      truth.magnitude.push_back(e.magnitude);
    }
  return truth;
}

// Compares rgb (vertices [first, first+count)) with `reference` under the tolerance; returns
// the largest |error| / tolerance seen (the margin printed in the summary).
double compare(const char* what, const Transfer& t, const Truth& truth,
               const std::vector<double>& reference, const std::vector<float>& rgb, uint32_t first,
               uint32_t count) {
  double worst = 0.0;
  int failures = 0;
  for (size_t i = 0; i < 3 * size_t(count); ++i) {
    const size_t k = 3 * size_t(first) + i;
    const double tol = prt_test::tolerance(t.order, truth.magnitude[k]);
    const double error = std::fabs(double(rgb[i]) - reference[k]);
    worst = std::max(worst, error / tol);
    if (error > tol && failures++ < 5)
      ADD_FAILURE() << what << ": vertex " << k / 3 << " channel " << k % 3 << " gives " << rgb[i]
                    << ", reference " << reference[k] << " (tolerance " << tol << ")";
  }
  return worst;
}

// One asset shaded on every backend; prints what was compared and what was skipped and why.
void check_all_backends(uint32_t order, uint32_t channels, uint32_t bits) {
  PRT_REQUIRE_GL(gl);
  const Transfer t = prt_test::random_transfer(order, kVertices, channels, bits, 1000 + order);
  const prt_test::Bytes blob = prt_test::make_blob(prt_test::encode(t), kVertices);
  const std::vector<float> light = prt_test::realistic_light(order, 77);
  const Truth truth = exact(t, light);
  Summary summary("order " + std::to_string(order) + ", " + std::to_string(channels) +
                  " channel(s), " + std::to_string(bits) + "-bit");

  // The scalar reference, checked against the exact sum first.
  const prt::ContextPtr cpu_ctx = prt_test::limited_context();
  LoadedAsset cpu_asset(cpu_ctx.get(), blob);
  ASSERT_EQ(cpu_asset.result, PRT_OK);
  std::vector<float> reference_rgb(3 * size_t(kVertices));
  ASSERT_EQ(prt_sh_shade(cpu_asset.asset, PRT_BACKEND_CPU, light.data(), 0, kVertices,
                         reference_rgb.data()),
            PRT_OK);
  summary.note("cpu-vs-exact", compare("cpu", t, truth, truth.value, reference_rgb, 0, kVertices));
  const std::vector<double> reference(reference_rgb.begin(), reference_rgb.end());

  for_each_simd_isa(summary, [&](prt_context* ctx, const std::string& name) {
    LoadedAsset asset(ctx, blob);
    ASSERT_EQ(asset.result, PRT_OK);
    std::vector<float> rgb(3 * size_t(kVertices));
    const prt_result r =
        prt_sh_shade(asset.asset, PRT_BACKEND_SIMD, light.data(), 0, kVertices, rgb.data());
    ASSERT_EQ(r, PRT_OK) << name << " is usable per prt_backend_get_info but prt_sh_shade returned "
                         << prt_result_string(r);
    double worst = compare(name.c_str(), t, truth, reference, rgb, 0, kVertices);
    // A range that starts and ends off any vector width.
    std::vector<float> part(3 * 997);
    ASSERT_EQ(prt_sh_shade(asset.asset, PRT_BACKEND_SIMD, light.data(), 1, 997, part.data()),
              PRT_OK);
    worst = std::max(worst, compare(name.c_str(), t, truth, reference, part, 1, 997));
    summary.note(name, worst);
  });

  // GL.
  {
    const prt::ContextPtr ctx = prt_test::limited_context();
    LoadedAsset asset(ctx.get(), blob);
    ASSERT_EQ(asset.result, PRT_OK);
    auto [shader, made] = prt::gl_sh_create(ctx.get(), asset.asset, headless_gl_get_proc, gl.gl);
    ASSERT_EQ(made, PRT_OK) << prt_context_last_message(ctx.get());
    ASSERT_EQ(prt_gl_sh_shade(shader.get(), light.data(), 0, kVertices), PRT_OK);
    prt_test::expect_gl_state_restored("prt_gl_sh_shade");
    std::vector<float> rgb(3 * size_t(kVertices));
    ASSERT_EQ(prt_gl_sh_read(shader.get(), 0, kVertices, rgb.data()), PRT_OK);
    double worst = compare("gl", t, truth, reference, rgb, 0, kVertices);
    std::vector<float> part(3 * 997);
    ASSERT_EQ(prt_gl_sh_read(shader.get(), 1, 997, part.data()), PRT_OK);
    worst = std::max(worst, compare("gl", t, truth, reference, part, 1, 997));
    summary.note(std::string("gl (") + headless_gl_renderer(gl.gl) + ")", worst);
  }
  summary.print("sh");
}

}  // namespace

std::vector<Case> sh_cases() {
  struct Layout {
    const char* name;
    uint32_t order, channels, bits;
  };
  const Layout layouts[] = {
      {"Order1Grey8Bit", 1, 1, 8},    {"Order2Rgb8Bit", 2, 3, 8}, {"Order3Grey16Bit", 3, 1, 16},
      {"Order6Rgb16Bit", 6, 3, 16},   {"Order8Rgb8Bit", 8, 3, 8}, {"Order16Grey16Bit", 16, 1, 16},
      {"Order16Rgb16Bit", 16, 3, 16},
  };
  std::vector<Case> cases;
  for (const Layout& l : layouts)
    cases.push_back({l.name, [l] { check_all_backends(l.order, l.channels, l.bits); }});
  return cases;
}

}  // namespace prt_conformance
