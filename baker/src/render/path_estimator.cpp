// SPDX-License-Identifier: MIT
#include "path_estimator.hpp"

#include <cmath>

#include "glossy_lobe.hpp"

namespace prt::bake::render {
namespace {

constexpr float kInvPi = 0.318309886183790671538f;

bool usable_normal(const glm::vec3& n) {
  const float len2 = glm::dot(n, n);
  return std::isfinite(len2) && len2 > 1e-12f;
}

// Power heuristic (beta = 2) weight of a strategy with density `a` against one with density `b`.
float power_heuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  return a2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

// The same against two others (the three strategies of a glossy surface), in double.
double power_heuristic(double a, double b, double c) {
  const double a2 = a * a;
  return a2 > 0.0 ? a2 / (a2 + b * b + c * c) : 0.0;
}

}  // namespace

PathEstimator::PathEstimator(const Scene& scene, const EmbreeScene& rays, const io::EnvMap& env,
                             const EnvDistribution& env_distribution,
                             const std::vector<glm::vec3>& vertex_albedo,
                             const std::vector<SurfaceBrdf>& mesh_brdf, int bounces)
    : scene_(scene),
      rays_(rays),
      env_(env),
      env_distribution_(env_distribution),
      vertex_albedo_(vertex_albedo),
      mesh_brdf_(mesh_brdf),
      bounces_(bounces) {
  std::size_t offset = 0;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    first_vertex_.push_back(offset);
    offset += scene.meshes[m].vertex_count();
    vertex_mesh_.resize(offset, static_cast<std::uint32_t>(m));
  }
}

glm::vec3 PathEstimator::sample(const SurfacePoint& point, const SampleStream& stream,
                                std::uint32_t index, std::uint32_t first_pair,
                                std::uint64_t* rays) const {
  glm::vec3 radiance(0.0f), throughput(1.0f);
  SurfacePoint x = point;
  for (int depth = 0;; ++depth) {
    const std::uint32_t pair = first_pair + 2u * static_cast<std::uint32_t>(depth);
    const bool last = depth == bounces_;
    SurfacePoint next;
    const Step step =
        mesh_brdf_[x.mesh].model == SurfaceBrdf::Model::Lambert
            ? lambert_step(x, stream, index, pair, last, &throughput, &radiance, &next, rays)
            : glossy_step(x, stream, index, pair, last, &throughput, &radiance, &next, rays);
    if (step == Step::Stop) break;
    x = next;
  }
  return radiance;
}

