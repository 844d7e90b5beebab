// SPDX-License-Identifier: MIT
#include "prt/baker/shadowfield/shadowfield_blob.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <prt/format/mesh_layout.h>
#include <prt/format/shadowfield_layout.h>
#include <prt/prt.h>
#include <prt/format/blob_writer.hpp>

#include "../common/numbers.hpp"
#include "prt/baker/context.hpp"

namespace prt::bake {
namespace {

using Bytes = std::vector<std::uint8_t>;

void fail_shadowfield_blob(const std::string& what) {
  throw Error("shadowfield blob: " + what);
}

void store_shells(std::uint8_t* p, const prt_sf_shells& s) {
  const float floats[6] = {s.centre[0], s.centre[1], s.centre[2], s.radius, s.inner, s.outer};
  for (int i = 0; i < 6; ++i) {
    std::uint32_t bits;
    std::memcpy(&bits, &floats[i], 4);
    prt_le_store_u32(p + 4 * i, bits);
  }
  prt_le_store_u32(p + PRT_BLOB_SFLD_SHELL_OFF_SHELLS, s.shells);
  prt_le_store_u32(p + PRT_BLOB_SFLD_SHELL_OFF_FACE_SIZE, s.face_size);
}

// The 128-byte header (reserved words zero) into p.
void store_header(std::uint8_t* p, const ShadowfieldObject& o, std::uint32_t bits) {
  const bool glossy = o.material.glossy;
  prt_le_store_u32(p + PRT_BLOB_SFLD_OFF_ORDER, o.order);
  prt_le_store_u32(p + PRT_BLOB_SFLD_OFF_TERMS, o.material.terms());
  prt_le_store_u32(p + PRT_BLOB_SFLD_OFF_GLOSSY, glossy ? 1u : 0u);
  prt_le_store_u32(p + PRT_BLOB_SFLD_OFF_VERTICES, static_cast<std::uint32_t>(o.positions.size()));
  prt_le_store_u32(p + PRT_BLOB_SFLD_OFF_BASIS, o.basis_size);
  prt_le_store_u32(p + PRT_BLOB_SFLD_OFF_BRDF_GRID, glossy ? o.material.brdf.grid.size : 0u);
  prt_le_store_u32(p + PRT_BLOB_SFLD_OFF_BITS, bits);
  store_shells(p + PRT_BLOB_SFLD_OFF_OOF_SHELLS, o.oof_shells);
  store_shells(p + PRT_BLOB_SFLD_OFF_SRF_SHELLS, o.srf_shells);
}

// The header's fields through the formats layer's own check; the layout on success.
prt_blob_sfld_layout checked_layout(const ShadowfieldObject& o, std::uint32_t bits) {
  if (o.positions.empty() || o.positions.size() > 0xffffffffu)
    fail_shadowfield_blob("the vertex count " + std::to_string(o.positions.size()) +
                          " is not in 1..2^32-1");
  std::uint8_t header[PRT_BLOB_SFLD_HEADER_SIZE] = {};
  store_header(header, o, bits);
  prt_blob_sfld_header h;
  prt_blob_sfld_layout layout{};
  prt_blob_sfld_read_header(header, &h);
  if (!prt_blob_sfld_layout_of(&h, &layout)) layout.raw_size = PRT_BLOB_SFLD_HEADER_SIZE;
  char msg[256];
  // Only the header's bytes are read; the size is the one the header implies.
  if (prt_blob_sfld_check_header(header, static_cast<std::size_t>(layout.raw_size), 1,
                                 o.positions.size(), &layout, msg, sizeof msg) != PRT_BLOB_OK)
    fail_shadowfield_blob(msg);
  return layout;
}

void check_size(const char* what, std::size_t size, std::uint64_t expected) {
  if (size != expected)
    fail_shadowfield_blob(std::string(what) + " has " + std::to_string(size) +
                          " values, the object needs " + std::to_string(expected));
}

void check_sizes(const ShadowfieldObject& o, const prt_blob_sfld_layout& l) {
  const std::uint64_t v = l.vertices;
  check_size("normals", o.normals.size(), v);
  check_size("albedo", o.albedo.size(), v);
  if (o.indices.size() % 3 != 0) fail_shadowfield_blob("the index count is not a multiple of 3");
  if (o.material.glossy) check_size("the g table", o.material.brdf.outgoing.size(), l.g_values);
  check_size("transfer", o.transfer.size(), l.transfer.count);
  check_size("oof", o.oof.size(), l.oof.count);
  check_size("basis", o.basis.size(), l.basis.count);
  check_size("vertex_weights", o.vertex_weights.size(), v);
  check_size("basis_inverse", o.basis_inverse.size(), std::uint64_t(l.basis_size) * l.basis_size);
  check_size("srf", o.srf.size(), l.srf.count);
}

void check_all_finite(const char* what, const std::vector<float>& values) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      fail_shadowfield_blob(std::string(what) + " value " + std::to_string(i) + " is not finite");
}

void check_values(const ShadowfieldObject& o) {
  const std::size_t v = o.positions.size();
  for (std::size_t i = 0; i < v; ++i) {
    if (!finite(o.positions[i]) || !finite(o.normals[i]))
      fail_shadowfield_blob("the position or normal of vertex " + std::to_string(i) +
                            " is not finite");
    const glm::vec3& a = o.albedo[i];
    if (!(std::min({a.x, a.y, a.z}) >= 0.0f && std::max({a.x, a.y, a.z}) <= 1.0f))
      fail_shadowfield_blob("the albedo of vertex " + std::to_string(i) + " is not in [0, 1]");
    if (!(o.vertex_weights[i] >= 0.0f) || !std::isfinite(o.vertex_weights[i]))
      fail_shadowfield_blob("the weight of vertex " + std::to_string(i) +
                            " is not finite and >= 0");
  }
  for (std::uint32_t index : o.indices)
    if (index >= v)
      fail_shadowfield_blob("index " + std::to_string(index) + " is not below the vertex count");
  if (o.material.glossy)
    for (double g : o.material.brdf.outgoing)
      if (!std::isfinite(static_cast<float>(g)))
        fail_shadowfield_blob("a g table value is not a finite f32");
  check_all_finite("transfer", o.transfer);
  check_all_finite("oof", o.oof);
  check_all_finite("basis", o.basis);
  check_all_finite("basis_inverse", o.basis_inverse);
  check_all_finite("srf", o.srf);
}

// Values [groups][repeat][width], value (g, m, c) in row g width + c (SPEC §7.5's rows).
struct Rows {
  std::uint64_t groups, repeat, width;
  std::uint64_t row(std::uint64_t index) const {
    return index / (repeat * width) * width + index % width;
  }
};

void measure(const std::vector<float>& values, const Rows& rows, QuantizedShadowfieldBlock& b) {
  for (std::size_t x = 0; x < values.size(); ++x) {
    const std::uint64_t r = rows.row(x);
    const float decoded = b.offsets[r] + b.scales[r] * static_cast<float>(b.q[x]);
    b.max_abs_error = std::max(b.max_abs_error, std::abs(double(decoded) - values[x]));
    b.max_abs_value = std::max(b.max_abs_value, std::abs(double(values[x])));
  }
}

QuantizedShadowfieldBlock quantize_block(const std::vector<float>& values, const Rows& rows,
                                         double levels) {
  const std::size_t row_count = rows.groups * rows.width;
  QuantizedShadowfieldBlock b;
  std::vector<float> lo(row_count, std::numeric_limits<float>::infinity());
  std::vector<float> hi(row_count, -std::numeric_limits<float>::infinity());
  for (std::size_t x = 0; x < values.size(); ++x) {
    const std::uint64_t r = rows.row(x);
    lo[r] = std::min(lo[r], values[x]);
    hi[r] = std::max(hi[r], values[x]);
  }
  b.offsets.assign(row_count, 0.0f);
  b.scales.assign(row_count, 0.0f);
  for (std::size_t r = 0; r < row_count; ++r) {
    if (!(lo[r] <= hi[r])) continue;  // a row without values (a grid of no points)
    b.offsets[r] = lo[r];
    b.scales[r] = hi[r] > lo[r] ? float((double(hi[r]) - double(lo[r])) / levels) : 0.0f;
  }
  b.q.assign(values.size(), 0);
  for (std::size_t x = 0; x < values.size(); ++x) {
    const std::uint64_t r = rows.row(x);
    if (b.scales[r] == 0.0f) continue;
    const double q = std::round((double(values[x]) - double(b.offsets[r])) / b.scales[r]);
    b.q[x] = static_cast<std::uint16_t>(std::clamp(q, 0.0, levels));
  }
  measure(values, rows, b);
  return b;
}

void store_f32s(std::uint8_t* p, const float* values, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t bits;
    std::memcpy(&bits, &values[i], 4);
    prt_le_store_u32(p + 4 * i, bits);
  }
}

