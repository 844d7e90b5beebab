// SPDX-License-Identifier: MIT
// Shading every vertex of the blob on a chosen backend, optionally several times to time it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "blob_scene.hpp"
#include "view_technique.hpp"

namespace prt::view {

enum class ViewBackend { Auto, Cpu, Simd, Gl };

// "auto" | "cpu" | "simd" | "gl"; throws ViewerError otherwise.
ViewBackend parse_backend(const std::string& name);

struct ShadingRun {
  std::vector<float> radiance;   // RGB per vertex, vertex order of the blob
  std::string backend;           // the backend that ran ("cpu", "simd", "gl")
  std::string isa;               // SIMD instruction set, "scalar", or the GL renderer
  std::vector<double> frame_ms;  // one entry per frame
  double median_ms = 0.0;
};

// Shades all vertices `frames` (>= 1) times under the light `technique` prepared and keeps the
// last result. CPU-side backends go through ViewTechnique::shade (auto = the context's best); gl
// through the technique's GL shader on a headless EGL context. A frame's time covers shading
// every vertex (for gl: the dispatch and a glFinish, not the read-back). Throws ViewerError with
// the runtime's reason when the backend cannot be used.
ShadingRun shade_vertices(const BlobScene& scene, const ViewTechnique& technique,
                          ViewBackend backend, int frames);

// The GL path: gl_shading.cpp, or gl_shading_unavailable.cpp (an error naming the build option)
// when prt-view is built without GL.
ShadingRun shade_vertices_gl(const BlobScene& scene, const ViewTechnique& technique, int frames);

// Median of the frame times (sorted copy).
double median(std::vector<double> values);

}  // namespace prt::view
