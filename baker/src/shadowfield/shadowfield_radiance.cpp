// SPDX-License-Identifier: MIT
#include "prt/baker/shadowfield/shadowfield_radiance.hpp"

#include "prt/baker/shadowfield/shadowfield_fields.hpp"

#include <prt/prt_sh.h>

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "../common/numbers.hpp"
#include "../common/thin_svd.hpp"
#include "../render/parallel_tasks.hpp"
#include "prt/baker/ray_batch.hpp"
#include "prt/baker/sampling.hpp"

namespace prt::bake {
namespace {

constexpr std::size_t kRadianceVerticesPerTask = 64;
constexpr std::size_t kRadiancePointsPerTask = 4;
// Stream key of the SRF's direction set (distinct from the other bakes' tags).
constexpr std::uint64_t kSrfDirectionsTag = 0x535246;  // "SRF"
// The largest field a bake may allocate, in floats: far above any useful grid, well below what
// would exhaust memory silently.
constexpr std::size_t kMaxSrfFloats = std::size_t(1) << 30;

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The mesh and material the bakes read, checked once.
void check_object(const ShadowfieldObject& object, const char* stage) {
  const std::string where = std::string("shadowfield ") + stage + ": ";
  const std::size_t vertices = object.positions.size();
  if (vertices == 0 || object.indices.empty()) throw Error(where + "the object has no triangles");
  if (object.normals.size() != vertices || object.albedo.size() != vertices)
    throw Error(where + "the object needs one normal and one albedo per vertex");
  if (object.indices.size() % 3 != 0)
    throw Error(where + "the object's index count is not a multiple of 3");
  for (std::uint32_t index : object.indices)
    if (index >= vertices)
      throw Error(where + "vertex index " + std::to_string(index) + " is out of range");
  for (const glm::vec3& albedo : object.albedo)
    if (!finite(albedo)) throw Error(where + "the object's albedo is not finite");
  const ShadowfieldMaterial& material = object.material;
  if (material.glossy && (material.brdf.terms == 0 ||
                          material.brdf.outgoing.size() !=
                              std::size_t(material.brdf.terms) * material.brdf.grid.count() ||
                          material.brdf.incident.size() != material.brdf.outgoing.size()))
    throw Error(where + "the glossy material's separable BRDF is incomplete");
}

struct Sphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};

// oof_shells' sphere when set, else the object's bounding sphere (shadowfield_fields.hpp).
Sphere object_sphere(const ShadowfieldObject& object, const char* stage) {
  Sphere sphere;
  if (object.oof_shells.radius > 0.0f) {
    sphere.centre = glm::vec3(object.oof_shells.centre[0], object.oof_shells.centre[1],
                              object.oof_shells.centre[2]);
    sphere.radius = object.oof_shells.radius;
    if (!finite(sphere.centre) || !std::isfinite(sphere.radius))
      throw Error(std::string("shadowfield ") + stage + ": oof_shells' sphere is not finite");
    return sphere;
  }
  const BoundingSphere bounds = bounding_sphere(object.positions);
  sphere.centre = bounds.centre;
  sphere.radius = bounds.radius;
  return sphere;
}

// Unit vertex normals; zero where the normal (or the position) is not usable.
std::vector<glm::vec3> unit_normals(const ShadowfieldObject& object) {
  std::vector<glm::vec3> normals(object.normals.size(), glm::vec3(0.0f));
  for (std::size_t v = 0; v < normals.size(); ++v) {
    const glm::vec3 n = object.normals[v];
    const float length2 = glm::dot(n, n);
    if (std::isfinite(length2) && length2 > 1e-12f && finite(object.positions[v]))
      normals[v] = n / std::sqrt(length2);
  }
  return normals;
}

glm::dvec3 local_direction(const Frame& frame, const glm::vec3& w) {
  return glm::dvec3(glm::dot(frame.t, w), glm::dot(frame.b, w), glm::dot(frame.n, w));
}

double luminance(const glm::vec3& rgb) {
  return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

// h_k of the material at a local incident direction.
double incident_term(const ShadowfieldMaterial& material, std::uint32_t term, const glm::dvec3& w) {
  return material.glossy ? material.brdf.incident_at(term, w) : 1.0 / kPi;
}

// One vertex's samples: column v of every row. Returns the rays cast.
std::size_t sample_vertex(const ShadowfieldObject& object, const EmbreeScene& scene,
                          const std::vector<glm::vec3>& lights, double intensity,
                          const glm::vec3& normal, std::size_t v, RayBatch& batch,
                          std::vector<glm::vec3>& to_light, std::vector<unsigned char>& visible,
                          ShadowfieldRadianceSamples& out) {
  const glm::vec3 p = object.positions[v];
  const glm::vec3 origin = scene.offset_origin(p, normal);
  for (std::size_t l = 0; l < lights.size(); ++l) to_light[l] = lights[l] - origin;
  // tfar = 1: blockers between the vertex and the light only.
  const std::size_t rays =
      batch.cast(origin, normal, to_light.data(), lights.size(), visible.data(), 0.0f, 1.0f);
  const double albedo = luminance(object.albedo[v]);
  const Frame frame(normal);
  const std::uint32_t terms = object.material.terms();
  for (std::size_t l = 0; l < lights.size(); ++l) {
    if (!visible[l]) continue;
    const glm::vec3 d = lights[l] - p;
    const double distance2 = glm::dot(d, d);
    const glm::vec3 w = d / std::sqrt(static_cast<float>(distance2));
    const double cosine = glm::dot(normal, w);
    if (!(cosine > 0.0)) continue;
    const glm::dvec3 local = local_direction(frame, w);
    for (std::uint32_t k = 0; k < terms; ++k)
      out.values[(l * terms + k) * out.vertices + v] =
          albedo * intensity * incident_term(object.material, k, local) * cosine / distance2;
  }
  return rays;
}

void check_progress(const Context& ctx, double fraction, const std::string& stage) {
  if (ctx.progress && !ctx.progress(fraction, stage)) throw Error("cancelled");
}

// The N leading right singular vectors of samples diag(sqrt(W)), unscaled by sqrt(W) and signed
// so each function's largest entry is positive: basis[i * V + v].
std::vector<float> principal_functions(const ShadowfieldRadianceSamples& samples,
                                       const std::vector<float>& weights, std::uint32_t size,
                                       std::vector<double>* singular_values) {
  const Eigen::Index vertices = static_cast<Eigen::Index>(samples.vertices);
  Eigen::VectorXd root(vertices);
  for (Eigen::Index v = 0; v < vertices; ++v) root[v] = std::sqrt(double(weights[v]));
  const Eigen::MatrixXd scaled = Eigen::Map<const RowMajorMatrix>(
                                     samples.values.data(), Eigen::Index(samples.rows), vertices) *
                                 root.asDiagonal();
  const ThinSvd svd = thin_svd(scaled, false);
  const Eigen::VectorXd& sigma = svd.singular_values;
  singular_values->assign(sigma.data(), sigma.data() + sigma.size());
  std::vector<float> basis(std::size_t(size) * samples.vertices, 0.0f);
  for (std::uint32_t i = 0; i < size; ++i) {
    float* function = basis.data() + std::size_t(i) * samples.vertices;
    for (Eigen::Index v = 0; v < vertices; ++v)
      if (root[v] > 0.0) function[v] = static_cast<float>(svd.v(v, i) / root[v]);
    const float* largest = std::max_element(function, function + vertices, [](float a, float b) {
      return std::fabs(a) < std::fabs(b);
    });
    if (*largest < 0.0f)
      for (Eigen::Index v = 0; v < vertices; ++v) function[v] = -function[v];
  }
  return basis;
}

// A^-1 for A = B W B^T, in double from the stored floats.
std::vector<float> normal_matrix_inverse(const std::vector<float>& basis,
                                         const std::vector<float>& weights, std::uint32_t size) {
  const Eigen::Index vertices = static_cast<Eigen::Index>(weights.size());
  const Eigen::MatrixXd b =
      Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          basis.data(), size, vertices)
          .cast<double>();
  const Eigen::VectorXd w =
      Eigen::Map<const Eigen::VectorXf>(weights.data(), vertices).cast<double>();
  const Eigen::MatrixXd a = b * w.asDiagonal() * b.transpose();
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  if (!lu.isInvertible())
    throw Error("shadowfield basis: the basis functions are not independent over the surface");
  const RowMajorMatrix inverse = lu.inverse();
  std::vector<float> out(std::size_t(size) * size);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(inverse.data()[i]);
  return out;
}

void check_srf_object(const ShadowfieldObject& object) {
  check_object(object, "srf");
  if (object.order < 2 || object.order > 6)
    throw Error("shadowfield srf: order must be in 2..6, not " + std::to_string(object.order));
  if (object.basis_size == 0 ||
      object.basis.size() != std::size_t(object.basis_size) * object.positions.size())
    throw Error("shadowfield srf: the object has no surface-radiance basis (bake it first)");
}

// The SRF's direction set: uniform on the sphere (z and phi uniform preserve area).
std::vector<glm::vec3> sphere_directions(std::uint32_t count, std::uint32_t seed) {
  const SampleStream stream(hash_key(seed, kSrfDirectionsTag));
  std::vector<glm::vec3> directions(count);
  for (std::uint32_t j = 0; j < count; ++j) {
    const glm::vec2 u = stream.get_2d(j, 0);
    const double z = 1.0 - 2.0 * u.x, s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * kPi * u.y;
    directions[j] = glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
  }
  return directions;
}

// What one SRF point sees: per direction, the glow g_k(wo) B_i(x) of every (i, k) at the hit.
class SrfPointSampler {
 public:
  SrfPointSampler(const ShadowfieldObject& object, const EmbreeScene& scene,
                  const std::vector<glm::vec3>& directions, const std::vector<glm::vec3>& normals)
      : object_(object),
        scene_(scene),
        directions_(directions),
        normals_(normals),
        terms_(object.material.terms()),
        g_(terms_),
        glow_(Eigen::Index(directions.size()), Eigen::Index(object.basis_size * terms_)) {}

