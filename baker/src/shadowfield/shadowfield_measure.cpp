// SPDX-License-Identifier: MIT
// A `shadowfield` scene measured against the path tracer, per time and bounce count
// (shadowfield_measure.hpp).
#include "prt/baker/shadowfield/shadowfield_measure.hpp"

#include <prt/prt_shadowfield.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <chrono>
#include <sstream>

#include "../common/numbers.hpp"
#include "../common/trade_common.hpp"
#include "prt/baker/demo_scene.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "prt/baker/text.hpp"
#include "prt/io/radiance_error.hpp"

namespace prt::bake {
namespace {

prt_shadowfield_transform runtime_transform(const ShadowfieldPlacement& placement) {
  prt_shadowfield_transform t{};
  t.struct_size = sizeof t;
  const glm::mat3 r = Instance::rotation_of(placement.rotation);
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) t.rotation[row * 3 + col] = r[col][row];  // glm: [col][row]
  t.translation[0] = placement.translation.x;
  t.translation[1] = placement.translation.y;
  t.translation[2] = placement.translation.z;
  t.scale = placement.scale;
  return t;
}

// The blobs loaded into a runtime scene with the description's instances placed at `time`.
struct RuntimeScene {
  std::vector<trade::RuntimeAsset> assets;
  prt::ContextPtr context;
  std::unique_ptr<prt_shadowfield_scene, void (*)(prt_shadowfield_scene*)> scene{
      nullptr, prt_shadowfield_scene_destroy};

  RuntimeScene(const ShadowfieldSceneDescription& description,
               const std::vector<std::vector<std::uint8_t>>& blobs, float time) {
    if (blobs.size() != description.objects.size())
      throw Error("shadowfield shade: " + std::to_string(blobs.size()) + " blobs for " +
                  std::to_string(description.objects.size()) + " objects");
    for (const std::vector<std::uint8_t>& blob : blobs)
      assets.push_back(trade::load_runtime_asset(blob));
    auto [made_context, made] = prt::create_context();
    trade::check_runtime(made, "prt_context_create");
    context = std::move(made_context);
    prt_shadowfield_scene* raw = nullptr;
    trade::check_runtime(prt_shadowfield_scene_create(
                             context.get(), std::uint32_t(description.instances.size()), &raw),
                         "prt_shadowfield_scene_create");
    scene.reset(raw);
    for (std::size_t o = 0; o < assets.size(); ++o) {
      std::uint32_t id = 0;
      trade::check_runtime(prt_shadowfield_scene_add_object(raw, assets[o].asset.get(), &id),
                           "adding object " + description.objects[o].name);
    }
    for (const ShadowfieldInstance& instance : description.instances)
      add(description, instance, time);
  }