void store_block(std::uint8_t* p, const prt_blob_sfld_block& at, std::uint32_t bits,
                 const QuantizedShadowfieldBlock& b) {
  if (b.offsets.size() != at.rows || b.q.size() != at.count)
    fail_shadowfield_blob("the quantised object does not match the object's sizes");
  for (std::size_t r = 0; r < at.rows; ++r) {
    store_f32s(p + at.params + 8 * r, &b.offsets[r], 1);
    store_f32s(p + at.params + 8 * r + 4, &b.scales[r], 1);
  }
  std::uint8_t* values = p + at.values;
  for (std::size_t x = 0; x < at.count; ++x) {
    if (bits == 8)
      values[x] = static_cast<std::uint8_t>(b.q[x]);
    else
      prt_le_store_u16(values + 2 * x, b.q[x]);
  }
}

void store_vec3s(std::uint8_t* p, const std::vector<glm::vec3>& v) {
  for (std::size_t i = 0; i < v.size(); ++i) store_f32s(p + 12 * i, &v[i].x, 3);
}

}  // namespace

void check_shadowfield_object(const ShadowfieldObject& object) {
  const prt_blob_sfld_layout layout = checked_layout(object, 16);
  check_sizes(object, layout);
  check_values(object);
}

QuantizedShadowfield quantize_shadowfield(const ShadowfieldObject& o, int bits) {
  if (bits != 8 && bits != 16) fail_shadowfield_blob("bits must be 8 or 16");
  check_shadowfield_object(o);
  const prt_blob_sfld_layout l = checked_layout(o, static_cast<std::uint32_t>(bits));
  const double levels = std::ldexp(1.0, bits) - 1.0;
  const std::uint64_t v = l.vertices, n2 = l.coefficients, k = l.terms, n = l.basis_size;
  QuantizedShadowfield out;
  out.bits = static_cast<std::uint32_t>(bits);
  out.transfer = quantize_block(o.transfer, {1, v, k * n2}, levels);
  out.oof = quantize_block(o.oof, {1, l.oof_points, n2}, levels);
  out.basis = quantize_block(o.basis, {n, v, 1}, levels);
  out.srf = quantize_block(o.srf, {n * k, l.srf_points, n2}, levels);
  return out;
}

