/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield` in the test-side table of exercises (support/technique_exercises.h):
 * every read of an asset's SFLD section the public API offers so far, its header. Plain C99 (the
 * fuzzer is C). */
#ifndef PRT_TEST_SHADOWFIELD_EXERCISE_H
#define PRT_TEST_SHADOWFIELD_EXERCISE_H

#include <prt/prt.h>

/* Returns 0 when prt_shadowfield_get_info failed: the load checked the header, so it cannot,
 * whatever the level. */
static int prt_test_exercise_shadowfield(const prt_asset* asset, prt_validation level) {
  prt_shadowfield_info info;
  (void)level;
  info.struct_size = sizeof info;
  return prt_shadowfield_get_info(asset, &info) == PRT_OK && info.vertex_count > 0;
}

#endif /* PRT_TEST_SHADOWFIELD_EXERCISE_H */
