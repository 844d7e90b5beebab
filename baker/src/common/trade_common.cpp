// SPDX-License-Identifier: MIT
// The pieces every technique's trade shares (trade_common.hpp).
#include "trade_common.hpp"

#include <prt/prt_sh.h>
#include <prt/prt_sh_asset.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "prt/baker/reference.hpp"
#include "prt/baker/sh/env_sh.hpp"
#include "prt/io/image_io.hpp"

namespace prt::bake::trade {

namespace fs = std::filesystem;

std::string stem(const std::string& path) {
  return fs::path(path).stem().string();
}

std::string optional_number(double value, const char* fmt) {
  return value < 0.0 ? "" : format(fmt, value);
}

std::string ms_text(double ms) {
  return ms < 0.0 ? "n/a" : format("%.3f", ms);
}

std::string joined(const std::vector<std::uint32_t>& values) {
  std::string text;
  for (std::uint32_t v : values) text += (text.empty() ? "" : ",") + std::to_string(v);
  return text;
}

void check_runtime(prt_result result, const std::string& what) {
  if (result != PRT_OK) throw Error(what + ": " + prt_result_string(result));
}

prt_env_image runtime_env_image(const io::EnvMap& map, int face_size, std::vector<float>* faces) {
  if (map.mapping() == io::EnvMapping::LatLong)
    return prt::latlong_env(map.width(), map.height(), map.pixels().data());
  if (map.mapping() == io::EnvMapping::VerticalCross) face_size = map.face_size();
  faces->clear();
  for (const std::vector<float>& face : io::resample_to_cube(map, face_size))
    faces->insert(faces->end(), face.begin(), face.end());
  return prt::cube_env(face_size, faces->data());
}

// --- SH lights ----------------------------------------------------------------------------------

namespace {

// The runtime's projection must agree with the baker's, which reads the map in its own mapping
// (io::EnvMap::texel) by separate code: a wrong face order or orientation would show here.
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

std::vector<float> ShLight::at_order(std::uint32_t order) const {
  return std::vector<float>(rgb.begin(), rgb.begin() + std::size_t(order) * order * 3);
}

ShLight load_sh_light(const std::string& path, std::uint32_t order, const Context& ctx) {
  ShLight light;
  light.name = stem(path);
  light.map =
      std::make_unique<io::EnvMap>(io::load_envmap(path, io::EnvMapping::Auto, ctx.io_messages()));
  const io::EnvMap& map = *light.map;
  light.rgb.resize(std::size_t(order) * order * 3);
  switch (map.mapping()) {
    case io::EnvMapping::LatLong: {
      light.projection = "runtime lat-long";
      const prt_env_image env = prt::latlong_env(map.width(), map.height(), map.pixels().data());
      check_runtime(prt_sh_project(order, &env, light.rgb.data()), path + ": prt_sh_project");
      break;
    }
    case io::EnvMapping::VerticalCross: {
      light.projection = "runtime cube";
      std::vector<float> packed;
      for (const auto& face : io::resample_to_cube(map, map.face_size()))
        packed.insert(packed.end(), face.begin(), face.end());
      const prt_env_image env = prt::cube_env(map.face_size(), packed.data());
      check_runtime(prt_sh_project(order, &env, light.rgb.data()), path + ": prt_sh_project");
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

Reference cached_reference(const Scene& scene, const io::EnvMap& map, const std::string& map_name,
                           int bounces, const TradeInput& input, const Context& ctx) {
  const std::string key = stem(input.scene) + "_" + map_name + "_b" + std::to_string(bounces) +
                          "_spp" + std::to_string(input.ref_spp) + "_seed" +
                          std::to_string(input.seed) + "_albedo-" + albedo_key(input.albedo);
  const std::string npy = input.cache_dir + "/" + key + ".npy", noise_file = npy + ".noise";
  Reference ref;
  std::ifstream noise_in(noise_file);
  if (noise_in >> ref.noise && cached_radiance(npy, &ref.radiance) &&
      ref.radiance.size() == scene.vertex_count()) {
    ctx.info("reference " + key + ": from the cache (" + format("noise %.3f %%)", 100 * ref.noise));
    return ref;
  }
  ReferenceSettings settings;
  settings.bounces = bounces;
  settings.spp = input.ref_spp;
  settings.seed = input.seed;
  if (!input.albedo.empty()) {
    settings.override_albedo = true;
    settings.albedo = parse_albedo(input.albedo);
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

// The tool's contexts read PRT_BACKEND / PRT_SIMD_ISA, so a user can time a lower backend.
static const prt_context_desc* tool_context_desc() {
  static const prt_context_desc desc = [] {
    prt_context_desc d = prt::sized<prt_context_desc>();
    d.flags = PRT_CONTEXT_READ_ENVIRONMENT;
    return d;
  }();
  return &desc;
}

RuntimeAsset load_runtime_asset(const std::vector<std::uint8_t>& blob) {
  RuntimeAsset loaded;
  prt_context* context = nullptr;
  check_runtime(prt_context_create(tool_context_desc(), &context), "prt_context_create");
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

double time_sh_shading(const prt_asset* asset, prt_backend backend, const std::vector<float>& light,
                       std::uint32_t vertices, int frames, std::vector<float>* out) {
  out->resize(std::size_t(vertices) * 3);
  return median_frame_ms(
      frames, std::string("prt_sh_shade(") + prt_backend_name(backend) + ")",
      [&] { return prt_sh_shade(asset, backend, light.data(), 0, vertices, out->data()); });
}

std::vector<glm::vec3> as_vec3(const std::vector<float>& rgb) {
  std::vector<glm::vec3> out(rgb.size() / 3);
  for (std::size_t v = 0; v < out.size(); ++v)
    out[v] = glm::vec3(rgb[3 * v], rgb[3 * v + 1], rgb[3 * v + 2]);
  return out;
}

// --- machine ------------------------------------------------------------------------------------

namespace {

// "model name" of /proc/cpuinfo, or "unknown".
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

// The SIMD backend as the runtime reports it: "usable, avx2" or "not usable (...)".
std::string simd_description() {
  prt_context* context = nullptr;
  if (prt_context_create(tool_context_desc(), &context) != PRT_OK) return "unknown";
  prt_backend_info info = prt::sized<prt_backend_info>();
  std::string text = "unknown";
  if (prt_backend_get_info(context, PRT_BACKEND_SIMD, &info) == PRT_OK) {
    text = info.usable ? std::string("usable, ") + prt_simd_isa_name(info.isa)
                       : std::string("not usable (") + (info.note ? info.note : "") + ")";
  }
  prt_context_destroy(context);
  return text;
}

}  // namespace

std::string scene_description(const std::string& path, const Scene& scene) {
  return "Scene `" + fs::path(path).filename().string() +
         "`: " + std::to_string(scene.vertex_count()) + " vertices, " +
         std::to_string(scene.triangle_count()) + " triangles";
}

std::string machine_description(unsigned bake_threads) {
  return cpu_model() + ", " + std::to_string(std::thread::hardware_concurrency()) +
         " hardware threads; bakes on " + std::to_string(bake_threads) +
         " threads; SIMD backend: " + simd_description();
}

// --- tables -------------------------------------------------------------------------------------

// A cell with a comma, quote or line break is quoted, its quotes doubled (RFC 4180).
void write_csv_row(std::ostream& out, const std::vector<std::string>& cells) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::string& cell = cells[i];
    out << (i ? "," : "");
    if (cell.find_first_of(",\"\n\r") == std::string::npos) {
      out << cell;
      continue;
    }
    out << '"';
    for (const char c : cell) out << (c == '"' ? "\"\"" : std::string(1, c));
    out << '"';
  }
  out << '\n';
}

void write_markdown_header(std::ostream& out, const std::vector<Column>& columns) {
  std::vector<std::string> titles;
  for (const Column& c : columns) titles.push_back(c.title);
  write_markdown_row(out, titles);
  out << '|';
  for (const Column& c : columns) out << (c.numeric ? "---:|" : "---|");
  out << '\n';
}

void write_markdown_row(std::ostream& out, const std::vector<std::string>& cells) {
  out << '|';
  for (const std::string& cell : cells) out << ' ' << cell << " |";
  out << '\n';
}

void check_written(const std::ostream& out, const std::string& path) {
  if (!out) throw Error(path + ": cannot write");
}

}  // namespace prt::bake::trade
