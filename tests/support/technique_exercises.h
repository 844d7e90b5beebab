/* SPDX-License-Identifier: MIT */
/* The test-side table of techniques: for each technique the runtime knows (prt_technique.h), how
 * a test exercises an asset holding its section. One row per technique, its exercise in the
 * technique's own test folder; code that tests every technique (the fuzzer) loops over
 * prt_asset_techniques() and this table, naming no technique. Plain C99. Included by relative path
 * so that a C target needs no include directory. */
#ifndef PRT_TEST_TECHNIQUE_EXERCISES_H
#define PRT_TEST_TECHNIQUE_EXERCISES_H

#include <prt/prt.h>

#include "../cloth/cloth_exercise.h"
#include "../pose/pose_exercise.h"
#include "../sh/sh_exercise.h"
#include "../shadowfield/shadowfield_exercise.h"
#include "../wavelet/wavelet_exercise.h"

/* Exercises every function of one technique on `asset` (loaded at `level`, holding the
 * technique's section). Returns 0 when a call failed that the level promises to succeed. */
typedef int (*prt_test_exercise_fn)(const prt_asset* asset, prt_validation level);

typedef struct prt_test_technique_exercise {
  prt_technique technique;
  prt_test_exercise_fn exercise;
} prt_test_technique_exercise;

static const prt_test_technique_exercise prt_test_technique_exercises[] = {
    {PRT_TECHNIQUE_SH, prt_test_exercise_sh},
    {PRT_TECHNIQUE_WAVELET, prt_test_exercise_wavelet},
    {PRT_TECHNIQUE_POSE, prt_test_exercise_pose},
    {PRT_TECHNIQUE_CLOTH, prt_test_exercise_cloth},
    {PRT_TECHNIQUE_SHADOWFIELD, prt_test_exercise_shadowfield},
};

#define PRT_TEST_TECHNIQUE_EXERCISE_COUNT \
  (sizeof prt_test_technique_exercises / sizeof prt_test_technique_exercises[0])

/* Runs the exercise of every technique `asset` holds. Returns 0 when one failed, or when the
 * asset holds a technique the table has no row for. */
static int prt_test_exercise_techniques(const prt_asset* asset, prt_validation level) {
  uint32_t held = prt_asset_techniques(asset);
  size_t i;
  int ok = 1;
  for (i = 0; i < PRT_TEST_TECHNIQUE_EXERCISE_COUNT; ++i) {
    const uint32_t bit = 1u << prt_test_technique_exercises[i].technique;
    if (!(held & bit)) continue;
    if (!prt_test_technique_exercises[i].exercise(asset, level)) ok = 0;
    held &= ~bit;
  }
  return ok && held == 0;
}

#endif /* PRT_TEST_TECHNIQUE_EXERCISES_H */