  void add(const ShadowfieldSceneDescription& description, const ShadowfieldInstance& instance,
           float time) {
    const prt_shadowfield_transform t = runtime_transform(instance.path.at(time));
    const ShadowfieldSceneObject& object = description.objects.at(instance.object);
    std::uint32_t id = 0;
    trade::check_runtime(
        prt_shadowfield_scene_add_instance(scene.get(), std::uint32_t(instance.object), &t, &id),
        "adding an instance of " + object.name);
    const std::uint32_t count = prt_shadowfield_instance_vertex_count(scene.get(), id);
    if (count != object.mesh.vertex_count())
      throw Error("shadowfield shade: the blob of " + object.name + " has " +
                  std::to_string(count) + " vertices, its object " +
                  std::to_string(object.mesh.vertex_count()));
  }
};

// Every instance's outgoing radiance through pass `pass`, instances in order.
std::vector<glm::vec3> runtime_output(const prt_shadowfield_scene* scene, std::uint32_t pass) {
  std::vector<glm::vec3> radiance;
  for (std::uint32_t i = 0; i < prt_shadowfield_scene_instance_count(scene); ++i) {
    const std::uint32_t count = prt_shadowfield_instance_vertex_count(scene, i);
    std::vector<float> rgb(std::size_t(count) * 3);
    trade::check_runtime(prt_shadowfield_output(scene, i, pass, 0, count, rgb.data()),
                         "prt_shadowfield_output");
    for (std::uint32_t v = 0; v < count; ++v)
      radiance.emplace_back(rgb[3 * v], rgb[3 * v + 1], rgb[3 * v + 2]);
  }
  return radiance;
}

// The instances' vertices of `object`, gathered from a whole-scene per-vertex array.
std::vector<glm::vec3> object_values(const ShadowfieldSceneDescription& description,
                                     const std::vector<std::size_t>& first_vertex,
                                     const std::vector<glm::vec3>& values, std::size_t object) {
  std::vector<glm::vec3> out;
  for (std::size_t i = 0; i < description.instances.size(); ++i) {
    if (description.instances[i].object != object) continue;
    out.insert(out.end(), values.begin() + first_vertex[i], values.begin() + first_vertex[i + 1]);
  }
  return out;
}

double mean_radiance(const std::vector<glm::vec3>& values) {
  double sum = 0.0;
  for (const glm::vec3& v : values) sum += double(v.x) + double(v.y) + double(v.z);
  return values.empty() ? 0.0 : sum / (3.0 * double(values.size()));
}

double relative_bias(const std::vector<glm::vec3>& estimate,
                     const std::vector<glm::vec3>& reference) {
  double difference = 0.0, total = 0.0;
  for (std::size_t v = 0; v < reference.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      difference += double(estimate[v][c]) - double(reference[v][c]);
      total += double(reference[v][c]);
    }
  }
  return total > 0.0 ? difference / total : 0.0;
}

void check_measure_settings(const ShadowfieldMeasureSettings& settings) {
  if (settings.times.empty() || settings.bounces.empty())
    throw Error("shadowfield measure: at least one time and one bounce count");
  for (const std::uint32_t b : settings.bounces) {
    if (b > PRT_SHADOWFIELD_MAX_BOUNCES)
      throw Error("shadowfield measure: " + std::to_string(b) + " bounces is above " +
                  std::to_string(PRT_SHADOWFIELD_MAX_BOUNCES));
  }
  for (const float t : settings.times)
    if (!std::isfinite(t)) throw Error("shadowfield measure: a time is not finite");
  if (settings.spp < 2) throw Error("shadowfield measure: spp must be >= 2");
  if (settings.probe_spacings.empty())
    throw Error("shadowfield measure: at least one probe spacing (0: per vertex)");
  for (const float s : settings.probe_spacings)
    if (!(s >= 0.0f) || !std::isfinite(s))
      throw Error("shadowfield measure: a probe spacing that is not finite and >= 0");
}

}  // namespace

SurfaceBrdf shadowfield_surface_brdf(const ShadowfieldMaterialDescription& material) {
  switch (material.model) {
    case ShadowfieldBrdfModel::Phong:
      return SurfaceBrdf::of(material.phong);
    case ShadowfieldBrdfModel::Ggx:
      return SurfaceBrdf::of(material.ggx);
    case ShadowfieldBrdfModel::Diffuse:
      break;
  }
  return SurfaceBrdf::lambert();
}

PlacedScene place_shadowfield_scene(const ShadowfieldSceneDescription& description, float time) {
  std::vector<Scene> objects;
  objects.reserve(description.objects.size());
  for (const ShadowfieldSceneObject& object : description.objects) objects.push_back(object.mesh);
  std::vector<Instance> instances;
  for (const ShadowfieldInstance& instance : description.instances) {
    const ShadowfieldPlacement placement = instance.path.at(time);
    Instance placed;
    placed.object = instance.object;
    placed.rotation = Instance::rotation_of(placement.rotation);
    placed.translation = placement.translation;
    placed.scale = placement.scale;
    instances.push_back(placed);
  }
  return place_instances(objects, instances);
}

ReferenceSettings shadowfield_reference_settings(const ShadowfieldSceneDescription& description,
                                                 const PlacedScene& placed, int bounces,
                                                 std::uint32_t spp, std::uint32_t seed) {
  ReferenceSettings settings;
  settings.bounces = bounces;
  settings.spp = spp;
  settings.seed = seed;
  std::vector<SurfaceBrdf> brdfs;
  for (const ShadowfieldSceneObject& object : description.objects)
    brdfs.push_back(shadowfield_surface_brdf(object.material));
  settings.mesh_brdfs = placed.mesh_values(brdfs);
  return settings;
}

