// SPDX-License-Identifier: MIT
#include "vertex_shading.hpp"

#include <prt/prt.hpp>

#include <algorithm>
#include <chrono>

namespace prt::view {
namespace {

prt_backend to_runtime(ViewBackend backend) {
  switch (backend) {
    case ViewBackend::Cpu:
      return PRT_BACKEND_CPU;
    case ViewBackend::Simd:
      return PRT_BACKEND_SIMD;
    case ViewBackend::Gl:
      return PRT_BACKEND_GL;
    case ViewBackend::Auto:
      break;
  }
  return PRT_BACKEND_AUTO;
}

// Why `backend` failed, in the runtime's words: the result and the backend query's note.
std::string backend_failure(const prt_context* context, const char* call, prt_backend backend,
                            prt_result result) {
  std::string text = std::string("backend ") + prt_backend_name(backend) + ": " + call +
                     " failed: " + prt_result_string(result);
  prt_backend_info info = prt::sized<prt_backend_info>();
  if (prt_backend_get_info(context, backend, &info) == PRT_OK && info.note && *info.note) {
    text += std::string(" (") + info.note + ")";
  }
  if (result == PRT_ERROR_UNSUPPORTED_BACKEND) {
    text += "; try --backend cpu";
  }
  return text;
}

}  // namespace

ViewBackend parse_backend(const std::string& name) {
  if (name == "auto") return ViewBackend::Auto;
  if (name == "cpu") return ViewBackend::Cpu;
  if (name == "simd") return ViewBackend::Simd;
  if (name == "gl") return ViewBackend::Gl;
  throw ViewerError("unknown backend '" + name + "' (expected auto, cpu, simd or gl)");
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

ShadingRun shade_vertices(const BlobScene& scene, const ViewTechnique& technique,
                          ViewBackend backend, int frames) {
  if (backend == ViewBackend::Gl) return shade_vertices_gl(scene, technique, frames);
  const prt_backend requested = to_runtime(backend);
  const prt_backend used =
      requested == PRT_BACKEND_AUTO ? prt_context_backend(scene.context()) : requested;
  const std::uint32_t vertices = scene.vertex_count();

  ShadingRun run;
  run.radiance.assign(3u * vertices, 0.0f);
  run.backend = prt_backend_name(used);
  run.isa = "scalar";
  if (used == PRT_BACKEND_SIMD) {
    prt_backend_info info = prt::sized<prt_backend_info>();
    if (prt_backend_get_info(scene.context(), PRT_BACKEND_SIMD, &info) == PRT_OK) {
      run.isa = prt_simd_isa_name(info.isa);
    }
  }
  for (int frame = 0; frame < std::max(frames, 1); ++frame) {
    const auto start = std::chrono::steady_clock::now();
    const prt_result result = technique.shade(scene, requested, 0, vertices, run.radiance.data());
    const auto stop = std::chrono::steady_clock::now();
    if (result != PRT_OK) {
      throw ViewerError(backend_failure(scene.context(), technique.shade_function(), used, result));
    }
    run.frame_ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
  }
  run.median_ms = median(run.frame_ms);
  return run;
}

}  // namespace prt::view
