// SPDX-License-Identifier: MIT
#include "prt/baker/sh/sh_transfer.hpp"

#include <prt/prt_sh.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>

#include "../common/numbers.hpp"
#include "../render/parallel_tasks.hpp"
#include "../render/vertex_directions.hpp"
#include "prt/baker/ray_batch.hpp"
#include "prt/baker/sampling.hpp"

namespace prt::bake {
namespace {

constexpr std::size_t kShVerticesPerTask = 64;
// Stream key of a vertex's directions (distinct from the reference renderer's tags, so a bake and
// a reference with the same seed never share sample points).
constexpr std::uint64_t kDirectionsTag = 0x5348;  // "SH"

void validate(const ShTransferSettings& s) {
  if (s.order < 1 || s.order > PRT_SH_MAX_ORDER) {
    throw Error("sh transfer: order must be in 1.." + std::to_string(PRT_SH_MAX_ORDER));
  }
  if (s.rays < 1) throw Error("sh transfer: rays per vertex must be >= 1");
  if (s.bounces < 0) throw Error("sh transfer: bounces must be >= 0");
  const glm::vec3& a = s.albedo;
  if (s.override_albedo &&
      !(a.r >= 0.0f && a.r <= 1.0f && a.g >= 0.0f && a.g <= 1.0f && a.b >= 0.0f && a.b <= 1.0f)) {
    throw Error("sh transfer: albedo must lie in [0,1]");
  }
}

// What every pass needs to know about a scene vertex (Scene order).
struct ShVertexTable {
  std::vector<glm::vec3> position, normal, albedo;
  std::vector<unsigned char> usable;       // finite position and usable normal
  std::vector<std::size_t> first_of_mesh;  // per mesh: its first vertex

  ShVertexTable(const Scene& scene, const ShTransferSettings& settings) {
    for (const Mesh& mesh : scene.meshes) {
      first_of_mesh.push_back(position.size());
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const glm::vec3 p = mesh.positions[v];
        const glm::vec3 n = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f);
        const bool ok = render::usable_normal(n) && render::finite_point(p);
        position.push_back(p);
        normal.push_back(ok ? glm::normalize(n) : glm::vec3(0.0f));
        usable.push_back(ok ? 1 : 0);
        albedo.push_back(settings.override_albedo ? settings.albedo : scene.vertex_albedo(mesh, v));
      }
    }
  }
  std::size_t size() const { return position.size(); }
};

// Bakes the vertices [first, first + count) of the table; a bounce pass needs them all.
class TransferBaker {
 public:
  TransferBaker(const Scene& scene, const EmbreeScene* rays, const ShTransferSettings& settings,
                const ShVertexTable& vertices, std::size_t first, std::size_t count)
      : scene_(scene),
        rays_(rays),
        settings_(settings),
        vertices_(vertices),
        first_(first),
        count_(count),
        coeffs_(static_cast<std::size_t>(settings.order) * settings.order),
        tasks_((count + kShVerticesPerTask - 1) / kShVerticesPerTask),
        task_rays_(tasks_, 0) {}

  // Pass 0: rho * mean over directions of V(w) y(w), V = 1 when unshadowed. Row v - first is
  // vertex v's: its directions are keyed by v, so a range's rows are the whole bake's.
  std::vector<float> direct(const Context& ctx) {
    std::vector<float> out(count_ * 3 * coeffs_, 0.0f);
    const bool shadowed = settings_.kind != ShTransferKind::Unshadowed;
    render::parallel_tasks(tasks_, ctx, "sh transfer: direct", [&](std::size_t task) {
      std::vector<double> sum(coeffs_);
      std::vector<float> y(coeffs_);
      std::vector<glm::vec3> w(settings_.rays);
      std::vector<unsigned char> visible(settings_.rays);
      std::unique_ptr<RayBatch> batch;
      if (shadowed) batch = std::make_unique<RayBatch>(*rays_);
      std::uint64_t traced = 0;
      for (std::size_t v = task_begin(task); v < task_end(task); ++v) {
        if (!vertices_.usable[v]) continue;
        const glm::vec3 n = vertices_.normal[v];
        const render::VertexDirections directions(settings_.seed, v, n, kDirectionsTag);
        for (std::uint32_t i = 0; i < settings_.rays; ++i) w[i] = directions(i);
        if (shadowed) {
          // Directions on the horizon get no weight; the batch marks them not visible.
          traced += batch->cast(rays_->offset_origin(vertices_.position[v], n), n, w.data(),
                                w.size(), visible.data());
        } else {
          for (std::uint32_t i = 0; i < settings_.rays; ++i) visible[i] = glm::dot(n, w[i]) > 0.0f;
        }
        std::fill(sum.begin(), sum.end(), 0.0);
        for (std::uint32_t i = 0; i < settings_.rays; ++i) {
          if (!visible[i]) continue;
          prt_sh_eval(settings_.order, &w[i].x, y.data());
          for (std::size_t k = 0; k < coeffs_; ++k) sum[k] += y[k];
        }
        store(v, sum, 0, &out);
      }
      task_rays_[task] += traced;
    });
    return out;
  }

