// SPDX-License-Identifier: MIT
// prtkit runtime, a thin header-only C++17 layer over the C API (prt/prt.h) for C++ users:
// owning handles (std::unique_ptr with the runtime's destroy functions as deleters), helpers
// that create or load a handle and return it with the prt_result, and builders of the structs
// callers fill in most (struct_size set, tight environment images). No exceptions are thrown and
// nothing is added to the library: every call goes straight to the C function of the same name,
// with its thread-safety rules.
//
//   auto [context, made] = prt::create_context();            // prt::ContextPtr, prt_result
//   auto [asset, loaded] = prt::load_asset_file(context.get(), "scene.prtk", PRT_VALIDATE_FULL);
//   if (loaded != PRT_OK) std::puts(prt_context_last_message(context.get()));
//   auto info = prt::sized<prt_sh_info>();                   // struct_size already set
//   prt_sh_get_info(asset.get(), &info);
//
// Destruction order is the C API's: shaders before their assets, assets before their context
// (declare the context first, so that it is destroyed last).
#ifndef PRT_PRT_HPP
#define PRT_PRT_HPP

#include <prt/prt.h>

#include <cstddef>
#include <cstdint>
#include <memory>

namespace prt {

struct ContextDeleter {
  void operator()(prt_context* context) const noexcept { prt_context_destroy(context); }
};
struct AssetDeleter {
  void operator()(prt_asset* asset) const noexcept { prt_asset_destroy(asset); }
};
struct GlShShaderDeleter {
  void operator()(prt_gl_sh_shader* shader) const noexcept { prt_gl_sh_destroy(shader); }
};
struct GlWaveletShaderDeleter {
  void operator()(prt_gl_wavelet_shader* shader) const noexcept { prt_gl_wavelet_destroy(shader); }
};
struct WaveletSourceDeleter {
  void operator()(prt_wavelet_source* source) const noexcept { prt_wavelet_source_destroy(source); }
};
struct SceneDeleter {
  void operator()(prt_scene* scene) const noexcept { prt_scene_destroy(scene); }
};

using ContextPtr = std::unique_ptr<prt_context, ContextDeleter>;
using AssetPtr = std::unique_ptr<prt_asset, AssetDeleter>;
using GlShShaderPtr = std::unique_ptr<prt_gl_sh_shader, GlShShaderDeleter>;
using GlWaveletShaderPtr = std::unique_ptr<prt_gl_wavelet_shader, GlWaveletShaderDeleter>;
using WaveletSourcePtr = std::unique_ptr<prt_wavelet_source, WaveletSourceDeleter>;
using ScenePtr = std::unique_ptr<prt_scene, SceneDeleter>;

// A handle and the result of the call that made it (the handle is empty unless result is PRT_OK).
// Binds to `auto [handle, result] = ...`.
template <typename Ptr>
struct Made {
  Ptr handle;
  prt_result result;
  bool ok() const noexcept { return result == PRT_OK; }
};

// A zero-initialised struct of the C API with struct_size set (prt_types.h), ready to be passed.
template <typename T>
T sized() noexcept {
  T value{};
  value.struct_size = sizeof(T);
  return value;
}

// An environment image (prt_env.h) of `width` x `height` lat-long texels, tightly packed.
inline prt_env_image latlong_env(std::uint32_t width, std::uint32_t height, const float* texels,
                                 std::uint32_t channels = 3,
                                 const float* rotation = nullptr) noexcept {
  prt_env_image env = sized<prt_env_image>();
  env.layout = PRT_ENV_LATLONG;
  env.width = width;
  env.height = height;
  env.channels = channels;
  env.texels = texels;
  env.rotation = rotation;
  return env;
}

// An environment image of six cube faces of face_size^2 texels, back to back, tightly packed.
inline prt_env_image cube_env(std::uint32_t face_size, const float* texels,
                              std::uint32_t channels = 3,
                              const float* rotation = nullptr) noexcept {
  prt_env_image env = latlong_env(face_size, face_size, texels, channels, rotation);
  env.layout = PRT_ENV_CUBE;
  return env;
}

// prt_context_create; desc may be nullptr (defaults).
inline Made<ContextPtr> create_context(const prt_context_desc* desc = nullptr) noexcept {
  prt_context* context = nullptr;
  const prt_result result = prt_context_create(desc, &context);
  return {ContextPtr(context), result};
}

// prt_asset_load_memory (copies the bytes).
inline Made<AssetPtr> load_asset_memory(prt_context* context, const void* data, std::size_t size,
                                        prt_validation validation) noexcept {
  prt_asset* asset = nullptr;
  const prt_result result = prt_asset_load_memory(context, data, size, validation, &asset);
  return {AssetPtr(asset), result};
}

// prt_asset_load_memory_borrowed (reads the bytes in place: they must outlive the asset).
inline Made<AssetPtr> load_asset_memory_borrowed(prt_context* context, const void* data,
                                                 std::size_t size,
                                                 prt_validation validation) noexcept {
  prt_asset* asset = nullptr;
  const prt_result result = prt_asset_load_memory_borrowed(context, data, size, validation, &asset);
  return {AssetPtr(asset), result};
}

// prt_asset_load_file.
inline Made<AssetPtr> load_asset_file(prt_context* context, const char* path,
                                      prt_validation validation) noexcept {
  prt_asset* asset = nullptr;
  const prt_result result = prt_asset_load_file(context, path, validation, &asset);
  return {AssetPtr(asset), result};
}

// prt_scene_load_file; desc may be nullptr (defaults).
inline Made<ScenePtr> load_scene_file(prt_context* context, const char* path,
                                      const prt_scene_desc* desc = nullptr) noexcept {
  prt_scene* scene = nullptr;
  const prt_result result = prt_scene_load_file(context, path, desc, &scene);
  return {ScenePtr(scene), result};
}

// prt_gl_sh_create (the GL context current on this thread).
inline Made<GlShShaderPtr> gl_sh_create(prt_context* context, const prt_asset* asset,
                                        prt_gl_loader_fn loader, void* loader_user) noexcept {
  prt_gl_sh_shader* shader = nullptr;
  const prt_result result = prt_gl_sh_create(context, asset, loader, loader_user, &shader);
  return {GlShShaderPtr(shader), result};
}

// prt_gl_wavelet_create (the GL context current on this thread).
inline Made<GlWaveletShaderPtr> gl_wavelet_create(prt_context* context, const prt_asset* asset,
                                                  prt_gl_loader_fn loader,
                                                  void* loader_user) noexcept {
  prt_gl_wavelet_shader* shader = nullptr;
  const prt_result result = prt_gl_wavelet_create(context, asset, loader, loader_user, &shader);
  return {GlWaveletShaderPtr(shader), result};
}

}  // namespace prt

#endif  // PRT_PRT_HPP
