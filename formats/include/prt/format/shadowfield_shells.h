/* SPDX-License-Identifier: MIT */
/* The shell grid of technique `shadowfield` (formats/SPEC.md §7.5, docs/shadowfield/design.md):
 * where an object's occlusion and source radiance fields are sampled, and how a point is read
 * between the samples. The baker samples at these points and the runtime interpolates them, so
 * both use this one definition. Plain C99, pure functions.
 *
 * An object's bounding sphere has centre c and radius r (its own frame). Shell s of S has radius
 *     r_s = r * inner * (outer / inner)^(s / (S - 1))        (r * inner when S = 1),
 * spaced evenly in log radius, because a field changes about as fast as the object's apparent
 * size, 1/distance. A shell holds 6 F^2 points, the cell centres of an F x F cube map (the
 * OpenGL face order +X, -X, +Y, -Y, +Z, -Z and each face's (s, t) axes), pushed out to the
 * shell: point (face, i, j) is c + r_s * normalize(cube_direction(face, (i + 1/2)/F, (j + 1/2)/F))
 * and has index (s * 6 + face) * F * F + j * F + i. */
#ifndef PRT_FORMAT_SHADOWFIELD_SHELLS_H
#define PRT_FORMAT_SHADOWFIELD_SHELLS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct prt_sf_shells {
  float centre[3];    /* the bounding sphere's centre, object frame */
  float radius;       /* r > 0 */
  float inner;        /* innermost shell / r, > 0 */
  float outer;        /* outermost shell / r, >= inner (= inner when shells = 1) */
  uint32_t shells;    /* S >= 1 */
  uint32_t face_size; /* F >= 1 */
} prt_sf_shells;

/* 6 F^2 and S * 6 F^2 (as uint64 so no product overflows). */
uint64_t prt_sf_points_per_shell(const prt_sf_shells* grid);
uint64_t prt_sf_point_count(const prt_sf_shells* grid);

/* Radius of shell s (< S). */
float prt_sf_shell_radius(const prt_sf_shells* grid, uint32_t shell);

/* The unnormalised direction of cube face `face` (0..5) at face coordinates (s, t) in [0, 1]. */
void prt_sf_cube_direction(uint32_t face, float s, float t, float out[3]);
/* The face a non-zero direction leaves the cube through and its (s, t) in [0, 1] on that face;
 * the inverse of prt_sf_cube_direction up to scale. Ties go to X before Y before Z. */
uint32_t prt_sf_cube_face(const float direction[3], float* s, float* t);

/* Position (object frame) of point `index` (< prt_sf_point_count). */
void prt_sf_point_position(const prt_sf_shells* grid, uint64_t index, float out[3]);

/* How a field is read at an object-frame point p: a weighted sum of at most 8 grid points,
 * bilinear on the cube face of p's direction from the centre (face coordinates clamped to the
 * outermost cell centres, so a face is read within itself) and linear in log radius between the
 * two shells around |p - c|.
 * - |p - c| below the innermost shell: that shell's value (the stated fallback: a receiver
 *   inside it, e.g. touching or interpenetrating, sees the field as at the innermost shell);
 *   `inside` is set to 1.
 * - beyond the outermost shell: no point (count 0): the field is read as absent (no occlusion,
 *   no radiance).
 * - "below" and "beyond" give way by a relative 1e-6, so a grid point rounded to float reads
 *   its own shell.
 * - p at the centre: the direction is +Y (any direction would do; the value is the innermost
 *   shell's there).
 * The weights are >= 0 and sum to 1 when count > 0. */
typedef struct prt_sf_lookup {
  uint32_t count;    /* 0, 4 or 8 */
  uint32_t inside;   /* 1 when p is inside the innermost shell */
  uint64_t index[8]; /* grid points */
  float weight[8];
} prt_sf_lookup;
void prt_sf_locate(const prt_sf_shells* grid, const float p[3], prt_sf_lookup* out);

#ifdef __cplusplus
}
#endif

#endif /* PRT_FORMAT_SHADOWFIELD_SHELLS_H */