  // glow(j, i K + k) for every direction j from point p.
  const Eigen::MatrixXd& sample(const glm::vec3& p) {
    glow_.setZero();
    for (std::size_t j = 0; j < directions_.size(); ++j) {
      RayHit hit;
      if (scene_.intersect(p, directions_[j], &hit) && hit.mesh == 0 &&
          std::size_t(hit.triangle) * 3 < object_.indices.size())
        add_hit(hit, directions_[j], Eigen::Index(j));
    }
    return glow_;
  }

 private:
  void add_hit(const RayHit& hit, const glm::vec3& w, Eigen::Index row) {
    const std::uint32_t* corner = object_.indices.data() + std::size_t(hit.triangle) * 3;
    const double weight[3] = {1.0 - hit.u - hit.v, hit.u, hit.v};
    glm::vec3 normal(0.0f);
    for (int c = 0; c < 3; ++c) normal += float(weight[c]) * normals_[corner[c]];
    if (!(glm::dot(normal, w) < 0.0f)) return;  // its back, or no usable normal there
    if (object_.material.glossy) {
      const Frame frame(glm::normalize(normal));
      const glm::dvec3 wo = local_direction(frame, -w);
      for (std::uint32_t k = 0; k < terms_; ++k) g_[k] = object_.material.brdf.outgoing_at(k, wo);
    } else {
      g_[0] = 1.0;
    }
    const std::size_t vertices = object_.positions.size();
    for (std::uint32_t i = 0; i < object_.basis_size; ++i) {
      const float* function = object_.basis.data() + std::size_t(i) * vertices;
      double value = 0.0;
      for (int c = 0; c < 3; ++c) value += weight[c] * function[corner[c]];
      for (std::uint32_t k = 0; k < terms_; ++k)
        glow_(row, Eigen::Index(i * terms_ + k)) = g_[k] * value;
    }
  }

