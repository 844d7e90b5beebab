// SPDX-License-Identifier: MIT
// The built-in default scene and sky: what ./scripts/demo and the tests use when no downloaded
// asset is at hand. Generated procedurally, so the repository ships no binary scene files.
#pragma once

#include <string>

#include "prt/baker/scene.hpp"
#include "prt/io/envmap.hpp"

namespace prt::bake {

// A grey ground tile with a sphere, a torus and a box on it (about 12k vertices), in the glTF
// frame (+Y up, metres). Materials carry distinct diffuse base colours.
Scene make_demo_scene();

// A lat-long sky (width x width/2): a blue-to-white gradient, a darker ground below the horizon
// and a small sun disc that holds most of the power, placed so that the default camera (looking
// down -Z) sees the shadows.
io::EnvMap make_demo_sky(int width = 512);

// Writes the meshes of a static scene (positions, normals, indices, base-colour materials) as a
// binary glTF 2.0 file. Throws Error when the file cannot be written.
void write_glb(const Scene& scene, const std::string& path);

// Writes an environment map as a Radiance .hdr image (the mapping follows from its shape).
void write_envmap_hdr(const io::EnvMap& env, const std::string& path);

}  // namespace prt::bake
