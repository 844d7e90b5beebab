// SPDX-License-Identifier: MIT
#include "prt/baker/sh/sh_blob.hpp"

#include "../common/technique_blob.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>

#include <nlohmann/json.hpp>

#include <prt/prt.h>
#include <prt/format/blob_writer.hpp>

namespace prt::bake {
namespace {

constexpr std::size_t kShtrHeaderBytes = 32;
constexpr std::uint32_t kShtrTag = prt::format::make_tag('S', 'H', 'T', 'R');

std::uint32_t kind_code(ShTransferKind kind) {
  switch (kind) {
    case ShTransferKind::Unshadowed:
      return 0;
    case ShTransferKind::Shadowed:
      return 1;
    case ShTransferKind::Interreflected:
      return 2;
  }
  return 1;
}

void store_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

void store_f32(std::uint8_t* p, float v) {
  std::uint32_t bits;
  std::memcpy(&bits, &v, 4);
  store_u32(p, bits);
}

// Min/max quantisation of one (channel, coefficient) column; fills offset, scale and q.
void quantize_column(const ShTransfer& transfer, int channel, std::size_t k, double levels,
                     QuantizedShTransfer& out) {
  const std::size_t n2 = transfer.coefficient_count();
  float lo = std::numeric_limits<float>::infinity();
  float hi = -lo;
  for (std::size_t v = 0; v < transfer.vertex_count; ++v) {
    const float t = transfer.vertex_channel(v, channel)[k];
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  if (transfer.vertex_count == 0) lo = hi = 0.0f;
  const std::size_t column = static_cast<std::size_t>(channel) * n2 + k;
  const float scale = hi > lo ? static_cast<float>((double(hi) - double(lo)) / levels) : 0.0f;
  out.offsets[column] = lo;
  out.scales[column] = scale;
  for (std::size_t v = 0; v < transfer.vertex_count; ++v) {
    double q = 0.0;
    if (scale > 0.0f) {
      q = std::round((double(transfer.vertex_channel(v, channel)[k]) - double(lo)) / scale);
      q = std::clamp(q, 0.0, levels);
    }
    out.q[(v * 3 + static_cast<std::size_t>(channel)) * n2 + k] = static_cast<std::uint16_t>(q);
  }
}

void measure_error(const ShTransfer& transfer, QuantizedShTransfer& out) {
  const std::size_t n2 = transfer.coefficient_count();
  double sum_sq = 0.0;
  for (std::size_t v = 0; v < transfer.vertex_count; ++v) {
    for (std::uint32_t c = 0; c < 3; ++c) {
      for (std::size_t k = 0; k < n2; ++k) {
        const double t = transfer.vertex_channel(v, static_cast<int>(c))[k];
        const double e = std::abs(double(out.dequantized(v, c, k)) - t);
        out.max_abs_error = std::max(out.max_abs_error, e);
        out.max_abs_value = std::max(out.max_abs_value, std::abs(t));
        sum_sq += e * e;
      }
    }
  }
  const double count = double(transfer.vertex_count) * 3.0 * double(n2);
  out.rms_abs_error = count > 0 ? std::sqrt(sum_sq / count) : 0.0;
}

// Compares the decoded transfer with the float one value by value.
void compare_decoded(const std::vector<float>& decoded, const ShTransfer& transfer,
                     const QuantizedShTransfer& quantized, ShBlobCheck& check) {
  const std::size_t n2 = quantized.coefficient_count();
  const double levels = std::ldexp(1.0, static_cast<int>(quantized.bits)) - 1.0;
  std::size_t failures = 0;
  for (std::size_t v = 0; v < quantized.vertex_count; ++v) {
    for (std::uint32_t c = 0; c < quantized.channels; ++c) {
      for (std::size_t k = 0; k < n2; ++k) {
        const std::size_t column = c * n2 + k;
        const double offset = quantized.offsets[column], scale = quantized.scales[column];
        // Half a step, plus float rounding of offset + scale * q at the column's magnitude.
        const double allowed =
            0.5 * scale +
            4.0 * std::numeric_limits<float>::epsilon() * (std::abs(offset) + scale * levels) +
            1e-30;
        const double t = transfer.vertex_channel(v, static_cast<int>(c))[k];
        const double error = std::abs(double(decoded[(v * quantized.channels + c) * n2 + k]) - t);
        check.max_abs_error = std::max(check.max_abs_error, error);
        check.max_budget_ratio = std::max(check.max_budget_ratio, error / allowed);
        if (!(error <= allowed)) ++failures;
      }
    }
  }
  check.passed = failures == 0;
  check.message =
      check.passed ? "decoded transfer within the quantisation budget"
                   : std::to_string(failures) + " decoded values outside the quantisation budget";
}

}  // namespace

ShBlobCheck check_sh_blob(const std::vector<std::uint8_t>& blob, const ShTransfer& transfer,
                          const QuantizedShTransfer& quantized) {
  ShBlobCheck check;
  const SelfCheckAsset loaded = load_for_self_check(blob);
  if (!loaded.asset) {
    check.message = loaded.failure;
    return check;
  }
  prt_context* raw_context = loaded.context.get();
  const RuntimeAssetPtr& asset = loaded.asset;
  prt_sh_info info = prt::sized<prt_sh_info>();
  prt_result result = prt_sh_get_info(asset.get(), &info);
  if (result != PRT_OK) {
    check.message = runtime_failure("prt_sh_get_info", result, raw_context);
    return check;
  }
  if (info.order != quantized.order || info.vertex_count != quantized.vertex_count ||
      info.channels != quantized.channels || info.bits != quantized.bits ||
      info.kind != kind_code(quantized.kind) || info.bounces != quantized.bounces ||
      transfer.vertex_count != quantized.vertex_count || transfer.order != quantized.order) {
    check.message = "the blob's SHTR header does not match the bake";
    return check;
  }
  std::vector<float> decoded(quantized.vertex_count * quantized.channels *
                             quantized.coefficient_count());
  result = prt_sh_decode_transfer(asset.get(), 0, info.vertex_count, decoded.data());
  if (result != PRT_OK) {
    check.message = runtime_failure("prt_sh_decode_transfer", result, raw_context);
    return check;
  }
  compare_decoded(decoded, transfer, quantized, check);
  return check;
}

void write_sh_bake_report(const std::string& path, const ShBakeReport& report) {
  const ShTransferSettings& s = report.settings;
  const ShTransfer& t = *report.transfer;
  const QuantizedShTransfer& q = *report.quantized;
  const double rays_per_second = t.seconds > 0.0 ? double(t.rays_traced) / t.seconds : 0.0;
  nlohmann::json json = {
      {"command", "bake"},
      {"technique", "sh"},
      {"scene",
       {{"file", report.scene},
        {"vertices", report.vertices},
        {"triangles", report.triangles},
        {"vertices_without_normal", t.vertices_without_normal}}},
      {"settings",
       {{"order", s.order},
        {"transfer", sh_transfer_kind_name(s.kind)},
        {"rays", s.rays},
        {"bounces", s.kind == ShTransferKind::Interreflected ? s.bounces : 0},
        {"seed", s.seed},
        {"bits", report.bits},
        {"threads", report.threads}}},
      {"bake",
       {{"seconds", t.seconds}, {"rays", t.rays_traced}, {"rays_per_second", rays_per_second}}},
      {"blob", {{"file", report.output}, {"bytes", report.blob_bytes}}},
      {"quantization",
       {{"bits", q.bits},
        {"max_abs_error", q.max_abs_error},
        {"rms_abs_error", q.rms_abs_error},
        {"max_abs_value", q.max_abs_value},
        {"max_error_relative", q.max_abs_value > 0 ? q.max_abs_error / q.max_abs_value : 0.0},
        {"rms_error_relative", q.max_abs_value > 0 ? q.rms_abs_error / q.max_abs_value : 0.0}}},
      {"self_check",
       {{"passed", report.check.passed},
        {"message", report.check.message},
        {"max_abs_error", report.check.max_abs_error},
        {"max_budget_ratio", report.check.max_budget_ratio}}},
  };
  if (s.override_albedo) json["settings"]["albedo"] = {s.albedo.r, s.albedo.g, s.albedo.b};
  std::ofstream file(path);
  if (!file || !(file << json.dump(2) << '\n')) throw Error(path + ": cannot write the report");
}

QuantizedShTransfer quantize_sh_transfer(const ShTransfer& transfer, int bits, int bounces) {
  if (bits != 8 && bits != 16) throw Error("SH quantisation: bits must be 8 or 16");
  if (transfer.order < 1 || transfer.order > 16) throw Error("SH quantisation: order not 1..16");
  const std::size_t n2 = transfer.coefficient_count();
  if (transfer.coefficients.size() != transfer.vertex_count * 3 * n2) {
    throw Error("SH quantisation: coefficient count does not match vertex count and order");
  }
  for (float t : transfer.coefficients) {
    if (!std::isfinite(t)) throw Error("SH quantisation: non-finite transfer coefficient");
  }
  QuantizedShTransfer out;
  out.order = transfer.order;
  out.channels = 3;
  out.bits = static_cast<std::uint32_t>(bits);
  out.kind = transfer.kind;
  out.bounces = static_cast<std::uint32_t>(std::max(bounces, 0));
  out.vertex_count = transfer.vertex_count;
  out.offsets.assign(3 * n2, 0.0f);
  out.scales.assign(3 * n2, 0.0f);
  out.q.assign(transfer.vertex_count * 3 * n2, 0);
  const double levels = std::ldexp(1.0, bits) - 1.0;
  for (int c = 0; c < 3; ++c) {
    for (std::size_t k = 0; k < n2; ++k) quantize_column(transfer, c, k, levels, out);
  }
  measure_error(transfer, out);
  return out;
}

std::vector<std::uint8_t> encode_shtr_section(const QuantizedShTransfer& quantized) {
  const std::size_t columns = quantized.channels * quantized.coefficient_count();
  const std::size_t value_bytes = quantized.bits / 8;
  const std::size_t table_bytes = 8 * columns;
  std::size_t size = kShtrHeaderBytes + table_bytes + quantized.q.size() * value_bytes;
  size = (size + 3) / 4 * 4;
  std::vector<std::uint8_t> bytes(size, 0);
  std::uint8_t* p = bytes.data();
  const std::uint32_t header[8] = {quantized.order,
                                   static_cast<std::uint32_t>(quantized.vertex_count),
                                   quantized.channels,
                                   quantized.bits,
                                   kind_code(quantized.kind),
                                   quantized.bounces,
                                   0,
                                   0};
  for (int i = 0; i < 8; ++i) store_u32(p + 4 * i, header[i]);
  p += kShtrHeaderBytes;
  for (std::size_t i = 0; i < columns; ++i, p += 8) {
    store_f32(p, quantized.offsets[i]);
    store_f32(p + 4, quantized.scales[i]);
  }
  for (std::uint16_t q : quantized.q) {
    *p++ = static_cast<std::uint8_t>(q);
    if (value_bytes == 2) *p++ = static_cast<std::uint8_t>(q >> 8);
  }
  return bytes;
}

std::vector<std::uint8_t> build_sh_blob(const Scene& scene, const QuantizedShTransfer& quantized,
                                        const std::string& info) {
  if (scene.vertex_count() != quantized.vertex_count) {
    throw Error("SH blob: the transfer has " + std::to_string(quantized.vertex_count) +
                " vertices, the scene " + std::to_string(scene.vertex_count()));
  }
  prt::format::BlobWriter writer = start_technique_blob(scene, info);
  const std::vector<std::uint8_t> shtr = encode_shtr_section(quantized);
  writer.add_section(kShtrTag, shtr.data(), shtr.size(), scene.vertex_count(), required_section());
  return writer.finish();
}

}  // namespace prt::bake
