// SPDX-License-Identifier: MIT
// --backend gl: the runtime's GL evaluator on a headless EGL context (Mesa llvmpipe on a machine
// without a GPU), entry points from the helper's loader, as a game would hand over its own.
#include <prt/prt.h>

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
struct GlShaderDeleter {
  void operator()(prt_gl_sh_shader* shader) const { prt_gl_sh_destroy(shader); }
};

std::string runtime_message(const BlobScene& scene, const char* call, prt_result result) {
  const char* message = prt_context_last_message(scene.context());
  return std::string("backend gl: ") + call + " failed: " + prt_result_string(result) +
         (message && *message ? std::string(": ") + message : std::string());
}

}  // namespace

ShadingRun shade_vertices_gl(const BlobScene& scene, const std::vector<float>& light, int frames) {
  char error[512] = {0};
  std::unique_ptr<headless_gl, GlContextDeleter> gl(headless_gl_create(error, sizeof error));
  if (!gl) throw ViewerError(std::string("backend gl: no headless GL context: ") + error);
  using FinishFn = void (*)(void);
  const auto finish = reinterpret_cast<FinishFn>(headless_gl_get_proc(gl.get(), "glFinish"));
  if (!finish) throw ViewerError("backend gl: the GL loader has no glFinish");

  prt_gl_sh_shader* raw = nullptr;
  const prt_result created = prt_gl_sh_create(scene.asset(), headless_gl_get_proc, gl.get(), &raw);
  if (created != PRT_OK) throw ViewerError(runtime_message(scene, "prt_gl_sh_create", created));
  std::unique_ptr<prt_gl_sh_shader, GlShaderDeleter> shader(raw);

  const std::uint32_t vertices = scene.transfer().vertex_count;
  ShadingRun run;
  run.backend = "gl";
  run.isa = headless_gl_renderer(gl.get());
  for (int frame = 0; frame < std::max(frames, 1); ++frame) {
    const auto start = std::chrono::steady_clock::now();
    const prt_result result = prt_gl_sh_shade(shader.get(), light.data(), 0, vertices);
    finish();
    const auto stop = std::chrono::steady_clock::now();
    if (result != PRT_OK) throw ViewerError(runtime_message(scene, "prt_gl_sh_shade", result));
    run.frame_ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
  }
  run.radiance.assign(3u * vertices, 0.0f);
  const prt_result read = prt_gl_sh_read(shader.get(), 0, vertices, run.radiance.data());
  if (read != PRT_OK) throw ViewerError(runtime_message(scene, "prt_gl_sh_read", read));
  run.median_ms = median(run.frame_ms);
  shader.reset();  // GL objects go while the context is still current
  return run;
}

}  // namespace prt::view
