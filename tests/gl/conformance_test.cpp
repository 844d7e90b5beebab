// SPDX-License-Identifier: MIT
// Backend conformance for `sh`: the same assets (random SHTR blobs of several orders, channel
// counts and bit depths; 10,007 vertices, a prime, so no backend's blocking divides it) shaded
// under a light with a realistic spread by the scalar reference (prt_sh_shade_on CPU), by the
// SIMD backend once per instruction set the CPU has (forced with simd_isa_limit) and by GL; each
// must agree with the reference within prt_test::tolerance (gl_test_util.hpp: the float dot
// product error bound gamma_(order²+8) * sum_j (|offset_j| + |scale_j q_j|) |L_j|, doubled). The
// reference itself is first checked against the exact double sum the same way.
//
// The same for `wavelet` (the Wavelet* tests): WVLT blobs built byte by byte (both
// parameterisations, S = 16 and 64; rows with no pair, one pair, a full 256-entry block, and
// random rows of up to 500 pairs; 10,007 vertices) shaded under a light with a few "sun"
// coefficients 10^4 times the rest, prepared by prt_wavelet_prepare_light, on cpu, simd per ISA
// and gl, each within prt_test::wavelet_tolerance (gamma_(pairs+4) * sum_j |q bs vs L|, doubled) of
// the reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "support/gl_test_util.hpp"

namespace {

using prt_test::ContextPtr;
using prt_test::LoadedAsset;
using prt_test::ShaderPtr;
using prt_test::Transfer;

constexpr uint32_t kVertices = 10007;

// Per vertex and channel: the exact value and the magnitude the tolerance scales with.
struct Truth {
  std::vector<double> value, magnitude;
};

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
  std::string summary = "order " + std::to_string(order) + ", " + std::to_string(channels) +
                        " channel(s), " + std::to_string(bits) + "-bit:";
  auto note = [&summary](const std::string& backend, double worst) {
    char text[96];
    std::snprintf(text, sizeof text, " %s (max err/tol %.3g)", backend.c_str(), worst);
    summary += text;
  };

  // The scalar reference, checked against the exact sum first.
  ContextPtr cpu_ctx(prt_test::make_context());
  LoadedAsset cpu_asset(cpu_ctx.get(), blob);
  ASSERT_EQ(cpu_asset.result, PRT_OK);
  std::vector<float> reference_rgb(3 * size_t(kVertices));
  ASSERT_EQ(prt_sh_shade(cpu_asset.asset, PRT_BACKEND_CPU, light.data(), 0, kVertices,
                         reference_rgb.data()),
            PRT_OK);
  note("cpu-vs-exact", compare("cpu", t, truth, truth.value, reference_rgb, 0, kVertices));
  const std::vector<double> reference(reference_rgb.begin(), reference_rgb.end());

  // SIMD, once per instruction set.
  for (prt_simd_isa isa : {PRT_SIMD_ISA_SSE41, PRT_SIMD_ISA_AVX2}) {
    const std::string name = std::string("simd/") + prt_simd_isa_name(isa);
    ContextPtr ctx(prt_test::make_context(PRT_BACKEND_AUTO, isa));
    prt_backend_info info = prt::sized<prt_backend_info>();
    ASSERT_EQ(prt_backend_get_info(ctx.get(), PRT_BACKEND_SIMD, &info), PRT_OK);
    if (!info.compiled || !info.usable || info.isa != isa) {
      summary += " [skipped " + name + ": " +
                 (!info.compiled || !info.usable
                      ? std::string(info.note)
                      : "this CPU tops out at " + std::string(prt_simd_isa_name(info.isa))) +
                 "]";
      continue;
    }
    LoadedAsset asset(ctx.get(), blob);
    ASSERT_EQ(asset.result, PRT_OK);
    std::vector<float> rgb(3 * size_t(kVertices));
    const prt_result r =
        prt_sh_shade(asset.asset, PRT_BACKEND_SIMD, light.data(), 0, kVertices, rgb.data());
    ASSERT_EQ(r, PRT_OK) << name << " is compiled in and usable per prt_backend_get_info ("
                         << info.note << ") but prt_sh_shade_on returned " << prt_result_string(r);
    double worst = compare(name.c_str(), t, truth, reference, rgb, 0, kVertices);
    // A range that starts and ends off any vector width.
    std::vector<float> part(3 * 997);
    ASSERT_EQ(prt_sh_shade(asset.asset, PRT_BACKEND_SIMD, light.data(), 1, 997, part.data()),
              PRT_OK);
    worst = std::max(worst, compare(name.c_str(), t, truth, reference, part, 1, 997));
    note(name, worst);
  }

