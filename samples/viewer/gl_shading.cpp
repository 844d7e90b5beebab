// SPDX-License-Identifier: MIT
// --backend gl: the runtime's GL evaluator on a headless EGL context (Mesa llvmpipe on a machine
// without a GPU), entry points from the helper's loader, as a game would hand over its own.
#include <prt/prt.hpp>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>

#include "headless_gl.h"
#include "vertex_shading.hpp"

namespace prt::view {
namespace {

struct GlContextDeleter {
  void operator()(headless_gl* gl) const { headless_gl_destroy(gl); }
};

std::string runtime_message(const BlobScene& scene, const std::string& call, prt_result result) {
  const char* message = prt_context_last_message(scene.context());
  return "backend gl: " + call + " failed: " + prt_result_string(result) +
         (message && *message ? std::string(": ") + message : std::string());
}

}  // namespace

ShadingRun shade_vertices_gl(const BlobScene& scene, const ViewTechnique& technique, int frames) {
  char error[512] = {0};
  std::unique_ptr<headless_gl, GlContextDeleter> gl(headless_gl_create(error, sizeof error));
  if (!gl) throw ViewerError(std::string("backend gl: no headless GL context: ") + error);
  using FinishFn = void (*)(void);
  const auto finish = reinterpret_cast<FinishFn>(headless_gl_get_proc(gl.get(), "glFinish"));
  if (!finish) throw ViewerError("backend gl: the GL loader has no glFinish");

  // The runtime's GL functions of a technique are prt_gl_<name>_create/shade/read.
  prt_technique_info info = prt::sized<prt_technique_info>();
  const std::string prefix =
      std::string("prt_gl_") +
      (prt_technique_get_info(technique.technique(), &info) == PRT_OK ? info.name : "?") + "_";
  prt_result created = PRT_OK;
  std::unique_ptr<GlVertexShader> shader =
      technique.create_gl(scene, headless_gl_get_proc, gl.get(), &created);
  if (!shader) throw ViewerError(runtime_message(scene, prefix + "create", created));

  const std::uint32_t vertices = scene.vertex_count();
  ShadingRun run;
  run.backend = "gl";
  run.isa = headless_gl_renderer(gl.get());
  for (int frame = 0; frame < std::max(frames, 1); ++frame) {
    const auto start = std::chrono::steady_clock::now();
    const prt_result result = shader->shade(0, vertices);
    finish();
    const auto stop = std::chrono::steady_clock::now();
    if (result != PRT_OK) throw ViewerError(runtime_message(scene, prefix + "shade", result));
    run.frame_ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
  }
  run.radiance.assign(3u * vertices, 0.0f);
  const prt_result read = shader->read(0, vertices, run.radiance.data());
  if (read != PRT_OK) throw ViewerError(runtime_message(scene, prefix + "read", read));
  run.median_ms = median(run.frame_ms);
  shader.reset();  // GL objects go while the context is still current
  return run;
}

}  // namespace prt::view