  const ShadowfieldObject& object_;
  const EmbreeScene& scene_;
  const std::vector<glm::vec3>& directions_;
  const std::vector<glm::vec3>& normals_;
  std::uint32_t terms_;
  std::vector<double> g_;  // g_k(wo) at the current hit
  Eigen::MatrixXd glow_;
};

}  // namespace

void check_basis_settings(const ShadowfieldBasisSettings& settings) {
  if (settings.size == 0) throw Error("shadowfield basis: size (N) must be at least 1");
  if (settings.lights == 0) throw Error("shadowfield basis: lights must be at least 1");
  if (!(settings.light_distance > 1.0) || !std::isfinite(settings.light_distance))
    throw Error(
        "shadowfield basis: light_distance must be finite and above 1 (lights outside the "
        "bounding sphere)");
}

void check_srf_settings(const SrfSettings& settings) {
  if (settings.shells < 1 || settings.shells > 256)
    throw Error("shadowfield srf: shells must be in 1..256");
  if (settings.face_size < 1 || settings.face_size > 256)
    throw Error("shadowfield srf: face_size must be in 1..256");
  if (!(settings.inner > 0.0f) || !std::isfinite(settings.inner))
    throw Error("shadowfield srf: inner must be finite and above 0");
  if (!(settings.outer >= settings.inner) || !std::isfinite(settings.outer))
    throw Error("shadowfield srf: outer must be finite and at least inner");
  if (settings.directions < 1 || settings.directions > (1u << 20))
    throw Error("shadowfield srf: directions must be in 1..2^20");
}