  // One bounce (Sloan 2002 §5): rho * mean over directions that hit the front of a surface of
  // the previous pass's transfer interpolated at the hit. The baker must cover every vertex
  // (`previous` is every vertex's pass).
  std::vector<float> bounce(const std::vector<float>& previous, int index, const Context& ctx) {
    std::vector<float> out(previous.size(), 0.0f);
    const std::string stage = "sh transfer: bounce " + std::to_string(index);
    render::parallel_tasks(tasks_, ctx, stage, [&](std::size_t task) {
      std::vector<double> sum(3 * coeffs_);
      std::vector<glm::vec3> w(settings_.rays);
      std::vector<RayHit> hits(settings_.rays);
      std::vector<unsigned char> found(settings_.rays);
      RayBatch batch(*rays_);
      std::uint64_t traced = 0;
      for (std::size_t v = task_begin(task); v < task_end(task); ++v) {
        if (!vertices_.usable[v]) continue;
        const glm::vec3 n = vertices_.normal[v];
        const render::VertexDirections directions(settings_.seed, v, n, kDirectionsTag);
        for (std::uint32_t i = 0; i < settings_.rays; ++i) w[i] = directions(i);
        // Directions on the horizon get no weight; the batch marks them not found.
        traced += batch.intersect(rays_->offset_origin(vertices_.position[v], n), n, w.data(),
                                  w.size(), hits.data(), found.data());
        std::fill(sum.begin(), sum.end(), 0.0);
        for (std::uint32_t i = 0; i < settings_.rays; ++i)
          if (found[i]) gather(hits[i], w[i], previous, &sum);
        store(v, sum, coeffs_, &out);
      }
      task_rays_[task] += traced;
    });
    return out;
  }

  std::uint64_t rays_traced() const {
    std::uint64_t total = 0;
    for (std::uint64_t r : task_rays_) total += r;
    return total;
  }

 private:
  std::size_t task_begin(std::size_t task) const { return first_ + task * kShVerticesPerTask; }
  std::size_t task_end(std::size_t task) const {
    return first_ + std::min(count_, (task + 1) * kShVerticesPerTask);
  }

  // Writes rho_c * sum / rays for each channel c into row v - first; sum holds channel_stride
  // values per channel (0: one set shared by the three channels).
  void store(std::size_t v, const std::vector<double>& sum, std::size_t channel_stride,
             std::vector<float>* out) const {
    for (int c = 0; c < 3; ++c) {
      const double scale = static_cast<double>(vertices_.albedo[v][c]) / settings_.rays;
      const double* s = sum.data() + c * channel_stride;
      float* t = out->data() + ((v - first_) * 3 + c) * coeffs_;
      for (std::size_t k = 0; k < coeffs_; ++k) t[k] = static_cast<float>(s[k] * scale);
    }
  }

  // Adds the barycentric interpolation of `previous` at the hit to sum (RGB x coefficients),
  // unless the ray arrived at the back of the surface or at an occluder.
  void gather(const RayHit& hit, const glm::vec3& w, const std::vector<float>& previous,
              std::vector<double>* sum) const {
    if (hit.mesh >= scene_.meshes.size()) return;  // an occluder reflects nothing
    const Mesh& mesh = scene_.meshes[hit.mesh];
    const std::size_t first = vertices_.first_of_mesh[hit.mesh];
    const std::size_t corner[3] = {first + mesh.indices[3 * hit.triangle],
                                   first + mesh.indices[3 * hit.triangle + 1],
                                   first + mesh.indices[3 * hit.triangle + 2]};
    const float weight[3] = {1.0f - hit.u - hit.v, hit.u, hit.v};
    glm::vec3 normal(0.0f);
    for (int j = 0; j < 3; ++j) normal += weight[j] * vertices_.normal[corner[j]];
    if (glm::dot(normal, w) >= 0.0f) return;  // back face, or no usable normal at the hit
    for (int j = 0; j < 3; ++j) {
      const float* t = previous.data() + corner[j] * 3 * coeffs_;
      for (std::size_t k = 0; k < 3 * coeffs_; ++k)
        (*sum)[k] += static_cast<double>(weight[j]) * t[k];
    }
  }

