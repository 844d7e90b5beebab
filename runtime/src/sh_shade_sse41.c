/* SPDX-License-Identifier: MIT */
/* sse41 kernel for sh shading: being written (issue 3). */
typedef int prt_sh_shade_sse41_in_progress;
