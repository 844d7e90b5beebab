// SPDX-License-Identifier: MIT
// One object's whole `shadowfield` bake (docs/shadowfield/design.md): its material separated,
// its occlusion field, self-shadowed transfer, surface-radiance basis and source radiance fields,
// each stage of shadowfield_fields.hpp and shadowfield_radiance.hpp in turn, over one ray-tracing
// scene of the object alone. What `prt-bake bake shadowfield`, the scenes and the trade share.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/context.hpp"
#include "prt/baker/scene.hpp"
#include "prt/baker/shadowfield/shadowfield_blob.hpp"
#include "prt/baker/shadowfield/shadowfield_fields.hpp"
#include "prt/baker/shadowfield/shadowfield_object.hpp"
#include "prt/baker/shadowfield/shadowfield_radiance.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"

namespace prt::bake {

struct ShadowfieldBakeSettings {
  ShadowfieldFieldSettings fields;  // order, OOF shells, rays
  ShadowfieldBasisSettings basis;   // N, lights
  SrfSettings srf;                  // the SRF's shells and rays
  SeparableBrdfOptions brdf;        // K and the BRDF table's grid (glossy materials)
  int bits = 16;                    // quantisation of the blob, 8 or 16
};

// Throws Error naming the first bad setting (each stage's own check, and the bits).
void check_shadowfield_bake_settings(const ShadowfieldBakeSettings& settings);

// The material a description bakes to: diffuse, or the model separated into settings' K terms.
ShadowfieldMaterial make_shadowfield_material(const ShadowfieldMaterialDescription& description,
                                              const SeparableBrdfOptions& options);

struct ShadowfieldBakeResult {
  ShadowfieldObject object;
  ShadowfieldBasisReport basis;
  SrfReport srf;
  std::size_t vertices_without_transfer = 0;  // bad normal or position: zero transfer
  double seconds_fields = 0.0, seconds_transfer = 0.0;
};

// The scene every stage casts rays into: the object alone as one mesh, so every stage sees the
// same triangles and the SRF's "mesh 0 glows" holds for an object made of several meshes.
Scene shadowfield_rays_scene(const ShadowfieldObject& object);

// Bakes the object `scene` holds (its meshes joined, make_shadowfield_object) with `material`.
// The SRF's shells are centred on the OOF's bounding sphere. Progress and cancellation through
// ctx; throws Error for bad settings or an object the stages refuse.
ShadowfieldBakeResult bake_shadowfield_object(const Scene& scene,
                                              const ShadowfieldMaterial& material,
                                              const ShadowfieldBakeSettings& settings,
                                              const Context& ctx);

// The blob of a baked object: quantised to settings.bits and written with `info`.
std::vector<std::uint8_t> shadowfield_blob_of(const ShadowfieldObject& object, int bits,
                                              const std::string& info);

}  // namespace prt::bake
