// SPDX-License-Identifier: MIT
// The baker's CLTH encoder (prt/baker/cloth/cloth_blob.hpp): it writes the bytes of the section
// built by hand from SPEC §7.4 (cloth/clth_test_section.hpp) when the values quantise exactly,
// round-trips any values within half a quantisation step, is deterministic, sizes the section as
// the layout header says, refuses what breaks the spec, and writes whole blobs the runtime loads.
#include <gtest/gtest.h>

#include <prt/format/cloth_layout.h>
#include <prt/baker/cloth/cloth_blob.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include "cloth/clth_test_section.hpp"
#include "support/mesh_blob.hpp"

namespace {

using namespace prt_test;
using prt::bake::ClothFabric;
using prt::bake::ClothFactor;
using prt::bake::ClothSection;
using prt::bake::ClothTangent;

int stored_value(const Bytes& b, size_t at, size_t k, uint32_t bits) {
  return bits == 8 ? int(int8_t(b[at + k])) : int(int16_t(prt_le_load_u16(b.data() + at + 2 * k)));
}

void set_stored_value(Bytes& b, size_t at, size_t k, uint32_t bits, int q) {
  if (bits == 8)
    b[at + k] = uint8_t(int8_t(q));
  else
    put_u16(b, at + 2 * k, uint16_t(int16_t(q)));
}

ClothFabric fabric_of(const ClthTestSection& h, size_t f) {
  ClothFabric fabric;
  fabric.name = h.fabrics[f].name;
  fabric.params.struct_size = sizeof fabric.params;
  for (size_t j = 0; j < 2; ++j) {
    const ClthThread& t = h.fabrics[f].threads[j];
    prt_cloth_thread& p = fabric.params.threads[j];
    p = {t.eta, {t.albedo[0], t.albedo[1], t.albedo[2]}, t.kd, t.gamma_s, t.gamma_v, t.coverage};
    for (uint32_t k = 0; k < t.count; ++k) {
      const ClthTangent& g = h.tangents[t.first + k];
      fabric.threads[j].push_back({g.offset, g.multiplicity, g.table, g.mirror != 0});
    }
  }
  return fabric;
}

// The hand-built section with one range of records per thread (as the encoder writes them),
// power-of-two scales and every column's first value at +qmax, and the description whose values
// are exactly scale x q: quantising it must give back exactly these bytes.
struct ExactCase {
  Bytes bytes;
  ClothSection section;
};

ExactCase exact_case(uint32_t bits) {
  ClthTestSection h = small_clth(bits);
  h.tangents.push_back(h.tangents[0]);
  h.tangents.push_back(h.tangents[0]);
  h.fabrics[1].threads[0].first = 3;
  h.fabrics[1].threads[1].first = 4;
  ExactCase c{h.bytes(), {}};
  c.section.grid = {h.xi_size, h.levels, h.lambda_min, h.lambda_max, h.view_theta, h.view_phi};
  for (size_t f = 0; f < h.fabrics.size(); ++f) c.section.fabrics.push_back(fabric_of(h, f));
  const int qmax = bits == 8 ? 127 : 32767;
  for (size_t q = 0; q < h.tables.size(); ++q) {
    prt::bake::ClothTable table;
    for (int cone = 0; cone < 2; ++cone) {
      const uint32_t rank = h.rank_of(q, cone);
      ClothFactor& f = cone ? table.cone : table.full;
      f.rank = rank;
      f.u.resize(h.rows() * rank);
      f.v.resize(h.columns() * rank);
      for (uint32_t r = 0; r < rank; ++r) {
        const float su = std::ldexp(1.0f, -int(r + q + 1)),
                    sv = std::ldexp(1.0f, -int(r + cone + 3));
        put_f32_at(c.bytes, h.factor_at(q, cone) + 4 * r, su);
        put_f32_at(c.bytes, h.factor_at(q, cone) + 4 * (rank + r), sv);
        set_stored_value(c.bytes, h.u_values_at(q, cone), r, bits, qmax);
        set_stored_value(c.bytes, h.v_values_at(q, cone), r, bits, qmax);
        for (size_t i = 0; i < h.rows(); ++i)
          f.u[i * rank + r] =
              su * float(stored_value(c.bytes, h.u_values_at(q, cone), i * rank + r, bits));
        for (size_t i = 0; i < h.columns(); ++i)
          f.v[i * rank + r] =
              sv * float(stored_value(c.bytes, h.v_values_at(q, cone), i * rank + r, bits));
      }
    }
    c.section.tables.push_back(table);
  }
  return c;
}

TEST(ClothBlob, EncodesTheSectionBuiltByHand) {
  for (uint32_t bits : {8u, 16u}) {
    const ExactCase c = exact_case(bits);
    const Bytes encoded = prt::bake::encode_clth_section(c.section, int(bits));
    ASSERT_EQ(encoded.size(), c.bytes.size()) << bits;
    for (size_t i = 0; i < encoded.size(); ++i)
      ASSERT_EQ(encoded[i], c.bytes[i]) << bits << " bits, byte " << i;
  }
}

// A description with random factors: a zero column, a column of one tiny value, ranks 1..64.
ClothSection random_section(uint32_t seed) {
  const ClthTestSection h = small_clth();
  ClothSection s;
  s.grid = {4, 3, 0.5f, 200.0f, 5, 7};
  s.fabrics = {fabric_of(h, 0), fabric_of(h, 1)};
  s.fabrics[1].threads[0][0].table = 2;
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  const uint32_t ranks[3][2] = {{1, 2}, {5, 3}, {64, 1}};
  for (const auto& rank : ranks) {
    prt::bake::ClothTable table;
    for (int cone = 0; cone < 2; ++cone) {
      ClothFactor& f = cone ? table.cone : table.full;
      f.rank = rank[cone];
      f.u.resize(s.grid.rows() * f.rank);
      f.v.resize(s.grid.columns() * f.rank);
      for (float& x : f.u) x = normal(rng) * 3.0f;
      for (float& x : f.v) x = normal(rng) * 0.01f;
    }
    s.tables.push_back(table);
  }
  for (size_t i = 0; i < s.grid.rows(); ++i) s.tables[1].full.u[i * 5 + 2] = 0.0f;
  for (size_t i = 0; i < s.grid.columns(); ++i) s.tables[1].cone.v[i * 3 + 1] = 0.0f;
  s.tables[1].cone.v[3 * 4 + 1] = -1e-30f;
  return s;
}

// |x - decoded| <= half the column's step, step = max |column| / qmax: the rounding's bound, with
// the step stored as f32 (relative 2^-24) and the decoded value rounded once to f32.
double worst_step_fraction(const ClothFactor& in, const ClothFactor& out, uint32_t bits,
                           const std::string& what) {
  const double qmax = bits == 8 ? 127.0 : 32767.0;
  double worst = 0.0;
  EXPECT_EQ(out.rank, in.rank) << what;
  for (const auto& [x, y] : {std::pair{&in.u, &out.u}, std::pair{&in.v, &out.v}}) {
    EXPECT_EQ(x->size(), y->size()) << what;
    for (uint32_t r = 0; r < in.rank; ++r) {
      double largest = 0.0;
      for (size_t i = r; i < x->size(); i += in.rank)
        largest = std::max(largest, std::fabs(double((*x)[i])));
      const double step = largest / qmax;
      for (size_t i = r; i < x->size(); i += in.rank) {
        const double error = std::fabs(double((*x)[i]) - double((*y)[i]));
        EXPECT_LE(error, 0.5 * step * (1.0 + 0x1p-23) + std::fabs((*x)[i]) * 0x1p-24)
            << what << " column " << r << " value " << i;
        if (step > 0.0) {
          worst = std::max(worst, error / step);
        } else {
          EXPECT_EQ((*y)[i], 0.0f) << what;
        }
      }
    }
  }
  return worst;
}

TEST(ClothBlob, RoundTripsWithinHalfAStep) {
  for (uint32_t bits : {8u, 16u}) {
    const ClothSection in = random_section(7);
    const Bytes bytes = prt::bake::encode_clth_section(in, int(bits));
    const auto out = prt::bake::decode_clth_section(bytes.data(), bytes.size());
    EXPECT_EQ(out.bits, int(bits));
    EXPECT_EQ(std::memcmp(&out.section.grid, &in.grid, sizeof in.grid), 0);
    ASSERT_EQ(out.section.fabrics.size(), in.fabrics.size());
    for (size_t f = 0; f < in.fabrics.size(); ++f) {
      const ClothFabric &a = in.fabrics[f], &b = out.section.fabrics[f];
      EXPECT_EQ(b.name, a.name);
      EXPECT_EQ(std::memcmp(&b.params, &a.params, sizeof a.params), 0) << f;
      for (int j = 0; j < 2; ++j) {
        ASSERT_EQ(b.threads[j].size(), a.threads[j].size());
        for (size_t k = 0; k < a.threads[j].size(); ++k) {
          EXPECT_EQ(b.threads[j][k].offset, a.threads[j][k].offset);
          EXPECT_EQ(b.threads[j][k].multiplicity, a.threads[j][k].multiplicity);
          EXPECT_EQ(b.threads[j][k].table, a.threads[j][k].table);
          EXPECT_EQ(b.threads[j][k].mirror, a.threads[j][k].mirror);
        }
      }
    }
    ASSERT_EQ(out.section.tables.size(), in.tables.size());
    double worst = 0.0;
    for (size_t q = 0; q < in.tables.size(); ++q) {
      const std::string what = std::to_string(bits) + " bits, table " + std::to_string(q);
      worst = std::max(worst, worst_step_fraction(in.tables[q].full, out.section.tables[q].full,
                                                  bits, what + " T"));
      worst = std::max(worst, worst_step_fraction(in.tables[q].cone, out.section.tables[q].cone,
                                                  bits, what + " T_c"));
    }
    // Many values: the worst rounding is close to half a step (the bound is reached).
    EXPECT_GT(worst, 0.49) << bits;
    RecordProperty("worst_error_in_steps_" + std::to_string(bits), std::to_string(worst));
  }
}

TEST(ClothBlob, SecondEncodeIsByteIdenticalAndSizedByTheLayout) {
  const ClothSection s = random_section(3);
  for (int bits : {8, 16}) {
    const Bytes a = prt::bake::encode_clth_section(s, bits);
    EXPECT_EQ(prt::bake::encode_clth_section(s, bits), a);
    prt_blob_clth_header h{};
    prt_blob_clth_layout l{};
    prt_blob_clth_read_header(a.data(), &h);
    ASSERT_EQ(prt_blob_clth_layout_of(&h, &l), 1);
    uint64_t size = l.data;
    for (const auto& t : s.tables)
      size +=
          prt_blob_clth_factor_size(&l, t.full.rank) + prt_blob_clth_factor_size(&l, t.cone.rank);
    EXPECT_EQ(a.size(), size) << bits;
    EXPECT_EQ(h.tangents, 5u);  // one record per offset of each thread, none shared
  }
}

// Ties round half away from zero; a column of zeros has scale 0.
TEST(ClothBlob, QuantisesHalfAwayFromZero) {
  ClothSection s = random_section(1);
  ClothFactor& f = s.tables[0].full;  // rank 1
  const float step = 0.125f;
  std::fill(f.u.begin(), f.u.end(), 0.0f);
  f.u[0] = 127 * step;
  f.u[1] = 2.5f * step;
  f.u[2] = -2.5f * step;
  f.u[3] = 0.49f * step;
  std::fill(s.tables[0].cone.v.begin(), s.tables[0].cone.v.end(), 0.0f);
  const Bytes bytes = prt::bake::encode_clth_section(s, 8);
  const auto out = prt::bake::decode_clth_section(bytes.data(), bytes.size());
  const ClothFactor& g = out.section.tables[0].full;
  EXPECT_EQ(g.u[0], 127 * step);
  EXPECT_EQ(g.u[1], 3 * step);
  EXPECT_EQ(g.u[2], -3 * step);
  EXPECT_EQ(g.u[3], 0.0f);
  for (float v : out.section.tables[0].cone.v) EXPECT_EQ(v, 0.0f);
  // The zero column's v_scale (rank 2: the scales at 8, 12 of table 0's T_c) is 0.
  prt_blob_clth_header h{};
  prt_blob_clth_layout l{};
  prt_blob_clth_read_header(bytes.data(), &h);
  prt_blob_clth_layout_of(&h, &l);
  const uint64_t cone = l.data + prt_blob_clth_factor_size(&l, 1);
  EXPECT_EQ(prt_blob_clth_load_f32(bytes.data() + cone + 8), 0.0f);
  EXPECT_EQ(prt_blob_clth_load_f32(bytes.data() + cone + 12), 0.0f);
}

void expect_refused(const ClothSection& s, int bits, const std::string& words) {
  try {
    prt::bake::encode_clth_section(s, bits);
    ADD_FAILURE() << "accepted, expected: " << words;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(ClothBlob, RefusesWhatBreaksTheSpec) {
  const ClothSection good = random_section(2);
  expect_refused(good, 12, "12 bits (must be 8 or 16)");
  auto with = [&](auto edit) {
    ClothSection s = good;
    edit(s);
    return s;
  };
  expect_refused(with([](ClothSection& s) { s.fabrics.clear(); }), 8, "0 fabrics");
  expect_refused(with([](ClothSection& s) { s.fabrics.resize(65, s.fabrics[0]); }), 8,
                 "65 fabrics");
  expect_refused(with([](ClothSection& s) { s.tables.clear(); }), 8, "0 tables");
  expect_refused(with([](ClothSection& s) { s.fabrics[0].name = ""; }), 8,
                 "fabric 0: a name of 0 bytes");
  expect_refused(with([](ClothSection& s) { s.fabrics[0].name = std::string(33, 'a'); }), 8,
                 "a name of 33 bytes (must be 1..32 bytes without NUL)");
  expect_refused(with([](ClothSection& s) { s.fabrics[0].name = std::string("a\0b", 3); }), 8,
                 "fabric 0: a name of 3 bytes");
  expect_refused(with([](ClothSection& s) { s.fabrics[1].threads[1].clear(); }), 8,
                 "a thread of 0 offsets");
  expect_refused(with([](ClothSection& s) { s.fabrics[1].threads[1].resize(17); }), 8,
                 "a thread of 17 offsets");
  expect_refused(with([](ClothSection& s) { s.grid.xi_size = 1; }), 8, "grid out of range");
  expect_refused(with([](ClothSection& s) { s.tables[2].cone.rank = 0; }), 8,
                 "table 2 T_c: rank 0");
  expect_refused(with([](ClothSection& s) { s.tables[1].full.u.pop_back(); }), 8,
                 "table 1 T: U holds");
  expect_refused(with([](ClothSection& s) { s.tables[0].cone.v[3] = std::nanf(""); }), 8,
                 "table 0 T_c: a factor value is not finite");
  // The rest is the formats checker's, in its words.
  expect_refused(with([](ClothSection& s) { s.fabrics[0].params.threads[1].coverage = 0.9f; }), 8,
                 "'CLTH': fabric 0: coverages 0.33 and 0.9 add up to more than 1");
  expect_refused(with([](ClothSection& s) { s.fabrics[1].threads[0][0].table = 3; }), 16,
                 "'CLTH': tangent 3: table 3 is not below 3 tables");
  expect_refused(with([](ClothSection& s) { s.fabrics[0].threads[1][1].offset = 0.3f; }), 8,
                 "'CLTH': fabric 0 thread 2: offset 0.3 appears twice");
  expect_refused(with([](ClothSection& s) { s.fabrics[1].params.threads[0].eta = 0.9f; }), 8,
                 "'CLTH': fabric 1 thread 1: eta 0.9 is not in [1, 4]");
  expect_refused(with([](ClothSection& s) { s.grid.lambda_min = 0.0f; }), 8,
                 "'CLTH': lambda_min 0 is not positive");
}

prt::bake::ClothMesh small_mesh() {
  prt::bake::ClothMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  m.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  m.tangents = {1, 0, 0, 1, 0, 0, 0.8f, 0.6f, 0, 1, 0, 0};
  m.triangles = {0, 1, 2, 2, 1, 3};
  return m;
}

TEST(ClothBlob, WholeBlobLoadsWithItsMesh) {
  const ClothSection s = random_section(5);
  const prt::bake::ClothMesh mesh = small_mesh();
  const Bytes blob = prt::bake::write_cloth_blob(s, 8, &mesh, "cloth test");
  EXPECT_EQ(prt::bake::write_cloth_blob(s, 8, &mesh, "cloth test"), blob);
  Context ctx;
  const LoadedAsset a(ctx.ctx, blob, PRT_VALIDATE_FULL);
  ASSERT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
  EXPECT_EQ(prt_asset_techniques(a.asset), 1u << PRT_TECHNIQUE_CLOTH);
  EXPECT_EQ(prt_asset_section_count(a.asset), 6u);  // INFO VPOS VNRM VTAN TRIS CLTH
  const void* data = nullptr;
  size_t size = 0;
  ASSERT_EQ(prt_asset_section_data(a.asset, PRT_SECTION_VTAN, &data, &size), PRT_OK);
  ASSERT_EQ(size, mesh.tangents.size() * 4);
  EXPECT_EQ(std::memcmp(data, mesh.tangents.data(), size), 0);
  ASSERT_EQ(prt_asset_section_data(a.asset, PRT_SECTION_INFO, &data, &size), PRT_OK);
  EXPECT_EQ(std::string(static_cast<const char*>(data), size), "cloth test");
  uint32_t f = 9;
  ASSERT_EQ(prt_cloth_find_fabric(a.asset, s.fabrics[1].name.c_str(), &f), PRT_OK);
  EXPECT_EQ(f, 1u);
  // Without a mesh or INFO: CLTH alone, which needs nothing else.
  const LoadedAsset bare(ctx.ctx, prt::bake::write_cloth_blob(s, 16, nullptr, ""));
  ASSERT_EQ(bare.result, PRT_OK) << prt_context_last_message(ctx.ctx);
  EXPECT_EQ(prt_asset_section_count(bare.asset), 1u);
  prt_cloth_info info = prt::sized<prt_cloth_info>();
  ASSERT_EQ(prt_cloth_get_info(bare.asset, &info), PRT_OK);
  EXPECT_EQ(info.bits, 16u);
  EXPECT_EQ(info.fabric_count, 2u);
}

TEST(ClothBlob, WholeBlobRefusesABadMesh) {
  const ClothSection s = random_section(5);
  const auto refused = [&](auto edit, const char* words) {
    prt::bake::ClothMesh m = small_mesh();
    edit(m);
    try {
      prt::bake::write_cloth_blob(s, 8, &m, "");
      ADD_FAILURE() << "accepted, expected: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused([](auto& m) { m.tangents.pop_back(); }, "not one tangent per vertex");
  refused([](auto& m) { m.normals.resize(3); }, "not one normal per vertex");
  refused([](auto& m) { m.positions.clear(); }, "one vertex or more");
  refused([](auto& m) { m.triangles[4] = 4; }, "index 4 is not below the vertex count");
  refused([](auto& m) { m.tangents[5] = INFINITY; }, "not finite");
  refused([](auto& m) { m.triangles.pop_back(); }, "multiple of 3");
}

// Raw (uncompressed) blobs of the encoder's section and a mesh with VTAN for the second reader
// written from SPEC.md alone (tests/format/spec_reader.py): one valid, one with a value -128.
// Written where PRT_CLOTH_RAW_BLOB says (the ctest fixture), each checked by the runtime here.
TEST(ClothBlob, RawBlobsForTheSpecReader) {
  const ClothSection s = random_section(11);
  const prt::bake::ClothMesh mesh = small_mesh();
  Bytes section = prt::bake::encode_clth_section(s, 8);
  const auto raw_blob = [&](const Bytes& clth) {
    prt::format::BlobWriter w;
    prt::format::SectionOptions required;
    required.required = true;
    w.add_section(PRT_BLOB_TAG_VPOS, mesh.positions.data(), mesh.positions.size() * 4, 4, required);
    w.add_section(PRT_BLOB_TAG_VTAN, mesh.tangents.data(), mesh.tangents.size() * 4, 4);
    w.add_section(PRT_BLOB_TAG_TRIS, mesh.triangles.data(), mesh.triangles.size() * 4, 2, required);
    w.add_section(PRT_BLOB_TAG_CLTH, clth.data(), clth.size(), s.fabrics.size(), required);
    return w.finish();
  };
  const Bytes good = raw_blob(section);
  prt_blob_clth_header h{};
  prt_blob_clth_layout l{};
  prt_blob_clth_read_header(section.data(), &h);
  ASSERT_EQ(prt_blob_clth_layout_of(&h, &l), 1);
  section[l.data + 8 * s.tables[0].full.rank] = 0x80;  // table 0 T's first V value: -128
  const Bytes bad = raw_blob(section);
  Context ctx;
  EXPECT_EQ(validate(ctx.ctx, good, PRT_VALIDATE_FULL), PRT_OK);
  EXPECT_EQ(validate(ctx.ctx, bad, PRT_VALIDATE_FULL), PRT_ERROR_CORRUPT);
  const char* path = std::getenv("PRT_CLOTH_RAW_BLOB");
  if (!path) return;
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(good.data()), std::streamsize(good.size()));
  std::ofstream(std::string(path) + ".bad", std::ios::binary)
      .write(reinterpret_cast<const char*>(bad.data()), std::streamsize(bad.size()));
}

}  // namespace
