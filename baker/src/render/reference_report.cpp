// SPDX-License-Identifier: MIT
#include <nlohmann/json.hpp>

#include <fstream>

#include "prt/baker/reference.hpp"

namespace prt::bake {
namespace {

nlohmann::json stats_json(const RenderStats& stats) {
  return {{"rays", stats.rays},
          {"seconds", stats.seconds},
          {"rays_per_second", stats.rays_per_second()}};
}

}  // namespace

void write_reference_report(const std::string& path, const ReferenceReport& report) {
  const ReferenceSettings& s = report.settings;
  nlohmann::json json = {
      {"command", "reference"},
      {"scene",
       {{"file", report.scene},
        {"vertices", report.vertices},
        {"triangles", report.triangles},
        {"dropped_triangles", report.dropped_triangles}}},
      {"environment",
       {{"file", report.env},
        {"mapping", report.env_mapping},
        {"rotate_degrees", report.env_rotate_degrees},
        {"rotation",
         "about world +Y: light that came from d comes from R d, "
         "R = [[c,0,s],[0,1,0],[-s,0,c]] (prt_sh_rotate's convention)"}}},
      {"settings",
       {{"bounces", s.bounces},
        {"spp", s.spp},
        {"image_spp", s.image_spp},
        {"seed", s.seed},
        {"brdf", surface_brdf_name(s.brdf)},
        {"threads", report.threads}}},
  };
  if (s.override_albedo) json["settings"]["albedo"] = {s.albedo.r, s.albedo.g, s.albedo.b};
  if (!s.mesh_brdfs.empty()) {
    nlohmann::json names = nlohmann::json::array();
    for (const SurfaceBrdf& brdf : s.mesh_brdfs) names.push_back(surface_brdf_name(brdf));
    json["settings"]["brdf"] = names;  // one per mesh
  }
  if (report.eye) json["settings"]["eye"] = {report.eye->x, report.eye->y, report.eye->z};
  if (report.has_vertices) {
    const VertexRadiance& v = report.vertex_result;
    json["vertices"] = stats_json(v.stats);
    json["vertices"]["relative_rmse"] = v.relative_rmse;
    json["vertices"]["vertices_without_normal"] = v.vertices_without_normal;
  }
  if (report.has_image) {
    json["image"] = stats_json(report.image_stats);
    json["image"]["width"] = report.image_width;
    json["image"]["height"] = report.image_height;
    json["image"]["exposure_ev"] = report.exposure_ev;
  }
  std::ofstream file(path);
  if (!file || !(file << json.dump(2) << '\n')) throw Error(path + ": cannot write the report");
}

}  // namespace prt::bake
