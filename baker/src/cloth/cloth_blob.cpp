// SPDX-License-Identifier: MIT
// The CLTH section bytes (formats/SPEC.md §7.4, formats/include/prt/format/cloth_layout.h), the
// description back from them, and a whole cloth blob.
#include "prt/baker/cloth/cloth_blob.hpp"

#include <prt/format/blob_reader.h>
#include <prt/format/cloth_layout.h>
#include <prt/prt_version.h>
#include <prt/format/blob_writer.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace prt::bake {
namespace {

using Bytes = std::vector<std::uint8_t>;

[[noreturn]] void fail_cloth_blob(const std::string& what) {
  throw std::invalid_argument("CLTH: " + what);
}

void put_u32(Bytes& b, std::uint64_t at, std::uint32_t v) {
  prt_le_store_u32(b.data() + at, v);
}

void put_f32(Bytes& b, std::uint64_t at, float v) {
  std::uint32_t bits;
  std::memcpy(&bits, &v, 4);
  put_u32(b, at, bits);
}

std::uint32_t tangent_record_count(const ClothSection& s) {
  std::size_t count = 0;
  for (const ClothFabric& f : s.fabrics) count += f.threads[0].size() + f.threads[1].size();
  return std::uint32_t(std::min<std::size_t>(count, UINT32_MAX));
}

prt_blob_clth_header header_of(const ClothSection& s, int bits) {
  prt_blob_clth_header h{};
  h.fabrics = std::uint32_t(s.fabrics.size());
  h.tangents = tangent_record_count(s);
  h.tables = std::uint32_t(s.tables.size());
  h.xi_size = s.grid.xi_size;
  h.levels = s.grid.lambda_levels;
  h.lambda_min = s.grid.lambda_min;
  h.lambda_max = s.grid.lambda_max;
  h.view_theta = s.grid.view_theta;
  h.view_phi = s.grid.view_phi;
  h.bits = std::uint32_t(bits);
  return h;
}

void check_factor(const ClothFactor& f, const ClothGrid& g, const std::string& where) {
  if (f.rank < 1 || f.rank > PRT_BLOB_CLTH_MAX_RANK)
    fail_cloth_blob(where + ": rank " + std::to_string(f.rank) + " (must be 1..64)");
  if (f.u.size() != g.rows() * f.rank || f.v.size() != g.columns() * f.rank)
    fail_cloth_blob(where + ": U holds " + std::to_string(f.u.size()) + " values and V " +
                    std::to_string(f.v.size()) + " for rank " + std::to_string(f.rank) + ", " +
                    std::to_string(g.rows()) + " rows and " + std::to_string(g.columns()) +
                    " columns");
  const auto finite = [](float x) { return std::isfinite(x); };
  if (!std::all_of(f.u.begin(), f.u.end(), finite) || !std::all_of(f.v.begin(), f.v.end(), finite))
    fail_cloth_blob(where + ": a factor value is not finite");
}

// What the encoder needs before it can index anything: the counts, sizes and names; the
// remaining rules of SPEC §7.4 are the formats checker's, run on the bytes afterwards.
prt_blob_clth_layout check_shape(const ClothSection& s, int bits) {
  if (bits != 8 && bits != 16) fail_cloth_blob(std::to_string(bits) + " bits (must be 8 or 16)");
  if (s.fabrics.empty() || s.fabrics.size() > PRT_BLOB_CLTH_MAX_FABRICS)
    fail_cloth_blob(std::to_string(s.fabrics.size()) + " fabrics (must be 1..64)");
  if (s.tables.empty() || s.tables.size() > PRT_BLOB_CLTH_MAX_TABLES)
    fail_cloth_blob(std::to_string(s.tables.size()) + " tables (must be 1..1024)");
  for (std::size_t i = 0; i < s.fabrics.size(); ++i) {
    const ClothFabric& f = s.fabrics[i];
    if (f.name.empty() || f.name.size() > PRT_BLOB_CLTH_NAME_SIZE ||
        f.name.find('\0') != std::string::npos)
      fail_cloth_blob("fabric " + std::to_string(i) + ": a name of " +
                      std::to_string(f.name.size()) + " bytes (must be 1..32 bytes without NUL)");
    for (const auto& thread : f.threads)
      if (thread.empty() || thread.size() > PRT_BLOB_CLTH_MAX_THREAD_TANGENTS)
        fail_cloth_blob("fabric " + std::to_string(i) + " has a thread of " +
                        std::to_string(thread.size()) + " offsets (must be 1..16)");
  }
  if (tangent_record_count(s) > PRT_BLOB_CLTH_MAX_TANGENTS)
    fail_cloth_blob(std::to_string(tangent_record_count(s)) +
                    " tangent records (must be at most 1024)");
  const prt_blob_clth_header h = header_of(s, bits);
  prt_blob_clth_layout layout{};
  if (!prt_blob_clth_layout_of(&h, &layout))
    fail_cloth_blob("grid out of range (N_xi, N_theta, N_phi 2..256, levels 1..64)");
  for (std::size_t q = 0; q < s.tables.size(); ++q) {
    check_factor(s.tables[q].full, s.grid, "table " + std::to_string(q) + " T");
    check_factor(s.tables[q].cone, s.grid, "table " + std::to_string(q) + " T_c");
  }
  return layout;
}

void write_header(Bytes& b, const prt_blob_clth_header& h) {
  put_u32(b, PRT_BLOB_CLTH_OFF_FABRICS, h.fabrics);
  put_u32(b, PRT_BLOB_CLTH_OFF_TANGENTS, h.tangents);
  put_u32(b, PRT_BLOB_CLTH_OFF_TABLES, h.tables);
  put_u32(b, PRT_BLOB_CLTH_OFF_XI_SIZE, h.xi_size);
  put_u32(b, PRT_BLOB_CLTH_OFF_LEVELS, h.levels);
  put_f32(b, PRT_BLOB_CLTH_OFF_LAMBDA_MIN, h.lambda_min);
  put_f32(b, PRT_BLOB_CLTH_OFF_LAMBDA_MAX, h.lambda_max);
  put_u32(b, PRT_BLOB_CLTH_OFF_VIEW_THETA, h.view_theta);
  put_u32(b, PRT_BLOB_CLTH_OFF_VIEW_PHI, h.view_phi);
  put_u32(b, PRT_BLOB_CLTH_OFF_BITS, h.bits);
  put_u32(b, PRT_BLOB_CLTH_OFF_FLAGS, 0);
}

void write_thread(Bytes& b, std::uint64_t at, const prt_cloth_thread& t, std::uint32_t first,
                  std::uint32_t count) {
  put_f32(b, at + PRT_BLOB_CLTH_THREAD_OFF_ETA, t.eta);
  for (int c = 0; c < 3; ++c) put_f32(b, at + PRT_BLOB_CLTH_THREAD_OFF_ALBEDO + 4 * c, t.albedo[c]);
  put_f32(b, at + PRT_BLOB_CLTH_THREAD_OFF_KD, t.kd);
  put_f32(b, at + PRT_BLOB_CLTH_THREAD_OFF_GAMMA_S, t.gamma_s);
  put_f32(b, at + PRT_BLOB_CLTH_THREAD_OFF_GAMMA_V, t.gamma_v);
  put_f32(b, at + PRT_BLOB_CLTH_THREAD_OFF_COVERAGE, t.coverage);
  put_u32(b, at + PRT_BLOB_CLTH_THREAD_OFF_FIRST, first);
  put_u32(b, at + PRT_BLOB_CLTH_THREAD_OFF_COUNT, count);
}

// The fabric and tangent records: each thread's offsets as one range, in fabric order.
void write_fabrics(Bytes& b, const ClothSection& s, const prt_blob_clth_layout& l) {
  std::uint32_t next = 0;
  for (std::size_t f = 0; f < s.fabrics.size(); ++f) {
    const ClothFabric& fabric = s.fabrics[f];
    const std::uint64_t at = l.fabrics + std::uint64_t(PRT_BLOB_CLTH_FABRIC_SIZE) * f;
    std::memcpy(b.data() + at + PRT_BLOB_CLTH_FABRIC_OFF_NAME, fabric.name.data(),
                fabric.name.size());
    for (std::uint32_t j = 0; j < 2; ++j) {
      const auto& tangents = fabric.threads[j];
      write_thread(b, at + PRT_BLOB_CLTH_FABRIC_OFF_THREADS + PRT_BLOB_CLTH_THREAD_SIZE * j,
                   fabric.params.threads[j], next, std::uint32_t(tangents.size()));
      for (const ClothTangent& t : tangents) {
        const std::uint64_t r = l.tangents + std::uint64_t(PRT_BLOB_CLTH_TANGENT_SIZE) * next++;
        put_f32(b, r + PRT_BLOB_CLTH_TANGENT_OFF_OFFSET, t.offset);
        put_u32(b, r + PRT_BLOB_CLTH_TANGENT_OFF_MULTIPLICITY, t.multiplicity);
        put_u32(b, r + PRT_BLOB_CLTH_TANGENT_OFF_TABLE, t.table);
        put_u32(b, r + PRT_BLOB_CLTH_TANGENT_OFF_MIRROR, t.mirror ? 1u : 0u);
      }
    }
  }
}

// Quantises column r of the row-major n x rank `values` into the value block at `block` (value
// r of row i at index i rank + r) and returns the column's scale.
float quantise_column(const std::vector<float>& values, std::uint32_t rank, std::uint32_t r,
                      int bits, std::uint8_t* block) {
  const double qmax = bits == 8 ? 127.0 : 32767.0;
  const std::size_t n = values.size() / rank;
  double largest = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    largest = std::max(largest, std::fabs(double(values[i * rank + r])));
  const float scale = float(largest / qmax);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t index = i * rank + r;
    // A scale that underflows f32 leaves the column 0 (its values are below f32's range anyway).
    const double q =
        scale > 0.0f ? std::clamp(std::round(double(values[index]) / scale), -qmax, qmax) : 0.0;
    if (bits == 8)
      block[index] = std::uint8_t(std::int8_t(q));
    else
      prt_le_store_u16(block + 2 * index, std::uint16_t(std::int16_t(q)));
  }
  return scale;
}

