// SPDX-License-Identifier: MIT
// The `wavelet` bake's self-check through the runtime, and its JSON report.
#include <prt/prt.h>
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <random>

#include <nlohmann/json.hpp>

#include "prt/baker/wavelet/wavelet_blob.hpp"

#include "../common/technique_blob.hpp"

namespace prt::bake {
namespace {

constexpr double kEps = std::numeric_limits<float>::epsilon();

bool header_matches(const prt_wavelet_info& info, const QuantizedWavelet& q) {
  return info.param == q.param && info.size == q.size &&
         info.faces == prt_wavelet_face_count(static_cast<prt_wavelet_param>(q.param)) &&
         info.coefficient_count == q.coefficient_count && info.block_count == q.block_count() &&
         info.vertex_count == q.vertex_count &&
         info.quantizer == static_cast<std::uint32_t>(q.quantizer) && info.keep == q.keep &&
         info.bounces == q.bounces && info.pair_count == q.pair_count();
}

// Every (V / 64)-th vertex (every vertex of a mesh below 128) and the one with the most pairs,
// each once, ascending.
std::vector<std::size_t> sample_vertices(const QuantizedWavelet& q) {
  std::vector<std::size_t> out;
  if (q.vertex_count == 0) return out;
  const std::size_t step = std::max<std::size_t>(1, q.vertex_count / 64);
  for (std::size_t v = 0; v < q.vertex_count; v += step) out.push_back(v);
  std::size_t fullest = 0;
  for (std::size_t v = 0; v < q.vertex_count; ++v) {
    if (q.row_start[v + 1] - q.row_start[v] > q.row_start[fullest + 1] - q.row_start[fullest])
      fullest = v;
  }
  const auto at = std::lower_bound(out.begin(), out.end(), fullest);
  if (at == out.end() || *at != fullest) out.insert(at, fullest);
  return out;
}

// Decoded row v against the quantised pairs (as a reader computes them: 2 ulps) and the float
// row (half a step plus rounding). Returns the failures.
std::size_t check_row(const std::vector<float>& decoded, std::size_t v, const WaveletTransfer& t,
                      const QuantizedWavelet& q, WaveletBlobCheck& check) {
  std::size_t failures = 0;
  std::vector<float> expected(decoded.size(), 0.0f);
  for (std::uint32_t p = q.row_start[v]; p < q.row_start[v + 1]; ++p) {
    for (int c = 0; c < 3; ++c) expected[std::size_t(q.index[p]) * 3 + c] = q.dequantized(v, c, p);
  }
  for (std::size_t i = 0; i < decoded.size(); ++i) {
    if (!(std::abs(double(decoded[i]) - expected[i]) <= 2.0 * kEps * std::abs(expected[i]))) {
      ++failures;
    }
  }
  for (std::uint64_t p = t.row_start[v]; p < t.row_start[v + 1]; ++p) {
    const double step =
        double(q.band_scale[wavelet_band(q.param, q.size, t.index[p])]) * q.grey_step[v];
    if (std::abs(double(t.value[p])) > 127.5 * step) continue;  // clamped (percentile scale)
    for (int c = 0; c < 3; ++c) {
      const double rho = t.albedo[v][c], exact = rho * t.value[p];
      const double allowed = rho * step / 2.0 + 4.0 * kEps * (std::abs(exact) + rho * step) + 1e-30;
      const double error = std::abs(decoded[std::size_t(t.index[p]) * 3 + c] - exact);
      check.max_decode_budget_ratio = std::max(check.max_decode_budget_ratio, error / allowed);
      if (!(error <= allowed)) ++failures;
    }
  }
  return failures;
}

// prt_wavelet_shade of a random light against a double dot product over the stored pairs.
std::string check_shading(const prt_asset* asset, const prt_context* context,
                          const QuantizedWavelet& q, std::uint32_t seed, WaveletBlobCheck& check) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<float> light(std::size_t(q.coefficient_count) * 4, 0.0f);
  for (std::size_t j = 0; j < q.coefficient_count; ++j) {
    for (int c = 0; c < 3; ++c) light[j * 4 + c] = uniform(random);
  }
  std::vector<float> prepared(light.size());
  prt_result r = prt_wavelet_prepare_light(asset, light.data(), prepared.data(), nullptr);
  if (r != PRT_OK) return runtime_failure("prt_wavelet_prepare_light", r, context);
  std::vector<float> shaded(q.vertex_count * 3);
  r = prt_wavelet_shade(asset, PRT_BACKEND_CPU, prepared.data(), nullptr, 0,
                        static_cast<std::uint32_t>(q.vertex_count), shaded.data());
  if (r != PRT_OK) return runtime_failure("prt_wavelet_shade", r, context);
  std::size_t failures = 0;
  for (std::size_t v = 0; v < q.vertex_count; ++v) {
    const double pairs = q.row_start[v + 1] - q.row_start[v];
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0, magnitude = 0.0;
      for (std::uint32_t p = q.row_start[v]; p < q.row_start[v + 1]; ++p) {
        const double term = double(q.q[p]) *
                            q.band_scale[wavelet_band(q.param, q.size, q.index[p])] *
                            q.vertex_scale[v * 3 + c] * light[std::size_t(q.index[p]) * 4 + c];
        sum += term;
        magnitude += std::abs(term);
      }
      const double error = std::abs(shaded[v * 3 + c] - sum);
      const double allowed = 2.0 * (pairs + 8.0) * kEps * magnitude + 1e-30;
      check.max_shade_relative_error =
          std::max(check.max_shade_relative_error, magnitude > 0 ? error / magnitude : error);
      if (!(error <= allowed)) ++failures;
    }
  }
  return failures ? std::to_string(failures) + " shaded values differ from the double product"
                  : std::string();
}

}  // namespace

