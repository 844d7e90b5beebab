// SPDX-License-Identifier: MIT
// The built-in default scene and sky: what ./scripts/demo and the tests use when no downloaded
// asset is at hand. Generated procedurally, so the repository ships no binary scene files.
#pragma once

#include <string>

#include "prt/baker/scene.hpp"
#include "prt/io/demo_sky.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake {

// A grey ground tile with a sphere, a torus and a box on it (about 12k vertices), in the glTF
// frame (+Y up, metres). Materials carry distinct diffuse base colours.
Scene make_demo_scene();

// The built-in sky (prt/io/demo_sky.hpp), shared with the samples.
using io::make_demo_sky;

// Writes the meshes of a static scene (positions, normals, indices, base-colour materials) as a
// binary glTF 2.0 file. Throws Error when the file cannot be written.
void write_glb(const Scene& scene, const std::string& path);

// Writes an environment map as a Radiance .hdr image (the mapping follows from its shape).
void write_envmap_hdr(const io::EnvMap& env, const std::string& path);

}  // namespace prt::bake