// One factorisation at `at`: the scales, then V's and U's values (the padding stays zero).
void write_factor(Bytes& b, std::uint64_t at, const ClothFactor& f, const prt_blob_clth_layout& l,
                  int bits) {
  const std::uint64_t v_values = at + 8u * f.rank;
  const std::uint64_t v_bytes = l.columns * f.rank * l.value_size;
  const std::uint64_t u_values = v_values + ((v_bytes + 3u) & ~std::uint64_t(3));
  for (std::uint32_t r = 0; r < f.rank; ++r) {
    put_f32(b, at + 4u * r, quantise_column(f.u, f.rank, r, bits, b.data() + u_values));
    put_f32(b, at + 4u * (f.rank + r), quantise_column(f.v, f.rank, r, bits, b.data() + v_values));
  }
}

std::uint64_t section_size(const ClothSection& s, const prt_blob_clth_layout& l) {
  std::uint64_t size = l.data;
  for (const ClothTable& t : s.tables)
    size += prt_blob_clth_factor_size(&l, t.full.rank) + prt_blob_clth_factor_size(&l, t.cone.rank);
  return size;
}

// The formats layer's full-validation check of the section's bytes; throws with its message.
void check_bytes(const std::uint8_t* bytes, std::size_t size) {
  prt_blob_section s{};
  s.tag = PRT_BLOB_TAG_CLTH;
  s.layout_version = PRT_BLOB_LAYOUT_VERSION_1;
  s.raw_size = size;
  s.element_count = size >= 4 ? prt_le_load_u32(bytes + PRT_BLOB_CLTH_OFF_FABRICS) : 0;
  char message[256] = "";
  if (prt_blob_check_content(&s, bytes, 0, message, sizeof message) != PRT_BLOB_OK)
    throw std::invalid_argument(message);
}

}  // namespace

