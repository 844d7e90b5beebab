// SPDX-License-Identifier: MIT
// Backend conformance of `wavelet` (tests/gl/conformance.hpp): WVLT blobs built byte by byte (both
// parameterisations, S = 16 and 64; rows with no pair, one pair, a full 256-entry block, and
// random rows of up to 500 pairs) shaded under a light with a few "sun" coefficients 10^4 times
// the rest, prepared by prt_wavelet_prepare_light, on cpu, simd per ISA and gl, each within
// prt_test::wavelet_tolerance (gamma_(pairs+4) * sum_j |q bs vs L|, doubled) of the reference.
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "gl/conformance.hpp"

namespace prt_conformance {
namespace {

using prt_test::ContextPtr;
using prt_test::LoadedAsset;
using prt_test::WvltPair;
using prt_test::WvltTransfer;

// Rows of every shape, by vertex index mod 6: none, one pair, one full block of 256, and three
// random rows of 1..500 pairs (distinct indices, values +-1..127).
WvltTransfer conformance_transfer(prt_wavelet_param param, uint32_t size, uint32_t seed) {
  WvltTransfer t = prt_test::wvlt_random(param, size, kVertices, 0, seed);
  const uint32_t coefficients = t.coefficients(), blocks = t.blocks();
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> pick(0, coefficients - 1), length(1, 500);
  std::uniform_int_distribution<int> value(1, 127);
  auto random_q = [&]() {
    const int q = value(rng);
    return int8_t(rng() % 2 ? -q : q);
  };
  std::vector<uint8_t> taken(coefficients);
  uint32_t keep = 0;
  for (uint32_t v = 0; v < kVertices; ++v) {
    std::vector<WvltPair>& row = t.rows[v];
    switch (v % 6) {
      case 0:
        break;
      case 1:
        row.push_back({pick(rng), random_q()});
        break;
      case 2:
        for (uint32_t i = 0; i < 256; ++i) row.push_back({256 * (v % blocks) + i, random_q()});
        break;
      default: {
        const uint32_t n = std::min(length(rng), coefficients);
        std::fill(taken.begin(), taken.end(), uint8_t(0));
        while (row.size() < n) {
          const uint32_t j = pick(rng);
          if (!taken[j]) taken[j] = 1, row.push_back({j, random_q()});
        }
        std::sort(row.begin(), row.end(),
                  [](const WvltPair& a, const WvltPair& b) { return a.j < b.j; });
      }
    }
    keep = std::max(keep, uint32_t(row.size()));
  }
  t.keep = keep;
  return t;
}

// Random light with a few "sun" coefficients 10^4 times the rest.
std::vector<float> sunny_light(uint32_t coefficients, uint32_t seed) {
  std::vector<float> light = prt_test::wvlt_random_light(coefficients, seed);
  std::mt19937 rng(seed);
  for (int i = 0; i < 8; ++i) {
    const size_t j = rng() % coefficients;
    for (size_t c = 0; c < 3; ++c) light[4 * j + c] *= 1e4f;
  }
  return light;
}

double compare_wavelet(const char* what, const WvltTransfer& t, const Truth& truth,
                       const std::vector<double>& reference, const std::vector<float>& rgb,
                       uint32_t first, uint32_t count) {
  double worst = 0.0;
  int failures = 0;
  for (size_t i = 0; i < 3 * size_t(count); ++i) {
    const size_t k = 3 * size_t(first) + i;
    const double tol = prt_test::wavelet_tolerance(t.rows[k / 3].size(), truth.magnitude[k]);
    const double error = std::fabs(double(rgb[i]) - reference[k]);
    worst = std::max(worst, error / tol);
    if (error > tol && failures++ < 5)
      ADD_FAILURE() << what << ": vertex " << k / 3 << " (" << t.rows[k / 3].size()
                    << " pairs) channel " << k % 3 << " gives " << rgb[i] << ", reference "
                    << reference[k] << " (tolerance " << tol << ")";
  }
  return worst;
}

void check_wavelet_backends(prt_wavelet_param param, uint32_t size) {
  PRT_REQUIRE_GL(gl);
  const WvltTransfer t = conformance_transfer(param, size, 500 + size + uint32_t(param));
  const prt_test::Bytes blob = prt_test::wvlt_make_blob(prt_test::wvlt_encode(t), kVertices);
  const std::vector<float> light = sunny_light(t.coefficients(), 31 + size);
  Truth truth;
  for (uint32_t v = 0; v < kVertices; ++v) {
    double value[3], magnitude[3];
    prt_test::wvlt_reference_shade(t, light, v, value, magnitude);
    truth.value.insert(truth.value.end(), value, value + 3);
    truth.magnitude.insert(truth.magnitude.end(), magnitude, magnitude + 3);
  }
  Summary summary(std::string(param == PRT_WAVELET_PARAM_CUBE ? "cube" : "paraboloid") + " S " +
                  std::to_string(size) + ", " + std::to_string(t.pair_count()) + " pairs");
  const uint32_t part_first = 3, part_count = 997;

  // The scalar reference, checked against the exact sum first; it also prepares the light.
  const prt::ContextPtr cpu_ctx = prt_test::limited_context();
  LoadedAsset cpu_asset(cpu_ctx.get(), blob);
  ASSERT_EQ(cpu_asset.result, PRT_OK) << prt_context_last_message(cpu_ctx.get());
  std::vector<float> prepared(light.size());
  std::vector<uint8_t> zero_blocks(t.blocks());
  ASSERT_EQ(
      prt_wavelet_prepare_light(cpu_asset.asset, light.data(), prepared.data(), zero_blocks.data()),
      PRT_OK);
  std::vector<float> reference_rgb(3 * size_t(kVertices));
  ASSERT_EQ(prt_wavelet_shade(cpu_asset.asset, PRT_BACKEND_CPU, prepared.data(), zero_blocks.data(),
                              0, kVertices, reference_rgb.data()),
            PRT_OK);
  summary.note("cpu-vs-exact",
               compare_wavelet("cpu", t, truth, truth.value, reference_rgb, 0, kVertices));
  const std::vector<double> reference(reference_rgb.begin(), reference_rgb.end());

  for_each_simd_isa(summary, [&](prt_context* ctx, const std::string& name) {
    LoadedAsset asset(ctx, blob);
    ASSERT_EQ(asset.result, PRT_OK);
    std::vector<float> rgb(3 * size_t(kVertices));
    const prt_result r = prt_wavelet_shade(asset.asset, PRT_BACKEND_SIMD, prepared.data(),
                                           zero_blocks.data(), 0, kVertices, rgb.data());
    ASSERT_EQ(r, PRT_OK) << name
                         << " is usable per prt_backend_get_info but prt_wavelet_shade returned "
                         << prt_result_string(r);
    double worst = compare_wavelet(name.c_str(), t, truth, reference, rgb, 0, kVertices);
    // A range that starts and ends off any vector width.
    std::vector<float> part(3 * size_t(part_count));
    ASSERT_EQ(prt_wavelet_shade(asset.asset, PRT_BACKEND_SIMD, prepared.data(), zero_blocks.data(),
                                part_first, part_count, part.data()),
              PRT_OK);
    worst = std::max(
        worst, compare_wavelet(name.c_str(), t, truth, reference, part, part_first, part_count));
    summary.note(name, worst);
  });

  // GL (which walks every pair, mask or not): a sub-range on a fresh shader first, then all.
  {
    const prt::ContextPtr ctx = prt_test::limited_context();
    LoadedAsset asset(ctx.get(), blob);
    ASSERT_EQ(asset.result, PRT_OK);
    auto [shader, made] =
        prt::gl_wavelet_create(ctx.get(), asset.asset, headless_gl_get_proc, gl.gl);
    ASSERT_EQ(made, PRT_OK) << prt_context_last_message(ctx.get());
    std::vector<float> part(3 * size_t(part_count));
    ASSERT_EQ(prt_gl_wavelet_shade(shader.get(), prepared.data(), part_first, part_count), PRT_OK);
    ASSERT_EQ(prt_gl_wavelet_read(shader.get(), part_first, part_count, part.data()), PRT_OK);
    double worst = compare_wavelet("gl", t, truth, reference, part, part_first, part_count);
    ASSERT_EQ(prt_gl_wavelet_shade(shader.get(), prepared.data(), 0, kVertices), PRT_OK);
    prt_test::expect_gl_state_restored("prt_gl_wavelet_shade");
    std::vector<float> rgb(3 * size_t(kVertices));
    ASSERT_EQ(prt_gl_wavelet_read(shader.get(), 0, kVertices, rgb.data()), PRT_OK);
    worst = std::max(worst, compare_wavelet("gl", t, truth, reference, rgb, 0, kVertices));
    summary.note(std::string("gl (") + headless_gl_renderer(gl.gl) + ")", worst);
  }
  summary.print("wavelet");
}

}  // namespace

std::vector<Case> wavelet_cases() {
  struct Domain {
    const char* name;
    prt_wavelet_param param;
    uint32_t size;
  };
  const Domain domains[] = {
      {"Cube16", PRT_WAVELET_PARAM_CUBE, 16},
      {"Cube64", PRT_WAVELET_PARAM_CUBE, 64},
      {"Paraboloid16", PRT_WAVELET_PARAM_DUAL_PARABOLOID, 16},
      {"Paraboloid64", PRT_WAVELET_PARAM_DUAL_PARABOLOID, 64},
  };
  std::vector<Case> cases;
  for (const Domain& d : domains)
    cases.push_back({d.name, [d] { check_wavelet_backends(d.param, d.size); }});
  return cases;
}

}  // namespace prt_conformance
