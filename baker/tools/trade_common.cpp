// SPDX-License-Identifier: MIT
// The pieces prt-bake trade and prt-bake trade-wavelet share (trade_common.hpp).
#include "trade_common.hpp"

#include <prt/prt_sh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "command.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "prt/io/image_io.hpp"

namespace prt::bake::cli {

namespace fs = std::filesystem;

std::string format(const char* fmt, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, value);
  return buffer;
}

std::string stem(const std::string& path) {
  return fs::path(path).stem().string();
}

std::string ms_text(double ms) {
  return ms < 0.0 ? "n/a" : format("%.3f", ms);
}

void check_runtime(prt_result result, const std::string& what) {
  if (result != PRT_OK) throw Error(what + ": " + prt_result_string(result));
}

// --- SH lights ----------------------------------------------------------------------------------

namespace {

// The runtime's projection must agree with the baker's, which reads the map in its own mapping
// (EnvMap::texel) by separate code: a wrong face order or orientation would show here.
void check_against_baker_projection(ShLight& light, std::uint32_t order, const Context& ctx) {
  const std::vector<float> baker = project_env_sh(*light.map, order).to_float();
  double largest = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < baker.size(); ++i) {
    largest = std::max(largest, double(std::abs(baker[i])));
    difference = std::max(difference, double(std::abs(baker[i] - light.rgb[i])));
  }
  const double relative = largest > 0.0 ? difference / largest : difference;
  ctx.info(light.name + ": " + light.projection + " projection agrees with the baker's to " +
           format("%.2g of the largest coefficient", relative));
  if (relative > 1e-4) {
    throw Error(light.map->source() + ": the runtime's SH projection differs from the baker's by " +
                format("%.3g of the largest coefficient", relative));
  }
  light.projection += format(" (= baker to %.0e)", relative);
}

}  // namespace

ShLight load_sh_light(const std::string& path, std::uint32_t order, const Context& ctx) {
  ShLight light;
  light.name = stem(path);
  light.map =
      std::make_unique<io::EnvMap>(io::load_envmap(path, io::EnvMapping::Auto, ctx.io_messages()));
  const io::EnvMap& map = *light.map;
  light.rgb.resize(std::size_t(order) * order * 3);
  switch (map.mapping()) {
    case io::EnvMapping::LatLong:
      light.projection = "runtime lat-long";
      check_runtime(prt_sh_project_latlong(order, map.width(), map.height(), map.pixels().data(),
                                           std::size_t(map.width()) * 3, light.rgb.data()),
                    path + ": prt_sh_project_latlong");
      break;
    case io::EnvMapping::VerticalCross: {
      light.projection = "runtime cube";
      const auto faces = io::resample_to_cube(map, map.face_size());
      const float* pointers[6];
      for (int i = 0; i < 6; ++i) pointers[i] = faces[i].data();
      check_runtime(prt_sh_project_cube(order, map.face_size(), pointers, light.rgb.data()),
                    path + ": prt_sh_project_cube");
      break;
    }
    default:  // the runtime takes lat-long and cube maps only; the baker projects the others
      light.projection = "baker " + std::string(io::env_mapping_name(map.mapping()));
      light.rgb = project_env_sh(map, order).to_float();
      return light;
  }
  check_against_baker_projection(light, order, ctx);
  return light;
}

// --- reference cache ----------------------------------------------------------------------------

namespace {

// A cached reference's radiance, or false when the file is missing or unreadable (then it is
// rendered again).
bool cached_radiance(const std::string& path, std::vector<glm::vec3>* radiance) {
  if (!fs::exists(path)) return false;
  try {
    *radiance = io::read_npy_vec3(path);
    return true;
  } catch (const Error&) {
    return false;
  }
}

std::string albedo_key(const std::string& albedo) {
  if (albedo.empty()) return "material";
  std::string key = albedo;
  std::replace(key.begin(), key.end(), ',', '-');
  return key;
}

}  // namespace