VertexRadiance render_shadowfield_reference(const ShadowfieldSceneDescription& description,
                                            const io::EnvMap& env, float time, int bounces,
                                            std::uint32_t spp, const glm::vec3& eye,
                                            const Context& ctx, std::uint32_t seed) {
  const PlacedScene placed = place_shadowfield_scene(description, time);
  const ReferenceSettings settings =
      shadowfield_reference_settings(description, placed, bounces, spp, seed);
  const ReferenceRenderer renderer(placed.scene, env, settings, ctx);
  return renderer.render_vertices(ctx, eye);
}

io::EnvMap load_shadowfield_env(const std::string& env, const std::string& shared_dir,
                                const Context& ctx) {
  if (env == kShadowfieldBuiltinSky || env == "sky") return make_demo_sky();
  const std::string path = shared_dir.empty() ? env : shared_dir + "/" + env;
  return io::load_envmap(path, io::EnvMapping::Auto, ctx.io_messages());
}

std::vector<std::vector<glm::vec3>> shade_shadowfield_scene(
    const ShadowfieldSceneDescription& description,
    const std::vector<std::vector<std::uint8_t>>& blobs, const std::vector<float>& light_sh,
    std::uint32_t light_order, float time, const std::vector<std::uint32_t>& bounces,
    const glm::vec3& eye, double* seconds, bool log_product, float probe_spacing) {
  if (bounces.empty()) throw Error("shadowfield shade: no bounce count");
  const RuntimeScene runtime(description, blobs, time);
  prt_shadowfield_scene* scene = runtime.scene.get();
  if (log_product)
    trade::check_runtime(prt_shadowfield_scene_set_product(scene, PRT_SHADOWFIELD_PRODUCT_LOG),
                         "prt_shadowfield_scene_set_product");
  const std::uint32_t order = prt_shadowfield_scene_order(scene);
  if (order > light_order || light_sh.size() < std::size_t(order) * order * 3)
    throw Error("shadowfield shade: the light's SH order is below the blobs'");
  // The light's leading order^2 coefficients (coefficient-major RGB).
  const std::vector<float> light(light_sh.begin(),
                                 light_sh.begin() + std::size_t(order) * order * 3);
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = *std::max_element(bounces.begin(), bounces.end());
  settings.backend = PRT_BACKEND_CPU;
  settings.bounce_probe_spacing = probe_spacing;
  const float eye_xyz[3] = {eye.x, eye.y, eye.z};
  const std::vector<float*> no_output(description.instances.size(), nullptr);
  const auto start = std::chrono::steady_clock::now();
  trade::check_runtime(
      prt_shadowfield_shade(scene, light.data(), eye_xyz, &settings, no_output.data()),
      "prt_shadowfield_shade");
  if (seconds) *seconds = seconds_since(start);
  std::vector<std::vector<glm::vec3>> out;
  for (const std::uint32_t b : bounces) out.push_back(runtime_output(scene, b));
  return out;
}

namespace {

// The row's figures of the runtime's radiance against the reference's.
void compare_with_reference(const ShadowfieldSceneDescription& description,
                            const PlacedScene& placed, const std::vector<glm::vec3>& runtime,
                            const VertexRadiance& reference, ShadowfieldMeasureRow& row) {
  row.reference_noise = reference.relative_rmse;
  row.nrmse = io::relative_rmse(runtime, reference.radiance);
  row.bias = relative_bias(runtime, reference.radiance);
  row.runtime_mean = mean_radiance(runtime);
  row.reference_mean = mean_radiance(reference.radiance);
  for (std::size_t o = 0; o < description.objects.size(); ++o) {
    const std::vector<glm::vec3> ours = object_values(description, placed.first_vertex, runtime, o);
    const std::vector<glm::vec3> theirs =
        object_values(description, placed.first_vertex, reference.radiance, o);
    row.object_nrmse.push_back(ours.empty() ? 0.0 : io::relative_rmse(ours, theirs));
    row.object_bias.push_back(relative_bias(ours, theirs));
  }
}

}  // namespace