std::vector<std::uint8_t> encode_clth_section(const ClothSection& section, int bits) {
  const prt_blob_clth_layout layout = check_shape(section, bits);
  Bytes bytes(section_size(section, layout), 0);
  write_header(bytes, header_of(section, bits));
  write_fabrics(bytes, section, layout);
  std::uint64_t at = layout.data;
  for (std::size_t q = 0; q < section.tables.size(); ++q) {
    const ClothTable& table = section.tables[q];
    const std::uint64_t record = layout.tables + std::uint64_t(PRT_BLOB_CLTH_TABLE_SIZE) * q;
    put_u32(bytes, record + PRT_BLOB_CLTH_TABLE_OFF_RANK, table.full.rank);
    put_u32(bytes, record + PRT_BLOB_CLTH_TABLE_OFF_CONE_RANK, table.cone.rank);
    for (const ClothFactor* f : {&table.full, &table.cone}) {
      write_factor(bytes, at, *f, layout, bits);
      at += prt_blob_clth_factor_size(&layout, f->rank);
    }
  }
  check_bytes(bytes.data(), bytes.size());
  return bytes;
}

namespace {

float get_f32(const std::uint8_t* p) {
  const std::uint32_t bits = prt_le_load_u32(p);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

prt_cloth_thread read_thread(const std::uint8_t* t) {
  prt_cloth_thread thread{};
  thread.eta = get_f32(t + PRT_BLOB_CLTH_THREAD_OFF_ETA);
  for (int c = 0; c < 3; ++c)
    thread.albedo[c] = get_f32(t + PRT_BLOB_CLTH_THREAD_OFF_ALBEDO + 4 * c);
  thread.kd = get_f32(t + PRT_BLOB_CLTH_THREAD_OFF_KD);
  thread.gamma_s = get_f32(t + PRT_BLOB_CLTH_THREAD_OFF_GAMMA_S);
  thread.gamma_v = get_f32(t + PRT_BLOB_CLTH_THREAD_OFF_GAMMA_V);
  thread.coverage = get_f32(t + PRT_BLOB_CLTH_THREAD_OFF_COVERAGE);
  return thread;
}

ClothTangent read_tangent(const std::uint8_t* t) {
  ClothTangent tangent;
  tangent.offset = get_f32(t + PRT_BLOB_CLTH_TANGENT_OFF_OFFSET);
  tangent.multiplicity = prt_le_load_u32(t + PRT_BLOB_CLTH_TANGENT_OFF_MULTIPLICITY);
  tangent.table = prt_le_load_u32(t + PRT_BLOB_CLTH_TANGENT_OFF_TABLE);
  tangent.mirror = prt_le_load_u32(t + PRT_BLOB_CLTH_TANGENT_OFF_MIRROR) != 0;
  return tangent;
}

ClothFabric read_fabric(const std::uint8_t* p, const prt_blob_clth_layout& l, std::uint32_t f) {
  const std::uint8_t* record = p + l.fabrics + std::uint64_t(PRT_BLOB_CLTH_FABRIC_SIZE) * f;
  const char* name = reinterpret_cast<const char*>(record + PRT_BLOB_CLTH_FABRIC_OFF_NAME);
  ClothFabric fabric;
  fabric.name.assign(name, std::find(name, name + PRT_BLOB_CLTH_NAME_SIZE, '\0'));
  fabric.params.struct_size = sizeof fabric.params;
  for (std::uint32_t j = 0; j < 2; ++j) {
    const std::uint8_t* t =
        record + PRT_BLOB_CLTH_FABRIC_OFF_THREADS + PRT_BLOB_CLTH_THREAD_SIZE * j;
    const std::uint32_t first = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_FIRST);
    const std::uint32_t count = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_COUNT);
    fabric.params.threads[j] = read_thread(t);
    for (std::uint32_t k = 0; k < count; ++k)
      fabric.threads[j].push_back(
          read_tangent(p + l.tangents + std::uint64_t(PRT_BLOB_CLTH_TANGENT_SIZE) * (first + k)));
  }
  return fabric;
}

