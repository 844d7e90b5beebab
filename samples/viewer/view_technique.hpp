// SPDX-License-Identifier: MIT
// What prt-view needs from a technique: one implementation per technique folder (<t>/),
// all listed in techniques.cpp. The shared viewer code (loading, maps, backends, GL context,
// drawing, comparing) goes through this interface only and names no technique.
//
// The viewer draws per-vertex radiance: a technique shades the vertices of the blob's mesh.
#pragma once

#include <prt/prt.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

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
  bool describe = true;  // prepare_light prints how it made the light
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
  // The GL buffer the shading writes: RGB float triples, 12-byte stride, one per vertex
  // (prt_gl_<t>_output_buffer), which a renderer binds as a vertex attribute.
  virtual std::uint32_t output_buffer() const = 0;
};

// A setting of the technique's light that a viewer may change while it runs (a slider or a
// check box in prt-viewer, an option of prt-view): a value of one kind in [min, max], read and
// written through get and set. set stores the value; it takes effect the next time the viewer
// calls prepare_light. The range is known once the blob is open (before, max is 0 and the value
// is the one given, unchecked).
struct LiveParameter {
  enum class Kind { Int, Float, Bool };
  std::string label;   // what the control shows, e.g. "light terms M"
  std::string option;  // the command-line option, e.g. "--light-coefficients"
  std::string help;    // the option's help text
  Kind kind = Kind::Int;
  double min = 0.0, max = 0.0;
  std::function<double()> get;
  std::function<void(double)> set;
};

class ViewTechnique {
 public:
  virtual ~ViewTechnique() = default;

  virtual prt_technique technique() const = 0;

  // Adds the technique's own options that are not live parameters to `app`, each in the help
  // section `group` (ViewTechniques adds the live parameters' options beside them).
  virtual void add_options(CLI::App&, const std::string& /*group*/) {}

  // The live parameters of the open blob's technique (none by default).
  virtual std::vector<LiveParameter> live_parameters() { return {}; }

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

  // Where the eye is (world x, y, z), given before shade() by viewers that know their camera;
  // only a technique whose shading depends on the view keeps it (the others ignore it).
  virtual void set_eye(const float /*eye*/[3]) {}

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