  // GL.
  {
    ContextPtr ctx(prt_test::make_context());
    LoadedAsset asset(ctx.get(), blob);
    ASSERT_EQ(asset.result, PRT_OK);
    prt_gl_sh_shader* raw = nullptr;
    ASSERT_EQ(prt_gl_sh_create(ctx.get(), asset.asset, headless_gl_get_proc, gl.gl, &raw), PRT_OK)
        << prt_context_last_message(ctx.get());
    ShaderPtr shader(raw);
    ASSERT_EQ(prt_gl_sh_shade(raw, light.data(), 0, kVertices), PRT_OK);
    std::vector<float> rgb(3 * size_t(kVertices));
    ASSERT_EQ(prt_gl_sh_read(raw, 0, kVertices, rgb.data()), PRT_OK);
    double worst = compare("gl", t, truth, reference, rgb, 0, kVertices);
    std::vector<float> part(3 * 997);
    ASSERT_EQ(prt_gl_sh_read(raw, 1, 997, part.data()), PRT_OK);
    worst = std::max(worst, compare("gl", t, truth, reference, part, 1, 997));
    note(std::string("gl (") + headless_gl_renderer(gl.gl) + ")", worst);
  }
  std::printf("conformance %s\n", summary.c_str());
  ::testing::Test::RecordProperty("backends", summary);
}

TEST(conformance, Order1Grey8Bit) {
  check_all_backends(1, 1, 8);
}
TEST(conformance, Order2Rgb8Bit) {
  check_all_backends(2, 3, 8);
}
TEST(conformance, Order3Grey16Bit) {
  check_all_backends(3, 1, 16);
}
TEST(conformance, Order6Rgb16Bit) {
  check_all_backends(6, 3, 16);
}
TEST(conformance, Order8Rgb8Bit) {
  check_all_backends(8, 3, 8);
}
TEST(conformance, Order16Grey16Bit) {
  check_all_backends(16, 1, 16);
}
TEST(conformance, Order16Rgb16Bit) {
  check_all_backends(16, 3, 16);
}

// ---- wavelet ------------------------------------------------------------------------------

