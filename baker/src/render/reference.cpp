// SPDX-License-Identifier: MIT
#include "prt/baker/reference.hpp"

#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>

#include "../common/numbers.hpp"
#include "parallel_tasks.hpp"
#include "path_estimator.hpp"

namespace prt::bake {
namespace {

// Stream keys: the two halves of a vertex's samples and an image pixel never share a stream.
enum StreamTag : std::uint64_t { kVertexHalfA = 0, kVertexHalfB = 1, kPixel = 2 };

constexpr std::size_t kReferenceVerticesPerTask = 64;

void validate(const ReferenceSettings& settings) {
  if (settings.bounces < 0) throw Error("reference renderer: --bounces must be >= 0");
  if (settings.spp < 2) {
    throw Error("reference renderer: --spp must be >= 2 (two halves for the noise estimate)");
  }
  if (settings.image_spp < 1) throw Error("reference renderer: --image-spp must be >= 1");
  const glm::vec3& a = settings.albedo;
  if (settings.override_albedo &&
      !(a.r >= 0.0f && a.r <= 1.0f && a.g >= 0.0f && a.g <= 1.0f && a.b >= 0.0f && a.b <= 1.0f)) {
    throw Error("reference renderer: --albedo must lie in [0,1]");
  }
}

void check_surface_brdf(const SurfaceBrdf& brdf) {
  if (brdf.model == SurfaceBrdf::Model::Phong) check_brdf(brdf.phong);
  if (brdf.model == SurfaceBrdf::Model::Ggx) check_brdf(brdf.ggx);
}

// One BRDF per mesh: mesh_brdfs, or the one every mesh shares.
std::vector<SurfaceBrdf> brdf_per_mesh(const Scene& scene, const ReferenceSettings& settings) {
  if (settings.mesh_brdfs.empty()) {
    check_surface_brdf(settings.brdf);
    return std::vector<SurfaceBrdf>(scene.meshes.size(), settings.brdf);
  }
  if (settings.mesh_brdfs.size() != scene.meshes.size()) {
    throw Error("reference renderer: " + std::to_string(settings.mesh_brdfs.size()) +
                " mesh BRDFs for " + std::to_string(scene.meshes.size()) + " meshes");
  }
  for (const SurfaceBrdf& brdf : settings.mesh_brdfs) check_surface_brdf(brdf);
  return settings.mesh_brdfs;
}

// The unit direction from `position` to the eye; the normal where there is no eye or it is at
// the position.
glm::vec3 towards_eye(const std::optional<glm::vec3>& eye, const glm::vec3& position,
                      const glm::vec3& normal) {
  if (!eye) return normal;
  const glm::vec3 d = *eye - position;
  const float length = glm::length(d);
  return length > 0.0f && std::isfinite(length) ? d / length : normal;
}

}  // namespace

struct ReferenceRenderer::Impl {
  const Scene& scene;
  const io::EnvMap& env;
  ReferenceSettings settings;
  EmbreeScene rays;
  EnvDistribution env_distribution;
  std::vector<glm::vec3> vertex_albedo;
  std::vector<SurfaceBrdf> mesh_brdf;
  render::PathEstimator estimator;

  Impl(const Scene& scene_in, const io::EnvMap& env_in, const ReferenceSettings& settings_in,
       const Context& ctx)
      : scene(scene_in),
        env(env_in),
        settings(settings_in),
        rays(scene_in, ctx),
        env_distribution(env_in),
        vertex_albedo(albedo_per_vertex(scene_in, settings_in)),
        mesh_brdf(brdf_per_mesh(scene_in, settings_in)),
        estimator(scene, rays, env, env_distribution, vertex_albedo, mesh_brdf,
                  settings_in.bounces) {}

  static std::vector<glm::vec3> albedo_per_vertex(const Scene& scene,
                                                  const ReferenceSettings& settings) {
    std::vector<glm::vec3> albedo;
    albedo.reserve(scene.vertex_count());
    for (const Mesh& mesh : scene.meshes) {
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        albedo.push_back(settings.override_albedo ? settings.albedo : scene.vertex_albedo(mesh, v));
      }
    }
    return albedo;
  }
};

ReferenceRenderer::ReferenceRenderer(const Scene& scene, const io::EnvMap& env,
                                     const ReferenceSettings& settings, const Context& ctx) {
  validate(settings);
  brdf_per_mesh(scene, settings);  // throws before the ray-tracing scene is built
  tbb::task_arena arena(static_cast<int>(ctx.thread_count()));
  arena.execute([&] { impl_ = std::make_unique<Impl>(scene, env, settings, ctx); });
  if (!impl_->env_distribution.valid()) {
    ctx.warn(env.source() + ": the environment is black everywhere; every radiance will be 0");
  }
}

ReferenceRenderer::~ReferenceRenderer() = default;

const EmbreeScene& ReferenceRenderer::embree_scene() const {
  return impl_->rays;
}
const ReferenceSettings& ReferenceRenderer::settings() const {
  return impl_->settings;
}

VertexRadiance ReferenceRenderer::render_vertices(const Context& ctx,
                                                  const std::optional<glm::vec3>& eye) const {
  std::vector<std::size_t> all(impl_->estimator.vertex_count());
  for (std::size_t v = 0; v < all.size(); ++v) all[v] = v;
  return render_vertices(all, ctx, eye);
}

