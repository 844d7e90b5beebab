// SPDX-License-Identifier: MIT
// The baker's SG light (cloth_light.hpp): the runtime's fit, its refinement against the
// smoothed map, their errors, the light's radiance and its JSON file.
#include "prt/baker/cloth/cloth_light.hpp"

#include <prt/prt.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../common/numbers.hpp"
#include "cloth_light_detail.hpp"
#include "prt/io/file.hpp"

namespace prt::bake {

namespace {

void check_sg_light_options(const SgLightOptions& options) {
  if (options.lobe_count < 1 || options.lobe_count > PRT_CLOTH_MAX_LOBES)
    throw Error("SG light: lobe_count " + std::to_string(options.lobe_count) + " is outside 1.." +
                std::to_string(PRT_CLOTH_MAX_LOBES));
  if (options.resolution < 1 || options.resolution > 1024)
    throw Error("SG light: resolution " + std::to_string(options.resolution) +
                " is outside 1..1024");
  for (double deg : options.smoothing_degrees)
    if (!(deg > 0.0 && deg <= 90.0))
      throw Error("SG light: a smoothing width of " + std::to_string(deg) +
                  " degrees is outside (0, 90]");
}

// The map as the runtime's env image: a lat-long map's own texels (its rotation given as the
// env's), anything else resampled to a cube whose faces `cube` holds.
prt_env_image env_image_of(const io::EnvMap& map, std::vector<float>* cube, float rotation[9]) {
  prt_env_image env = prt::sized<prt_env_image>();
  env.channels = 3;
  if (map.mapping() == io::EnvMapping::LatLong) {
    env.layout = PRT_ENV_LATLONG;
    env.width = static_cast<std::uint32_t>(map.width());
    env.height = static_cast<std::uint32_t>(map.height());
    env.texels = map.pixels().data();
    if (map.rotated()) {
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) rotation[r * 3 + c] = map.rotation()[c][r];  // column-major
      env.rotation = rotation;
    }
    return env;
  }
  const int face = map.mapping() == io::EnvMapping::VerticalCross ? map.face_size()
                                                                  : std::max(16, map.width() / 4);
  for (const std::vector<float>& f : io::resample_to_cube(map, face))
    cube->insert(cube->end(), f.begin(), f.end());
  env.layout = PRT_ENV_CUBE;
  env.width = env.height = static_cast<std::uint32_t>(face);
  env.texels = cube->data();
  return env;
}

SgLightError measure(const sg_light::MapGrid& grid,
                     const std::vector<sg_light::SmoothedTarget>& targets,
                     const std::vector<sg_light::Lobe>& lobes) {
  SgLightError error;
  error.relative = sg_light::relative_error(grid, lobes);
  for (const sg_light::SmoothedTarget& target : targets)
    error.smoothed.push_back(sg_light::smoothed_error(target, lobes));
  error.power = sg_light::power_error(grid, lobes);
  return error;
}

nlohmann::ordered_json error_json(const SgLightError& error) {
  return {{"relative", error.relative}, {"smoothed", error.smoothed}, {"power", error.power}};
}

SgLightError error_from_json(const nlohmann::json& j) {
  SgLightError error;
  error.relative = j.at("relative").get<double>();
  error.smoothed = j.at("smoothed").get<std::vector<double>>();
  error.power = j.at("power").get<double>();
  return error;
}

prt_cloth_lobe lobe_from_json(const nlohmann::json& j) {
  prt_cloth_lobe lobe{};
  const auto axis = j.at("axis").get<std::vector<double>>();
  const auto rgb = j.at("rgb").get<std::vector<double>>();
  if (axis.size() != 3 || rgb.size() != 3) throw Error("a lobe's axis or rgb is not 3 numbers");
  for (int c = 0; c < 3; ++c) {
    lobe.axis[c] = static_cast<float>(axis[c]);
    lobe.rgb[c] = static_cast<float>(rgb[c]);
    if (!std::isfinite(lobe.rgb[c]) || lobe.rgb[c] < 0.0f)
      throw Error("a lobe's rgb is negative or not finite");
  }
  lobe.sharpness = static_cast<float>(j.at("sharpness").get<double>());
  const double length =
      std::sqrt(double(lobe.axis[0]) * lobe.axis[0] + double(lobe.axis[1]) * lobe.axis[1] +
                double(lobe.axis[2]) * lobe.axis[2]);
  if (!(std::fabs(length - 1.0) <= 1e-3)) throw Error("a lobe's axis is not of unit length");
  if (!(lobe.sharpness >= PRT_CLOTH_MIN_SHARPNESS && lobe.sharpness <= PRT_CLOTH_MAX_SHARPNESS))
    throw Error("a lobe's sharpness is outside [" + std::to_string(PRT_CLOTH_MIN_SHARPNESS) + ", " +
                std::to_string(PRT_CLOTH_MAX_SHARPNESS) + "]");
  return lobe;
}

}  // namespace

