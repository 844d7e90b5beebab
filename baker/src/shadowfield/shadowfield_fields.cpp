// SPDX-License-Identifier: MIT
#include "prt/baker/shadowfield/shadowfield_fields.hpp"

#include <prt/prt_sh.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "../common/numbers.hpp"
#include "../render/parallel_tasks.hpp"
#include "../render/vertex_directions.hpp"
#include "prt/baker/ray_batch.hpp"
#include "prt/baker/sampling.hpp"

namespace prt::bake {
namespace {

constexpr std::size_t kFieldPointsPerTask = 64;
constexpr std::size_t kFieldVerticesPerTask = 64;
// Stream keys, distinct from the other bakes' and the reference renderer's.
constexpr std::uint64_t kFieldDirectionsTag = 0x53464f46;  // "SFOF"
constexpr std::uint64_t kTransferTag = 0x53465454;         // "SFTT"

void check_range(const char* name, std::uint32_t value, std::uint32_t lo, std::uint32_t hi) {
  if (value < lo || value > hi) {
    throw Error("shadowfield fields: " + std::string(name) + " is " + std::to_string(value) +
                ", must be in " + std::to_string(lo) + ".." + std::to_string(hi));
  }
}

void check_order(std::uint32_t order) {
  check_range("order", order, 2, 6);
}

std::size_t coefficient_count(std::uint32_t order) {
  return static_cast<std::size_t>(order) * order;
}

// The SH of every direction of a fixed set, and the set split by the horizon of one axis so that
// RayBatch, which casts only above a normal's horizon, casts each half in packets.
class FieldDirections {
 public:
  FieldDirections(std::uint32_t order, std::uint32_t count, std::uint32_t seed)
      : coeffs_(coefficient_count(order)), basis_(count * coeffs_) {
    const std::vector<glm::vec3> directions = occlusion_field_directions(count, seed);
    for (std::uint32_t j = 0; j < count; ++j) {
      const glm::vec3& w = directions[j];
      prt_sh_eval(order, &w.x, basis_.data() + j * coeffs_);
      // The split RayBatch::cast makes, so each half is cast whole.
      if (glm::dot(kAxis, w) > 0.0f) {
        upper_.push_back(w);
        upper_index_.push_back(j);
      } else if (glm::dot(-kAxis, w) > 0.0f) {
        lower_.push_back(w);
        lower_index_.push_back(j);
      } else {
        horizon_.push_back(w);
        horizon_index_.push_back(j);
      }
    }
  }

  std::size_t size() const { return basis_.size() / coeffs_; }

  // escaped[j] = 1 when direction j from `origin` misses the object.
  void cast(const EmbreeScene& rays, RayBatch& batch, const glm::vec3& origin,
            std::vector<unsigned char>& flags, std::vector<unsigned char>& escaped) const {
    flags.resize(size());
    escaped.assign(size(), 0);
    batch.cast(origin, kAxis, upper_.data(), upper_.size(), flags.data());
    for (std::size_t k = 0; k < upper_.size(); ++k) escaped[upper_index_[k]] = flags[k];
    batch.cast(origin, -kAxis, lower_.data(), lower_.size(), flags.data());
    for (std::size_t k = 0; k < lower_.size(); ++k) escaped[lower_index_[k]] = flags[k];
    for (std::size_t k = 0; k < horizon_.size(); ++k)
      escaped[horizon_index_[k]] = rays.occluded(origin, horizon_[k]) ? 0 : 1;
  }

  // out[i] = (4 pi / M) sum over escaped j of y_i(w_j).
  void project(const std::vector<unsigned char>& escaped, std::vector<double>& sum,
               float* out) const {
    sum.assign(coeffs_, 0.0);
    for (std::size_t j = 0; j < escaped.size(); ++j) {
      if (!escaped[j]) continue;
      const float* y = basis_.data() + j * coeffs_;
      for (std::size_t i = 0; i < coeffs_; ++i) sum[i] += y[i];
    }
    const double weight = 4.0 * kPi / static_cast<double>(size());
    for (std::size_t i = 0; i < coeffs_; ++i) out[i] = static_cast<float>(sum[i] * weight);
  }

