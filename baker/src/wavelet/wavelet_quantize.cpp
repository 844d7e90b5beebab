// SPDX-License-Identifier: MIT
// The two 8-bit quantisers of prt/baker/wavelet/wavelet_blob.hpp.
#include <prt/prt_wavelet.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "prt/baker/wavelet/wavelet_blob.hpp"

namespace prt::bake {
namespace {

std::uint32_t log2_size(std::uint32_t size) {
  std::uint32_t l = 0;
  while ((1u << l) < size) ++l;
  return l;
}

// The band of every coefficient, looked up once instead of per stored pair.
std::vector<std::uint32_t> band_table(const WaveletTransfer& t) {
  std::vector<std::uint32_t> band(t.coefficient_count);
  for (std::uint32_t j = 0; j < t.coefficient_count; ++j)
    band[j] = wavelet_band(t.param, t.size, j);
  return band;
}

// Largest |value| of each band over all vertices, or its `percentile` quantile when < 1.
std::vector<float> band_magnitudes(const WaveletTransfer& t, const std::vector<std::uint32_t>& band,
                                   std::uint32_t bands, double percentile) {
  std::vector<float> largest(bands, 0.0f);
  if (percentile >= 1.0) {
    for (std::size_t p = 0; p < t.index.size(); ++p) {
      float& m = largest[band[t.index[p]]];
      m = std::max(m, std::abs(t.value[p]));
    }
    return largest;
  }
  std::vector<std::vector<float>> values(bands);
  for (std::size_t p = 0; p < t.index.size(); ++p) {
    values[band[t.index[p]]].push_back(std::abs(t.value[p]));
  }
  for (std::uint32_t b = 0; b < bands; ++b) {
    if (values[b].empty()) continue;
    const auto k = static_cast<std::size_t>(percentile * double(values[b].size() - 1));
    std::nth_element(values[b].begin(), values[b].begin() + k, values[b].end());
    largest[b] = values[b][k];
  }
  return largest;
}

float largest_in_row(const WaveletTransfer& t, std::size_t v) {
  float m = 0.0f;
  for (std::uint64_t p = t.row_start[v]; p < t.row_start[v + 1]; ++p) {
    m = std::max(m, std::abs(t.value[p]));
  }
  return m;
}

void measure_error(const WaveletTransfer& t, QuantizedWavelet& out, double sum_sq) {
  const double count = double(t.index.size());
  out.rms_abs_error = count > 0 ? std::sqrt(sum_sq / count) : 0.0;
}

}  // namespace

const char* wavelet_quantizer_name(WaveletQuantizer quantizer) {
  return quantizer == WaveletQuantizer::Vertex ? "vertex" : "band";
}

WaveletQuantizer parse_wavelet_quantizer(const char* name) {
  if (name && std::strcmp(name, "vertex") == 0) return WaveletQuantizer::Vertex;
  if (name && std::strcmp(name, "band") == 0) return WaveletQuantizer::Band;
  throw Error(std::string("wavelet: unknown quantizer '") + (name ? name : "") +
              "' (vertex or band)");
}

std::uint32_t wavelet_band(std::uint32_t param, std::uint32_t size, std::uint32_t j) {
  return prt_wavelet_band(static_cast<prt_wavelet_param>(param), size, j);
}

std::uint32_t wavelet_band_count(std::uint32_t param, std::uint32_t size) {
  return prt_wavelet_face_count(static_cast<prt_wavelet_param>(param)) * (log2_size(size) + 1);
}

QuantizedWavelet quantize_wavelet_transfer(const WaveletTransfer& t, WaveletQuantizer quantizer,
                                           std::uint32_t keep, double band_percentile) {
  if (prt_wavelet_coefficient_count(static_cast<prt_wavelet_param>(t.param), t.size) !=
          t.coefficient_count ||
      t.row_start.size() != t.vertex_count + 1 || t.index.size() != t.value.size() ||
      t.albedo.size() != t.vertex_count) {
    throw Error("wavelet quantisation: inconsistent transfer");
  }
  if (!(band_percentile > 0.0 && band_percentile <= 1.0)) {
    throw Error("wavelet quantisation: band percentile must lie in (0, 1]");
  }
  for (float value : t.value) {
    if (!std::isfinite(value)) throw Error("wavelet quantisation: non-finite coefficient");
  }
  for (std::uint32_t j : t.index) {
    if (j >= t.coefficient_count)
      throw Error("wavelet quantisation: coefficient index out of range");
  }
  const std::vector<std::uint32_t> band = band_table(t);
  QuantizedWavelet out;
  out.param = t.param;
  out.size = t.size;
  out.vertex_count = t.vertex_count;
  out.coefficient_count = t.coefficient_count;
  out.quantizer = quantizer;
  out.keep = keep;
  const std::uint32_t bands = wavelet_band_count(t.param, t.size);
  out.band_scale.assign(bands, 1.0f);
  if (quantizer == WaveletQuantizer::Band) {
    const std::vector<float> m = band_magnitudes(t, band, bands, band_percentile);
    for (std::uint32_t b = 0; b < bands; ++b) out.band_scale[b] = m[b] / 127.0f;
  }
  out.vertex_scale.resize(t.vertex_count * 3);
  out.grey_step.resize(t.vertex_count);
  out.row_start.assign(t.vertex_count + 1, 0);
  double sum_sq = 0.0;
  for (std::size_t v = 0; v < t.vertex_count; ++v) {
    const float grey = quantizer == WaveletQuantizer::Vertex ? largest_in_row(t, v) / 127.0f : 1.0f;
    out.grey_step[v] = grey;
    for (int c = 0; c < 3; ++c) out.vertex_scale[v * 3 + c] = t.albedo[v][c] * grey;
    for (std::uint64_t p = t.row_start[v]; p < t.row_start[v + 1]; ++p) {
      const double step = double(out.band_scale[band[t.index[p]]]) * grey;
      double q = step > 0.0 ? std::round(double(t.value[p]) / step) : 0.0;
      if (std::abs(q) > 127.0) {
        q = std::clamp(q, -127.0, 127.0);
        ++out.clamped;
      }
      const double error = std::abs(q * step - double(t.value[p]));
      out.max_abs_error = std::max(out.max_abs_error, error);
      out.max_abs_value = std::max(out.max_abs_value, std::abs(double(t.value[p])));
      sum_sq += error * error;
      if (q == 0.0) {
        ++out.dropped_to_zero;
        continue;
      }
      out.index.push_back(t.index[p]);
      out.q.push_back(static_cast<std::int8_t>(q));
    }
    out.row_start[v + 1] = static_cast<std::uint32_t>(out.q.size());
  }
  measure_error(t, out, sum_sq);
  return out;
}

WaveletTransfer dequantize_wavelet_transfer(const QuantizedWavelet& quantized,
                                            const WaveletTransfer& transfer) {
  WaveletTransfer out = transfer;
  out.index = quantized.index;
  out.value.resize(quantized.q.size());
  out.row_start.assign(quantized.row_start.begin(), quantized.row_start.end());
  for (std::size_t v = 0; v < quantized.vertex_count; ++v) {
    for (std::uint32_t p = quantized.row_start[v]; p < quantized.row_start[v + 1]; ++p) {
      out.value[p] = static_cast<float>(quantized.grey(v, p));
    }
  }
  return out;
}

}  // namespace prt::bake