std::vector<glm::vec3> shadowfield_light_positions(std::uint32_t count, const glm::vec3& centre,
                                                   float distance) {
  const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
  std::vector<glm::vec3> lights(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count, s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden_angle * i;
    lights[i] =
        centre + distance * glm::vec3(float(s * std::cos(phi)), float(z), float(s * std::sin(phi)));
  }
  return lights;
}

std::vector<float> shadowfield_vertex_weights(const ShadowfieldObject& object) {
  std::vector<double> sum(object.positions.size(), 0.0);
  for (std::size_t t = 0; t + 2 < object.indices.size(); t += 3) {
    const std::uint32_t a = object.indices[t], b = object.indices[t + 1], c = object.indices[t + 2];
    if (a >= sum.size() || b >= sum.size() || c >= sum.size()) continue;
    const glm::dvec3 pa(object.positions[a]), pb(object.positions[b]), pc(object.positions[c]);
    const double area = 0.5 * glm::length(glm::cross(pb - pa, pc - pa));
    if (!std::isfinite(area)) continue;
    for (std::uint32_t v : {a, b, c}) sum[v] += area / 3.0;
  }
  return std::vector<float>(sum.begin(), sum.end());
}

ShadowfieldRadianceSamples shadowfield_radiance_samples(const ShadowfieldObject& object,
                                                        const EmbreeScene& scene,
                                                        const std::vector<glm::vec3>& lights,
                                                        double intensity, const Context& ctx) {
  check_object(object, "basis");
  ShadowfieldRadianceSamples samples;
  samples.vertices = object.positions.size();
  samples.rows = lights.size() * object.material.terms();
  samples.values.assign(samples.rows * samples.vertices, 0.0);
  const std::vector<glm::vec3> normals = unit_normals(object);
  const std::size_t tasks =
      (samples.vertices + kRadianceVerticesPerTask - 1) / kRadianceVerticesPerTask;
  std::vector<std::uint64_t> task_rays(tasks, 0);
  render::parallel_tasks(tasks, ctx, "shadowfield basis: samples", [&](std::size_t task) {
    RayBatch batch(scene);
    std::vector<glm::vec3> to_light(lights.size());
    std::vector<unsigned char> visible(lights.size());
    const std::size_t end = std::min(samples.vertices, (task + 1) * kRadianceVerticesPerTask);
    for (std::size_t v = task * kRadianceVerticesPerTask; v < end; ++v)
      if (normals[v] != glm::vec3(0.0f))
        task_rays[task] += sample_vertex(object, scene, lights, intensity, normals[v], v, batch,
                                         to_light, visible, samples);
  });
  for (std::uint64_t rays : task_rays) samples.rays_traced += rays;
  return samples;
}

