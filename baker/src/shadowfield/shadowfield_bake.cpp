// SPDX-License-Identifier: MIT
#include "prt/baker/shadowfield/shadowfield_bake.hpp"

#include <chrono>
#include <utility>

#include "../common/numbers.hpp"
#include "prt/baker/embree_scene.hpp"

namespace prt::bake {
Scene shadowfield_rays_scene(const ShadowfieldObject& object) {
  Mesh mesh;
  mesh.name = "shadowfield object";
  mesh.positions = object.positions;
  mesh.normals = object.normals;
  mesh.indices = object.indices;
  Scene scene;
  scene.meshes.push_back(std::move(mesh));
  return scene;
}

void check_shadowfield_bake_settings(const ShadowfieldBakeSettings& settings) {
  check_shadowfield_field_settings(settings.fields);
  check_basis_settings(settings.basis);
  check_srf_settings(settings.srf);
  if (settings.bits != 8 && settings.bits != 16)
    throw Error("shadowfield: bits must be 8 or 16, not " + std::to_string(settings.bits));
  if (settings.brdf.terms < 1 || settings.brdf.grid_size < 4 || settings.brdf.grid_size > 64)
    throw Error("shadowfield: the BRDF needs at least one term and a grid of 4..64");
}

ShadowfieldMaterial make_shadowfield_material(const ShadowfieldMaterialDescription& description,
                                              const SeparableBrdfOptions& options) {
  ShadowfieldMaterial material;
  switch (description.model) {
    case ShadowfieldBrdfModel::Diffuse:
      return material;
    case ShadowfieldBrdfModel::Phong:
      material.brdf = separate_brdf(brdf_function(description.phong), options);
      break;
    case ShadowfieldBrdfModel::Ggx:
      material.brdf = separate_brdf(brdf_function(description.ggx), options);
      break;
  }
  material.glossy = true;
  return material;
}

ShadowfieldBakeResult bake_shadowfield_object(const Scene& scene,
                                              const ShadowfieldMaterial& material,
                                              const ShadowfieldBakeSettings& settings,
                                              const Context& ctx) {
  check_shadowfield_bake_settings(settings);
  ShadowfieldBakeResult result;
  result.object = make_shadowfield_object(scene, material, settings.fields.order);
  const EmbreeScene rays(shadowfield_rays_scene(result.object), ctx);

  auto start = std::chrono::steady_clock::now();
  bake_occlusion_field(result.object, rays, settings.fields, ctx);
  result.seconds_fields = seconds_since(start);
  start = std::chrono::steady_clock::now();
  result.vertices_without_transfer = bake_self_transfer(result.object, rays, settings.fields, ctx);
  result.seconds_transfer = seconds_since(start);
  result.basis = bake_surface_basis(result.object, rays, settings.basis, ctx);
  result.srf = bake_source_radiance_fields(result.object, rays, settings.srf, ctx);
  return result;
}

std::vector<std::uint8_t> shadowfield_blob_of(const ShadowfieldObject& object, int bits,
                                              const std::string& info) {
  return build_shadowfield_blob(object, quantize_shadowfield(object, bits), info);
}

}  // namespace prt::bake
