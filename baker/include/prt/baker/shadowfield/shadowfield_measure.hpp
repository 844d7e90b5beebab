// SPDX-License-Identifier: MIT
// A `shadowfield` scene measured against the path tracer (docs/shadowfield/accuracy.md): at each
// time the instances are placed on their paths, the runtime shades every instance's vertices
// after b bounces, and the reference renderer traces the same placed scene with b indirect
// bounces; the rows state the error per time and bounce count.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/baker/context.hpp"
#include "prt/baker/instances.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake {

// The exact BRDF of a material description, for the reference renderer (not the separated one).
SurfaceBrdf shadowfield_surface_brdf(const ShadowfieldMaterialDescription& material);

// The description's instances placed at `time` (their paths' placements), objects' meshes as
// they are in the description: the world scene the reference renders, instances in order.
PlacedScene place_shadowfield_scene(const ShadowfieldSceneDescription& description, float time);

// The reference renderer's settings for a placed scene: each mesh its object's exact BRDF,
// albedo from the materials.
ReferenceSettings shadowfield_reference_settings(const ShadowfieldSceneDescription& description,
                                                 const PlacedScene& placed, int bounces,
                                                 std::uint32_t spp, std::uint32_t seed = 0);

// Per-vertex outgoing radiance of the whole scene at `time` towards `eye`, every instance's
// vertices in its object's order, instances in order.
VertexRadiance render_shadowfield_reference(const ShadowfieldSceneDescription& description,
                                            const io::EnvMap& env, float time, int bounces,
                                            std::uint32_t spp, const glm::vec3& eye,
                                            const Context& ctx, std::uint32_t seed = 0);

// The environment of a scene: the built-in sky, or the map the description names under
// shared_dir. Throws Error when it cannot be read.
io::EnvMap load_shadowfield_env(const std::string& env, const std::string& shared_dir,
                                const Context& ctx);

struct ShadowfieldMeasureSettings {
  std::vector<float> times{0.0f};                  // seconds on the scene's paths
  std::vector<std::uint32_t> bounces{0, 1, 2, 3};  // each <= PRT_SHADOWFIELD_MAX_BOUNCES
  std::uint32_t spp = 1024;                        // the reference's samples per vertex
  std::uint32_t seed = 0;
  std::optional<glm::vec3> eye;  // default: the description's camera eye
  bool log_product = false;      // the runtime combines blockers by the log-space product
  // The runtime's bounce probe spacings (prt_shadowfield_settings::bounce_probe_spacing), each
  // measured against the same references; 0: per vertex.
  std::vector<float> probe_spacings{0.0f};
};

struct ShadowfieldMeasureRow {
  float time = 0.0f;
  std::uint32_t bounces = 0;
  float probe_spacing = 0.0f;
  // relative RMSE over every instance's vertices and the three channels (io::relative_rmse),
  // and the relative bias sum(runtime - reference) / sum(reference).
  double nrmse = 0.0, bias = 0.0;
  double reference_noise = 0.0;  // the reference's own relative RMSE estimate
  // Mean radiance over every vertex and channel: how much light each side has, so the light
  // each side's bounces add can be compared across rows.
  double runtime_mean = 0.0, reference_mean = 0.0;
  std::vector<double> object_nrmse;  // per object, over the vertices of all its instances
  std::vector<double> object_bias;   // per object, as bias
  double seconds_runtime = 0.0;      // the runtime's frame through every bounce asked for
  double seconds_reference = 0.0;
};

// The runtime's per-vertex radiance, instances in order (as render_shadowfield_reference), of
// the scene at `time` through pass b for each b of `bounces` (one vector per b). blobs: one
// baked blob per object of the description, in order; `light_sh` the environment's SH in the
// runtime's layout (project_env_sh) at least at the blobs' order; log_product: blockers combined
// by the log-space product; probe_spacing: the bounce probes' (0: per vertex). Throws Error when
// a blob does not load or its vertex count is not its object's.
std::vector<std::vector<glm::vec3>> shade_shadowfield_scene(
    const ShadowfieldSceneDescription& description,
    const std::vector<std::vector<std::uint8_t>>& blobs, const std::vector<float>& light_sh,
    std::uint32_t light_order, float time, const std::vector<std::uint32_t>& bounces,
    const glm::vec3& eye, double* seconds = nullptr, bool log_product = false,
    float probe_spacing = 0.0f);

// One row per time, bounce count and probe spacing, in that order. Throws Error for
// bad settings or blobs that do not match the description.
std::vector<ShadowfieldMeasureRow> measure_shadowfield_scene(
    const ShadowfieldSceneDescription& description,
    const std::vector<std::vector<std::uint8_t>>& blobs, const io::EnvMap& env,
    const ShadowfieldMeasureSettings& settings, const Context& ctx);

// The rows as a markdown table (one column per object: its NRMSE and bias, by its name).
std::string shadowfield_measure_markdown(const ShadowfieldSceneDescription& description,
                                         const std::vector<ShadowfieldMeasureRow>& rows);

}  // namespace prt::bake