  const Scene& scene_;
  const EmbreeScene* rays_;
  const ShTransferSettings& settings_;
  const ShVertexTable& vertices_;
  std::size_t first_, count_, coeffs_, tasks_;
  std::vector<std::uint64_t> task_rays_;  // per task, summed at the end: deterministic
};

}  // namespace

const char* sh_transfer_kind_name(ShTransferKind kind) {
  switch (kind) {
    case ShTransferKind::Unshadowed:
      return "unshadowed";
    case ShTransferKind::Shadowed:
      return "shadowed";
    case ShTransferKind::Interreflected:
      return "interreflected";
  }
  return "unknown";
}

ShTransferKind parse_sh_transfer_kind(const char* name) {
  for (ShTransferKind kind :
       {ShTransferKind::Unshadowed, ShTransferKind::Shadowed, ShTransferKind::Interreflected}) {
    if (name && std::strcmp(name, sh_transfer_kind_name(kind)) == 0) return kind;
  }
  throw Error(std::string("sh transfer: unknown kind '") + (name ? name : "") +
              "' (unshadowed, shadowed or interreflected)");
}

namespace {

// An Embree scene of `scene` when the kind traces rays and none is given (null otherwise).
std::unique_ptr<EmbreeScene> sh_own_rays(const Scene& scene, const EmbreeScene* rays,
                                         const ShTransferSettings& settings, const Context& ctx) {
  std::unique_ptr<EmbreeScene> own;
  if (!rays && settings.kind != ShTransferKind::Unshadowed) {
    tbb::task_arena arena(static_cast<int>(ctx.thread_count()));
    arena.execute([&] { own = std::make_unique<EmbreeScene>(scene, ctx); });
  }
  return own;
}

void warn_sh_without_normal(const ShTransfer& transfer, const Context& ctx) {
  if (transfer.vertices_without_normal == 0) return;
  ctx.warn("sh transfer: " + std::to_string(transfer.vertices_without_normal) +
           " vertices have no usable normal (zero or non-finite) or position; their transfer "
           "is 0");
}

// The direct pass of vertices [first, first + count), without timing or warning.
ShTransfer sh_direct_range(const Scene& scene, const EmbreeScene* rays,
                           const ShTransferSettings& settings, const ShVertexTable& vertices,
                           std::size_t first, std::size_t count, const Context& ctx) {
  if (first > vertices.size() || count > vertices.size() - first) {
    throw Error("sh transfer: vertices [" + std::to_string(first) + ", " +
                std::to_string(first + count) + ") are not all in the scene (" +
                std::to_string(vertices.size()) + " vertices)");
  }
  TransferBaker baker(scene, rays, settings, vertices, first, count);
  ShTransfer result;
  result.order = settings.order;
  result.kind = settings.kind;
  result.vertex_count = count;
  result.coefficients = baker.direct(ctx);
  for (std::size_t v = first; v < first + count; ++v)
    result.vertices_without_normal += vertices.usable[v] ? 0 : 1;
  result.rays_traced = baker.rays_traced();
  return result;
}

// The bounce passes added to every vertex's direct pass, without timing or warning.
void sh_bounces(const Scene& scene, const EmbreeScene* rays, const ShTransferSettings& settings,
                const ShVertexTable& vertices, ShTransfer& whole, const Context& ctx) {
  if (whole.order != settings.order || whole.kind != settings.kind ||
      whole.vertex_count != vertices.size() ||
      whole.coefficients.size() != vertices.size() * 3 * whole.coefficient_count()) {
    throw Error("sh transfer: the bounces need every vertex's direct pass with these settings");
  }
  if (settings.kind != ShTransferKind::Interreflected || settings.bounces == 0) return;
  TransferBaker baker(scene, rays, settings, vertices, 0, vertices.size());
  std::vector<float> pass = whole.coefficients;
  for (int b = 1; b <= settings.bounces; ++b) {
    pass = baker.bounce(pass, b, ctx);
    for (std::size_t i = 0; i < pass.size(); ++i) whole.coefficients[i] += pass[i];
  }
  whole.rays_traced += baker.rays_traced();
}

}  // namespace

