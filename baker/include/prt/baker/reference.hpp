// SPDX-License-Identifier: MIT
// The reference renderer: Monte Carlo path tracing of diffuse and glossy surfaces lit by an
// environment map, over the Embree scene. It is the ground truth every PRT technique is measured
// against, so it uses none of their approximations (no SH, no wavelets, no precomputed
// visibility, no separable BRDF).
//
// Estimator (docs/reference-renderer.md): outgoing radiance at a surface point x with normal n
// and albedo rho towards wo, L(x, wo) = rho * integral of f(w, wo) L_in(w) max(0, n.w) dw, with
// f = 1/pi (Lambert) or an exact glossy BRDF (shadowfield_brdf.hpp), where L_in is the
// environment where the ray escapes and, for up to `bounces` indirect bounces, the outgoing
// radiance of the surface it hits towards x. Each path vertex takes one environment sample
// (importance sampled by luminance) and one BRDF sample (cosine-weighted; on a glossy surface
// cosine or lobe sampling, picked at random), combined with the power heuristic (multiple
// importance sampling, Veach 1997). Samples come from Owen-scrambled Sobol streams
// (sampling.hpp) keyed by a hash of the seed and the vertex or pixel index, so results are
// deterministic for a seed whatever the thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/embree_scene.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/shadowfield/shadowfield_brdf.hpp"
#include "prt/io/camera.hpp"
#include "prt/io/envmap.hpp"
#include "prt/io/image_io.hpp"

namespace prt::bake {

// A surface's BRDF. Its colour is the albedo (ReferenceSettings::albedo or the material's),
// which multiplies the whole BRDF: f_rgb(w, wo) = albedo * f(w, wo), with f = 1/pi for Lambert.
struct SurfaceBrdf {
  enum class Model { Lambert, Phong, Ggx };
  Model model = Model::Lambert;
  PhongBrdf phong;  // Model::Phong only
  GgxBrdf ggx;      // Model::Ggx only

  static SurfaceBrdf lambert() { return SurfaceBrdf{}; }
  static SurfaceBrdf of(const PhongBrdf& brdf) { return {Model::Phong, brdf, {}}; }
  static SurfaceBrdf of(const GgxBrdf& brdf) { return {Model::Ggx, {}, brdf}; }
};

// "lambert", "phong:N[,specular[,diffuse]]" or "ggx:ALPHA[,F0]" (defaults those of PhongBrdf
// and GgxBrdf); throws Error on anything else or on parameters check_brdf rejects.
SurfaceBrdf parse_surface_brdf(const std::string& text);
// The same syntax back, e.g. "phong:10,1,0".
std::string surface_brdf_name(const SurfaceBrdf& brdf);

struct ReferenceSettings {
  int bounces = 0;               // indirect bounces; 0 = direct environment light with visibility
  std::uint32_t spp = 1024;      // samples per vertex (>= 2: two halves for the noise estimate)
  std::uint32_t image_spp = 64;  // samples per pixel
  std::uint32_t seed = 0;
  bool override_albedo = false;  // true: every surface has `albedo`; false: from the materials
  glm::vec3 albedo{0.8f};        // linear RGB in [0,1]
  SurfaceBrdf brdf;              // every mesh's BRDF, unless mesh_brdfs is given
  std::vector<SurfaceBrdf> mesh_brdfs;  // empty, or one per scene mesh (e.g. per instance)
};

struct RenderStats {
  std::uint64_t rays = 0;  // rays traced (occlusion and closest-hit)
  double seconds = 0.0;
  double rays_per_second() const {
    return seconds > 0.0 ? static_cast<double>(rays) / seconds : 0.0;
  }
};

struct VertexRadiance {
  std::vector<glm::vec3> radiance;  // linear outgoing radiance per vertex, in Scene order
  // Estimated relative RMSE of `radiance`: the samples of each vertex are split into two
  // independent halves A and B (nA + nB = spp); RMSE = sqrt(mean |A-B|^2 * nA*nB) / spp over
  // all vertices and channels, divided by the RMS of `radiance`.
  double relative_rmse = 0.0;
  std::size_t vertices_without_normal = 0;  // no usable normal: radiance left at 0
  RenderStats stats;
};

class ReferenceRenderer {
 public:
  // Builds the ray-tracing scene and the environment's importance distribution. `scene` and
  // `env` must outlive the renderer. Throws Error on invalid settings (spp < 2, image_spp < 1,
  // bounces < 0, albedo outside [0,1], a bad BRDF, mesh_brdfs neither empty nor one per mesh).
  ReferenceRenderer(const Scene& scene, const io::EnvMap& env, const ReferenceSettings& settings,
                    const Context& ctx);
  ~ReferenceRenderer();
  ReferenceRenderer(const ReferenceRenderer&) = delete;
  ReferenceRenderer& operator=(const ReferenceRenderer&) = delete;

  // Outgoing radiance at every vertex towards `eye` (world position), or along the vertex normal
  // without one (or where the eye is at the vertex), on ctx.thread_count() threads; reports
  // progress through ctx and throws Error("cancelled") if the progress callback returns false. A
  // Lambertian surface's radiance does not depend on the eye: it is the same, bit for bit.
  VertexRadiance render_vertices(const Context& ctx,
                                 const std::optional<glm::vec3>& eye = std::nullopt) const;
  // The same for the listed vertices only (Scene order indices), radiance in the list's order:
  // each vertex gets the same samples, hence the same bits, as in the whole scene's render, and
  // the noise estimate is over the listed vertices. Throws Error for an index out of range.
  VertexRadiance render_vertices(const std::vector<std::size_t>& subset, const Context& ctx,
                                 const std::optional<glm::vec3>& eye = std::nullopt) const;
  // A camera image: primary rays jittered in each pixel; a hit is shaded by the same estimator as
  // the vertices (at the hit, with its interpolated normal and albedo, towards the camera), a
  // miss shows the map.
  io::LinearImage render_image(const io::Camera& camera, int width, int height, const Context& ctx,
                               RenderStats* stats = nullptr) const;

  const EmbreeScene& embree_scene() const;
  const ReferenceSettings& settings() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// What `prt-bake reference --report` writes.
struct ReferenceReport {
  std::string scene, env, env_mapping;
  double env_rotate_degrees = 0.0;  // the environment turned about world +Y (EnvMap::rotation)
  std::size_t vertices = 0, triangles = 0, dropped_triangles = 0;
  ReferenceSettings settings;
  std::optional<glm::vec3> eye;
  unsigned threads = 1;
  bool has_vertices = false;
  VertexRadiance vertex_result;  // radiance not written, only its statistics
  bool has_image = false;
  int image_width = 0, image_height = 0;
  float exposure_ev = 0.0f;
  RenderStats image_stats;
};

// Writes the report as JSON. Throws Error naming the file if it cannot be written.
void write_reference_report(const std::string& path, const ReferenceReport& report);

}  // namespace prt::bake