PathEstimator::Step PathEstimator::lambert_step(const SurfacePoint& x, const SampleStream& stream,
                                                std::uint32_t index, std::uint32_t pair, bool last,
                                                glm::vec3* throughput, glm::vec3* radiance,
                                                SurfacePoint* next, std::uint64_t* rays) const {
  const bool at_vertex = glm::dot(x.geometric_normal, x.geometric_normal) == 0.0f;
  const glm::vec3 origin =
      rays_.offset_origin(x.position, at_vertex ? x.normal : x.geometric_normal);
  // A direction under the triangle's plane would start inside the surface: it gets nothing.
  auto leaves_surface = [&](const glm::vec3& w) {
    return at_vertex || glm::dot(w, x.geometric_normal) > 0.0f;
  };

  // Strategy 1: a direction from the environment's importance distribution.
  if (env_distribution_.valid()) {
    float env_pdf = 0.0f;
    const glm::vec3 w = env_distribution_.sample(stream.get_2d(index, pair), &env_pdf);
    const float cos_w = glm::dot(x.normal, w);
    if (cos_w > 0.0f && env_pdf > 0.0f && leaves_surface(w)) {
      ++*rays;
      // Find the texels and start loading them now: the ray hides their memory latency.
      const io::EnvMap::Footprint texels = env_.footprint(w);
      env_.prefetch(texels);
      if (!rays_.occluded(origin, w)) {
        const float weight = power_heuristic(env_pdf, cos_w * kInvPi);
        *radiance += *throughput * x.albedo * env_.footprint_radiance(texels) *
                     (kInvPi * cos_w / env_pdf * weight);
      }
    }
  }

  // Strategy 2: a cosine-weighted direction (f cos / pdf = albedo); continues the path.
  const Frame frame(x.normal);
  const glm::vec3 w = frame.to_world(cosine_hemisphere(stream.get_2d(index, pair + 1)));
  const float cos_w = glm::dot(x.normal, w);
  if (!(cos_w > 0.0f) || !leaves_surface(w)) return Step::Stop;
  // Only an escaping ray needs the environment and its multiple-importance weight; their
  // memory is fetched while the ray is traced.
  const io::EnvMap::Footprint texels = env_.footprint(w);
  env_.prefetch(texels);
  const std::size_t cell = env_distribution_.valid() ? env_distribution_.cell(w) : 0;
  if (env_distribution_.valid()) env_distribution_.prefetch_cell(cell);
  auto escaped = [&] {
    const float weight = env_distribution_.valid()
                             ? power_heuristic(cos_w * kInvPi, env_distribution_.cell_pdf(cell))
                             : 1.0f;
    return *throughput * x.albedo * env_.footprint_radiance(texels) * weight;
  };
  ++*rays;
  if (last) {
    if (!rays_.occluded(origin, w)) *radiance += escaped();
    return Step::Stop;
  }
  RayHit hit;
  if (!rays_.intersect(origin, w, &hit)) {
    *radiance += escaped();
    return Step::Stop;
  }
  if (hit.mesh >= scene_.meshes.size()) return Step::Stop;  // an occluder: black
  *throughput *= x.albedo;
  if (*throughput == glm::vec3(0.0f)) return Step::Stop;  // a black surface ends the path
  *next = surface_at(hit, w);
  return Step::Continue;
}

PathEstimator::Step PathEstimator::glossy_step(const SurfacePoint& x, const SampleStream& stream,
                                               std::uint32_t index, std::uint32_t pair, bool last,
                                               glm::vec3* throughput, glm::vec3* radiance,
                                               SurfacePoint* next, std::uint64_t* rays) const {
  const GlossyLobe lobe(mesh_brdf_[x.mesh], x.normal, x.outgoing);
  if (!lobe.visible()) return Step::Stop;  // seen from behind: f = 0
  const bool at_vertex = glm::dot(x.geometric_normal, x.geometric_normal) == 0.0f;
  const glm::vec3 origin =
      rays_.offset_origin(x.position, at_vertex ? x.normal : x.geometric_normal);
  auto leaves_surface = [&](const glm::vec3& w) {
    return at_vertex || glm::dot(w, x.geometric_normal) > 0.0f;
  };

  // Strategy 1: the environment's importance distribution.
  if (env_distribution_.valid()) {
    float env_pdf = 0.0f;
    const glm::vec3 w = env_distribution_.sample(stream.get_2d(index, pair), &env_pdf);
    const float cos_w = glm::dot(x.normal, w);
    const double f = cos_w > 0.0f && env_pdf > 0.0f && leaves_surface(w) ? lobe.f(w) : 0.0;
    if (f > 0.0) {
      ++*rays;
      if (!rays_.occluded(origin, w)) {
        const GlossyLobe::Densities d = lobe.densities(w);
        const double weight = power_heuristic(env_pdf, d.cosine, d.lobe);
        *radiance += *throughput * x.albedo * env_.radiance(w) *
                     static_cast<float>(f * cos_w / env_pdf * weight);
      }
    }
  }

  // Strategies 2 and 3: cosine or lobe sampling, one picked at random; continues the path.
  const GlossyLobe::Sample sample = lobe.sample(stream.get_2d(index, pair + 1));
  const glm::vec3 w = sample.direction;
  const float cos_w = glm::dot(x.normal, w);
  if (!(cos_w > 0.0f) || !leaves_surface(w)) return Step::Stop;
  const GlossyLobe::Densities d = lobe.densities(w);
  const double f = lobe.f(w), picked = sample.from_lobe ? d.lobe : d.cosine;
  if (!(picked > 0.0) || !(f > 0.0)) return Step::Stop;
  // Light from the environment: the one-sample estimate of the picked strategy, weighted by the
  // power heuristic over all three.
  auto escaped = [&] {
    const double env_pdf = env_distribution_.valid() ? env_distribution_.pdf(w) : 0.0;
    const double weight = sample.from_lobe ? power_heuristic(d.lobe, d.cosine, env_pdf)
                                           : power_heuristic(d.cosine, d.lobe, env_pdf);
    return *throughput * x.albedo * env_.radiance(w) *
           static_cast<float>(f * cos_w / picked * weight);
  };
  ++*rays;
  if (last) {
    if (!rays_.occluded(origin, w)) *radiance += escaped();
    return Step::Stop;
  }
  RayHit hit;
  if (!rays_.intersect(origin, w, &hit)) {
    *radiance += escaped();
    return Step::Stop;
  }
  if (hit.mesh >= scene_.meshes.size()) return Step::Stop;  // an occluder: black
  // Light from other surfaces has only these two strategies: the path goes on with the density
  // of the direction whichever strategy picked it (their balance heuristic).
  *throughput *= x.albedo * static_cast<float>(f * cos_w / d.sum());
  if (*throughput == glm::vec3(0.0f)) return Step::Stop;
  *next = surface_at(hit, w);
  return Step::Continue;
}

