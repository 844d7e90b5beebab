// SPDX-License-Identifier: MIT
// Technique `shadowfield` split into shards (docs/farm.md): a shard bakes a range of the units
// (occlusion field shells, source radiance field shells, self transfer vertex blocks) and the
// merge joins them into the whole bake's object.
//
// What the merge still does: it separates the BRDF again (a small table, as every shard does),
// rebuilds the object from the scene and its shell grids, and copies the parts' values into
// place. It traces no ray. The surface-radiance basis (lights x
// vertices rays and an SVD) is not a unit: every source radiance shell is projected on it, so a
// shard that holds source radiance shells bakes the basis itself and carries it, and the merge
// takes it from the first of them (refusing a part whose basis differs) instead of baking it
// again.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "prt/baker/shadowfield/shadowfield_bake.hpp"

#include "../common/numbers.hpp"
#include "../common/shard_payload.hpp"
#include "shadowfield_technique.hpp"

namespace prt::bake {
namespace {

// A shard's payload: this header, the --brdf text (brdf_chars), then the range's values: the
// occlusion shells' field (point-major), when it holds source radiance shells the surface basis
// (basis, vertex weights, inverse, singular values) and their fields (field-major over the
// range's points), and the vertex blocks' transfer (vertex-major). Native byte order. The merge
// quantises with its own --bits, so the bits are not a setting of the payload.
constexpr std::uint32_t kShadowfieldShardMagic = 0x44534653;  // "SFSD"
constexpr std::uint32_t kShadowfieldShardVersion = 1;
struct ShadowfieldShardHeader {
  std::uint32_t magic = kShadowfieldShardMagic, version = kShadowfieldShardVersion;
  std::uint32_t order = 0, terms = 0, brdf_grid = 0;
  std::uint32_t oof_shells = 0, oof_face_size = 0, srf_shells = 0, srf_face_size = 0;
  std::uint32_t basis = 0, lights = 0, field_rays = 0, transfer_rays = 0, srf_rays = 0;
  std::uint32_t seed = 0, override_albedo = 0;
  glm::vec3 albedo{0.0f};  // when override_albedo
  std::uint32_t brdf_chars = 0;
  double inner = 0.0, outer = 0.0;
  std::uint64_t scene = 0;  // shard_scene_fingerprint of the scene baked (--albedo applied)
  std::uint64_t vertices = 0, units = 0, first = 0, count = 0;
  std::uint64_t without_transfer = 0;  // vertices of its blocks given zero transfer
  std::uint64_t basis_rays = 0, basis_samples = 0, singular_values = 0;  // when it has a basis
  double seconds_fields = 0.0, seconds_transfer = 0.0, seconds_basis = 0.0, seconds_srf = 0.0;
};
static_assert(sizeof(ShadowfieldShardHeader) == 200, "ShadowfieldShardHeader has padding");

// Vertices per transfer block: an occlusion shell's points (at least 1 for unchecked settings).
std::size_t shadowfield_shard_block(const ShadowfieldBakeSettings& settings) {
  return std::max<std::size_t>(
      1, 6 * std::size_t(settings.fields.oof_face_size) * settings.fields.oof_face_size);
}

// The units of [first, first + count) by kind: shells of each grid, then vertices.
struct ShadowfieldShardSpan {
  std::uint32_t oof_first = 0, oof_count = 0, srf_first = 0, srf_count = 0;
  std::size_t vertex_first = 0, vertex_count = 0;
};

// The part of [first, end) inside [lo, lo + size), from lo.
std::pair<std::size_t, std::size_t> shadowfield_shard_overlap(std::size_t first, std::size_t end,
                                                              std::size_t lo, std::size_t size) {
  const std::size_t a = std::max(first, lo), b = std::min(end, lo + size);
  return a < b ? std::make_pair(a - lo, b - a) : std::make_pair(std::size_t(0), std::size_t(0));
}

ShadowfieldShardSpan shadowfield_shard_span(const ShadowfieldBakeSettings& settings,
                                            std::size_t vertices, std::size_t first,
                                            std::size_t count) {
  const std::size_t end = first + count, oof = settings.fields.oof_shells,
                    srf = settings.srf.shells, block = shadowfield_shard_block(settings);
  ShadowfieldShardSpan span;
  const auto o = shadowfield_shard_overlap(first, end, 0, oof);
  span.oof_first = static_cast<std::uint32_t>(o.first);
  span.oof_count = static_cast<std::uint32_t>(o.second);
  const auto s = shadowfield_shard_overlap(first, end, oof, srf);
  span.srf_first = static_cast<std::uint32_t>(s.first);
  span.srf_count = static_cast<std::uint32_t>(s.second);
  const auto b = shadowfield_shard_overlap(first, end, oof + srf, (vertices + block - 1) / block);
  span.vertex_first = std::min(vertices, b.first * block);
  span.vertex_count = std::min(vertices, (b.first + b.second) * block) - span.vertex_first;
  return span;
}

// What a part of this bake states about it, the range and the figures left 0.
ShadowfieldShardHeader shadowfield_shard_header(const Scene& scene,
                                                const ShadowfieldShardBake& bake) {
  const ShadowfieldBakeSettings& s = bake.settings;
  ShadowfieldShardHeader h;
  h.order = s.fields.order;
  h.terms = s.brdf.terms;
  h.brdf_grid = s.brdf.grid_size;
  h.oof_shells = s.fields.oof_shells;
  h.oof_face_size = s.fields.oof_face_size;
  h.srf_shells = s.srf.shells;
  h.srf_face_size = s.srf.face_size;
  h.basis = s.basis.size;
  h.lights = s.basis.lights;
  h.field_rays = s.fields.field_directions;
  h.transfer_rays = s.fields.transfer_rays;
  h.srf_rays = s.srf.directions;
  h.seed = s.fields.seed;
  h.override_albedo = bake.override_albedo ? 1 : 0;
  if (bake.override_albedo) h.albedo = bake.albedo;
  h.brdf_chars = static_cast<std::uint32_t>(bake.brdf.size());
  h.inner = bake.inner;
  h.outer = bake.outer;
  h.scene = shard_scene_fingerprint(scene);
  h.vertices = scene.vertex_count();
  h.units = shadowfield_shard_units(scene, s);
  return h;
}

// Reads a part's header and --brdf; Error naming what differs from `expected` (this merge's).
ShadowfieldShardHeader read_shadowfield_shard_header(ShardPayloadReader& in,
                                                     const ShadowfieldShardHeader& expected,
                                                     const std::string& brdf) {
  const auto h = in.get<ShadowfieldShardHeader>();
  if (h.magic != kShadowfieldShardMagic)
    throw Error(in.who() + " is not a shard of technique shadowfield");
  if (h.version != kShadowfieldShardVersion) {
    throw Error(in.who() + " has shadowfield shard version " + std::to_string(h.version) +
                ", this baker reads " + std::to_string(kShadowfieldShardVersion));
  }
  const std::vector<char> text = in.get_vector<char>(h.brdf_chars);
  const auto albedo = [](const ShadowfieldShardHeader& x) {
    return x.override_albedo ? shard_value_text(x.albedo) : std::string("from the materials");
  };
  ShardSettingsDiff diff;
  diff.compare("--brdf", std::string(text.begin(), text.end()), brdf);
  diff.compare("--order", h.order, expected.order);
  diff.compare("--terms", h.terms, expected.terms);
  diff.compare("--brdf-grid", h.brdf_grid, expected.brdf_grid);
  diff.compare("--shells", h.oof_shells, expected.oof_shells);
  diff.compare("--face-size", h.oof_face_size, expected.oof_face_size);
  diff.compare("--srf-shells", h.srf_shells, expected.srf_shells);
  diff.compare("--srf-face-size", h.srf_face_size, expected.srf_face_size);
  diff.compare("--inner", h.inner, expected.inner);
  diff.compare("--outer", h.outer, expected.outer);
  diff.compare("--basis", h.basis, expected.basis);
  diff.compare("--lights", h.lights, expected.lights);
  diff.compare("--field-rays", h.field_rays, expected.field_rays);
  diff.compare("--transfer-rays", h.transfer_rays, expected.transfer_rays);
  diff.compare("--srf-rays", h.srf_rays, expected.srf_rays);
  diff.compare("--seed", h.seed, expected.seed);
  diff.compare("--albedo", albedo(h), albedo(expected));
  diff.check(in.who());
  if (h.scene != expected.scene)
    throw Error(in.who() + " was baked from another scene (its geometry or materials differ)");
  return h;
}

// The basis a part carries (and the figures of its bake), as bake_surface_basis leaves it.
struct ShadowfieldShardBasis {
  std::vector<float> basis, weights, inverse;
  std::vector<double> singular_values;
};

void put_shadowfield_shard_basis(ShardPayloadWriter& out, const ShadowfieldObject& object,
                                 const ShadowfieldBasisReport& report) {
  out.put_vector(object.basis);
  out.put_vector(object.vertex_weights);
  out.put_vector(object.basis_inverse);
  out.put_vector(report.singular_values);
}

// Sized by the merge's own settings and scene, which the part's header was checked against.
ShadowfieldShardBasis get_shadowfield_shard_basis(ShardPayloadReader& in,
                                                  const ShadowfieldShardHeader& expected,
                                                  std::uint64_t singular_values) {
  ShadowfieldShardBasis b;
  b.basis = in.get_vector<float>(std::size_t(expected.basis) * expected.vertices);
  b.weights = in.get_vector<float>(expected.vertices);
  b.inverse = in.get_vector<float>(std::size_t(expected.basis) * expected.basis);
  b.singular_values = in.get_vector<double>(singular_values);
  return b;
}

bool same_shadowfield_shard_basis(const ShadowfieldShardBasis& a, const ShadowfieldShardBasis& b) {
  const auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  return same(a.basis, b.basis) && same(a.weights, b.weights) && same(a.inverse, b.inverse) &&
         same(a.singular_values, b.singular_values);
}

// One part read back: its header and values.
struct ShadowfieldShardPart {
  ShadowfieldShardHeader header;
  ShadowfieldShardSpan span;
  std::vector<float> oof, srf, transfer;
  ShadowfieldShardBasis basis;
};

// The object with its grids set, as the stages see it before their fields are baked.
ShadowfieldObject shadowfield_shard_object(const Scene& scene, const ShadowfieldMaterial& material,
                                           const ShadowfieldBakeSettings& settings) {
  ShadowfieldObject object = make_shadowfield_object(scene, material, settings.fields.order);
  object.oof_shells = occlusion_field_grid(object, settings.fields);
  return object;
}

// Every part read and checked: the headers first (their settings, scene and ranges), as the
// values' sizes follow from ranges that cover the units; then each part's values.
std::vector<ShadowfieldShardPart> read_shadowfield_shard_parts(
    const std::vector<std::vector<std::uint8_t>>& parts, const ShadowfieldShardHeader& expected,
    const ShadowfieldShardBake& bake, std::uint32_t terms) {
  const ShadowfieldBakeSettings& s = bake.settings;
  std::vector<ShardPayloadReader> readers;
  readers.reserve(parts.size());
  std::vector<ShadowfieldShardPart> read(parts.size());
  std::vector<ShardPartRange> spans;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    readers.emplace_back(parts[i], "shadowfield merge: shard " + std::to_string(i));
    read[i].header = read_shadowfield_shard_header(readers[i], expected, bake.brdf);
    spans.push_back({read[i].header.first, read[i].header.count, read[i].header.units});
  }
  check_shard_ranges("shadowfield", kShadowfieldShardUnit, spans, expected.units);
  const std::size_t coeffs = std::size_t(s.fields.order) * s.fields.order;
  const std::size_t oof_shell = 6 * std::size_t(s.fields.oof_face_size) * s.fields.oof_face_size;
  const std::size_t srf_shell = 6 * std::size_t(s.srf.face_size) * s.srf.face_size;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    ShadowfieldShardPart& part = read[i];
    ShardPayloadReader& in = readers[i];
    part.span = shadowfield_shard_span(s, expected.vertices, part.header.first, part.header.count);
    part.oof = in.get_vector<float>(part.span.oof_count * oof_shell * coeffs);
    if (part.span.srf_count > 0) {
      part.basis = get_shadowfield_shard_basis(in, expected, part.header.singular_values);
      part.srf = in.get_vector<float>(std::size_t(s.basis.size) * terms * part.span.srf_count *
                                      srf_shell * coeffs);
    }
    part.transfer = in.get_vector<float>(part.span.vertex_count * terms * coeffs);
    in.finish();
  }
  return read;
}