 private:
  static constexpr glm::vec3 kAxis{0.0f, 1.0f, 0.0f};
  std::size_t coeffs_;
  std::vector<float> basis_;  // direction-major, n^2 per direction
  std::vector<glm::vec3> upper_, lower_, horizon_;
  std::vector<std::uint32_t> upper_index_, lower_index_, horizon_index_;
};

void check_object(const ShadowfieldObject& object, const ShadowfieldFieldSettings& settings) {
  check_shadowfield_field_settings(settings);
  if (object.order != settings.order) {
    throw Error("shadowfield fields: the object has order " + std::to_string(object.order) +
                ", the settings " + std::to_string(settings.order));
  }
  if (object.positions.empty()) throw Error("shadowfield fields: the object has no vertices");
  if (object.normals.size() != object.positions.size()) {
    throw Error("shadowfield fields: the object has " + std::to_string(object.normals.size()) +
                " normals for " + std::to_string(object.positions.size()) + " vertices");
  }
}

// One vertex's transfer: sum[k * n^2 + i] = sum over unblocked directions of weight_k y_i, with
// weight_k = pi h_k(w_local) (1 for a diffuse surface, h = 1/pi).
class TransferSampler {
 public:
  TransferSampler(const ShadowfieldObject& object, const EmbreeScene& rays,
                  const ShadowfieldFieldSettings& settings)
      : object_(object),
        rays_(rays),
        settings_(settings),
        coeffs_(coefficient_count(object.order)),
        terms_(object.material.terms()),
        batch_(rays),
        local_(settings.transfer_rays),
        world_(settings.transfer_rays),
        visible_(settings.transfer_rays),
        y_(coeffs_),
        sum_(terms_ * coeffs_) {}

  // Writes terms x n^2 values to out; false (and zeros) for a vertex without a usable normal.
  bool vertex(std::size_t v, float* out) {
    const glm::vec3 p = object_.positions[v], normal = object_.normals[v];
    std::fill(out, out + terms_ * coeffs_, 0.0f);
    if (!render::usable_normal(normal) || !render::finite_point(p)) return false;
    const glm::vec3 n = glm::normalize(normal);
    const render::VertexDirections directions(settings_.seed, v, n, kTransferTag);
    for (std::uint32_t i = 0; i < settings_.transfer_rays; ++i) {
      local_[i] = directions.local(i);
      world_[i] = directions.frame.to_world(local_[i]);
    }
    // Directions on the horizon get no weight; the batch marks them not visible.
    batch_.cast(rays_.offset_origin(p, n), n, world_.data(), world_.size(), visible_.data());
    std::fill(sum_.begin(), sum_.end(), 0.0);
    for (std::uint32_t d = 0; d < settings_.transfer_rays; ++d) {
      if (!visible_[d]) continue;
      prt_sh_eval(object_.order, &world_[d].x, y_.data());
      for (std::uint32_t k = 0; k < terms_; ++k) {
        const double weight = term_weight(k, local_[d]);
        double* s = sum_.data() + k * coeffs_;
        for (std::size_t i = 0; i < coeffs_; ++i) s[i] += weight * y_[i];
      }
    }
    const double scale = 1.0 / settings_.transfer_rays;
    for (std::size_t i = 0; i < sum_.size(); ++i) out[i] = static_cast<float>(sum_[i] * scale);
    return true;
  }

 private:
  double term_weight(std::uint32_t k, const glm::vec3& local) const {
    if (!object_.material.glossy) return 1.0;
    return kPi * object_.material.brdf.incident_at(k, glm::dvec3(local));
  }

