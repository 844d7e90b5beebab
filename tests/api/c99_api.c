/* SPDX-License-Identifier: MIT */
/* Compiled as strict C99 with -Wall -Wextra -Werror -pedantic: the umbrella header and a few
 * calls through it, the struct_size convention, the enums and the environment image from C. Each
 * header is also compiled alone (generated files, see CMakeLists.txt). Exits non-zero at the
 * first check that fails; prints its line only when all passed. */
#include <prt/format/blob_layout.h>
#include <prt/format/blob_reader.h>
#include <prt/prt.h>

#include <stdio.h>

int main(void) {
  prt_context* context = NULL;
  prt_context_desc desc = {0};
  prt_backend_info info;
  prt_technique_info technique;
  prt_env_image env = {0};
  static float texels[8 * 4 * 3];
  float sh[4 * 3];
  prt_wavelet_param param = PRT_WAVELET_PARAM_CUBE;
  prt_result result;
  desc.struct_size = sizeof desc;
  desc.flags = PRT_CONTEXT_READ_ENVIRONMENT;
  if (prt_get_version() != PRT_VERSION) return 1;
  result = prt_context_create(&desc, &context);
  if (result != PRT_OK) return 2;
  info.struct_size = sizeof info;
  if (prt_backend_get_info(context, PRT_BACKEND_CPU, &info) != PRT_OK || !info.usable) return 3;
  if (prt_asset_validate(context, "PRTK", 4, PRT_VALIDATE_QUICK, NULL, 0) != PRT_ERROR_TRUNCATED)
    return 4;
  technique.struct_size = sizeof technique;
  if (prt_technique_get_info(PRT_TECHNIQUE_WAVELET, &technique) != PRT_OK ||
      technique.section_tag != PRT_SECTION_WVLT)
    return 5;
  env.struct_size = sizeof env;
  env.layout = PRT_ENV_LATLONG;
  env.width = 8;
  env.height = 4;
  env.channels = 3;
  env.texels = texels;
  if (prt_env_image_validate(&env) != PRT_OK || prt_sh_project(2, &env, sh) != PRT_OK) return 6;
  if (prt_wavelet_face_count(param) != 6u) return 7;
  printf("prtkit %s from C99: %s\n", prt_get_version_string(), prt_context_last_message(context));
  prt_context_destroy(context);
  return 0;
}
