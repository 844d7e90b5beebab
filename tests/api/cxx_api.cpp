// SPDX-License-Identifier: MIT
// The public C headers used from C++ (-Wall -Wextra -Werror -pedantic): C linkage, no clashes;
// and the C++ layer prt/prt.hpp: handles, helpers and struct builders. Exits non-zero at the
// first check that fails; prints its line only when all passed.
#include <prt/format/blob_reader.h>
#include <prt/prt.hpp>

#include <cstdio>
#include <type_traits>
#include <vector>

int main() {
  static_assert(std::is_same_v<prt::ContextPtr::pointer, prt_context*>);
  static_assert(std::is_same_v<prt::AssetPtr::pointer, prt_asset*>);
  static_assert(std::is_same_v<prt::GlShShaderPtr::pointer, prt_gl_sh_shader*>);
  static_assert(std::is_same_v<prt::GlWaveletShaderPtr::pointer, prt_gl_wavelet_shader*>);
  auto [context, made] = prt::create_context();
  if (made != PRT_OK || !context) return 1;
  const prt_backend backend = prt_context_backend(context.get());
  if (prt_blob_find_kind(PRT_BLOB_TAG_VPOS, 1) == nullptr) return 2;
  // A failed load gives an empty handle and the result.
  const char not_a_blob[] = "not a blob";
  auto loaded =
      prt::load_asset_memory(context.get(), not_a_blob, sizeof not_a_blob, PRT_VALIDATE_QUICK);
  if (loaded.ok() || loaded.handle || loaded.result != PRT_ERROR_BAD_MAGIC) return 3;
  if (prt::load_asset_file(context.get(), "/nonexistent/blob.prtk", PRT_VALIDATE_FULL).result !=
      PRT_ERROR_IO)
    return 4;
  auto info = prt::sized<prt_technique_info>();
  if (info.struct_size != sizeof info || prt_technique_get_info(PRT_TECHNIQUE_SH, &info) != PRT_OK)
    return 5;
  const std::vector<float> texels(6 * 4 * 4 * 3, 1.0f);
  const prt_env_image cube = prt::cube_env(4, texels.data());
  std::vector<float> light(4 * 6 * 16 * 16);
  if (prt_wavelet_resample(PRT_WAVELET_PARAM_CUBE, 16, &cube, light.data()) != PRT_OK) return 6;
  std::printf("prtkit %s from C++: best backend %s\n", prt_get_version_string(),
              prt_backend_name(backend));
  return 0;
}
