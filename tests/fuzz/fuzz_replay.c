/* SPDX-License-Identifier: MIT */
/* Runs the fuzz target on files given on the command line (no libFuzzer needed). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
  int i;
  for (i = 1; i < argc; ++i) {
    FILE* f = fopen(argv[i], "rb");
    uint8_t* bytes;
    long n;
    size_t len;
    if (!f || fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
      fprintf(stderr, "fuzz_replay: cannot read %s\n", argv[i]);
      return 1;
    }
    bytes = (uint8_t*)malloc((size_t)n + 1);
    if (!bytes) return 1;
    len = fread(bytes, 1, (size_t)n, f);
    fclose(f);
    /* Every prefix too, each in its own exact-size allocation. */
    for (; len > 0; --len) {
      uint8_t* exact = (uint8_t*)malloc(len);
      if (!exact) return 1;
      memcpy(exact, bytes, len);
      LLVMFuzzerTestOneInput(exact, len);
      free(exact);
    }
    LLVMFuzzerTestOneInput(bytes, 0);
    free(bytes);
    printf("fuzz_replay: %s ok\n", argv[i]);
  }
  return 0;
}
