/* SPDX-License-Identifier: MIT */
/* Helpers shared by the runtime's SH files (not public). */
#ifndef PRT_RUNTIME_SH_INTERNAL_H
#define PRT_RUNTIME_SH_INTERNAL_H

#include <prt/prt_sh.h>

/* All order*order basis values at a unit direction given in the SH frame (x_sh, y_sh, z_sh),
 * in double. order must be 1..PRT_SH_MAX_ORDER. */
void prt_sh_eval_sh_frame_d(uint32_t order, double x, double y, double z, double* out);

/* Normalises a world direction and maps it to the SH frame; returns 0 for a zero or
 * non-finite vector. */
int prt_sh_world_to_sh_frame(const float dir[3], double sh_dir[3]);

#endif /* PRT_RUNTIME_SH_INTERNAL_H */