  const ShadowfieldObject& object_;
  const EmbreeScene& rays_;
  const ShadowfieldFieldSettings& settings_;
  std::size_t coeffs_;
  std::uint32_t terms_;
  RayBatch batch_;
  std::vector<glm::vec3> local_, world_;
  std::vector<unsigned char> visible_;
  std::vector<float> y_;
  std::vector<double> sum_;
};

}  // namespace

void check_shadowfield_field_settings(const ShadowfieldFieldSettings& s) {
  check_order(s.order);
  check_range("oof_shells", s.oof_shells, 1, 64);
  check_range("oof_face_size", s.oof_face_size, 1, 128);
  check_range("field_directions", s.field_directions, 1, 65536);
  check_range("transfer_rays", s.transfer_rays, 1, 65536);
  if (!(std::isfinite(s.inner) && s.inner > 0.0f)) {
    throw Error("shadowfield fields: inner is " + std::to_string(s.inner) +
                ", must be finite and > 0");
  }
  if (!std::isfinite(s.outer) || (s.oof_shells > 1 && !(s.outer > s.inner)) ||
      !(s.outer >= s.inner)) {
    throw Error("shadowfield fields: outer is " + std::to_string(s.outer) +
                ", must be finite and above inner (" + std::to_string(s.inner) +
                "; equal only with one shell)");
  }
}

BoundingSphere bounding_sphere(const std::vector<glm::vec3>& positions) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  float largest = 0.0f;
  bool any = false;
  for (const glm::vec3& p : positions) {
    if (!render::finite_point(p)) continue;
    any = true;
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  if (!any) throw Error("shadowfield fields: no finite vertex position to bound");
  BoundingSphere sphere;
  sphere.centre = 0.5f * (lo + hi);
  float radius = 0.0f;
  for (const glm::vec3& p : positions)
    if (render::finite_point(p)) radius = std::max(radius, glm::distance(p, sphere.centre));
  // Relative to float precision of the coordinates, so shells of a point stay apart.
  sphere.radius = std::max(radius, 1e-5f * std::max(1.0f, largest));
  return sphere;
}

ShadowfieldObject make_shadowfield_object(const Scene& scene, const ShadowfieldMaterial& material,
                                          std::uint32_t order) {
  check_order(order);
  if (material.glossy && material.brdf.terms == 0) {
    throw Error("shadowfield fields: a glossy material needs at least one BRDF term");
  }
  if (scene.vertex_count() == 0) throw Error("shadowfield fields: the scene has no vertices");
  ShadowfieldObject object;
  object.order = order;
  object.material = material;
  for (const Mesh& mesh : scene.meshes) {
    const auto first = static_cast<std::uint32_t>(object.positions.size());
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const glm::vec3 n = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f);
      object.positions.push_back(mesh.positions[v]);
      // Unit, as the runtime rebuilds the tangent frame from it; an unusable one is stored as 0.
      object.normals.push_back(render::usable_normal(n) ? glm::normalize(n) : glm::vec3(0.0f));
      object.albedo.push_back(scene.vertex_albedo(mesh, v));
    }
    for (std::uint32_t index : mesh.indices) object.indices.push_back(first + index);
  }
  return object;
}

std::vector<glm::vec3> occlusion_field_directions(std::uint32_t count, std::uint32_t seed) {
  const SampleStream stream(hash_key(seed, 0, kFieldDirectionsTag));
  std::vector<glm::vec3> directions(count);
  for (std::uint32_t j = 0; j < count; ++j) {
    const glm::vec2 u = stream.get_2d(j, 0);
    const double z = 1.0 - 2.0 * u.x, s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * kPi * u.y;
    directions[j] = glm::vec3(glm::dvec3(s * std::cos(phi), s * std::sin(phi), z));
  }
  return directions;
}

prt_sf_shells occlusion_field_grid(const ShadowfieldObject& object,
                                   const ShadowfieldFieldSettings& settings) {
  check_object(object, settings);
  const BoundingSphere sphere = bounding_sphere(object.positions);
  prt_sf_shells grid{};
  for (int c = 0; c < 3; ++c) grid.centre[c] = sphere.centre[c];
  grid.radius = sphere.radius;
  grid.inner = settings.inner;
  grid.outer = settings.oof_shells == 1 ? settings.inner : settings.outer;
  grid.shells = settings.oof_shells;
  grid.face_size = settings.oof_face_size;
  return grid;
}