double ShadowfieldBasisReport::energy_kept_by(std::size_t n) const {
  double total = 0.0, kept = 0.0;
  for (std::size_t i = 0; i < singular_values.size(); ++i) {
    total += singular_values[i] * singular_values[i];
    if (i < n) kept += singular_values[i] * singular_values[i];
  }
  return total > 0.0 ? kept / total : 1.0;
}

ShadowfieldBasisReport bake_surface_basis(ShadowfieldObject& object, const EmbreeScene& scene,
                                          const ShadowfieldBasisSettings& settings,
                                          const Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  check_basis_settings(settings);
  check_object(object, "basis");
  const std::size_t vertices = object.positions.size();
  const std::size_t sample_count = std::size_t(settings.lights) * object.material.terms();
  if (settings.size > vertices || settings.size > sample_count)
    throw Error("shadowfield basis: size (N = " + std::to_string(settings.size) +
                ") exceeds the vertex count (" + std::to_string(vertices) +
                ") or the sample count (" + std::to_string(sample_count) + ")");
  const Sphere sphere = object_sphere(object, "basis");
  std::vector<float> weights = shadowfield_vertex_weights(object);
  double total_weight = 0.0;
  for (float w : weights) total_weight += w;
  if (!(total_weight > 0.0)) throw Error("shadowfield basis: the object has no surface area");

  const float distance = static_cast<float>(settings.light_distance) * sphere.radius;
  const std::vector<glm::vec3> lights =
      shadowfield_light_positions(settings.lights, sphere.centre, distance);
  const ShadowfieldRadianceSamples samples =
      shadowfield_radiance_samples(object, scene, lights, double(distance) * distance, ctx);

  ShadowfieldBasisReport report;
  report.samples = samples.rows;
  report.rays_traced = samples.rays_traced;
  check_progress(ctx, 0.0, "shadowfield basis: pca");
  std::vector<float> basis =
      principal_functions(samples, weights, settings.size, &report.singular_values);
  object.basis_inverse = normal_matrix_inverse(basis, weights, settings.size);
  object.basis = std::move(basis);
  object.basis_size = settings.size;
  object.vertex_weights = std::move(weights);
  check_progress(ctx, 1.0, "shadowfield basis: pca");
  report.energy_kept = report.energy_kept_by(settings.size);
  report.seconds = seconds_since(start);
  ctx.info("shadowfield basis: " + std::to_string(settings.size) + " functions keep " +
           std::to_string(100.0 * report.energy_kept) + "% of the energy of " +
           std::to_string(report.samples) + " samples");
  return report;
}

