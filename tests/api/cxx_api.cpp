// SPDX-License-Identifier: MIT
// The public C headers used from C++ (-Wall -Wextra -Werror -pedantic): C linkage, no clashes.
#include <prt/format/blob_reader.h>
#include <prt/prt.h>

#include <cstdio>

int main() {
  prt_context* context = nullptr;
  if (prt_context_create(nullptr, &context) != PRT_OK) return 1;
  const prt_backend backend = prt_context_backend(context);
  prt_context_destroy(context);
  if (prt_blob_find_kind(PRT_BLOB_TAG_VPOS, 1) == nullptr) return 2;
  std::printf("prtkit %s from C++: best backend %s\n", prt_get_version_string(),
              prt_backend_name(backend));
  return 0;
}