using prt_test::WaveletShaderPtr;
using prt_test::WvltAsset;
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
  const WvltTransfer t = conformance_transfer(param, size, 500 + size + param);
  const prt_test::Bytes blob = prt_test::wvlt_make_blob(prt_test::wvlt_encode(t), kVertices);
  const std::vector<float> light = sunny_light(t.coefficients(), 31 + size);
  Truth truth;
  for (uint32_t v = 0; v < kVertices; ++v) {
    double value[3], magnitude[3];
    prt_test::wvlt_reference_shade(t, light, v, value, magnitude);
    truth.value.insert(truth.value.end(), value, value + 3);
    truth.magnitude.insert(truth.magnitude.end(), magnitude, magnitude + 3);
  }
  std::string summary = std::string(param == PRT_WAVELET_PARAM_CUBE ? "cube" : "paraboloid") +
                        " S " + std::to_string(size) + ", " + std::to_string(t.pair_count()) +
                        " pairs:";
  auto note = [&summary](const std::string& backend, double worst) {
    char text[96];
    std::snprintf(text, sizeof text, " %s (max err/tol %.3g)", backend.c_str(), worst);
    summary += text;
  };
  const uint32_t part_first = 3, part_count = 997;

  // The scalar reference, checked against the exact sum first; it also prepares the light.
  ContextPtr cpu_ctx(prt_test::make_context());
  WvltAsset cpu_asset(cpu_ctx.get(), blob);
  ASSERT_EQ(cpu_asset.result, PRT_OK) << prt_context_last_message(cpu_ctx.get());
  std::vector<float> prepared(light.size());
  ASSERT_EQ(prt_wavelet_prepare_light(cpu_asset.asset, light.data(), prepared.data(), nullptr),
            PRT_OK);
  std::vector<float> reference_rgb(3 * size_t(kVertices));
  ASSERT_EQ(prt_wavelet_shade(cpu_asset.asset, PRT_BACKEND_CPU, prepared.data(), nullptr, 0,
                              kVertices, reference_rgb.data()),
            PRT_OK);
  note("cpu-vs-exact", compare_wavelet("cpu", t, truth, truth.value, reference_rgb, 0, kVertices));
  const std::vector<double> reference(reference_rgb.begin(), reference_rgb.end());

  // SIMD, once per instruction set.
  for (prt_simd_isa isa : {PRT_SIMD_ISA_SSE41, PRT_SIMD_ISA_AVX2}) {
    const std::string name = std::string("simd/") + prt_simd_isa_name(isa);
    ContextPtr ctx(prt_test::make_context(PRT_BACKEND_AUTO, isa));
    prt_backend_info info = prt::sized<prt_backend_info>();
    ASSERT_EQ(prt_backend_get_info(ctx.get(), PRT_BACKEND_SIMD, &info), PRT_OK);
    if (!info.compiled || !info.usable || info.isa != isa) {
      summary += " [skipped " + name + ": " +
                 (!info.compiled || !info.usable
                      ? std::string(info.note)
                      : "this CPU tops out at " + std::string(prt_simd_isa_name(info.isa))) +
                 "]";
      continue;
    }
    WvltAsset asset(ctx.get(), blob);
    ASSERT_EQ(asset.result, PRT_OK);
    std::vector<float> rgb(3 * size_t(kVertices));
    const prt_result r = prt_wavelet_shade(asset.asset, PRT_BACKEND_SIMD, prepared.data(), nullptr,
                                           0, kVertices, rgb.data());
    ASSERT_EQ(r, PRT_OK) << name << " is compiled in and usable per prt_backend_get_info ("
                         << info.note << ") but prt_wavelet_shade_on returned "
                         << prt_result_string(r);
    double worst = compare_wavelet(name.c_str(), t, truth, reference, rgb, 0, kVertices);
    // A range that starts and ends off any vector width.
    std::vector<float> part(3 * size_t(part_count));
    ASSERT_EQ(prt_wavelet_shade(asset.asset, PRT_BACKEND_SIMD, prepared.data(), nullptr, part_first,
                                part_count, part.data()),
              PRT_OK);
    worst = std::max(
        worst, compare_wavelet(name.c_str(), t, truth, reference, part, part_first, part_count));
    note(name, worst);
  }

  // GL: a sub-range on a fresh shader first, then everything.
  {
    ContextPtr ctx(prt_test::make_context());
    WvltAsset asset(ctx.get(), blob);
    ASSERT_EQ(asset.result, PRT_OK);
    prt_gl_wavelet_shader* raw = nullptr;
    ASSERT_EQ(prt_gl_wavelet_create(ctx.get(), asset.asset, headless_gl_get_proc, gl.gl, &raw),
              PRT_OK)
        << prt_context_last_message(ctx.get());
    WaveletShaderPtr shader(raw);
    std::vector<float> part(3 * size_t(part_count));
    ASSERT_EQ(prt_gl_wavelet_shade(raw, prepared.data(), part_first, part_count), PRT_OK);
    ASSERT_EQ(prt_gl_wavelet_read(raw, part_first, part_count, part.data()), PRT_OK);
    double worst = compare_wavelet("gl", t, truth, reference, part, part_first, part_count);
    ASSERT_EQ(prt_gl_wavelet_shade(raw, prepared.data(), 0, kVertices), PRT_OK);
    std::vector<float> rgb(3 * size_t(kVertices));
    ASSERT_EQ(prt_gl_wavelet_read(raw, 0, kVertices, rgb.data()), PRT_OK);
    worst = std::max(worst, compare_wavelet("gl", t, truth, reference, rgb, 0, kVertices));
    note(std::string("gl (") + headless_gl_renderer(gl.gl) + ")", worst);
  }
  std::printf("conformance wavelet %s\n", summary.c_str());
  ::testing::Test::RecordProperty("backends", summary);
}

TEST(conformance, WaveletCube16) {
  check_wavelet_backends(PRT_WAVELET_PARAM_CUBE, 16);
}
TEST(conformance, WaveletCube64) {
  check_wavelet_backends(PRT_WAVELET_PARAM_CUBE, 64);
}
TEST(conformance, WaveletParaboloid16) {
  check_wavelet_backends(PRT_WAVELET_PARAM_DUAL_PARABOLOID, 16);
}
TEST(conformance, WaveletParaboloid64) {
  check_wavelet_backends(PRT_WAVELET_PARAM_DUAL_PARABOLOID, 64);
}

}  // namespace