prt_sf_shells source_radiance_field_grid(const ShadowfieldObject& object,
                                         const SrfSettings& settings) {
  check_srf_settings(settings);
  check_srf_object(object);
  const Sphere sphere = object_sphere(object, "srf");
  prt_sf_shells shells{};
  for (int a = 0; a < 3; ++a) shells.centre[a] = sphere.centre[a];
  shells.radius = sphere.radius;
  shells.inner = settings.inner;
  shells.outer = settings.shells == 1 ? settings.inner : settings.outer;
  shells.shells = settings.shells;
  shells.face_size = settings.face_size;
  const std::size_t fields = std::size_t(object.basis_size) * object.material.terms();
  const std::size_t coefficients = std::size_t(object.order) * object.order;
  const std::uint64_t points = prt_sf_point_count(&shells);
  if (double(fields) * double(points) * double(coefficients) > double(kMaxSrfFloats))
    throw Error("shadowfield srf: " + std::to_string(fields) + " fields of " +
                std::to_string(points) + " points exceed the size limit");
  return shells;
}

std::vector<float> bake_source_radiance_shells(const ShadowfieldObject& object,
                                               const EmbreeScene& scene,
                                               const SrfSettings& settings,
                                               std::uint32_t first_shell, std::uint32_t shell_count,
                                               const Context& ctx) {
  const prt_sf_shells shells = source_radiance_field_grid(object, settings);
  if (first_shell > shells.shells || shell_count > shells.shells - first_shell)
    throw Error("shadowfield srf: shells [" + std::to_string(first_shell) + ", " +
                std::to_string(std::uint64_t(first_shell) + shell_count) + ") are beyond the " +
                std::to_string(shells.shells) + " of the grid");
  const std::uint32_t terms = object.material.terms();
  const std::size_t fields = std::size_t(object.basis_size) * terms;
  const std::size_t coefficients = std::size_t(object.order) * object.order;
  const std::uint64_t first = first_shell * prt_sf_points_per_shell(&shells);
  const std::uint64_t points = shell_count * prt_sf_points_per_shell(&shells);

  const std::vector<glm::vec3> directions = sphere_directions(settings.directions, settings.seed);
  Eigen::MatrixXd sh(Eigen::Index(directions.size()), Eigen::Index(coefficients));
  std::vector<float> y(coefficients);
  for (std::size_t j = 0; j < directions.size(); ++j) {
    prt_sh_eval(object.order, &directions[j].x, y.data());
    for (std::size_t c = 0; c < coefficients; ++c) sh(Eigen::Index(j), Eigen::Index(c)) = y[c];
  }
  const double weight = 4.0 * kPi / double(directions.size());
  const std::vector<glm::vec3> normals = unit_normals(object);

  std::vector<float> srf(fields * points * coefficients, 0.0f);
  const std::size_t tasks =
      std::size_t((points + kRadiancePointsPerTask - 1) / kRadiancePointsPerTask);
  render::parallel_tasks(tasks, ctx, "shadowfield srf", [&](std::size_t task) {
    SrfPointSampler sampler(object, scene, directions, normals);
    const std::uint64_t end = std::min<std::uint64_t>(points, (task + 1) * kRadiancePointsPerTask);
    for (std::uint64_t point = task * kRadiancePointsPerTask; point < end; ++point) {
      float position[3];
      prt_sf_point_position(&shells, first + point, position);
      const Eigen::MatrixXd field =
          sampler.sample(glm::vec3(position[0], position[1], position[2])).transpose() * sh *
          weight;
      for (std::size_t f = 0; f < fields; ++f)
        for (std::size_t c = 0; c < coefficients; ++c)
          srf[(f * points + point) * coefficients + c] =
              static_cast<float>(field(Eigen::Index(f), Eigen::Index(c)));
    }
  });
  return srf;
}

SrfReport bake_source_radiance_fields(ShadowfieldObject& object, const EmbreeScene& scene,
                                      const SrfSettings& settings, const Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  const prt_sf_shells shells = source_radiance_field_grid(object, settings);
  object.srf = bake_source_radiance_shells(object, scene, settings, 0, shells.shells, ctx);
  object.srf_shells = shells;
  SrfReport report;
  report.points = prt_sf_point_count(&shells);
  report.floats = object.srf.size();
  report.rays_traced = report.points * settings.directions;
  report.seconds = seconds_since(start);
  return report;
}

}  // namespace prt::bake
