// SPDX-License-Identifier: MIT
// Backend conformance of `shadowfield` (tests/gl/conformance.hpp): blobs built here from formulas
// (the SFLD layout of formats/SPEC.md §7.5, 16-bit rows, written with the public layout header
// and the blob writer, no baker) loaded through the public API, a scene of a receiver patch of
// kVertices vertices (a prime: no SIMD block or work group divides it) and two instances of a
// glossy source that shadow it and light it, shaded on every backend (scalar, SIMD per
// instruction set, GL) after 0 and 2 bounces, each within the tolerance of the arithmetic of the
// scalar reference.
//
// The tolerances, on each instance's largest scalar radiance: SIMD sums the same products in
// another order with fused multiply-adds, so per output a sum of n rounded terms, n = passes x
// (8 field reads + 2 n^2 rotation and transfer terms + the source's vertices in its projection),
// parts from the scalar one by the probabilistic bound 2 sqrt(n) u (Higham and Mary 2019; u =
// 2^-24), as tests/shadowfield/simd checks for its kernels; GL also evaluates log (the shell)
// and atan (the g table's map) not correctly rounded, which tests/shadowfield/gl measured at most
// 15 u and holds to 32 u; here both bounds are added for GL.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <prt/format/mesh_layout.h>
#include <prt/format/shadowfield_layout.h>
#include <prt/format/blob_writer.hpp>

#include "gl/conformance.hpp"
#include "support/blob_test_util.hpp"

