/* SPDX-License-Identifier: MIT */
/* A tiny C99 consumer of the installed (or add_subdirectory'd) runtime: loads a blob with full
 * validation, prints its section count, and evaluates SH basis functions, whose maths needs libm
 * at the link of a static runtime. Usage: consumer FILE.prtk */
#include <prt/prt.h>

#include <stdio.h>

int main(int argc, char** argv) {
  prt_context* context = NULL;
  prt_asset* asset = NULL;
  const float up[3] = {0.0f, 1.0f, 0.0f};
  float basis[4];
  if (argc != 2 || prt_context_create(NULL, &context) != PRT_OK) return 2;
  if (prt_asset_load_file(context, argv[1], PRT_VALIDATE_FULL, &asset) != PRT_OK) {
    fprintf(stderr, "consumer: %s\n", prt_context_last_message(context));
    prt_context_destroy(context);
    return 1;
  }
  if (prt_sh_eval(2, up, basis) != PRT_OK) return 3;
  printf("consumer: prtkit %s loaded %u sections; Y_10(up) = %.6f\n", prt_get_version_string(),
         (unsigned)prt_asset_section_count(asset), basis[2]);
  prt_asset_destroy(asset);
  prt_context_destroy(context);
  return 0;
}
