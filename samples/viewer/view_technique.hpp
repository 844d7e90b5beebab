// SPDX-License-Identifier: MIT
// What prt-view needs from a technique: one implementation per technique folder (<t>/),
// all listed in techniques.cpp. The shared viewer code (loading, maps, backends, GL context,
// drawing, comparing) goes through this interface only and names no technique.
//
// The viewer draws per-vertex radiance: a technique shades the vertices of the blob's mesh.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <memory>
#include <string>

#include "blob_scene.hpp"
#include "prt/io/envmap.hpp"

namespace CLI {
class App;
}

namespace prt::view {

// The light the shared options ask for: the map as read (no rotation of its own), its file name
// for messages, and the turn about world +Y (formats/SPEC.md, Turning the environment).
struct LightRequest {
  const prt::io::EnvMap* map = nullptr;
  std::string map_path;
  double rotate_degrees = 0.0;
};

// A technique's GPU shading of one asset, made on the GL context current on this thread; holds
// the technique's GL objects (released while the context is still current).
class GlVertexShader {
 public:
  virtual ~GlVertexShader() = default;
  // Queues shading of vertices [first, first+count) under the technique's prepared light.
  virtual prt_result shade(std::uint32_t first, std::uint32_t count) = 0;
  // Reads the shaded RGB of vertices [first, first+count) back (count*3 floats).
  virtual prt_result read(std::uint32_t first, std::uint32_t count, float* rgb) = 0;
};

class ViewTechnique {
 public:
  virtual ~ViewTechnique() = default;

  virtual prt_technique technique() const = 0;

  // Adds the technique's own options to `app`, each in the help section `group`.
  virtual void add_options(CLI::App& app, const std::string& group) = 0;

  // The technique's section tag (a PRT_TAG), for messages.
  virtual std::uint32_t section_tag() const = 0;

  // Reads the technique's header from the scene's asset and returns the number of vertices its
  // section shades. Throws ViewerError when the runtime refuses.
  virtual std::uint32_t open(const BlobScene& scene) = 0;

  // Prints what the header holds: one line, starting with the blob's path.
  virtual void describe(const BlobScene& scene) const = 0;

  // Turns the map into the technique's light with the runtime, prints how (one line, starting
  // with the map's path) and keeps the light for shade() and the GL shader. Throws ViewerError.
  virtual void prepare_light(const BlobScene& scene, const LightRequest& request) = 0;

  // The runtime function shade() calls, for messages.
  virtual const char* shade_function() const = 0;

  // Shades vertices [first, first+count) on a CPU-side backend into rgb (count*3 floats).
  virtual prt_result shade(const BlobScene& scene, prt_backend backend, std::uint32_t first,
                           std::uint32_t count, float* rgb) const = 0;

  // The technique's GL shader for the scene's asset (prt_gl_<name>_create); empty with the
  // runtime's result in *result on failure. The shader reads the light prepare_light kept.
  virtual std::unique_ptr<GlVertexShader> create_gl(const BlobScene& scene, prt_gl_loader_fn loader,
                                                    void* loader_user,
                                                    prt_result* result) const = 0;
};

}  // namespace prt::view