// The n x rank values of the block at `block`, value r of each row times scales[r].
std::vector<float> dequantise(const std::uint8_t* block, const std::uint8_t* scales,
                              std::uint64_t n, std::uint32_t rank, std::uint32_t value_size) {
  std::vector<float> out(n * rank);
  for (std::uint64_t i = 0; i < n; ++i)
    for (std::uint32_t r = 0; r < rank; ++r) {
      const std::uint64_t index = i * rank + r;
      const int q = value_size == 1 ? int(std::int8_t(block[index]))
                                    : int(std::int16_t(prt_le_load_u16(block + 2 * index)));
      out[index] = float(double(get_f32(scales + 4u * r)) * q);
    }
  return out;
}

ClothFactor read_factor(const std::uint8_t* p, std::uint64_t at, std::uint32_t rank,
                        const prt_blob_clth_layout& l) {
  const std::uint64_t v_values = at + 8u * rank;
  const std::uint64_t v_bytes = l.columns * rank * l.value_size;
  const std::uint64_t u_values = v_values + ((v_bytes + 3u) & ~std::uint64_t(3));
  ClothFactor f;
  f.rank = rank;
  f.u = dequantise(p + u_values, p + at, l.rows, rank, l.value_size);
  f.v = dequantise(p + v_values, p + at + 4u * rank, l.columns, rank, l.value_size);
  return f;
}

