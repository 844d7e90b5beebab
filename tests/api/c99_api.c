/* SPDX-License-Identifier: MIT */
/* Compiled as strict C99 with -Wall -Wextra -Werror -pedantic: the umbrella header and a few
 * calls through it. Each header is also compiled alone (generated files, see CMakeLists.txt). */
#include <prt/format/blob_layout.h>
#include <prt/format/blob_reader.h>
#include <prt/prt.h>

#include <stdio.h>

int main(void) {
  prt_context* context = NULL;
  prt_context_desc desc = {0};
  prt_backend_info info;
  prt_result result;
  desc.struct_size = sizeof desc;
  if (prt_get_version() != PRT_VERSION) return 1;
  result = prt_context_create(&desc, &context);
  if (result != PRT_OK) return 2;
  info.struct_size = sizeof info;
  if (prt_backend_get_info(context, PRT_BACKEND_CPU, &info) != PRT_OK || !info.usable) return 3;
  if (prt_asset_validate(context, "PRTK", 4, PRT_VALIDATE_QUICK, NULL, 0) != PRT_ERROR_TRUNCATED)
    return 4;
  printf("prtkit %s from C99: %s\n", prt_get_version_string(), prt_context_last_message(context));
  prt_context_destroy(context);
  return 0;
}
