// SPDX-License-Identifier: MIT
// 8-bit quantisation of a sparse wavelet transfer and the `wavelet` blob (sections INFO, VPOS,
// VNRM, TRIS, WVLT; formats/SPEC.md §7.2).
//
// Both quantisers keep zero exactly (a coefficient that rounds to 0 is dropped) and round half
// away from zero into -127..127, the SPEC's writers' rules:
//   vertex (0, the implementation report's scheme): band scales 1, vertex scale rho_c * m_v/127
//          with m_v the vertex's largest kept |coefficient|;
//   band   (1): band scale m_b/127 with m_b the largest kept |coefficient| of band b (face x
//          wavelet level) over all vertices, vertex scale rho_c.
// Band is the command's default because it measures the smaller error (docs/wavelet/trade.md
// compares the two).
// `band_percentile` < 1 (measurement only) puts m_b at that quantile of |coefficient| in the band
// instead of its maximum, clamping larger values to +-127: that breaks the SPEC's writers' rule
// (m_b = the maximum), so the prt-bake command does not offer it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/scene.hpp"
#include "prt/baker/wavelet/wavelet_transfer.hpp"

namespace prt::bake {

enum class WaveletQuantizer : std::uint32_t { Vertex = 0, Band = 1 };
// "vertex" | "band"; parse throws Error on anything else.
const char* wavelet_quantizer_name(WaveletQuantizer quantizer);
WaveletQuantizer parse_wavelet_quantizer(const char* name);

// The band of coefficient j (§7.2): face * (log2 S + 1) + Haar level + 1 (prt_wavelet_band).
std::uint32_t wavelet_band(std::uint32_t param, std::uint32_t size, std::uint32_t j);
std::uint32_t wavelet_band_count(std::uint32_t param, std::uint32_t size);

struct QuantizedWavelet {
  std::uint32_t param = 0, size = 0;
  std::size_t vertex_count = 0;
  std::uint32_t coefficient_count = 0;
  WaveletQuantizer quantizer = WaveletQuantizer::Band;
  std::uint32_t keep = 0, bounces = 0;   // informational
  std::vector<float> band_scale;         // F * (log2 S + 1)
  std::vector<float> vertex_scale;       // V * 3
  std::vector<float> grey_step;          // V: vs without the albedo (m_v/127, or 1 for band)
  std::vector<std::uint32_t> row_start;  // V + 1, into index / q
  std::vector<std::uint32_t> index;      // global coefficient j, ascending per row
  std::vector<std::int8_t> q;            // never 0 or -128
  // Error of q * step against the float (grey, kept) coefficients, and against their largest.
  double max_abs_error = 0.0, rms_abs_error = 0.0, max_abs_value = 0.0;
  std::size_t dropped_to_zero = 0;  // kept coefficients that quantised to 0
  std::size_t clamped = 0;          // coefficients beyond the scale (band_percentile < 1 only)

  std::size_t pair_count() const { return q.size(); }
  std::uint32_t block_count() const { return coefficient_count / 256; }
  // t[v][c][j] of §7.2 for stored pair p of vertex v, computed as a reader does.
  float dequantized(std::size_t v, int c, std::size_t p) const {
    return float(q[p]) * band_scale[wavelet_band(param, size, index[p])] * vertex_scale[v * 3 + c];
  }
  // The grey value of pair p of vertex v: q * bs * grey_step.
  double grey(std::size_t v, std::size_t p) const {
    return double(q[p]) * band_scale[wavelet_band(param, size, index[p])] * grey_step[v];
  }
};

QuantizedWavelet quantize_wavelet_transfer(const WaveletTransfer& transfer,
                                           WaveletQuantizer quantizer, std::uint32_t keep,
                                           double band_percentile = 1.0);

// The float transfer rebuilt from the quantised one (grey rows = q * step), to measure what
// the quantisation costs with shade_wavelet_transfer.
WaveletTransfer dequantize_wavelet_transfer(const QuantizedWavelet& quantized,
                                            const WaveletTransfer& transfer);

// The raw bytes of the WVLT section (little-endian, zero-padded to a multiple of 4).
std::vector<std::uint8_t> encode_wvlt_section(const QuantizedWavelet& quantized);

// The complete blob: INFO (skipped when empty), VPOS, VNRM, TRIS and WVLT, zstd where it helps.
// The same inputs give the same bytes. Throws Error when the vertex count is not the scene's.
std::vector<std::uint8_t> build_wavelet_blob(const Scene& scene, const QuantizedWavelet& quantized,
                                             const std::string& info);

// The baker's self-check: the blob loaded through the runtime at full validation; its header
// as baked; prt_wavelet_decode_transfer of sample vertices equal to the quantised rows and within
// half a step of the float ones; prt_wavelet_shade of a random light equal to a double dot product.
struct WaveletBlobCheck {
  bool passed = false;
  std::string message;
  std::size_t rows_checked = 0;
  double max_decode_budget_ratio = 0.0;  // max |decoded - rho t| / (rho step / 2 + rounding)
  double max_shade_relative_error = 0.0;
};
WaveletBlobCheck check_wavelet_blob(const std::vector<std::uint8_t>& blob,
                                    const WaveletTransfer& transfer,
                                    const QuantizedWavelet& quantized, std::uint32_t seed = 1);

struct WaveletBakeReport {
  std::string scene, output;
  std::size_t vertices = 0, triangles = 0;
  WaveletTransferSettings settings;
  unsigned threads = 1;
  const WaveletTransfer* transfer = nullptr;
  const QuantizedWavelet* quantized = nullptr;
  std::size_t blob_bytes = 0;
  WaveletBlobCheck check;
};
// Writes the bake report as JSON; throws Error when the file cannot be written.
void write_wavelet_bake_report(const std::string& path, const WaveletBakeReport& report);

}  // namespace prt::bake