WaveletBlobCheck check_wavelet_blob(const std::vector<std::uint8_t>& blob,
                                    const WaveletTransfer& transfer,
                                    const QuantizedWavelet& quantized, std::uint32_t seed) {
  WaveletBlobCheck check;
  prt_context* raw_context = nullptr;
  // The check shades on the scalar backend; a context without SIMD also skips the SIMD
  // kernels' load-time repack of the rows, which it would not use.
  prt_context_desc desc = prt::sized<prt_context_desc>();
  desc.backend_limit = PRT_BACKEND_CPU;
  if (prt_context_create(&desc, &raw_context) != PRT_OK) {
    check.message = "cannot create a runtime context";
    return check;
  }
  const RuntimeContextPtr context(raw_context);
  prt_asset* raw_asset = nullptr;
  prt_result r =
      prt_asset_load_memory(raw_context, blob.data(), blob.size(), PRT_VALIDATE_FULL, &raw_asset);
  if (r != PRT_OK) {
    check.message = runtime_failure("prt_asset_load_memory (full validation)", r, raw_context);
    return check;
  }
  const RuntimeAssetPtr asset(raw_asset);
  prt_wavelet_info info = prt::sized<prt_wavelet_info>();
  r = prt_wavelet_get_info(raw_asset, &info);
  if (r != PRT_OK) {
    check.message = runtime_failure("prt_wavelet_get_info", r, raw_context);
    return check;
  }
  if (!header_matches(info, quantized) || transfer.vertex_count != quantized.vertex_count) {
    check.message = "the blob's WVLT header does not match the bake";
    return check;
  }
  std::vector<float> decoded(std::size_t(quantized.coefficient_count) * 3);
  std::size_t failures = 0;
  for (std::size_t v : sample_vertices(quantized)) {
    r = prt_wavelet_decode_transfer(raw_asset, static_cast<std::uint32_t>(v), 1, decoded.data());
    if (r != PRT_OK) {
      check.message = runtime_failure("prt_wavelet_decode_transfer", r, raw_context);
      return check;
    }
    failures += check_row(decoded, v, transfer, quantized, check);
    ++check.rows_checked;
  }
  if (failures) {
    check.message = std::to_string(failures) + " decoded values differ from the quantised rows";
    return check;
  }
  check.message = check_shading(raw_asset, raw_context, quantized, seed, check);
  check.passed = check.message.empty();
  if (check.passed) {
    check.message = std::to_string(check.rows_checked) +
                    " decoded rows match the quantised ones; runtime shading matches a double "
                    "product on every vertex";
  }
  return check;
}

void write_wavelet_bake_report(const std::string& path, const WaveletBakeReport& report) {
  const WaveletTransferSettings& s = report.settings;
  const WaveletTransfer& t = *report.transfer;
  const QuantizedWavelet& q = *report.quantized;
  std::size_t baked = 0;
  for (unsigned char b : t.baked) baked += b;
  const double per_vertex = q.vertex_count ? 1.0 / double(q.vertex_count) : 0.0;
  nlohmann::json json = {
      {"command", "bake"},
      {"technique", "wavelet"},
      {"scene",
       {{"file", report.scene},
        {"vertices", report.vertices},
        {"triangles", report.triangles},
        {"vertices_baked", baked},
        {"vertices_without_normal", t.vertices_without_normal}}},
      {"settings",
       {{"param", wavelet_param_name(s.param)},
        {"size", s.size},
        {"coefficients", t.coefficient_count},
        {"samples_per_texel", s.samples},
        {"keep", s.keep},
        {"keep_energy", s.keep_energy},
        {"bounces", s.bounces},
        {"quantizer", wavelet_quantizer_name(q.quantizer)},
        {"seed", s.seed},
        {"threads", report.threads},
        {"vertex_stride", s.vertex_stride}}},
      {"bake",
       {{"seconds", t.seconds},
        {"rays", t.rays_traced},
        {"rays_per_second", t.seconds > 0 ? double(t.rays_traced) / t.seconds : 0.0},
        {"mean_nonzeros_before_truncation", t.mean_nonzeros_before},
        {"mean_energy_kept", t.mean_energy_kept}}},
      {"blob",
       {{"file", report.output},
        {"bytes", report.blob_bytes},
        {"bytes_per_vertex", double(report.blob_bytes) * per_vertex},
        {"pairs", q.pair_count()},
        {"nonzeros_per_vertex", double(q.pair_count()) * per_vertex}}},
      {"quantization",
       {{"quantizer", wavelet_quantizer_name(q.quantizer)},
        {"max_abs_error", q.max_abs_error},
        {"rms_abs_error", q.rms_abs_error},
        {"max_abs_value", q.max_abs_value},
        {"rms_error_relative", q.max_abs_value > 0 ? q.rms_abs_error / q.max_abs_value : 0.0},
        {"dropped_to_zero", q.dropped_to_zero}}},
      {"self_check",
       {{"passed", report.check.passed},
        {"message", report.check.message},
        {"rows_checked", report.check.rows_checked},
        {"max_decode_budget_ratio", report.check.max_decode_budget_ratio},
        {"max_shade_relative_error", report.check.max_shade_relative_error}}},
  };
  if (s.override_albedo) json["settings"]["albedo"] = {s.albedo.r, s.albedo.g, s.albedo.b};
  std::ofstream file(path);
  if (!file || !(file << json.dump(2) << '\n')) throw Error(path + ": cannot write the report");
}

}  // namespace prt::bake