VertexRadiance ReferenceRenderer::render_vertices(const std::vector<std::size_t>& subset,
                                                  const Context& ctx,
                                                  const std::optional<glm::vec3>& eye) const {
  const auto start = std::chrono::steady_clock::now();
  const render::PathEstimator& estimator = impl_->estimator;
  const ReferenceSettings& settings = impl_->settings;
  for (const std::size_t v : subset) {
    if (v >= estimator.vertex_count())
      throw Error("reference renderer: vertex " + std::to_string(v) + " is not in the scene");
  }
  const std::size_t vertices = subset.size();
  const std::uint32_t spp_a = (settings.spp + 1) / 2, spp_b = settings.spp / 2;

  VertexRadiance result;
  result.radiance.assign(vertices, glm::vec3(0.0f));
  std::vector<glm::vec3> difference(vertices, glm::vec3(0.0f));  // mean of A - mean of B
  std::vector<unsigned char> has_normal(vertices, 0);
  const std::size_t tasks = (vertices + kReferenceVerticesPerTask - 1) / kReferenceVerticesPerTask;
  std::vector<std::uint64_t> task_rays(tasks, 0);

  render::parallel_tasks(tasks, ctx, "reference: vertices", [&](std::size_t task) {
    const std::size_t end = std::min(vertices, (task + 1) * kReferenceVerticesPerTask);
    for (std::size_t v = task * kReferenceVerticesPerTask; v < end; ++v) {
      const std::size_t vertex = subset[v];  // v: where the result goes; vertex: which one
      render::SurfacePoint point;
      if (!estimator.vertex_point(vertex, &point)) continue;
      point.outgoing = towards_eye(eye, point.position, point.normal);
      has_normal[v] = 1;
      const SampleStream half_a(hash_key(settings.seed, vertex, kVertexHalfA));
      const SampleStream half_b(hash_key(settings.seed, vertex, kVertexHalfB));
      glm::dvec3 sum_a(0.0), sum_b(0.0);
      for (std::uint32_t i = 0; i < spp_a; ++i) {
        sum_a += glm::dvec3(estimator.sample(point, half_a, i, 0, &task_rays[task]));
      }
      for (std::uint32_t i = 0; i < spp_b; ++i) {
        sum_b += glm::dvec3(estimator.sample(point, half_b, i, 0, &task_rays[task]));
      }
      result.radiance[v] = glm::vec3((sum_a + sum_b) / static_cast<double>(settings.spp));
      difference[v] =
          glm::vec3(sum_a / static_cast<double>(spp_a) - sum_b / static_cast<double>(spp_b));
    }
  });

  // Reductions in vertex order, after the parallel part: deterministic.
  double difference_sq = 0.0, radiance_sq = 0.0;
  std::size_t counted = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    if (!has_normal[v]) {
      ++result.vertices_without_normal;
      continue;
    }
    const glm::dvec3 d(difference[v]), l(result.radiance[v]);
    difference_sq += glm::dot(d, d);
    radiance_sq += glm::dot(l, l);
    ++counted;
  }
  if (counted > 0 && radiance_sq > 0.0) {
    // Var(full) / Var(A - B) = (1/n) / (1/nA + 1/nB) = nA nB / n^2.
    const double rmse = std::sqrt(difference_sq / (3.0 * counted) * spp_a * spp_b) / settings.spp;
    result.relative_rmse = rmse / std::sqrt(radiance_sq / (3.0 * counted));
  }
  if (result.vertices_without_normal > 0) {
    ctx.warn("reference: " + std::to_string(result.vertices_without_normal) +
             " vertices have no usable normal; their radiance is 0");
  }
  for (std::uint64_t r : task_rays) result.stats.rays += r;
  result.stats.seconds = seconds_since(start);
  return result;
}

io::LinearImage ReferenceRenderer::render_image(const io::Camera& camera, int width, int height,
                                                const Context& ctx, RenderStats* stats) const {
  if (width <= 0 || height <= 0) throw Error("reference renderer: image size must be positive");
  const auto start = std::chrono::steady_clock::now();
  const render::PathEstimator& estimator = impl_->estimator;
  const ReferenceSettings& settings = impl_->settings;
  io::LinearImage image;
  image.width = width;
  image.height = height;
  image.pixels.assign(static_cast<std::size_t>(width) * height, glm::vec3(0.0f));
  image.coverage.assign(image.pixels.size(), 0.0f);
  std::vector<std::uint64_t> row_rays(height, 0);

  render::parallel_tasks(
      static_cast<std::size_t>(height), ctx, "reference: image", [&](std::size_t y) {
        for (int x = 0; x < width; ++x) {
          const std::size_t pixel = y * static_cast<std::size_t>(width) + x;
          const SampleStream stream(hash_key(settings.seed, pixel, kPixel));
          glm::dvec3 sum(0.0);
          std::uint32_t hits = 0;
          for (std::uint32_t i = 0; i < settings.image_spp; ++i) {
            const glm::vec2 jitter = stream.get_2d(i, 0);
            const glm::vec3 dir = camera.direction((x + jitter.x) / width, (y + jitter.y) / height);
            ++row_rays[y];
            RayHit hit;
            if (impl_->rays.intersect(camera.eye, dir, &hit)) {
              ++hits;
              if (hit.mesh >= impl_->scene.meshes.size()) continue;  // an occluder: black
              const render::SurfacePoint point = estimator.surface_at(hit, dir);
              sum += glm::dvec3(estimator.sample(point, stream, i, 1, &row_rays[y]));
            } else {
              sum += glm::dvec3(impl_->env.radiance(dir));
            }
          }
          image.pixels[pixel] = glm::vec3(sum / static_cast<double>(settings.image_spp));
          image.coverage[pixel] = static_cast<float>(hits) / static_cast<float>(settings.image_spp);
        }
      });

  if (stats) {
    stats->rays = 0;
    for (std::uint64_t r : row_rays) stats->rays += r;
    stats->seconds = seconds_since(start);
  }
  return image;
}

}  // namespace prt::bake
