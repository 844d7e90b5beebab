// SPDX-License-Identifier: MIT
// prt_cloth_app_blob: writes a cloth blob of cloth_app_blob.hpp (the presets with tables baked
// on small grids, or over constant tables with --constant) for prt-cloth's tests and for trying
// it by hand:
//   prt_cloth_app_blob OUT.prtk [--constant] [--sheet | --scene SCENE.gltf] [FABRIC...]
// --sheet adds the bent sheet of the tests, --scene the scene's meshes (positions, normals and
// glTF tangents, world space, as the baker imports them); neither: no mesh.
#include <prt/baker/context.hpp>
#include <prt/baker/scene.hpp>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "cloth/app/cloth_app_blob.hpp"

namespace {

prt::bake::ClothMesh scene_mesh(const std::string& path) {
  const prt::bake::Scene scene = prt::bake::import_scene(path, prt::bake::Context{});
  prt::bake::ClothMesh mesh;
  for (const prt::bake::Mesh& m : scene.meshes) {
    const std::uint32_t base = std::uint32_t(mesh.positions.size() / 3);
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
      const glm::vec3 p = m.positions[v], n = m.normals[v];
      const glm::vec3 t =
          m.tangents.empty() ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(m.tangents[v]);
      mesh.positions.insert(mesh.positions.end(), {p.x, p.y, p.z});
      mesh.normals.insert(mesh.normals.end(), {n.x, n.y, n.z});
      mesh.tangents.insert(mesh.tangents.end(), {t.x, t.y, t.z});
    }
    for (std::uint32_t i : m.indices) mesh.triangles.push_back(base + i);
  }
  return mesh;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUT.prtk [--constant] [--sheet | --scene SCENE] [FABRIC...]\n",
                 argv[0]);
    return 2;
  }
  try {
    std::vector<std::string> fabrics;
    prt::bake::ClothMesh mesh;
    bool with_mesh = false, constant = false;
    for (int i = 2; i < argc; ++i) {
      if (std::strcmp(argv[i], "--constant") == 0) {
        constant = true;
      } else if (std::strcmp(argv[i], "--sheet") == 0) {
        mesh = prt_cloth_app_test::bent_sheet(), with_mesh = true;
      } else if (std::strcmp(argv[i], "--scene") == 0 && i + 1 < argc) {
        mesh = scene_mesh(argv[++i]), with_mesh = true;
      } else {
        fabrics.push_back(argv[i]);
      }
    }
    const std::vector<std::uint8_t> bytes = prt::bake::write_cloth_blob(
        constant ? prt_cloth_app_test::preset_section(fabrics)
                 : prt_cloth_app_test::baked_section(fabrics),
        16, with_mesh ? &mesh : nullptr,
        constant ? "prt_cloth_app_blob: presets over constant tables"
                 : "prt_cloth_app_blob: presets, tables baked on small grids");
    std::ofstream(argv[1], std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    std::printf("wrote %s (%zu bytes, %zu vertices)\n", argv[1], bytes.size(),
                mesh.positions.size() / 3);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
    return 1;
  }
}