Reference cached_reference(const Scene& scene, const io::EnvMap& map, const ReferenceRequest& r,
                           const Context& ctx) {
  const std::string key = stem(r.scene_path) + "_" + r.map_name + "_b" + std::to_string(r.bounces) +
                          "_spp" + std::to_string(r.spp) + "_seed" + std::to_string(r.seed) +
                          "_albedo-" + albedo_key(r.albedo);
  const std::string npy = r.cache_dir + "/" + key + ".npy", noise_file = npy + ".noise";
  Reference ref;
  std::ifstream noise_in(noise_file);
  if (noise_in >> ref.noise && cached_radiance(npy, &ref.radiance) &&
      ref.radiance.size() == scene.vertex_count()) {
    ctx.info("reference " + key + ": from the cache (" + format("noise %.3f %%)", 100 * ref.noise));
    return ref;
  }
  ReferenceSettings settings;
  settings.bounces = r.bounces;
  settings.spp = r.spp;
  settings.seed = r.seed;
  if (!r.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(r.albedo);
  }
  ctx.info("reference " + key + ": rendering");
  const ReferenceRenderer renderer(scene, map, settings, ctx);
  VertexRadiance result = renderer.render_vertices(ctx);
  ctx.info(format("  noise %.3f %%, ", 100 * result.relative_rmse) +
           format("%.1f s", result.stats.seconds));
  io::write_npy_vec3(npy, result.radiance);
  std::ofstream noise_out(noise_file);
  noise_out.precision(17);
  noise_out << result.relative_rmse << "\n";
  if (!noise_out) throw Error(noise_file + ": cannot write");
  ref.radiance = std::move(result.radiance);
  ref.noise = result.relative_rmse;
  return ref;
}

double noise_removed(double error, double noise) {
  return std::sqrt(std::max(0.0, error * error - noise * noise));
}

// --- runtime ------------------------------------------------------------------------------------

RuntimeAsset load_runtime_asset(const std::vector<std::uint8_t>& blob) {
  RuntimeAsset loaded;
  prt_context* context = nullptr;
  check_runtime(prt_context_create(nullptr, &context), "prt_context_create");
  loaded.context.reset(context);
  prt_asset* asset = nullptr;
  const prt_result result =
      prt_asset_load_memory(context, blob.data(), blob.size(), PRT_VALIDATE_FULL, &asset);
  if (result != PRT_OK) {
    throw Error(std::string("loading the blob through the runtime: ") +
                prt_context_last_message(context));
  }
  loaded.asset.reset(asset);
  return loaded;
}

double median_frame_ms(int frames, const std::string& what,
                       const std::function<prt_result()>& frame) {
  const prt_result first = frame();
  if (first == PRT_ERROR_UNSUPPORTED_BACKEND) return -1.0;
  check_runtime(first, what);
  std::vector<double> ms;
  for (int f = 0; f < frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    frame();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

std::vector<glm::vec3> as_vec3(const std::vector<float>& rgb) {
  std::vector<glm::vec3> out(rgb.size() / 3);
  for (std::size_t v = 0; v < out.size(); ++v)
    out[v] = glm::vec3(rgb[3 * v], rgb[3 * v + 1], rgb[3 * v + 2]);
  return out;
}

// --- machine ------------------------------------------------------------------------------------

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "unknown";
}

std::string simd_description() {
  prt_context* context = nullptr;
  if (prt_context_create(nullptr, &context) != PRT_OK) return "unknown";
  prt_backend_info info{};
  std::string text = "unknown";
  if (prt_backend_get_info(context, PRT_BACKEND_SIMD, &info) == PRT_OK) {
    text = info.usable ? std::string("usable, ") + prt_simd_isa_name(info.isa)
                       : std::string("not usable (") + (info.note ? info.note : "") + ")";
  }
  prt_context_destroy(context);
  return text;
}

}  // namespace prt::bake::cli