std::vector<std::uint8_t> encode_sfld_section(const ShadowfieldObject& o,
                                              const QuantizedShadowfield& quantized) {
  const prt_blob_sfld_layout l = checked_layout(o, quantized.bits);
  check_sizes(o, l);
  Bytes bytes(static_cast<std::size_t>(l.raw_size), 0);
  std::uint8_t* p = bytes.data();
  store_header(p, o, quantized.bits);
  store_vec3s(p + l.albedo, o.albedo);
  if (o.material.glossy) {
    const std::vector<float> g(o.material.brdf.outgoing.begin(), o.material.brdf.outgoing.end());
    store_f32s(p + l.g_table, g.data(), g.size());
  }
  store_block(p, l.transfer, quantized.bits, quantized.transfer);
  store_block(p, l.oof, quantized.bits, quantized.oof);
  store_block(p, l.basis, quantized.bits, quantized.basis);
  store_f32s(p + l.vertex_weights, o.vertex_weights.data(), o.vertex_weights.size());
  store_f32s(p + l.basis_inverse, o.basis_inverse.data(), o.basis_inverse.size());
  store_block(p, l.srf, quantized.bits, quantized.srf);
  return bytes;
}

std::vector<std::uint8_t> build_shadowfield_blob(const ShadowfieldObject& o,
                                                 const QuantizedShadowfield& quantized,
                                                 const std::string& info) {
  check_shadowfield_object(o);
  const Bytes sfld = encode_sfld_section(o, quantized);
  const std::size_t vertices = o.positions.size();
  Bytes positions(12 * vertices), normals(12 * vertices), indices(4 * o.indices.size());
  store_vec3s(positions.data(), o.positions);
  store_vec3s(normals.data(), o.normals);
  for (std::size_t i = 0; i < o.indices.size(); ++i)
    prt_le_store_u32(&indices[4 * i], o.indices[i]);
  prt::format::SectionOptions required;
  required.compression = prt::format::Compression::kZstd;
  required.required = true;
  prt::format::BlobWriter w;
  w.set_producer("prtkit " PRT_VERSION_STRING);
  if (!info.empty()) w.add_section(PRT_BLOB_TAG_INFO, info.data(), info.size(), info.size());
  w.add_section(PRT_BLOB_TAG_VPOS, positions.data(), positions.size(), vertices, required);
  w.add_section(PRT_BLOB_TAG_VNRM, normals.data(), normals.size(), vertices, required);
  w.add_section(PRT_BLOB_TAG_TRIS, indices.data(), indices.size(), o.indices.size() / 3, required);
  w.add_section(PRT_BLOB_TAG_SFLD, sfld.data(), sfld.size(), 1, required);
  return w.finish();
}

}  // namespace prt::bake
