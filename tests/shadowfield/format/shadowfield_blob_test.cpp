// SPDX-License-Identifier: MIT
// The baker's SFLD writer (prt/baker/shadowfield/shadowfield_blob.hpp) through the runtime's
// load at full validation: the header as prt_shadowfield_get_info reports it, the size from
// SPEC §7.5's formula written out here, and the decoded object (the runtime's private
// prt_sf_object) against the input: f32 blocks exactly, quantised ones within half a step of
// each row's own min/max, at 8 and 16 bits. Then byte-identical rebuilds, the object domain's
// count, and the writer's refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "shadowfield/sfld_test_object.hpp"
#include "support/mesh_blob.hpp"

extern "C" {
#include "shadowfield/shadowfield_asset_internal.h"
}

namespace {

using namespace prt_test;
using prt::bake::ShadowfieldObject;

std::uint64_t align4(std::uint64_t x) {
  return (x + 3) / 4 * 4;
}

// SPEC §7.5: Q(R, C) = 8 R + align4(C b / 8), and the blocks' sum.
std::uint64_t spec_raw_size(const ShadowfieldObject& o, std::uint64_t bits) {
  const std::uint64_t v = o.positions.size(), n2 = o.order * o.order, k = o.material.terms();
  const std::uint64_t g = o.material.glossy ? o.material.brdf.grid.size : 0, n = o.basis_size;
  const std::uint64_t p_oof =
      o.oof_shells.shells * 6 * o.oof_shells.face_size * o.oof_shells.face_size;
  const std::uint64_t p_srf =
      o.srf_shells.shells * 6 * o.srf_shells.face_size * o.srf_shells.face_size;
  auto q = [bits](std::uint64_t rows, std::uint64_t count) {
    return 8 * rows + align4(count * bits / 8);
  };
  return 128 + 12 * v + 4 * k * g * g + q(k * n2, v * k * n2) + q(n2, p_oof * n2) + q(n, n * v) +
         4 * v + 4 * n * n + q(n * k * n2, n * k * p_srf * n2);
}

// How far the decoded values are from the input, against half a step of each row's range.
struct BlockError {
  double max_error = 0.0;
  double max_budget_ratio = 0.0;  // max error / (scale / 2 + float rounding), <= 1 passes
};

// Rows as SPEC §7.5 numbers them: values [groups][repeat][width], row g width + c.
BlockError compare_block(const std::vector<float>& input, const float* decoded, std::size_t groups,
                         std::size_t repeat, std::size_t width, int bits) {
  const double levels = std::ldexp(1.0, bits) - 1.0;
  const double eps = std::numeric_limits<float>::epsilon();
  std::vector<float> lo(groups * width, 1e30f), hi(groups * width, -1e30f);
  auto row = [&](std::size_t x) { return x / (repeat * width) * width + x % width; };
  for (std::size_t x = 0; x < input.size(); ++x) {
    lo[row(x)] = std::min(lo[row(x)], input[x]);
    hi[row(x)] = std::max(hi[row(x)], input[x]);
  }
  BlockError e;
  for (std::size_t x = 0; x < input.size(); ++x) {
    const double scale = (double(hi[row(x)]) - lo[row(x)]) / levels;
    const double allowed =
        0.5 * scale + 4 * eps * (std::abs(double(lo[row(x)])) + scale * levels) + 1e-30;
    const double error = std::abs(double(decoded[x]) - input[x]);
    e.max_error = std::max(e.max_error, error);
    e.max_budget_ratio = std::max(e.max_budget_ratio, error / allowed);
  }
  return e;
}

void expect_shells(const prt_shadowfield_shells& got, const prt_sf_shells& want) {
  for (int i = 0; i < 3; ++i) EXPECT_EQ(got.centre[i], want.centre[i]);
  EXPECT_EQ(got.radius, want.radius);
  EXPECT_EQ(got.inner, want.inner);
  EXPECT_EQ(got.outer, want.outer);
  EXPECT_EQ(got.shells, want.shells);
  EXPECT_EQ(got.face_size, want.face_size);
}

void expect_info(const prt_shadowfield_info& info, const ShadowfieldObject& o, std::uint32_t bits) {
  EXPECT_EQ(info.order, o.order);
  EXPECT_EQ(info.terms, o.material.terms());
  EXPECT_EQ(info.glossy, o.material.glossy ? 1u : 0u);
  EXPECT_EQ(info.vertex_count, o.positions.size());
  EXPECT_EQ(info.basis_size, o.basis_size);
  EXPECT_EQ(info.brdf_grid, o.material.glossy ? o.material.brdf.grid.size : 0u);
  expect_shells(info.oof_shells, o.oof_shells);
  expect_shells(info.srf_shells, o.srf_shells);
  EXPECT_EQ(info.bits, bits);
  EXPECT_EQ(info.bytes, spec_raw_size(o, bits));
}

void expect_vec3s(const float* got, const std::vector<glm::vec3>& want, const char* what) {
  for (std::size_t i = 0; i < want.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(got[3 * i + c], want[i][c]) << what << " " << i;
}

void expect_floats(const float* got, const std::vector<float>& want, const char* what) {
  for (std::size_t i = 0; i < want.size(); ++i) ASSERT_EQ(got[i], want[i]) << what << " " << i;
}

// The f32 blocks and the mesh, exactly.
void expect_exact_parts(const prt_sf_object& d, const ShadowfieldObject& o) {
  EXPECT_EQ(d.order, o.order);
  EXPECT_EQ(d.terms, o.material.terms());
  EXPECT_EQ(d.vertex_count, o.positions.size());
  EXPECT_EQ(d.basis_size, o.basis_size);
  expect_vec3s(d.positions, o.positions, "positions");
  expect_vec3s(d.normals, o.normals, "normals");
  expect_vec3s(d.albedo, o.albedo, "albedo");
  if (o.material.glossy) {
    ASSERT_NE(d.g_table, nullptr);
    for (std::size_t i = 0; i < o.material.brdf.outgoing.size(); ++i)
      ASSERT_EQ(d.g_table[i], float(o.material.brdf.outgoing[i])) << i;
  } else {
    EXPECT_EQ(d.g_table, nullptr);
  }
  expect_floats(d.vertex_weights, o.vertex_weights, "vertex weights");
  expect_floats(d.basis_inverse, o.basis_inverse, "basis inverse");
  EXPECT_EQ(std::memcmp(&d.oof_shells, &o.oof_shells, sizeof d.oof_shells), 0);
  EXPECT_EQ(std::memcmp(&d.srf_shells, &o.srf_shells, sizeof d.srf_shells), 0);
}

// Loads the baker's blob at full validation and checks everything; returns the quantised
// blocks' errors (transfer, OOF, basis, SRF).
std::vector<BlockError> round_trip(const ShadowfieldObject& o, int bits) {
  const auto quantized = prt::bake::quantize_shadowfield(o, bits);
  Context ctx;
  const LoadedAsset a(ctx.ctx, prt::bake::build_shadowfield_blob(o, quantized, "test"));
  EXPECT_EQ(a.result, PRT_OK) << prt_context_last_message(ctx.ctx);
  if (a.result != PRT_OK) return {};
  EXPECT_EQ(prt_asset_techniques(a.asset), 1u << PRT_TECHNIQUE_SHADOWFIELD);
  prt_shadowfield_info info = prt::sized<prt_shadowfield_info>();
  EXPECT_EQ(prt_shadowfield_get_info(a.asset, &info), PRT_OK);
  expect_info(info, o, std::uint32_t(bits));
  const prt_sf_object* d = prt_internal_sf_object(a.asset);
  EXPECT_NE(d, nullptr);
  if (!d) return {};
  expect_exact_parts(*d, o);
  const std::size_t v = o.positions.size(), n2 = o.order * o.order, k = o.material.terms();
  const std::size_t n = o.basis_size;
  const std::size_t p_srf = o.srf.size() / (n * k * n2), p_oof = o.oof.size() / n2;
  return {compare_block(o.transfer, d->transfer, 1, v, k * n2, bits),
          compare_block(o.oof, d->oof, 1, p_oof, n2, bits),
          compare_block(o.basis, d->basis, n, v, 1, bits),
          compare_block(o.srf, d->srf, n * k, p_srf, n2, bits)};
}

TEST(ShadowfieldBlob, DecodesWithinHalfAStepAt16And8Bits) {
  for (bool glossy : {true, false})
    for (int bits : {16, 8}) {
      SCOPED_TRACE(std::string(glossy ? "glossy " : "diffuse ") + std::to_string(bits));
      const std::vector<BlockError> errors = round_trip(sf_test_object(glossy), bits);
      ASSERT_EQ(errors.size(), 4u);
      for (const BlockError& e : errors) {
        EXPECT_LE(e.max_budget_ratio, 1.0);
        // Rounding uses most of the half step somewhere: the budget is not vacuous.
        EXPECT_GT(e.max_budget_ratio, 0.5);
      }
    }
}

TEST(ShadowfieldBlob, ConstantRowIsExact) {
  const ShadowfieldObject o = sf_test_object();
  Context ctx;
  const LoadedAsset a(
      ctx.ctx, prt::bake::build_shadowfield_blob(o, prt::bake::quantize_shadowfield(o, 8), ""));
  ASSERT_EQ(a.result, PRT_OK);
  const prt_sf_object* d = prt_internal_sf_object(a.asset);
  for (std::size_t p = 0; p < 48; ++p) ASSERT_EQ(d->oof[p * 9 + 3], 0.25f) << p;
}

TEST(ShadowfieldBlob, ReportsEachBlocksErrorWithinItsBudget) {
  const ShadowfieldObject o = sf_test_object();
  for (int bits : {8, 16}) {
    const auto q = prt::bake::quantize_shadowfield(o, bits);
    EXPECT_EQ(q.bits, std::uint32_t(bits));
    for (const auto* b : {&q.transfer, &q.oof, &q.basis, &q.srf}) {
      const float max_scale = *std::max_element(b->scales.begin(), b->scales.end());
      EXPECT_GT(b->max_abs_error, 0.0);
      EXPECT_LE(b->max_abs_error, 0.5 * max_scale * (1 + 1e-3));
    }
    EXPECT_EQ(q.oof.scales[3], 0.0f);
    EXPECT_EQ(q.oof.offsets[3], 0.25f);
  }
}

TEST(ShadowfieldBlob, SameInputSameBytes) {
  const ShadowfieldObject o = sf_test_object();
  for (int bits : {8, 16}) {
    const auto first =
        prt::bake::build_shadowfield_blob(o, prt::bake::quantize_shadowfield(o, bits), "info");
    const auto second =
        prt::bake::build_shadowfield_blob(o, prt::bake::quantize_shadowfield(o, bits), "info");
    EXPECT_EQ(first, second);
  }
}

TEST(ShadowfieldBlob, EncodedSizeIsTheSpecs) {
  const ShadowfieldObject o = sf_test_object();
  for (int bits : {8, 16}) {
    const auto sfld = prt::bake::encode_sfld_section(o, prt::bake::quantize_shadowfield(o, bits));
    EXPECT_EQ(sfld.size(), spec_raw_size(o, std::uint64_t(bits)));
    EXPECT_EQ(sf_layout(sfld).raw_size, sfld.size());
  }
}

// The object domain's size is SFLD's element count, 1, as the vertex domain's is VPOS's.
TEST(ShadowfieldBlob, SfldCountsTheObjectDomain) {
  const ShadowfieldObject o = sf_test_object();
  const auto blob =
      prt::bake::build_shadowfield_blob(o, prt::bake::quantize_shadowfield(o, 16), "");
  prt_blob_header h;
  char msg[256];
  ASSERT_EQ(prt_blob_validate_structure(blob.data(), blob.size(), &h, msg, sizeof msg), PRT_BLOB_OK)
      << msg;
  EXPECT_EQ(prt_blob_domain_counter(PRT_BLOB_DOMAIN_OBJECT)->tag, PRT_BLOB_TAG_SFLD);
  EXPECT_EQ(prt_blob_domain_count(blob.data(), &h, PRT_BLOB_DOMAIN_OBJECT), 1u);
  EXPECT_EQ(prt_blob_domain_count(blob.data(), &h, PRT_BLOB_DOMAIN_VERTEX), 6u);
  const Bytes mesh = mesh_only_blob();
  ASSERT_EQ(prt_blob_validate_structure(mesh.data(), mesh.size(), &h, msg, sizeof msg),
            PRT_BLOB_OK);
  EXPECT_EQ(prt_blob_domain_count(mesh.data(), &h, PRT_BLOB_DOMAIN_OBJECT), 0u);
}

TEST(ShadowfieldBlob, InfoWithoutSectionOrArguments) {
  Context ctx;
  const LoadedAsset a(ctx.ctx, mesh_only_blob());
  ASSERT_EQ(a.result, PRT_OK);
  prt_shadowfield_info info = prt::sized<prt_shadowfield_info>();
  EXPECT_EQ(prt_shadowfield_get_info(a.asset, &info), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_internal_sf_object(a.asset), nullptr);
  EXPECT_EQ(prt_shadowfield_get_info(nullptr, &info), PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_shadowfield_get_info(a.asset, nullptr), PRT_ERROR_INVALID_ARGUMENT);
  info.struct_size = 0;
  EXPECT_EQ(prt_shadowfield_get_info(a.asset, &info), PRT_ERROR_INVALID_ARGUMENT);
}

TEST(ShadowfieldBlob, DecodedBytesAreTheObjectsFloats) {
  const ShadowfieldObject o = sf_test_object();
  Context ctx;
  const LoadedAsset a(
      ctx.ctx, prt::bake::build_shadowfield_blob(o, prt::bake::quantize_shadowfield(o, 16), ""));
  ASSERT_EQ(a.result, PRT_OK);
  prt_shadowfield_info info = prt::sized<prt_shadowfield_info>();
  ASSERT_EQ(prt_shadowfield_get_info(a.asset, &info), PRT_OK);
  const std::size_t floats = 3 * 3 * o.positions.size() + o.material.brdf.outgoing.size() +
                             o.transfer.size() + o.oof.size() + o.basis.size() +
                             o.vertex_weights.size() + o.basis_inverse.size() + o.srf.size();
  EXPECT_EQ(info.decoded_bytes, 4 * floats);
}

// The zstd sections decoded at quick validation give the same object as at full.
TEST(ShadowfieldBlob, QuickLoadDecodesTheSameObject) {
  const ShadowfieldObject o = sf_test_object();
  const auto blob =
      prt::bake::build_shadowfield_blob(o, prt::bake::quantize_shadowfield(o, 16), "");
  Context ctx;
  const LoadedAsset full(ctx.ctx, blob, PRT_VALIDATE_FULL),
      quick(ctx.ctx, blob, PRT_VALIDATE_QUICK);
  ASSERT_EQ(full.result, PRT_OK);
  ASSERT_EQ(quick.result, PRT_OK);
  const prt_sf_object* a = prt_internal_sf_object(full.asset);
  const prt_sf_object* b = prt_internal_sf_object(quick.asset);
  prt_shadowfield_info info = prt::sized<prt_shadowfield_info>();
  ASSERT_EQ(prt_shadowfield_get_info(quick.asset, &info), PRT_OK);
  // The object's floats are one allocation from positions to the SRF's end.
  const std::size_t floats = std::size_t(info.decoded_bytes / 4);
  ASSERT_EQ(b->srf + o.srf.size() - b->positions, std::ptrdiff_t(floats));
  EXPECT_EQ(std::memcmp(a->positions, b->positions, 4 * floats), 0);
}

// One vertex, no triangle, order 2, one shell of 1 x 1 faces per grid, diffuse: each transfer
// and basis row holds one value, so it is stored exactly.
TEST(ShadowfieldBlob, SmallestObject) {
  ShadowfieldObject o;
  o.order = 2;
  o.positions = {glm::vec3(0.5f, 0.0f, 0.0f)};
  o.normals = {glm::vec3(0.0f, 1.0f, 0.0f)};
  o.albedo = {glm::vec3(1.0f, 0.0f, 0.5f)};
  o.transfer = sf_values(4, 0.1f, 1.0f);
  o.oof_shells = prt_sf_shells{{0.5f, 0.0f, 0.0f}, 0.01f, 1.0f, 1.0f, 1, 1};
  o.oof = sf_values(6 * 4, 0.2f, 1.0f);
  o.basis_size = 1;
  o.basis = {0.75f};
  o.vertex_weights = {0.0f};
  o.basis_inverse = {4.0f};
  o.srf_shells = o.oof_shells;
  o.srf = sf_values(6 * 4, 0.3f, 1.0f);
  for (int bits : {8, 16}) {
    const std::vector<BlockError> errors = round_trip(o, bits);
    ASSERT_EQ(errors.size(), 4u);
    EXPECT_EQ(errors[0].max_error, 0.0);
    EXPECT_EQ(errors[2].max_error, 0.0);
    EXPECT_LE(errors[1].max_budget_ratio, 1.0);
    EXPECT_LE(errors[3].max_budget_ratio, 1.0);
  }
}

// The layout header's row functions (SPEC §7.5's rows) read from the section's bytes give the
// runtime's decoded values bit for bit.
TEST(ShadowfieldBlob, RowFunctionsGiveTheDecodedValues) {
  const ShadowfieldObject o = sf_test_object();
  for (int bits : {8, 16}) {
    const auto quantized = prt::bake::quantize_shadowfield(o, bits);
    const Bytes sfld = prt::bake::encode_sfld_section(o, quantized);
    const prt_blob_sfld_layout l = sf_layout(sfld);
    Context ctx;
    const LoadedAsset a(ctx.ctx, prt::bake::build_shadowfield_blob(o, quantized, ""));
    ASSERT_EQ(a.result, PRT_OK);
    const prt_sf_object* d = prt_internal_sf_object(a.asset);
    using RowFn = std::uint64_t (*)(const prt_blob_sfld_layout*, std::uint64_t);
    const struct {
      const prt_blob_sfld_block* block;
      RowFn row;
      const float* decoded;
    } blocks[] = {{&l.transfer, prt_blob_sfld_transfer_row, d->transfer},
                  {&l.oof, prt_blob_sfld_oof_row, d->oof},
                  {&l.basis, prt_blob_sfld_basis_row, d->basis},
                  {&l.srf, prt_blob_sfld_srf_row, d->srf}};
    for (const auto& b : blocks)
      for (std::uint64_t x = 0; x < b.block->count; ++x) {
        const std::uint8_t* pair = sfld.data() + b.block->params + 8 * b.row(&l, x);
        const std::uint8_t* value = sfld.data() + b.block->values + x * l.value_size;
        const std::uint32_t q = bits == 8 ? *value : prt_le_load_u16(value);
        const float expected =
            prt_blob_sfld_load_f32(pair) + prt_blob_sfld_load_f32(pair + 4) * float(q);
        ASSERT_EQ(b.decoded[x], expected) << x;
      }
  }
}

// The writer refuses what the layout cannot hold, naming it.
TEST(ShadowfieldBlob, WriterRefusesBadObjects) {
  auto refuses = [](ShadowfieldObject o, const char* field) {
    try {
      prt::bake::quantize_shadowfield(o, 16);
      ADD_FAILURE() << "accepted: " << field;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  ShadowfieldObject o = sf_test_object();
  o.order = 7;
  refuses(o, "order");
  o = sf_test_object();
  o.transfer.pop_back();
  refuses(o, "transfer");
  o = sf_test_object();
  o.srf[5] = std::numeric_limits<float>::quiet_NaN();
  refuses(o, "srf");
  o = sf_test_object();
  o.albedo[2].y = 1.5f;
  refuses(o, "albedo");
  o = sf_test_object();
  o.vertex_weights[1] = -1.0f;
  refuses(o, "weight");
  o = sf_test_object();
  o.indices[4] = 6;
  refuses(o, "index");
  o = sf_test_object();
  o.oof_shells.radius = 0.0f;
  refuses(o, "radius");
  o = sf_test_object();
  o.basis_size = 7;  // more than the 6 vertices
  refuses(o, "basis size");
  o = sf_test_object();
  o.positions.clear();
  refuses(o, "vertex count");
  EXPECT_THROW(prt::bake::quantize_shadowfield(sf_test_object(), 12), std::exception);
}

}  // namespace