std::vector<prt_cloth_lobe> fast_sg_light(const io::EnvMap& map, const SgLightOptions& options,
                                          prt_cloth_fit_report* report) {
  check_sg_light_options(options);
  std::vector<float> cube;
  float rotation[9];
  const prt_env_image env = env_image_of(map, &cube, rotation);
  auto [context, made] = prt::create_context();
  if (made != PRT_OK) throw Error("SG light: the runtime context could not be made");
  prt_cloth_fit_desc desc = prt::sized<prt_cloth_fit_desc>();
  desc.lobe_count = options.lobe_count;
  desc.resolution = options.resolution;
  prt_cloth_fit_report fit_report = prt::sized<prt_cloth_fit_report>();
  std::vector<prt_cloth_lobe> lobes(options.lobe_count);
  if (prt_cloth_fit_light(context.get(), &env, &desc, lobes.data(), &fit_report) != PRT_OK)
    throw Error(map.source() + ": prt_cloth_fit_light: " + prt_context_last_message(context.get()));
  lobes.resize(fit_report.lobe_count);
  if (report) *report = fit_report;
  return lobes;
}

SgLightFit fit_sg_light(const io::EnvMap& map, const SgLightOptions& options, const Context& ctx) {
  check_sg_light_options(options);
  SgLightFit fit;
  fit.lobe_count = options.lobe_count;
  fit.resolution = options.resolution;
  fit.smoothing_degrees = options.smoothing_degrees;
  const std::vector<prt_cloth_lobe> fast = fast_sg_light(map, options);
  const sg_light::MapGrid fine = sg_light::grid_of(map, 2 * options.resolution);
  const sg_light::MapGrid grid = sg_light::coarser(fine);
  const auto targets = sg_light::smoothed_targets(fine, options.smoothing_degrees, ctx);
  fit.fast = measure(grid, targets, sg_light::to_lobes(fast));
  // The finest kernel's sharpness: lobes at least this sharp are points to every kernel.
  double fixed_sharpness = 0.0;
  for (double deg : options.smoothing_degrees)
    fixed_sharpness = std::max(fixed_sharpness, std::pow(180.0 / (deg * kPi), 2.0));
  const sg_light::Refinement refined =
      sg_light::refine(targets, sg_light::to_lobes(fast), fixed_sharpness, options.max_steps, ctx);
  for (const prt_cloth_lobe& lobe : sg_light::to_cloth_lobes(refined.lobes))
    if (lobe.rgb[0] > 0.0f || lobe.rgb[1] > 0.0f || lobe.rgb[2] > 0.0f) fit.lobes.push_back(lobe);
  fit.error = measure(grid, targets, sg_light::to_lobes(fit.lobes));
  fit.fixed_lobes = refined.fixed;
  fit.steps = refined.steps;
  // The refinement compared errors in double; should rounding to float undo a gain, the
  // runtime's fit stands.
  for (std::size_t i = 0; i < fit.error.smoothed.size(); ++i) {
    if (fit.error.smoothed[i] > fit.fast.smoothed[i]) {
      fit.lobes = fast;
      fit.error = fit.fast;
      fit.steps = 0;
      break;
    }
  }
  return fit;
}