// The first part that holds source radiance shells, whose basis the merge takes; Error when
// another such part projected its shells on a different basis.
const ShadowfieldShardPart& shadowfield_shard_basis_part(
    const std::vector<ShadowfieldShardPart>& read) {
  const ShadowfieldShardPart* first = nullptr;
  std::size_t first_index = 0;
  for (std::size_t i = 0; i < read.size(); ++i) {
    if (read[i].span.srf_count == 0) continue;
    if (!first) {
      first = &read[i];
      first_index = i;
    } else if (!same_shadowfield_shard_basis(first->basis, read[i].basis)) {
      throw Error("shadowfield merge: shard " + std::to_string(i) +
                  " projected its source radiance shells on another surface basis than shard " +
                  std::to_string(first_index) + " (their machines trace rays differently)");
    }
  }
  if (!first) throw Error("shadowfield merge: no shard holds the source radiance shells");
  return *first;
}

}  // namespace

std::size_t shadowfield_shard_units(const Scene& scene, const ShadowfieldBakeSettings& settings) {
  const std::size_t block = shadowfield_shard_block(settings);
  return std::size_t(settings.fields.oof_shells) + settings.srf.shells +
         (scene.vertex_count() + block - 1) / block;
}

std::vector<std::uint8_t> bake_shadowfield_shard(const Scene& scene,
                                                 const ShadowfieldMaterial& material,
                                                 const ShadowfieldShardBake& bake,
                                                 std::size_t first, std::size_t count,
                                                 const Context& ctx) {
  const ShadowfieldBakeSettings& s = bake.settings;
  check_shadowfield_bake_settings(s);
  ShadowfieldShardHeader h = shadowfield_shard_header(scene, bake);
  if (first > h.units || count > h.units - first) {
    throw Error("shadowfield shard: " + std::string(kShadowfieldShardUnit) + " [" +
                std::to_string(first) + ", " + std::to_string(first + count) +
                ") are beyond the bake's " + std::to_string(h.units));
  }
  h.first = first;
  h.count = count;
  const ShadowfieldShardSpan span = shadowfield_shard_span(s, h.vertices, first, count);
  ShadowfieldObject object = shadowfield_shard_object(scene, material, s);
  const EmbreeScene rays(shadowfield_rays_scene(object), ctx);

  auto start = std::chrono::steady_clock::now();
  const std::vector<float> oof =
      bake_occlusion_shells(object, rays, s.fields, span.oof_first, span.oof_count, ctx);
  h.seconds_fields = seconds_since(start);
  ShadowfieldBasisReport basis;
  std::vector<float> srf;
  if (span.srf_count > 0) {
    basis = bake_surface_basis(object, rays, s.basis, ctx);
    h.basis_rays = basis.rays_traced;
    h.basis_samples = basis.samples;
    h.singular_values = basis.singular_values.size();
    h.seconds_basis = basis.seconds;
    start = std::chrono::steady_clock::now();
    srf = bake_source_radiance_shells(object, rays, s.srf, span.srf_first, span.srf_count, ctx);
    h.seconds_srf = seconds_since(start);
  }
  start = std::chrono::steady_clock::now();
  std::vector<float> transfer;
  h.without_transfer = bake_self_transfer_range(object, rays, s.fields, span.vertex_first,
                                                span.vertex_count, &transfer, ctx);
  h.seconds_transfer = seconds_since(start);

  ShardPayloadWriter out;
  out.put(h);
  out.put_array(bake.brdf.data(), bake.brdf.size());
  out.put_vector(oof);
  if (span.srf_count > 0) put_shadowfield_shard_basis(out, object, basis);
  out.put_vector(srf);
  out.put_vector(transfer);
  return std::move(out).bytes();
}

