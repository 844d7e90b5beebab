/* SPDX-License-Identifier: MIT */
/* prtkit runtime C API, umbrella header: include this one. C99 and C++.
 *
 * Conventions: every fallible call returns a prt_result (PRT_OK = 0); handles are opaque; the
 * caller may supply the allocator and a message callback per context; the runtime has no global
 * mutable state and never prints. Each header states the thread safety of its functions. */
#ifndef PRT_H
#define PRT_H

#include <prt/prt_asset.h>
#include <prt/prt_backend.h>
#include <prt/prt_cloth.h>
#include <prt/prt_cloth_asset.h>
#include <prt/prt_context.h>
#include <prt/prt_env.h>
#include <prt/prt_gl.h>
#include <prt/prt_pose_asset.h>
#include <prt/prt_scene.h>
#include <prt/prt_sh.h>
#include <prt/prt_sh_asset.h>
#include <prt/prt_shadowfield.h>
#include <prt/prt_shadowfield_asset.h>
#include <prt/prt_technique.h>
#include <prt/prt_types.h>
#include <prt/prt_version.h>
#include <prt/prt_wavelet.h>
#include <prt/prt_wavelet_asset.h>
#include <prt/prt_wavelet_source.h>
#include <prt/prt_workers.h>

#endif /* PRT_H */