namespace prt_conformance {
namespace {

constexpr double kUnit = 1.0 / 16777216.0;  // u = 2^-24
constexpr uint32_t kSourceVertices = 37;    // the source's patch: 37 vertices, odd
constexpr uint32_t kBounces = 2;

// A shadowfield object to write, in the float values SPEC §7.5 stores.
struct Object {
  uint32_t order = 3, terms = 1, glossy = 0, brdf_grid = 0, basis_size = 0;
  std::vector<float> positions, normals, albedo, g_table, transfer, oof, basis, weights, inverse,
      srf;
  std::vector<uint32_t> indices;
  prt_sf_shells oof_shells{}, srf_shells{};
  uint32_t vertices() const { return uint32_t(positions.size() / 3); }
};

float wave(size_t index, float seed, float amplitude) {
  return amplitude * float(std::sin(0.61803 * double(index) + seed));
}

// A row of `count` vertices along x at height 0 (bent a little in y so every normal differs),
// normals near +y, two triangles per neighbouring pair with a vertex above: a strip.
Object patch(uint32_t order, uint32_t vertices, float width, float seed) {
  Object o;
  o.order = order;
  const uint32_t n2 = order * order;
  for (uint32_t v = 0; v < vertices; ++v) {
    const float t = vertices > 1 ? float(v) / float(vertices - 1) : 0.5f;
    const float x = width * (t - 0.5f), z = 0.3f * width * wave(v, seed, 1.0f);
    o.positions.insert(o.positions.end(), {x, 0.02f * wave(v, seed + 1.0f, 1.0f), z});
    const float nx = 0.2f * wave(v, seed + 2.0f, 1.0f), nz = 0.2f * wave(v, seed + 3.0f, 1.0f);
    const float length = std::sqrt(nx * nx + 1.0f + nz * nz);
    o.normals.insert(o.normals.end(), {nx / length, 1.0f / length, nz / length});
    o.albedo.insert(o.albedo.end(), {0.5f + 0.3f * wave(v, seed, 1.0f), 0.6f,
                                     0.5f + 0.2f * wave(v, seed + 4.0f, 1.0f)});
  }
  for (uint32_t v = 0; v + 2 < vertices; ++v) o.indices.insert(o.indices.end(), {v, v + 1, v + 2});
  // Transfer: a clamped-cosine-like band 0 and 1 with a varying rest, per term.
  for (uint32_t v = 0; v < vertices; ++v)
    for (uint32_t k = 0; k < o.terms; ++k)
      for (uint32_t i = 0; i < n2; ++i)
        o.transfer.push_back(i == 0 ? 0.28f + 0.05f * wave(v, seed, 1.0f)
                                    : 0.1f * wave(v * n2 + i, seed + float(k), 1.0f));
  const float radius = 0.6f * width;
  o.oof_shells = prt_sf_shells{{0.0f, 0.0f, 0.0f}, radius, 0.25f, 4.0f, 4, 3};
  o.srf_shells = prt_sf_shells{{0.0f, 0.0f, 0.0f}, radius, 0.25f, 4.0f, 3, 2};
  const uint64_t points = prt_sf_point_count(&o.oof_shells);
  for (uint64_t p = 0; p < points; ++p)
    for (uint32_t i = 0; i < n2; ++i)
      o.oof.push_back(i == 0 ? 2.0f + 0.8f * wave(p, seed, 1.0f)
                             : 0.4f * wave(p * n2 + i, seed + 5.0f, 1.0f));
  return o;
}

// Two BRDF terms on a 5 x 5 g table, the transfer's second term a scaled first; a radiance basis
// of 3 functions and its source fields.
void make_glossy_source(Object& o, float seed) {
  const uint32_t n2 = o.order * o.order, v = o.vertices();
  o.glossy = 1;
  o.terms = 2;
  o.brdf_grid = 5;
  for (uint32_t k = 0; k < 2; ++k)
    for (uint32_t cell = 0; cell < 25; ++cell)
      o.g_table.push_back(1.0f + 0.3f * wave(cell + 25 * k, seed, 1.0f));
  const std::vector<float> one = o.transfer;
  o.transfer.clear();
  for (uint32_t x = 0; x < v; ++x)
    for (uint32_t k = 0; k < 2; ++k)
      for (uint32_t i = 0; i < n2; ++i) o.transfer.push_back((1.0f - 0.4f * k) * one[x * n2 + i]);
  o.basis_size = 3;
  for (uint32_t j = 0; j < 3; ++j)
    for (uint32_t x = 0; x < v; ++x) o.basis.push_back(0.4f + 0.2f * wave(x + 7 * j, seed, 1.0f));
  o.weights.assign(v, 1.0f / float(v));
  o.inverse = {1.0f, 0.1f, 0.0f, 0.0f, 1.0f, 0.2f, 0.1f, 0.0f, 1.0f};
  const uint64_t points = prt_sf_point_count(&o.srf_shells);
  for (uint64_t e = 0; e < 3 * 2 * points * n2; ++e)
    o.srf.push_back(e % n2 == 0 ? 0.3f + 0.1f * wave(e, seed, 1.0f) : 0.05f * wave(e, seed, 1.0f));
}

// A receiver without a basis needs none of the source's blocks but the grid; N >= 1 is stored:
// one constant function with zero source fields (it glows with nothing).
void make_quiet_basis(Object& o) {
  const uint32_t n2 = o.order * o.order, v = o.vertices();
  o.basis_size = 1;
  o.basis.assign(v, 1.0f);
  o.weights.assign(v, 1.0f / float(v));
  o.inverse = {1.0f};
  o.srf.assign(o.terms * prt_sf_point_count(&o.srf_shells) * n2, 0.0f);
}

// Appends a quantised block (SPEC §7.5): per row, offset = min, scale = (max - min) / 65535.
void put_block(prt_test::Bytes& b, const prt_blob_sfld_block& block, const std::vector<float>& x,
               uint64_t (*row_of)(const prt_blob_sfld_layout*, uint64_t),
               const prt_blob_sfld_layout& l) {
  std::vector<float> lo(block.rows, INFINITY), hi(block.rows, -INFINITY);
  for (uint64_t e = 0; e < x.size(); ++e) {
    const uint64_t r = row_of(&l, e);
    lo[r] = std::min(lo[r], x[e]);
    hi[r] = std::max(hi[r], x[e]);
  }
  std::vector<float> scale(block.rows);
  for (uint64_t r = 0; r < block.rows; ++r) {
    scale[r] = (hi[r] - lo[r]) / 65535.0f;
    std::memcpy(&b[block.params + 8 * r], &lo[r], 4);
    std::memcpy(&b[block.params + 8 * r + 4], &scale[r], 4);
  }
  for (uint64_t e = 0; e < x.size(); ++e) {
    const uint64_t r = row_of(&l, e);
    const double q = scale[r] > 0.0f ? std::round((x[e] - lo[r]) / scale[r]) : 0.0;
    prt_test::put_u16(b, block.values + 2 * e, uint16_t(std::clamp(q, 0.0, 65535.0)));
  }
}

void put_floats(prt_test::Bytes& b, uint64_t at, const std::vector<float>& x) {
  std::memcpy(&b[at], x.data(), 4 * x.size());
}

void put_shells(prt_test::Bytes& b, size_t at, const prt_sf_shells& s) {
  std::memcpy(&b[at], s.centre, 12);
  std::memcpy(&b[at + 12], &s.radius, 4);
  std::memcpy(&b[at + 16], &s.inner, 4);
  std::memcpy(&b[at + 20], &s.outer, 4);
  prt_test::put_u32(b, at + 24, s.shells);
  prt_test::put_u32(b, at + 28, s.face_size);
}

uint64_t transfer_row(const prt_blob_sfld_layout* l, uint64_t i) {
  return prt_blob_sfld_transfer_row(l, i);
}
uint64_t oof_row(const prt_blob_sfld_layout* l, uint64_t i) {
  return prt_blob_sfld_oof_row(l, i);
}
uint64_t basis_row(const prt_blob_sfld_layout* l, uint64_t i) {
  return prt_blob_sfld_basis_row(l, i);
}
uint64_t srf_row(const prt_blob_sfld_layout* l, uint64_t i) {
  return prt_blob_sfld_srf_row(l, i);
}

// The object's blob: VPOS, VNRM, TRIS and a 16-bit SFLD.
prt_test::Bytes blob_of(const Object& o) {
  prt_blob_sfld_header h{};
  h.order = o.order;
  h.terms = o.terms;
  h.glossy = o.glossy;
  h.vertices = o.vertices();
  h.basis_size = o.basis_size;
  h.brdf_grid = o.brdf_grid;
  h.bits = 16;
  h.oof_shells = o.oof_shells;
  h.srf_shells = o.srf_shells;
  prt_blob_sfld_layout l{};
  EXPECT_EQ(prt_blob_sfld_layout_of(&h, &l), 1);
  prt_test::Bytes b(l.raw_size, 0);
  const uint32_t words[8] = {h.order,      h.terms,     h.glossy, h.vertices,
                             h.basis_size, h.brdf_grid, h.bits,   0};
  for (int w = 0; w < 8; ++w) prt_test::put_u32(b, 4 * w, words[w]);
  put_shells(b, PRT_BLOB_SFLD_OFF_OOF_SHELLS, o.oof_shells);
  put_shells(b, PRT_BLOB_SFLD_OFF_SRF_SHELLS, o.srf_shells);
  put_floats(b, l.albedo, o.albedo);
  if (o.glossy) put_floats(b, l.g_table, o.g_table);
  put_block(b, l.transfer, o.transfer, transfer_row, l);
  put_block(b, l.oof, o.oof, oof_row, l);
  put_block(b, l.basis, o.basis, basis_row, l);
  put_floats(b, l.vertex_weights, o.weights);
  put_floats(b, l.basis_inverse, o.inverse);
  put_block(b, l.srf, o.srf, srf_row, l);

  prt::format::SectionOptions required;
  required.required = true;
  prt::format::BlobWriter w;
  const size_t v = o.vertices();
  w.add_section(PRT_BLOB_TAG_VPOS, o.positions.data(), 12 * v, v, required);
  w.add_section(PRT_BLOB_TAG_VNRM, o.normals.data(), 12 * v, v, required);
  w.add_section(PRT_BLOB_TAG_TRIS, o.indices.data(), 4 * o.indices.size(), o.indices.size() / 3,
                required);
  w.add_section(PRT_BLOB_TAG_SFLD, b.data(), b.size(), 1, required);
  return w.finish();
}

struct AssetDeleter {
  void operator()(prt_asset* a) const { prt_asset_destroy(a); }
};
struct SceneDeleter {
  void operator()(prt_shadowfield_scene* s) const { prt_shadowfield_scene_destroy(s); }
};
struct GlDeleter {
  void operator()(prt_gl_shadowfield* s) const { prt_gl_shadowfield_destroy(s); }
};
using AssetPtr = std::unique_ptr<prt_asset, AssetDeleter>;
using ScenePtr = std::unique_ptr<prt_shadowfield_scene, SceneDeleter>;
using GlPtr = std::unique_ptr<prt_gl_shadowfield, GlDeleter>;

AssetPtr load(prt_context* context, const prt_test::Bytes& blob) {
  prt_asset* asset = nullptr;
  EXPECT_EQ(prt_asset_load_memory(context, blob.data(), blob.size(), PRT_VALIDATE_FULL, &asset),
            PRT_OK)
      << prt_context_last_message(context);
  return AssetPtr(asset);
}

prt_shadowfield_transform placed(float angle, float tx, float ty, float tz, float scale) {
  prt_shadowfield_transform t = prt::sized<prt_shadowfield_transform>();
  const float c = std::cos(angle), s = std::sin(angle);
  const float r[9] = {c, 0, s, 0, 1, 0, -s, 0, c};  // about +y
  std::copy(r, r + 9, t.rotation);
  t.translation[0] = tx, t.translation[1] = ty, t.translation[2] = tz;
  t.scale = scale;
  return t;
}

// The receiver patch at the origin, the source standing over it twice: tilted and scaled, each
// within the other's outer shell.
ScenePtr make_scene(prt_context* context, const prt_asset* receiver, const prt_asset* source) {
  prt_shadowfield_scene* made = nullptr;
  EXPECT_EQ(prt_shadowfield_scene_create(context, 3, &made), PRT_OK);
  ScenePtr scene(made);
  uint32_t r = 0, s = 0, id = 0;
  EXPECT_EQ(prt_shadowfield_scene_add_object(made, receiver, &r), PRT_OK);
  EXPECT_EQ(prt_shadowfield_scene_add_object(made, source, &s), PRT_OK);
  const prt_shadowfield_transform t[3] = {placed(0.0f, 0.0f, 0.0f, 0.0f, 1.0f),
                                          placed(0.7f, 0.3f, 0.5f, 0.1f, 0.8f),
                                          placed(2.1f, -0.4f, 0.8f, -0.2f, 1.3f)};
  EXPECT_EQ(prt_shadowfield_scene_add_instance(made, r, &t[0], &id), PRT_OK);
  EXPECT_EQ(prt_shadowfield_scene_add_instance(made, s, &t[1], &id), PRT_OK);
  EXPECT_EQ(prt_shadowfield_scene_add_instance(made, s, &t[2], &id), PRT_OK);
  return scene;
}

using Frame = std::vector<std::vector<float>>;  // per instance, V x 3

Frame empty_frame(prt_shadowfield_scene* scene) {
  Frame out(prt_shadowfield_scene_instance_count(scene));
  for (uint32_t i = 0; i < out.size(); ++i)
    out[i].assign(3 * size_t(prt_shadowfield_instance_vertex_count(scene, i)), -1.0f);
  return out;
}

prt_shadowfield_settings settings_for(uint32_t bounces, prt_backend backend) {
  prt_shadowfield_settings s = prt::sized<prt_shadowfield_settings>();
  s.bounces = bounces;
  s.backend = backend;
  return s;
}

// The largest |a - b| / (bound on the instance's largest |b|) over every instance.
double worst_over_bound(const Frame& a, const Frame& b, double bound_in_u) {
  double worst = 0.0;
  for (size_t i = 0; i < b.size(); ++i) {
    double scale = 0.0;
    for (const float x : b[i]) scale = std::max(scale, double(std::fabs(x)));
    const double bound = bound_in_u * kUnit * scale;
    for (size_t e = 0; e < b[i].size(); ++e) {
      const double d = std::fabs(double(a[i][e]) - b[i][e]);
      if (bound > 0.0)
        worst = std::max(worst, d / bound);
      else if (d > 0.0)
        worst = INFINITY;
    }
  }
  return worst;
}

void check_all_backends(uint32_t order) {
  PRT_REQUIRE_GL(gl);
  Object receiver = patch(order, kVertices, 3.0f, 0.5f);
  make_quiet_basis(receiver);
  Object source = patch(order, kSourceVertices, 0.8f, 1.5f);
  make_glossy_source(source, 2.5f);
  const prt_test::Bytes receiver_blob = blob_of(receiver), source_blob = blob_of(source);
  const std::vector<float> light = prt_test::realistic_light(order, 91);
  const float eye[3] = {1.0f, 4.0f, 2.5f};
  Summary summary("order " + std::to_string(order) + ", " + std::to_string(kVertices) + " + 2 x " +
                  std::to_string(kSourceVertices) + " vertices, glossy source");

  // The scalar reference, 0 and kBounces bounces; every value finite, and bounces change it.
  const prt::ContextPtr cpu_ctx = prt_test::limited_context();
  const AssetPtr r_asset = load(cpu_ctx.get(), receiver_blob);
  const AssetPtr s_asset = load(cpu_ctx.get(), source_blob);
  ASSERT_TRUE(r_asset && s_asset);
  const ScenePtr cpu_scene = make_scene(cpu_ctx.get(), r_asset.get(), s_asset.get());
  Frame expected[2];
  for (uint32_t b = 0; b < 2; ++b) {
    expected[b] = empty_frame(cpu_scene.get());
    std::vector<float*> out;
    for (auto& x : expected[b]) out.push_back(x.data());
    const prt_shadowfield_settings s = settings_for(b * kBounces, PRT_BACKEND_CPU);
    ASSERT_EQ(prt_shadowfield_shade(cpu_scene.get(), light.data(), eye, &s, out.data()), PRT_OK)
        << prt_context_last_message(cpu_ctx.get());
    for (const auto& x : expected[b])
      for (const float value : x) ASSERT_TRUE(std::isfinite(value));
  }
  ASSERT_GT(worst_over_bound(expected[1], expected[0], 1e4), 1.0)
      << "the bounces must change the radiance, else they were not compared";

  const double n2 = double(order) * order;
  const double terms = (kBounces + 1.0) * (8.0 + 2.0 * n2 + kSourceVertices);
  const double simd_u = 2.0 * std::sqrt(terms), gl_u = simd_u + 32.0;

  for_each_simd_isa(summary, [&](prt_context* ctx, const std::string& name) {
    const ScenePtr scene = make_scene(ctx, r_asset.get(), s_asset.get());
    double worst = 0.0;
    for (uint32_t b = 0; b < 2; ++b) {
      Frame got = empty_frame(scene.get());
      std::vector<float*> out;
      for (auto& x : got) out.push_back(x.data());
      const prt_shadowfield_settings s = settings_for(b * kBounces, PRT_BACKEND_SIMD);
      const prt_result r = prt_shadowfield_shade(scene.get(), light.data(), eye, &s, out.data());
      if (r == PRT_ERROR_UNSUPPORTED_BACKEND) {
        summary.skip(name, "shadowfield's SIMD kernels need AVX2 and FMA");
        return;
      }
      ASSERT_EQ(r, PRT_OK) << name;
      worst = std::max(worst, worst_over_bound(got, expected[b], simd_u));
    }
    EXPECT_LE(worst, 1.0) << name;
    summary.note(name, worst);
  });

  {
    const ScenePtr scene = make_scene(cpu_ctx.get(), r_asset.get(), s_asset.get());
    prt_gl_shadowfield* made = nullptr;
    ASSERT_EQ(prt_gl_shadowfield_create(scene.get(), headless_gl_get_proc, gl.gl, &made), PRT_OK)
        << prt_context_last_message(cpu_ctx.get());
    const GlPtr shader(made);
    double worst = 0.0;
    for (uint32_t b = 0; b < 2; ++b) {
      const prt_shadowfield_settings s = settings_for(b * kBounces, PRT_BACKEND_GL);
      ASSERT_EQ(prt_gl_shadowfield_shade(shader.get(), light.data(), eye, &s), PRT_OK)
          << prt_context_last_message(cpu_ctx.get());
      Frame got = empty_frame(scene.get());
      for (uint32_t i = 0; i < got.size(); ++i)
        ASSERT_EQ(
            prt_gl_shadowfield_read(shader.get(), i, 0, uint32_t(got[i].size() / 3), got[i].data()),
            PRT_OK);
      worst = std::max(worst, worst_over_bound(got, expected[b], gl_u));
    }
    EXPECT_LE(worst, 1.0) << "gl";
    summary.note("gl", worst);
  }
  summary.print("shadowfield");
}

}  // namespace

std::vector<Case> shadowfield_cases() {
  std::vector<Case> cases;
  for (const uint32_t order : {2u, 3u, 5u})
    cases.push_back({"Order" + std::to_string(order) + "GlossySourcesAndBounces",
                     [order] { check_all_backends(order); }});
  return cases;
}

}  // namespace prt_conformance