std::vector<ShadowfieldMeasureRow> measure_shadowfield_scene(
    const ShadowfieldSceneDescription& description,
    const std::vector<std::vector<std::uint8_t>>& blobs, const io::EnvMap& env,
    const ShadowfieldMeasureSettings& settings, const Context& ctx) {
  check_measure_settings(settings);
  const glm::vec3 eye = settings.eye.value_or(description.camera.eye);
  // At the largest order a shadowfield blob has; the scene takes its leading coefficients.
  const EnvSh env_sh = project_env_sh(env, 6u);
  const std::vector<float> light = env_sh.to_float();
  std::vector<ShadowfieldMeasureRow> rows;
  for (const float time : settings.times) {
    // Per probe spacing, the runtime's radiance per bounce count and its frame's time.
    std::vector<std::vector<std::vector<glm::vec3>>> runtime;
    std::vector<double> seconds_runtime(settings.probe_spacings.size());
    for (std::size_t s = 0; s < settings.probe_spacings.size(); ++s)
      runtime.push_back(shade_shadowfield_scene(description, blobs, light, env_sh.order, time,
                                                settings.bounces, eye, &seconds_runtime[s],
                                                settings.log_product, settings.probe_spacings[s]));
    const PlacedScene placed = place_shadowfield_scene(description, time);
    for (std::size_t b = 0; b < settings.bounces.size(); ++b) {
      const auto start = std::chrono::steady_clock::now();
      const ReferenceSettings reference_settings = shadowfield_reference_settings(
          description, placed, int(settings.bounces[b]), settings.spp, settings.seed);
      const ReferenceRenderer renderer(placed.scene, env, reference_settings, ctx);
      const VertexRadiance reference = renderer.render_vertices(ctx, eye);
      const double seconds_reference = seconds_since(start);
      for (std::size_t s = 0; s < settings.probe_spacings.size(); ++s) {
        ShadowfieldMeasureRow row;
        row.time = time;
        row.bounces = settings.bounces[b];
        row.probe_spacing = settings.probe_spacings[s];
        row.seconds_reference = seconds_reference;
        row.seconds_runtime = seconds_runtime[s];
        compare_with_reference(description, placed, runtime[s][b], reference, row);
        ctx.info(
            format("t = %g s, %u bounces, probes %g: NRMSE %.2f %%, bias %+.2f %% "
                   "(reference noise %.2f %%)",
                   double(time), row.bounces, double(row.probe_spacing), 100.0 * row.nrmse,
                   100.0 * row.bias, 100.0 * row.reference_noise));
        rows.push_back(std::move(row));
      }
    }
  }
  return rows;
}

std::string shadowfield_measure_markdown(const ShadowfieldSceneDescription& description,
                                         const std::vector<ShadowfieldMeasureRow>& rows) {
  std::ostringstream md;
  md << "| time (s) | bounces | probe spacing | NRMSE % | bias % | ref. noise % | mean runtime | "
        "mean ref.";
  for (const ShadowfieldSceneObject& object : description.objects)
    md << " | " << object.name << " NRMSE (bias) %";
  md << " | runtime (ms) | reference (s) |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
        "---:";
  for (std::size_t o = 0; o < description.objects.size(); ++o) md << " | ---:";
  md << " | ---: | ---: |\n";
  for (const ShadowfieldMeasureRow& row : rows) {
    md << format("| %g | %u | %g | %.2f | %+.2f | %.2f", double(row.time), row.bounces,
                 double(row.probe_spacing), 100 * row.nrmse, 100 * row.bias,
                 100 * row.reference_noise);
    md << format(" | %.4g | %.4g", row.runtime_mean, row.reference_mean);
    for (std::size_t o = 0; o < row.object_nrmse.size(); ++o)
      md << format(" | %.2f (%+.1f)", 100 * row.object_nrmse[o], 100 * row.object_bias[o]);
    md << format(" | %.1f | %.1f |\n", 1e3 * row.seconds_runtime, row.seconds_reference);
  }
  return md.str();
}

}  // namespace prt::bake