void check_mesh(const ClothMesh& m) {
  const std::size_t floats = m.positions.size();
  const auto fail_mesh = [](const std::string& what) {
    throw std::invalid_argument("cloth mesh: " + what);
  };
  if (floats == 0 || floats % 3 != 0) fail_mesh("positions are not x, y, z of one vertex or more");
  if (!m.normals.empty() && m.normals.size() != floats) fail_mesh("not one normal per vertex");
  if (!m.tangents.empty() && m.tangents.size() != floats) fail_mesh("not one tangent per vertex");
  if (m.triangles.size() % 3 != 0) fail_mesh("triangle indices are not a multiple of 3");
  const auto finite = [](float x) { return std::isfinite(x); };
  for (const auto* v : {&m.positions, &m.normals, &m.tangents})
    if (!std::all_of(v->begin(), v->end(), finite)) fail_mesh("a float is not finite");
  for (std::uint32_t i : m.triangles)
    if (i >= floats / 3) fail_mesh("index " + std::to_string(i) + " is not below the vertex count");
}

void add_mesh(prt::format::BlobWriter& w, const ClothMesh& m) {
  prt::format::SectionOptions optional, required;
  optional.compression = prt::format::Compression::kZstd;
  required = optional;
  required.required = true;
  const std::size_t vertices = m.positions.size() / 3;
  // The floats and indices are stored as in memory: the baker builds on little-endian hosts only.
  w.add_section(PRT_BLOB_TAG_VPOS, m.positions.data(), m.positions.size() * 4, vertices, required);
  if (!m.normals.empty())
    w.add_section(PRT_BLOB_TAG_VNRM, m.normals.data(), m.normals.size() * 4, vertices, optional);
  if (!m.tangents.empty())
    w.add_section(PRT_BLOB_TAG_VTAN, m.tangents.data(), m.tangents.size() * 4, vertices, optional);
  w.add_section(PRT_BLOB_TAG_TRIS, m.triangles.data(), m.triangles.size() * 4,
                m.triangles.size() / 3, required);
}

}  // namespace

DecodedClothSection decode_clth_section(const std::uint8_t* bytes, std::size_t size) {
  check_bytes(bytes, size);
  prt_blob_clth_header h{};
  prt_blob_clth_layout l{};
  prt_blob_clth_read_header(bytes, &h);
  prt_blob_clth_layout_of(&h, &l);  // valid: checked
  DecodedClothSection out;
  out.bits = int(h.bits);
  out.section.grid = {h.xi_size, h.levels, h.lambda_min, h.lambda_max, h.view_theta, h.view_phi};
  for (std::uint32_t f = 0; f < h.fabrics; ++f)
    out.section.fabrics.push_back(read_fabric(bytes, l, f));
  std::uint64_t at = l.data;
  for (std::uint32_t q = 0; q < h.tables; ++q) {
    const std::uint8_t* record = bytes + l.tables + std::uint64_t(PRT_BLOB_CLTH_TABLE_SIZE) * q;
    ClothTable table;
    table.full = read_factor(bytes, at, prt_le_load_u32(record + PRT_BLOB_CLTH_TABLE_OFF_RANK), l);
    at += prt_blob_clth_factor_size(&l, table.full.rank);
    table.cone =
        read_factor(bytes, at, prt_le_load_u32(record + PRT_BLOB_CLTH_TABLE_OFF_CONE_RANK), l);
    at += prt_blob_clth_factor_size(&l, table.cone.rank);
    out.section.tables.push_back(std::move(table));
  }
  return out;
}

std::vector<std::uint8_t> write_cloth_blob(const ClothSection& section, int bits,
                                           const ClothMesh* mesh, const std::string& info) {
  if (mesh) check_mesh(*mesh);
  const Bytes clth = encode_clth_section(section, bits);
  prt::format::BlobWriter w;
  w.set_producer("prtkit " PRT_VERSION_STRING);
  if (!info.empty()) w.add_section(PRT_BLOB_TAG_INFO, info.data(), info.size(), info.size());
  if (mesh) add_mesh(w, *mesh);
  prt::format::SectionOptions required;
  required.compression = prt::format::Compression::kZstd;
  required.required = true;
  w.add_section(PRT_BLOB_TAG_CLTH, clth.data(), clth.size(), section.fabrics.size(), required);
  return w.finish();
}

}  // namespace prt::bake