std::vector<float> bake_occlusion_shells(const ShadowfieldObject& object, const EmbreeScene& rays,
                                         const ShadowfieldFieldSettings& settings,
                                         std::uint32_t first_shell, std::uint32_t shell_count,
                                         const Context& ctx) {
  const prt_sf_shells grid = occlusion_field_grid(object, settings);
  if (first_shell > grid.shells || shell_count > grid.shells - first_shell) {
    throw Error("shadowfield fields: occlusion shells [" + std::to_string(first_shell) + ", " +
                std::to_string(std::uint64_t(first_shell) + shell_count) + ") are beyond the " +
                std::to_string(grid.shells) + " of the grid");
  }
  const std::size_t coeffs = coefficient_count(settings.order);
  const auto per_shell = static_cast<std::size_t>(prt_sf_points_per_shell(&grid));
  const std::size_t first = first_shell * per_shell, points = shell_count * per_shell;
  const FieldDirections directions(settings.order, settings.field_directions, settings.seed);
  std::vector<float> field(points * coeffs);
  const std::size_t tasks = (points + kFieldPointsPerTask - 1) / kFieldPointsPerTask;
  render::parallel_tasks(tasks, ctx, "shadowfield: occlusion field", [&](std::size_t task) {
    RayBatch batch(rays);
    std::vector<unsigned char> flags, escaped;
    std::vector<double> sum;
    const std::size_t end = std::min(points, (task + 1) * kFieldPointsPerTask);
    for (std::size_t p = task * kFieldPointsPerTask; p < end; ++p) {
      glm::vec3 origin;
      prt_sf_point_position(&grid, first + p, &origin.x);
      directions.cast(rays, batch, origin, flags, escaped);
      directions.project(escaped, sum, field.data() + p * coeffs);
    }
  });
  return field;
}

void bake_occlusion_field(ShadowfieldObject& object, const EmbreeScene& rays,
                          const ShadowfieldFieldSettings& settings, const Context& ctx) {
  object.oof = bake_occlusion_shells(object, rays, settings, 0, settings.oof_shells, ctx);
  object.oof_shells = occlusion_field_grid(object, settings);
}

std::size_t bake_self_transfer_range(const ShadowfieldObject& object, const EmbreeScene& rays,
                                     const ShadowfieldFieldSettings& settings, std::size_t first,
                                     std::size_t count, std::vector<float>* transfer,
                                     const Context& ctx) {
  check_object(object, settings);
  const std::size_t vertices = object.positions.size();
  if (first > vertices || count > vertices - first) {
    throw Error("shadowfield fields: transfer vertices [" + std::to_string(first) + ", " +
                std::to_string(first + count) + ") are beyond the object's " +
                std::to_string(vertices));
  }
  const std::size_t stride = object.material.terms() * coefficient_count(object.order);
  transfer->assign(count * stride, 0.0f);
  std::vector<unsigned char> bad(count, 0);
  const std::size_t tasks = (count + kFieldVerticesPerTask - 1) / kFieldVerticesPerTask;
  render::parallel_tasks(tasks, ctx, "shadowfield: transfer", [&](std::size_t task) {
    TransferSampler sampler(object, rays, settings);
    const std::size_t end = std::min(count, (task + 1) * kFieldVerticesPerTask);
    for (std::size_t v = task * kFieldVerticesPerTask; v < end; ++v)
      bad[v] = sampler.vertex(first + v, transfer->data() + v * stride) ? 0 : 1;
  });
  return static_cast<std::size_t>(std::count(bad.begin(), bad.end(), 1));
}

std::size_t bake_self_transfer(ShadowfieldObject& object, const EmbreeScene& rays,
                               const ShadowfieldFieldSettings& settings, const Context& ctx) {
  std::vector<float> transfer;
  const std::size_t without_normal =
      bake_self_transfer_range(object, rays, settings, 0, object.positions.size(), &transfer, ctx);
  if (without_normal > 0) {
    ctx.warn("shadowfield: " + std::to_string(without_normal) +
             " vertices have no usable normal (zero or non-finite) or position; their transfer "
             "is 0");
  }
  object.transfer = std::move(transfer);
  return without_normal;
}

}  // namespace prt::bake
