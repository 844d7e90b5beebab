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

std::string runtime_message(const BlobScene& scene, const std::string& call, prt_result result) {
  const char* message = prt_context_last_message(scene.context());
  return "backend gl: " + call + " failed: " + prt_result_string(result) +
         (message && *message ? std::string(": ") + message : std::string());
}

// The prt_gl_<technique>_* calls of one technique, so that one loop drives both.
template <typename Shader>
struct GlTechnique {
  const char* name;  // "sh" or "wavelet", for messages
  prt_result (*create)(prt_context*, const prt_asset*, prt_gl_loader_fn, void*, Shader**);
  void (*destroy)(Shader*);
  prt_result (*shade)(Shader*, const float*, std::uint32_t, std::uint32_t);
  prt_result (*read)(Shader*, std::uint32_t, std::uint32_t, float*);
};

template <typename Shader>
ShadingRun run_gl(const GlTechnique<Shader>& technique, const BlobScene& scene,
                  const std::vector<float>& light, int frames) {
  char error[512] = {0};
  std::unique_ptr<headless_gl, GlContextDeleter> gl(headless_gl_create(error, sizeof error));
  if (!gl) throw ViewerError(std::string("backend gl: no headless GL context: ") + error);
  using FinishFn = void (*)(void);
  const auto finish = reinterpret_cast<FinishFn>(headless_gl_get_proc(gl.get(), "glFinish"));
  if (!finish) throw ViewerError("backend gl: the GL loader has no glFinish");

  const std::string prefix = std::string("prt_gl_") + technique.name + "_";
  Shader* raw = nullptr;
  const prt_result created =
      technique.create(scene.context(), scene.asset(), headless_gl_get_proc, gl.get(), &raw);
  if (created != PRT_OK) throw ViewerError(runtime_message(scene, prefix + "create", created));
  std::unique_ptr<Shader, void (*)(Shader*)> shader(raw, technique.destroy);

  const std::uint32_t vertices = scene.vertex_count();
  ShadingRun run;
  run.backend = "gl";
  run.isa = headless_gl_renderer(gl.get());
  for (int frame = 0; frame < std::max(frames, 1); ++frame) {
    const auto start = std::chrono::steady_clock::now();
    const prt_result result = technique.shade(shader.get(), light.data(), 0, vertices);
    finish();
    const auto stop = std::chrono::steady_clock::now();
    if (result != PRT_OK) throw ViewerError(runtime_message(scene, prefix + "shade", result));
    run.frame_ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
  }
  run.radiance.assign(3u * vertices, 0.0f);
  const prt_result read = technique.read(shader.get(), 0, vertices, run.radiance.data());
  if (read != PRT_OK) throw ViewerError(runtime_message(scene, prefix + "read", read));
  run.median_ms = median(run.frame_ms);
  shader.reset();  // GL objects go while the context is still current
  return run;
}

}  // namespace

ShadingRun shade_vertices_gl(const BlobScene& scene, const std::vector<float>& light, int frames) {
  if (scene.technique() == Technique::Sh) {
    const GlTechnique<prt_gl_sh_shader> sh{"sh", prt_gl_sh_create, prt_gl_sh_destroy,
                                           prt_gl_sh_shade, prt_gl_sh_read};
    return run_gl(sh, scene, light, frames);
  }
  const GlTechnique<prt_gl_wavelet_shader> wavelet{"wavelet", prt_gl_wavelet_create,
                                                   prt_gl_wavelet_destroy, prt_gl_wavelet_shade,
                                                   prt_gl_wavelet_read};
  return run_gl(wavelet, scene, light, frames);
}

}  // namespace prt::view