SgLightError measure_sg_light(const io::EnvMap& map, const std::vector<prt_cloth_lobe>& lobes,
                              const SgLightOptions& options, const Context& ctx) {
  check_sg_light_options(options);
  const sg_light::MapGrid fine = sg_light::grid_of(map, 2 * options.resolution);
  return measure(sg_light::coarser(fine),
                 sg_light::smoothed_targets(fine, options.smoothing_degrees, ctx),
                 sg_light::to_lobes(lobes));
}

glm::vec3 sg_radiance(const std::vector<prt_cloth_lobe>& lobes, const glm::vec3& direction) {
  glm::dvec3 sum{0.0};
  const glm::dvec3 d(direction);
  for (const prt_cloth_lobe& l : lobes) {
    const double t = d.x * l.axis[0] + d.y * l.axis[1] + d.z * l.axis[2];
    sum += glm::dvec3(l.rgb[0], l.rgb[1], l.rgb[2]) * std::exp(double(l.sharpness) * (t - 1.0));
  }
  return glm::vec3(sum);
}

std::string sg_light_json(const SgLightFit& fit) {
  nlohmann::ordered_json lobes = nlohmann::ordered_json::array();
  for (const prt_cloth_lobe& l : fit.lobes) {
    lobes.push_back({{"axis", {shortest(l.axis[0]), shortest(l.axis[1]), shortest(l.axis[2])}},
                     {"sharpness", shortest(l.sharpness)},
                     {"rgb", {shortest(l.rgb[0]), shortest(l.rgb[1]), shortest(l.rgb[2])}}});
  }
  nlohmann::ordered_json j;
  j["lobes"] = lobes;
  j["fit"] = {{"lobe_count", fit.lobe_count},
              {"resolution", fit.resolution},
              {"smoothing_degrees", fit.smoothing_degrees},
              {"fixed_lobes", fit.fixed_lobes},
              {"steps", fit.steps},
              {"error", error_json(fit.error)},
              {"fast", error_json(fit.fast)}};
  return j.dump(1) + "\n";
}

void write_sg_light(const std::string& path, const SgLightFit& fit) {
  std::ofstream file(path, std::ios::binary);
  file << sg_light_json(fit);
  if (!file.flush()) throw Error(path + ": cannot be written");
}

SgLightFit read_sg_light(const std::string& path) {
  const std::vector<unsigned char> bytes = io::read_file(path);
  SgLightFit fit;
  try {
    const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end());
    const nlohmann::json& lobes = j.at("lobes");
    if (!lobes.is_array() || lobes.size() > PRT_CLOTH_MAX_LOBES)
      throw Error("\"lobes\" is not an array of at most " + std::to_string(PRT_CLOTH_MAX_LOBES));
    for (const nlohmann::json& lobe : lobes) fit.lobes.push_back(lobe_from_json(lobe));
    if (j.contains("fit")) {
      const nlohmann::json& f = j.at("fit");
      fit.lobe_count = f.at("lobe_count").get<std::uint32_t>();
      fit.resolution = f.at("resolution").get<std::uint32_t>();
      fit.smoothing_degrees = f.at("smoothing_degrees").get<std::vector<double>>();
      fit.fixed_lobes = f.at("fixed_lobes").get<std::uint32_t>();
      fit.steps = f.at("steps").get<std::uint32_t>();
      fit.error = error_from_json(f.at("error"));
      fit.fast = error_from_json(f.at("fast"));
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not an SG light: " + e.what());
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  return fit;
}

}  // namespace prt::bake