ShTransfer compute_sh_transfer(const Scene& scene, const EmbreeScene* rays,
                               const ShTransferSettings& settings, const Context& ctx) {
  validate(settings);
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<EmbreeScene> own_rays = sh_own_rays(scene, rays, settings, ctx);
  if (own_rays) rays = own_rays.get();
  const ShVertexTable vertices(scene, settings);
  ShTransfer result = sh_direct_range(scene, rays, settings, vertices, 0, vertices.size(), ctx);
  sh_bounces(scene, rays, settings, vertices, result, ctx);
  warn_sh_without_normal(result, ctx);
  result.seconds = seconds_since(start);
  return result;
}

ShTransfer compute_sh_direct_range(const Scene& scene, const EmbreeScene* rays,
                                   const ShTransferSettings& settings, std::size_t first,
                                   std::size_t count, const Context& ctx) {
  validate(settings);
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<EmbreeScene> own_rays = sh_own_rays(scene, rays, settings, ctx);
  if (own_rays) rays = own_rays.get();
  const ShVertexTable vertices(scene, settings);
  ShTransfer result = sh_direct_range(scene, rays, settings, vertices, first, count, ctx);
  warn_sh_without_normal(result, ctx);
  result.seconds = seconds_since(start);
  return result;
}

ShTransfer join_sh_ranges(std::vector<ShTransfer> ranges) {
  if (ranges.empty()) throw Error("sh transfer: no ranges to join");
  std::size_t floats = 0;
  for (const ShTransfer& part : ranges) floats += part.coefficients.size();
  ShTransfer whole = std::move(ranges.front());
  whole.coefficients.reserve(floats);
  for (std::size_t i = 1; i < ranges.size(); ++i) {
    ShTransfer& part = ranges[i];
    if (part.order != whole.order || part.kind != whole.kind) {
      throw Error("sh transfer: range " + std::to_string(i) +
                  " has another order or kind than range 0");
    }
    whole.vertex_count += part.vertex_count;
    whole.coefficients.insert(whole.coefficients.end(), part.coefficients.begin(),
                              part.coefficients.end());
    whole.vertices_without_normal += part.vertices_without_normal;
    whole.rays_traced += part.rays_traced;
    whole.seconds += part.seconds;
    std::vector<float>().swap(part.coefficients);  // freed as soon as copied
  }
  return whole;
}

void add_sh_bounces(const Scene& scene, const EmbreeScene* rays, const ShTransferSettings& settings,
                    ShTransfer& whole_direct, const Context& ctx) {
  validate(settings);
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<EmbreeScene> own_rays;
  if (settings.kind == ShTransferKind::Interreflected && settings.bounces > 0) {
    own_rays = sh_own_rays(scene, rays, settings, ctx);
    if (own_rays) rays = own_rays.get();
  }
  const ShVertexTable vertices(scene, settings);
  sh_bounces(scene, rays, settings, vertices, whole_direct, ctx);
  warn_sh_without_normal(whole_direct, ctx);
  whole_direct.seconds += seconds_since(start);
}

std::vector<glm::vec3> shade_sh_transfer(const ShTransfer& transfer,
                                         const std::vector<glm::vec3>& light) {
  const std::size_t n = transfer.coefficient_count();
  if (light.size() != n) {
    throw Error("sh transfer: light has " + std::to_string(light.size()) +
                " SH coefficients, the transfer needs " + std::to_string(n));
  }
  std::vector<glm::vec3> radiance(transfer.vertex_count, glm::vec3(0.0f));
  for (std::size_t v = 0; v < transfer.vertex_count; ++v) {
    for (int c = 0; c < 3; ++c) {
      const float* t = transfer.vertex_channel(v, c);
      double sum = 0.0;
      for (std::size_t k = 0; k < n; ++k) sum += static_cast<double>(t[k]) * light[k][c];
      radiance[v][c] = static_cast<float>(sum);
    }
  }
  return radiance;
}

}  // namespace prt::bake
