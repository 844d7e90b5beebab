// SPDX-License-Identifier: MIT
// Quantisation of an SH transfer and the `sh` blob (sections INFO, VPOS, VNRM, TRIS, SHTR; the
// SHTR layout is formats/SPEC.md's "sh" section).
//
// Quantisation is min/max per (channel, coefficient) over all vertices: offset = min,
// scale = (max - min) / (2^bits - 1), q = round((t - min) / scale), rounded half away from zero
// and clamped to [0, 2^bits - 1]; a constant coefficient gets scale 0 and q = 0, so it is exact.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/scene.hpp"
#include "prt/baker/sh/sh_transfer.hpp"

namespace prt::bake {

struct QuantizedShTransfer {
  std::uint32_t order = 0;
  std::uint32_t channels = 3;  // the transfer's R, G, B (the layout also allows 1)
  std::uint32_t bits = 16;     // 8 or 16
  ShTransferKind kind = ShTransferKind::Shadowed;
  std::uint32_t bounces = 0;  // informational
  std::size_t vertex_count = 0;
  // channels * order^2 each, index c * order^2 + k.
  std::vector<float> offsets;
  std::vector<float> scales;
  // vertex_count * channels * order^2, index (v * channels + c) * order^2 + k.
  std::vector<std::uint16_t> q;
  // Error of offset + scale * q against the float transfer (dequantised in float, as a reader
  // does), over every value.
  double max_abs_error = 0.0;
  double rms_abs_error = 0.0;
  double max_abs_value = 0.0;  // max |t|, the scale the errors can be read against

  std::size_t coefficient_count() const { return static_cast<std::size_t>(order) * order; }
  float dequantized(std::size_t vertex, std::uint32_t channel, std::size_t k) const {
    const std::size_t i = channel * coefficient_count() + k;
    return offsets[i] + scales[i] * static_cast<float>(
                                        q[(vertex * channels + channel) * coefficient_count() + k]);
  }
};

// Quantises all three channels of `transfer` to `bits` (8 or 16; Error otherwise). `bounces` is
// stored as given (informational).
QuantizedShTransfer quantize_sh_transfer(const ShTransfer& transfer, int bits, int bounces = 0);

// The raw bytes of the SHTR section (little-endian, zero-padded to a multiple of 4).
std::vector<std::uint8_t> encode_shtr_section(const QuantizedShTransfer& quantized);

// The complete blob: INFO (`info`, skipped when empty), VPOS, VNRM, TRIS (world space, vertices
// in Scene order, indices offset per mesh) and SHTR; zstd where it makes a section smaller.
// Producer "prtkit <version>". The same inputs give the same bytes. Throws Error when the
// transfer's vertex count is not the scene's.
std::vector<std::uint8_t> build_sh_blob(const Scene& scene, const QuantizedShTransfer& quantized,
                                        const std::string& info);

// The baker's self-check: `blob` loaded through the runtime at full validation and its transfer
// decoded (prt_sh_decode_transfer) must match the float `transfer` within the quantisation
// budget, |decoded - t| <= scale/2 per value plus float rounding.
struct ShBlobCheck {
  bool passed = false;
  std::string message;            // what failed, or a summary
  double max_abs_error = 0.0;     // max |decoded - t|
  double max_budget_ratio = 0.0;  // max |decoded - t| / allowed, <= 1 when passed
};
ShBlobCheck check_sh_blob(const std::vector<std::uint8_t>& blob, const ShTransfer& transfer,
                          const QuantizedShTransfer& quantized);

struct ShBakeReport {
  std::string scene;
  std::size_t vertices = 0, triangles = 0;
  ShTransferSettings settings;
  int bits = 16;
  unsigned threads = 1;
  const ShTransfer* transfer = nullptr;  // seconds, rays traced, vertices without normal
  const QuantizedShTransfer* quantized = nullptr;
  std::string output;
  std::size_t blob_bytes = 0;
  ShBlobCheck check;
};
// Writes the bake report as JSON; throws Error when the file cannot be written.
void write_sh_bake_report(const std::string& path, const ShBakeReport& report);

}  // namespace prt::bake