SurfacePoint PathEstimator::surface_at(const RayHit& hit, const glm::vec3& dir) const {
  const Mesh& mesh = scene_.meshes[hit.mesh];
  const std::uint32_t i0 = mesh.indices[3 * hit.triangle], i1 = mesh.indices[3 * hit.triangle + 1],
                      i2 = mesh.indices[3 * hit.triangle + 2];
  const float w0 = 1.0f - hit.u - hit.v;
  const glm::vec3 &p0 = mesh.positions[i0], &p1 = mesh.positions[i1], &p2 = mesh.positions[i2];
  SurfacePoint point;
  point.position = w0 * p0 + hit.u * p1 + hit.v * p2;
  glm::vec3 ng = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  if (glm::dot(ng, dir) > 0.0f) ng = -ng;
  point.geometric_normal = ng;
  glm::vec3 ns = ng;
  if (mesh.normals.size() == mesh.positions.size()) {
    const glm::vec3 n = w0 * mesh.normals[i0] + hit.u * mesh.normals[i1] + hit.v * mesh.normals[i2];
    if (usable_normal(n)) ns = glm::normalize(n);
  }
  point.normal = glm::dot(ns, ng) < 0.0f ? -ns : ns;
  point.outgoing = -dir;
  point.mesh = hit.mesh;
  const std::size_t first = first_vertex_[hit.mesh];
  point.albedo = w0 * vertex_albedo_[first + i0] + hit.u * vertex_albedo_[first + i1] +
                 hit.v * vertex_albedo_[first + i2];
  return point;
}

bool PathEstimator::vertex_point(std::size_t vertex, SurfacePoint* point) const {
  const std::uint32_t m = vertex_mesh_[vertex];
  const Mesh& mesh = scene_.meshes[m];
  const std::size_t local = vertex - first_vertex_[m];
  if (local >= mesh.normals.size() || !usable_normal(mesh.normals[local])) return false;
  const glm::vec3 p = mesh.positions[local];
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  point->position = p;
  point->normal = glm::normalize(mesh.normals[local]);
  point->geometric_normal = glm::vec3(0.0f);
  point->albedo = vertex_albedo_[vertex];
  point->outgoing = point->normal;
  point->mesh = m;
  return true;
}

}  // namespace prt::bake::render
