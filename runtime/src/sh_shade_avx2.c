/* SPDX-License-Identifier: MIT */
/* avx2 kernel for sh shading: being written (issue 3). */
typedef int prt_sh_shade_avx2_in_progress;
