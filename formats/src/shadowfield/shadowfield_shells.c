/* SPDX-License-Identifier: MIT */
/* The shell grid of technique `shadowfield` (prt/format/shadowfield_shells.h). */
#include <prt/format/shadowfield_shells.h>

#include <math.h>

uint64_t prt_sf_points_per_shell(const prt_sf_shells* grid) {
  return 6u * (uint64_t)grid->face_size * grid->face_size;
}

uint64_t prt_sf_point_count(const prt_sf_shells* grid) {
  return prt_sf_points_per_shell(grid) * grid->shells;
}

float prt_sf_shell_radius(const prt_sf_shells* grid, uint32_t shell) {
  if (grid->shells <= 1u) return grid->radius * grid->inner;
  const double x = (double)shell / (double)(grid->shells - 1u);
  return (float)(grid->radius * grid->inner * pow((double)grid->outer / grid->inner, x));
}

void prt_sf_cube_direction(uint32_t face, float s, float t, float out[3]) {
  const float a = 2.0f * s - 1.0f, b = 2.0f * t - 1.0f;
  switch (face) {
    case 0:
      out[0] = 1.0f;
      out[1] = -b;
      out[2] = -a;
      break; /* +X */
    case 1:
      out[0] = -1.0f;
      out[1] = -b;
      out[2] = a;
      break; /* -X */
    case 2:
      out[0] = a;
      out[1] = 1.0f;
      out[2] = b;
      break; /* +Y */
    case 3:
      out[0] = a;
      out[1] = -1.0f;
      out[2] = -b;
      break; /* -Y */
    case 4:
      out[0] = a;
      out[1] = -b;
      out[2] = 1.0f;
      break; /* +Z */
    default:
      out[0] = -a;
      out[1] = -b;
      out[2] = -1.0f;
      break; /* -Z */
  }
}

uint32_t prt_sf_cube_face(const float d[3], float* s, float* t) {
  const float ax = fabsf(d[0]), ay = fabsf(d[1]), az = fabsf(d[2]);
  uint32_t face;
  float sc, tc, ma;
  if (ax >= ay && ax >= az) {
    ma = ax;
    face = d[0] >= 0.0f ? 0u : 1u;
    sc = d[0] >= 0.0f ? -d[2] : d[2];
    tc = -d[1];
  } else if (ay >= az) {
    ma = ay;
    face = d[1] >= 0.0f ? 2u : 3u;
    sc = d[0];
    tc = d[1] >= 0.0f ? d[2] : -d[2];
  } else {
    ma = az;
    face = d[2] >= 0.0f ? 4u : 5u;
    sc = d[2] >= 0.0f ? d[0] : -d[0];
    tc = -d[1];
  }
  *s = 0.5f * (sc / ma + 1.0f);
  *t = 0.5f * (tc / ma + 1.0f);
  return face;
}

void prt_sf_point_position(const prt_sf_shells* grid, uint64_t index, float out[3]) {
  const uint64_t f2 = (uint64_t)grid->face_size * grid->face_size;
  const uint32_t shell = (uint32_t)(index / (6u * f2));
  const uint64_t in_shell = index % (6u * f2);
  const uint32_t face = (uint32_t)(in_shell / f2);
  const uint32_t j = (uint32_t)((in_shell % f2) / grid->face_size);
  const uint32_t i = (uint32_t)(in_shell % grid->face_size);
  float d[3];
  prt_sf_cube_direction(face, ((float)i + 0.5f) / (float)grid->face_size,
                        ((float)j + 0.5f) / (float)grid->face_size, d);
  const float length = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const float r = prt_sf_shell_radius(grid, shell);
  for (int c = 0; c < 3; ++c) out[c] = grid->centre[c] + r * d[c] / length;
}

/* The two cells around face coordinate u in [0, 1] and the weight of the second, clamped to the
 * outermost cell centres. */
static void bracket_cells(float u, uint32_t size, uint32_t* first, float* frac) {
  float x = u * (float)size - 0.5f;
  if (!(x > 0.0f)) x = 0.0f;
  if (x > (float)(size - 1u)) x = (float)(size - 1u);
  uint32_t i = (uint32_t)x;
  if (i + 1u >= size) i = size >= 2u ? size - 2u : 0u;
  *first = i;
  *frac = size >= 2u ? x - (float)i : 0.0f;
}

void prt_sf_locate(const prt_sf_shells* grid, const float p[3], prt_sf_lookup* out) {
  out->count = 0u;
  out->inside = 0u;
  float d[3] = {p[0] - grid->centre[0], p[1] - grid->centre[1], p[2] - grid->centre[2]};
  const double rho = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
  /* A point on a shell, rounded to float, must read that shell: the bounds give way by
   * kShellSlack (relative), far above float rounding and far below any shell spacing. */
  const double kShellSlack = 1e-6;
  const double r0 = (double)grid->radius * grid->inner;
  const double r1 = (double)grid->radius * grid->outer;
  if (!(rho <= r1 * (1.0 + kShellSlack))) return; /* beyond the outermost shell, or not finite */
  if (!(rho > 0.0)) {
    d[0] = 0.0f;
    d[1] = 1.0f;
    d[2] = 0.0f;
  }
  uint32_t shell = 0u;
  float shell_frac = 0.0f;
  if (rho < r0 || grid->shells == 1u) {
    out->inside = rho < r0 * (1.0 - kShellSlack) ? 1u : 0u;
  } else {
    double x = (double)(grid->shells - 1u) * log(rho / r0) / log((double)grid->outer / grid->inner);
    if (x > (double)(grid->shells - 1u)) x = (double)(grid->shells - 1u);
    shell = (uint32_t)x;
    if (shell + 1u >= grid->shells) shell = grid->shells - 2u;
    shell_frac = (float)(x - (double)shell);
  }
  float s, t;
  const uint32_t face = prt_sf_cube_face(d, &s, &t);
  uint32_t i, j;
  float fi, fj;
  bracket_cells(s, grid->face_size, &i, &fi);
  bracket_cells(t, grid->face_size, &j, &fj);
  const uint32_t di = grid->face_size >= 2u ? 1u : 0u;
  const uint64_t f2 = (uint64_t)grid->face_size * grid->face_size;
  const uint32_t shells_used = grid->shells >= 2u && out->inside == 0u ? 2u : 1u;
  uint32_t n = 0u;
  for (uint32_t k = 0; k < shells_used; ++k) {
    const float ws = shells_used == 2u ? (k == 0u ? 1.0f - shell_frac : shell_frac) : 1.0f;
    const uint64_t base = ((uint64_t)(shell + k) * 6u + face) * f2;
    for (uint32_t c = 0; c < 4u; ++c) {
      const uint32_t ci = i + ((c & 1u) ? di : 0u), cj = j + ((c & 2u) ? di : 0u);
      const float wi = (c & 1u) ? fi : 1.0f - fi, wj = (c & 2u) ? fj : 1.0f - fj;
      out->index[n] = base + (uint64_t)cj * grid->face_size + ci;
      out->weight[n] = ws * wi * wj;
      ++n;
    }
  }
  out->count = n;
}
