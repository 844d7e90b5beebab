/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the AVX2 + FMA backend of `cloth` shading (cloth_shade_avx2.c, compiled
 * with those flags). Only cloth_shade.c calls it, and only when the context's SIMD ISA is AVX2 or
 * above. It follows the scalar reference (cloth_shade.c, cloth_integrals.c, cloth_tables.c) step
 * by step in float, eight samples at a time; each sample's bits are the same wherever a call's
 * range starts, so split ranges give the one-range call's bits. */
#ifndef PRT_RUNTIME_CLOTH_SHADE_SIMD_H
#define PRT_RUNTIME_CLOTH_SHADE_SIMD_H

#include "cloth_shade_internal.h"

#if defined(PRT_HAS_X86_SIMD)
/* Samples [first, first + count) into out_rgb (3 count floats), as the scalar shade_scalar. The
 * light and fabric are prepared (prt_cloth_prepare_light / _fabric); the method's flags may undo
 * the kernel's own savings for measuring them: PRT_CLOTH_NO_FRAME_CACHE (what the frame alone
 * decides, computed for every batch), PRT_CLOTH_NO_LOBE_SHARING (per-lobe terms computed per
 * tangent) and PRT_CLOTH_TANGENT_COPIES (each copy of a tangent shaded apart). */
void prt_cloth_shade_avx2(const prt_cloth_view* view, const prt_cloth_fabric_prep* fabric,
                          const prt_cloth_light_prep* light, const prt_cloth_method* method,
                          const prt_cloth_pixels* pixels, uint32_t first, uint32_t count,
                          float* out_rgb);
#endif

#endif /* PRT_RUNTIME_CLOTH_SHADE_SIMD_H */