ShadowfieldBakeResult merge_shadowfield_shards(const Scene& scene,
                                               const ShadowfieldMaterial& material,
                                               const ShadowfieldShardBake& bake,
                                               const std::vector<std::vector<std::uint8_t>>& parts,
                                               const Context&) {
  const ShadowfieldBakeSettings& s = bake.settings;
  check_shadowfield_bake_settings(s);
  const ShadowfieldShardHeader expected = shadowfield_shard_header(scene, bake);
  const std::vector<ShadowfieldShardPart> read =
      read_shadowfield_shard_parts(parts, expected, bake, material.terms());
  const ShadowfieldShardPart& with_basis = shadowfield_shard_basis_part(read);

  ShadowfieldBakeResult result;
  ShadowfieldObject& object = result.object;
  object = shadowfield_shard_object(scene, material, s);
  object.basis = with_basis.basis.basis;
  object.vertex_weights = with_basis.basis.weights;
  object.basis_inverse = with_basis.basis.inverse;
  object.basis_size = s.basis.size;
  result.basis.samples = with_basis.header.basis_samples;
  result.basis.singular_values = with_basis.basis.singular_values;
  result.basis.energy_kept = result.basis.energy_kept_by(s.basis.size);
  result.basis.rays_traced = with_basis.header.basis_rays;
  result.basis.seconds = with_basis.header.seconds_basis;
  object.srf_shells = source_radiance_field_grid(object, s.srf);

  // The fields are field-major: each field's points, shard after shard.
  const std::size_t fields = std::size_t(s.basis.size) * material.terms();
  object.srf.reserve(fields * prt_sf_point_count(&object.srf_shells) * object.order * object.order);
  const std::size_t shell_values =
      prt_sf_points_per_shell(&object.srf_shells) * object.order * object.order;
  for (std::size_t f = 0; f < fields; ++f) {
    for (const ShadowfieldShardPart& part : read) {
      const auto from = part.srf.begin() + std::ptrdiff_t(f * part.span.srf_count * shell_values);
      object.srf.insert(object.srf.end(), from,
                        from + std::ptrdiff_t(part.span.srf_count * shell_values));
    }
  }
  for (const ShadowfieldShardPart& part : read) {
    object.oof.insert(object.oof.end(), part.oof.begin(), part.oof.end());
    object.transfer.insert(object.transfer.end(), part.transfer.begin(), part.transfer.end());
    result.vertices_without_transfer += part.header.without_transfer;
    result.seconds_fields += part.header.seconds_fields;
    result.seconds_transfer += part.header.seconds_transfer;
    result.srf.seconds += part.header.seconds_srf;
  }
  result.srf.points = prt_sf_point_count(&object.srf_shells);
  result.srf.floats = object.srf.size();
  result.srf.rays_traced = result.srf.points * s.srf.directions;
  return result;
}

}  // namespace prt::bake
