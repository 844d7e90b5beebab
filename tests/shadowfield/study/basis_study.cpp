// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s basis comparison (docs/shadowfield/basis.md): SH, Haar, Fourier
// cosine and PCA bases of 4, 8 and 16 terms for the radiance of the floor under the teapot and
// of spot over a floor, printed as a markdown table (or CSV with --csv). Assets come from the
// shared folder; --seed S changes the sky's samples and the receiver's rays; --threads N limits
// the threads.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "prt/baker/demo_scene.hpp"
#include "prt/baker/shadowfield/shadowfield_basis_study.hpp"
#include "support/test_files.hpp"

namespace {

using namespace prt::bake;

constexpr int kFloorSide = 64;  // 4,096 vertices, the paper's floor

Mesh only_mesh(const std::string& path, const Context& ctx) {
  Scene scene = import_scene(path, ctx);
  if (scene.meshes.size() != 1) throw Error(path + ": expected one mesh");
  return std::move(scene.meshes[0]);
}

glm::vec3 lowest(const Mesh& mesh) {
  glm::vec3 lo(INFINITY);
  for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p);
  return lo;
}

// The floor (surface) under the teapot (receiver); the teapot stands on it, both +Y up.
BasisStudyScene floor_scene(const Context& ctx) {
  const std::string path = prt_test::shared_asset("meshes/teapot.obj");
  if (path.empty()) throw Error("meshes/teapot.obj is not in the shared assets");
  Mesh teapot = only_mesh(path, ctx);
  const float base = lowest(teapot).y;
  return {"floor", make_study_floor(glm::vec2(0.0f), 6.0f, base, kFloorSide), std::move(teapot)};
}

// spot (surface, with its uv layout) standing on a floor (receiver).
BasisStudyScene spot_scene(const Context& ctx) {
  const std::string path = prt_test::shared_asset("meshes/spot.obj");
  if (path.empty()) throw Error("meshes/spot.obj is not in the shared assets");
  Mesh spot = only_mesh(path, ctx);
  const float base = lowest(spot).y;
  return {"spot", std::move(spot), make_study_floor(glm::vec2(0.0f), 1.5f, base, kFloorSide)};
}

// The best other family's error over the PCA's, per lighting and size, for each error.
void print_margins(const BasisStudyReport& report) {
  std::printf(
      "\n| lighting | terms | best other (radiance) | its error / PCA's | "
      "best other (image) | its error / PCA's |\n|---|---|---|---|---|---|\n");
  for (const BasisStudyRow& pca : report.rows) {
    if (pca.basis != "PCA") continue;
    const BasisStudyRow *radiance = nullptr, *image = nullptr;
    for (const BasisStudyRow& row : report.rows) {
      if (row.basis == "PCA" || row.lighting != pca.lighting || row.terms != pca.terms) continue;
      if (!radiance || row.radiance_error < radiance->radiance_error) radiance = &row;
      if (!image || row.image_error < image->image_error) image = &row;
    }
    if (!radiance || !image) continue;
    std::printf("| %s | %u | %s | %.2f | %s | %.2f |\n", pca.lighting.c_str(), pca.terms,
                radiance->basis.c_str(), radiance->radiance_error / pca.radiance_error,
                image->basis.c_str(), image->image_error / pca.image_error);
  }
}

void print(const BasisStudyReport& report, const BasisStudyScene& scene, bool csv) {
  if (!csv) {
    std::printf(
        "\n%s: %zu vertices, receiver %zu vertices; %zu point-lit and %zu sky-lit "
        "radiances; sky noise (relative RMSE) %.4f; PCA keeps %.4f of its training "
        "energy; %.1f s\n\n",
        scene.name.c_str(), report.surface_vertices, report.receiver_vertices,
        report.point_lightings, report.sky_lightings, report.sky_noise, report.pca_energy_kept,
        report.seconds);
    std::printf("| surface | lighting | terms | basis | radiance error | image error |\n");
    std::printf("|---|---|---|---|---|---|\n");
  }
  for (const BasisStudyRow& row : report.rows)
    std::printf(csv ? "%s,%s,%u,%s,%.5f,%.5f\n" : "| %s | %s | %u | %s | %.4f | %.4f |\n",
                row.surface.c_str(), row.lighting.c_str(), row.terms, row.basis.c_str(),
                row.radiance_error, row.image_error);
  if (!csv) print_margins(report);
}

}  // namespace

int main(int argc, char** argv) {
  bool csv = false;
  Context ctx;
  BasisStudySettings settings;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--csv") == 0) {
      csv = true;
    } else if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
      settings.seed = std::uint32_t(std::strtoul(argv[++i], nullptr, 10));
    } else if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
      ctx.threads = unsigned(std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "usage: %s [--csv] [--seed S] [--threads N]\n", argv[0]);
      return 2;
    }
  }
  try {
    const prt::io::EnvMap sky = make_demo_sky(256);
    if (csv) std::printf("surface,lighting,terms,basis,radiance_error,image_error\n");
    for (const BasisStudyScene& scene : {floor_scene(ctx), spot_scene(ctx)})
      print(compare_surface_bases(scene, sky, settings, ctx), scene, csv);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "prt_shadowfield_basis_study: %s\n", error.what());
    return 1;
  }
  return 0;
}
