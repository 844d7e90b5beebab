/* SPDX-License-Identifier: MIT */
#include "reader_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

prt_blob_status prt_blob_fail(prt_blob_status status, char* msg, size_t cap, const char* fmt, ...) {
  if (msg && cap > 0) {
    va_list args;
    va_start(args, fmt);
    vsnprintf(msg, cap, fmt, args);
    va_end(args);
  }
  return status;
}

int prt_blob_bytes_are_zero(const uint8_t* p, size_t n) {
  size_t i;
  for (i = 0; i < n; ++i)
    if (p[i] != 0) return 0;
  return 1;
}

float prt_blob_load_f32(const uint8_t* p) {
  uint32_t bits = prt_le_load_u32(p);
  float f;
  memcpy(&f, &bits, sizeof f);
  return f;
}

int prt_blob_f32_is_finite(float f) {
  return f == f && f - f == 0.0f;
}
