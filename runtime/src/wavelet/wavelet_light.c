/* SPDX-License-Identifier: MIT */
/* The wavelet light, once per frame (SPEC §14): an environment map resampled onto a
 * parameterisation as power per texel, Haar-transformed per face, and cut to the M most
 * important coefficients.
 * No heap: the target's 4th float accumulates the landed solid angle (0 = nothing landed). */
#include <float.h>
#include <math.h>
#include <string.h>

#include "env_internal.h"
#include "sphere_internal.h"
#include "wavelet_internal.h"
#include "wavelet_light_internal.h"

/* A channel value as the light uses it: NaN, infinities and negatives count as 0. */
static float sanitised(float value) {
  return (value > 0.0f && value <= FLT_MAX) ? value : 0.0f; /* NaN fails both */
}

/* The source map, for the nearest-texel fill of empty targets. */
typedef struct light_source {
  const prt_env_view* env;
  const float* banded;  /* a lat-long map's texels in bands (see PRT_WAVELET_BAND_ROWS), or NULL */
  double largest_texel; /* the largest source texel's solid angle */
} light_source;

/* The largest texel solid angle of a lat-long map (the rows next to the equator) and of cube
 * faces (the face centre: at most the texel around (0, 0) of the face plane). */
double prt_wavelet_latlong_largest_texel(uint32_t width, uint32_t height) {
  const uint32_t y = height / 2u;
  const double top = cos(PRT_SPHERE_PI * (double)(y > 0u ? y - 1u : 0u) / (double)height);
  const double equator = cos(PRT_SPHERE_PI * (double)y / (double)height);
  const double bottom = cos(PRT_SPHERE_PI * (double)(y + 1u) / (double)height);
  const double band = fmax(top - equator, equator - bottom);
  return 2.0 * PRT_SPHERE_PI / (double)width * band;
}

double prt_wavelet_cube_largest_texel(uint32_t face_size) {
  const double half = 1.0 / (double)face_size; /* a texel centred on the face centre */
  return prt_cube_rect_solid_angle(-half, half, -half, half);
}

/* The smallest texel solid angle of the target: the cube's corner texel; on the paraboloid the
 * Jacobian 4/(1+r^2)^2 is at least 1 inside the disc, so (2/S)^2 bounds it from below. */
static double target_smallest_texel(uint32_t param, uint32_t size) {
  const double step = 2.0 / (double)size;
  if (param == PRT_WAVELET_PARAM_CUBE)
    return prt_cube_rect_solid_angle(-1.0, -1.0 + step, -1.0, -1.0 + step);
  return step * step;
}

/* The 3x3 rotation (row-major) in double; NULL is the identity (prt_internal_env_open checked
 * that a given one is a rotation). */
static void load_rotation(const float* rotation, double r[9]) {
  uint32_t i;
  for (i = 0; i < 9u; ++i) r[i] = rotation ? (double)rotation[i] : (i % 4u == 0u ? 1.0 : 0.0);
}

/* The RGB of the source's texel in direction e, sanitised. */
static void nearest_source_texel(const light_source* source, const double e[3], float rgb[3]) {
  const prt_env_view* env = source->env;
  const float* texel;
  size_t channel_step = 1u;
  uint32_t c;
  if (env->layout == PRT_ENV_LATLONG) {
    const double u = 0.5 + atan2(e[0], -e[2]) / (2.0 * PRT_SPHERE_PI);
    const double cos_theta = e[1] > 1.0 ? 1.0 : (e[1] < -1.0 ? -1.0 : e[1]);
    const double v = acos(cos_theta) / PRT_SPHERE_PI;
    uint32_t x = (uint32_t)(u * (double)env->width), y = (uint32_t)(v * (double)env->height);
    if (x >= env->width) x = env->width - 1u;
    if (y >= env->height) y = env->height - 1u;
    if (source->banded) {
      texel = source->banded + prt_wavelet_banded_at(env->width, x, y);
      channel_step = PRT_WAVELET_BAND_ROWS;
    } else {
      texel = prt_env_texel(env, 0u, x, y);
    }
  } else {
    const uint32_t n = env->width;
    double sc, tc;
    const uint32_t face = prt_cube_face_coords(e[0], e[1], e[2], &sc, &tc);
    texel = prt_env_texel(env, face, prt_face_texel(sc, n), prt_face_texel(tc, n));
  }
  for (c = 0; c < 3u; ++c) rgb[c] = sanitised(texel[c * channel_step]);
}

/* The value of a target texel nothing landed in: the source's nearest texel in direction R^T c
 * (outside paraboloid texels: 0). */
static void fill_empty_texel(uint32_t param, uint32_t size, uint32_t face, uint32_t x, uint32_t y,
                             const double r[9], const light_source* source, float* texel) {
  float centre[3];
  double e[3];
  uint32_t c;
  if (!prt_wavelet_texel_inside(param, size, x, y)) {
    texel[0] = texel[1] = texel[2] = 0.0f;
    return;
  }
  prt_wavelet_direction(param, size, face, (float)x + 0.5f, (float)y + 0.5f, centre);
  for (c = 0; c < 3u; ++c) e[c] = r[c] * centre[0] + r[3 + c] * centre[1] + r[6 + c] * centre[2];
  nearest_source_texel(source, e, texel);
}

/* Turns what landed in every target texel (sum of L dw in RGB, sum of dw in the 4th float) into
 * the texel's power, radiance x its solid angle dw (SPEC §14). When every source texel is at most
 * as large as the smallest target texel, the landed power is the texel's power as it is, so the
 * source's power is kept exactly: a sun a few source texels wide keeps its power however many
 * source texels happen to land in its target (their count varies by +-25 % at S = 64 from a 1k
 * map; scaling by dw over the landed solid angle would make that a +-25 % error in the sun). A
 * coarser source gives the mean radiance of what landed times dw (a constant map gives L dw). A
 * texel nothing landed in takes the nearest source texel's radiance times dw. dw depends on
 * (x, y) only, so it is computed once for all faces. */
static void finish_resample(uint32_t param, uint32_t size, const double r[9],
                            const light_source* source, const double* solid_angles,
                            float* out_rgba) {
  const uint32_t faces = prt_wavelet_face_count(param);
  const int keep_power = source->largest_texel <= target_smallest_texel(param, size);
  uint32_t f, x, y, c;
  for (y = 0; y < size; ++y) {
    for (x = 0; x < size; ++x) {
      const double solid_angle = solid_angles
                                     ? solid_angles[(size_t)y * size + x]
                                     : prt_wavelet_texel_solid_angle(param, size, 0u, x, y);
      for (f = 0; f < faces; ++f) {
        float* texel = out_rgba + 4u * (((size_t)f * size + y) * size + x);
        if (texel[3] <= 0.0f) {
          fill_empty_texel(param, size, f, x, y, r, source, texel);
          for (c = 0; c < 3u; ++c) texel[c] = (float)((double)texel[c] * solid_angle);
        } else if (!keep_power) {
          const double scale = solid_angle / (double)texel[3];
          for (c = 0; c < 3u; ++c) texel[c] = (float)((double)texel[c] * scale);
        }
        texel[3] = 0.0f;
      }
    }
  }
}

/* Splats one source texel, turned direction (x, y, z) = R d: radiance * dw and dw into the
 * target holding that direction. */
static inline void splat_texel(uint32_t texel, const float* rgb, float solid_angle,
                               float* out_rgba) {
  float* target = out_rgba + 4u * (size_t)texel;
  target[0] += sanitised(rgb[0]) * solid_angle;
  target[1] += sanitised(rgb[1]) * solid_angle;
  target[2] += sanitised(rgb[2]) * solid_angle;
  target[3] += solid_angle;
}

static inline void splat(uint32_t param, uint32_t size, double x, double y, double z,
                         const float* rgb, float solid_angle, float* out_rgba) {
  splat_texel(prt_wavelet_locate_unit(param, size, x, y, z), rgb, solid_angle, out_rgba);
}

/* Columns per block of the lat-long loop: their turned azimuth vectors fit a 12 KiB stack table;
 * each block repeats the per-row set-up (4 trigonometric calls per row). */
#define COLUMN_BLOCK 512u

/* Per lat-long row: R d = sin t g(f) + cos t R e_y, and the row's solid angle (SPEC §12:
 * theta in [pi y / H, pi (y + 1) / H], dw = (2 pi / W)(cos theta0 - cos theta1)). */
typedef struct latlong_row {
  double sin_theta, up[3];
  float solid_angle;
  const float* rgb;  /* the block's first texel of the row */
  uint32_t channels; /* floats per texel */
} latlong_row;

static void setup_row(const prt_env_view* env, uint32_t first, uint32_t y, const double r[9],
                      latlong_row* row) {
  const uint32_t width = env->width, height = env->height;
  const double theta = PRT_SPHERE_PI * ((double)y + 0.5) / (double)height;
  const double cos_top = cos(PRT_SPHERE_PI * (double)y / (double)height);
  const double cos_bottom = cos(PRT_SPHERE_PI * (double)(y + 1u) / (double)height);
  const double cos_theta = cos(theta);
  row->sin_theta = sin(theta);
  row->up[0] = cos_theta * r[1];
  row->up[1] = cos_theta * r[4];
  row->up[2] = cos_theta * r[7];
  row->solid_angle = (float)(2.0 * PRT_SPHERE_PI / (double)width * (cos_top - cos_bottom));
  row->rgb = prt_env_texel(env, 0u, first, y);
  row->channels = env->channels;
}

/* Splats columns [0, count) of a block's row; param is a literal at each call, so the inlined
 * locate has no param branch. */
static inline void splat_row_for_param(uint32_t param, uint32_t size, const double* turned_azimuth,
                                       uint32_t count, const latlong_row* row, float* out_rgba) {
  uint32_t x;
  for (x = 0; x < count; ++x) {
    const double* g = turned_azimuth + 3 * x;
    splat(param, size, row->sin_theta * g[0] + row->up[0], row->sin_theta * g[1] + row->up[1],
          row->sin_theta * g[2] + row->up[2], row->rgb + (size_t)row->channels * x,
          row->solid_angle, out_rgba);
  }
}

static void splat_row(uint32_t param, uint32_t size, const double* turned_azimuth, uint32_t count,
                      const latlong_row* row, float* out_rgba) {
  if (param == PRT_WAVELET_PARAM_CUBE)
    splat_row_for_param(PRT_WAVELET_PARAM_CUBE, size, turned_azimuth, count, row, out_rgba);
  else
    splat_row_for_param(PRT_WAVELET_PARAM_DUAL_PARABOLOID, size, turned_azimuth, count, row,
                        out_rgba);
}

/* A lat-long direction is d = sin t (sin f, 0, -cos f) + cos t (0, 1, 0) (SPEC §12), so
 * R d = sin t g(f) + cos t R e_y with g(f) = R (sin f, 0, -cos f) per column: the loop runs over
 * blocks of columns, with g tabulated once per block, then over the block's rows. */
static void splat_latlong(uint32_t param, uint32_t size, const prt_env_view* env, const double r[9],
                          float* out_rgba) {
  const uint32_t width = env->width, height = env->height;
  const double column_step = 2.0 * PRT_SPHERE_PI / (double)width;
  double turned_azimuth[3 * COLUMN_BLOCK];
  latlong_row row;
  uint32_t first, x, y;
  for (first = 0; first < width; first += COLUMN_BLOCK) {
    const uint32_t count = width - first < COLUMN_BLOCK ? width - first : COLUMN_BLOCK;
    for (x = 0; x < count; ++x) {
      /* Column centre: f = 2 pi ((x + 1/2) / W - 1/2). */
      const double phi = column_step * ((double)(first + x) + 0.5) - PRT_SPHERE_PI;
      const double sin_phi = sin(phi), cos_phi = cos(phi);
      turned_azimuth[3 * x] = r[0] * sin_phi - r[2] * cos_phi;
      turned_azimuth[3 * x + 1] = r[3] * sin_phi - r[5] * cos_phi;
      turned_azimuth[3 * x + 2] = r[6] * sin_phi - r[8] * cos_phi;
    }
    for (y = 0; y < height; ++y) {
      setup_row(env, first, y, r, &row);
      splat_row(param, size, turned_azimuth, count, &row, out_rgba);
    }
  }
}

static void splat_cube(uint32_t param, uint32_t size, const prt_env_view* env, const double r[9],
                       float* out_rgba) {
  const uint32_t face_size = env->width;
  const double step = 2.0 / (double)face_size;
  uint32_t i, j, f;
  /* The six faces share texel solid angles and face coordinates: compute them once per texel. */
  for (j = 0; j < face_size; ++j) {
    const double t0 = step * (double)j - 1.0, t1 = t0 + step, tc = 0.5 * (t0 + t1);
    double corner_top = prt_cube_corner_solid_angle(-1.0, t0);
    double corner_bottom = prt_cube_corner_solid_angle(-1.0, t1);
    for (i = 0; i < face_size; ++i) {
      const double s1 = step * (double)(i + 1u) - 1.0, sc = s1 - 0.5 * step;
      const double next_top = prt_cube_corner_solid_angle(s1, t0);
      const double next_bottom = prt_cube_corner_solid_angle(s1, t1);
      const double solid_angle = fabs(next_bottom - corner_bottom - next_top + corner_top);
      const double inv_length = 1.0 / sqrt(1.0 + sc * sc + tc * tc);
      for (f = 0; f < 6u; ++f)
        splat_texel(prt_wavelet_locate_cube_texel(param, size, r, f, sc, tc, inv_length),
                    prt_env_texel(env, f, i, j), (float)solid_angle, out_rgba);
      corner_top = next_top;
      corner_bottom = next_bottom;
    }
  }
}

prt_result prt_wavelet_resample(prt_wavelet_param param, uint32_t size, const prt_env_image* image,
                                float* out_rgba) {
  prt_env_view env;
  double r[9];
  light_source source;
  if (!prt_wavelet_domain_valid(param, size) || !out_rgba ||
      prt_internal_env_open(image, &env) != PRT_OK)
    return PRT_ERROR_INVALID_ARGUMENT;
  load_rotation(env.rotation, r);
  memset(out_rgba, 0, 4u * sizeof(float) * prt_wavelet_coefficient_count(param, size));
  source.env = &env;
  source.banded = NULL;
  if (env.layout == PRT_ENV_LATLONG) {
    splat_latlong(param, size, &env, r, out_rgba);
    source.largest_texel = prt_wavelet_latlong_largest_texel(env.width, env.height);
  } else {
    splat_cube(param, size, &env, r, out_rgba);
    source.largest_texel = prt_wavelet_cube_largest_texel(env.width);
  }
  finish_resample(param, size, r, &source, NULL, out_rgba);
  return PRT_OK;
}

void prt_wavelet_finish_resample(uint32_t param, uint32_t size, const double r[9],
                                 const prt_env_view* env, const float* banded, double largest_texel,
                                 const double* solid_angles, float* out_rgba) {
  light_source source;
  source.env = env;
  source.banded = banded;
  source.largest_texel = largest_texel;
  finish_resample(param, size, r, &source, solid_angles, out_rgba);
}

prt_result prt_wavelet_transform_light(prt_wavelet_param param, uint32_t size, float* rgba) {
  const uint32_t faces = prt_wavelet_face_count(param);
  uint32_t f;
  if (!prt_wavelet_domain_valid(param, size) || !rgba) return PRT_ERROR_INVALID_ARGUMENT;
  for (f = 0; f < faces; ++f) {
    const prt_result result = prt_haar_forward(size, 4u, rgba + 4u * (size_t)f * size * size);
    if (result != PRT_OK) return result;
  }
  return PRT_OK;
}

/* ---- Selection: a radix select on the bit patterns of the (non-negative) float weights. ---- */

#define DIGIT_BITS 11u
#define HISTOGRAM_SIZE (1u << DIGIT_BITS)
/* The detail coefficients whose weights share the threshold's first digit are listed for the
 * passes over the later digits, so that those read a few instead of every coefficient; when
 * more share it (a flat light), those passes read every coefficient. */
#define CANDIDATES 2048u

typedef struct selection {
  uint32_t prefix;      /* the threshold's bits found so far */
  uint32_t prefix_mask; /* which bits those are */
  uint32_t remaining;   /* how many to keep among the weights matching the prefix */
  uint32_t histogram[HISTOGRAM_SIZE];
  uint32_t area[PRT_WAVELET_MAX_SIZE]; /* support area of a detail coefficient by max(x, y) */
  uint32_t listed;                     /* coefficients sharing the first digit */
  uint32_t candidate[CANDIDATES + 1u]; /* their indices (the last slot takes the overflow) */
} selection;

/* The digit of pass 0, 1, 2: bits 21..31, 10..20, 0..9. */
static uint32_t digit_shift(uint32_t pass) {
  return pass == 0u ? 21u : (pass == 1u ? 10u : 0u);
}
static uint32_t digit_mask(uint32_t pass) {
  return pass == 2u ? 0x3FFu : 0x7FFu;
}

/* The weight's float bit pattern (orders as the weight, weights being >= 0; NaN counts as 0).
 * Each product of floats is exact in double and area is a power of two, so the value does not
 * depend on how the compiler fuses the arithmetic: every pass sees the same bits. */
static uint32_t weight_bits(const float* coefficient, uint32_t area) {
  const double luminance = (double)0.2126f * fabs((double)coefficient[0]) +
                           (double)0.7152f * fabs((double)coefficient[1]) +
                           (double)0.0722f * fabs((double)coefficient[2]);
  const float weight = (float)(luminance * (double)area);
  uint32_t bits;
  if (weight != weight) return 0u;
  memcpy(&bits, &weight, sizeof bits);
  return bits;
}

/* area[k] = (S >> level)^2 for the level of max(x, y) = k >= 1: level = floor(log2 k). */
static void tabulate_areas(uint32_t size, uint32_t* area) {
  uint32_t k, support = size;
  for (k = 1u; k < size; ++k) {
    if ((k & (k - 1u)) == 0u && k > 1u) support >>= 1; /* k = 2^level starts a level */
    area[k] = support * support;
  }
}

/* The weight bits parked in coefficient k's padding float. */
static uint32_t parked_bits(const float* rgba, size_t k) {
  uint32_t bits;
  memcpy(&bits, rgba + 4u * k + 3u, sizeof bits);
  return bits;
}

/* Pass 0: every detail coefficient's weight bits, parked in its padding float for the later
 * passes (the last one writes it back as 0), and the histogram of their first digit. */
static void first_pass(uint32_t faces, uint32_t size, selection* state, float* rgba) {
  uint32_t f, x, y;
  for (f = 0; f < faces; ++f)
    for (y = 0; y < size; ++y)
      for (x = (y == 0u ? 1u : 0u); x < size; ++x) {
        float* coefficient = rgba + 4u * (((size_t)f * size + y) * size + x);
        const uint32_t bits = weight_bits(coefficient, state->area[x > y ? x : y]);
        memcpy(coefficient + 3, &bits, sizeof bits);
        ++state->histogram[bits >> digit_shift(0u)];
      }
}

/* Lists the detail coefficients whose first digit is the threshold's (state->listed may exceed
 * CANDIDATES: then the list is incomplete and not used). */
static void list_candidates(uint32_t faces, uint32_t size, selection* state, const float* rgba) {
  const uint32_t area = size * size;
  uint32_t f, k, listed = 0u;
  for (f = 0; f < faces; ++f)
    for (k = f * area + 1u; k < (f + 1u) * area; ++k) { /* past the face's scaling coefficient */
      state->candidate[listed < CANDIDATES ? listed : CANDIDATES] = k;
      listed += (parked_bits(rgba, k) & state->prefix_mask) == state->prefix;
    }
  state->listed = listed;
}

/* Passes 1 and 2: the histogram of the next digit of the weights that match the prefix. */
static void digit_pass(uint32_t faces, uint32_t size, uint32_t pass, selection* state,
                       const float* rgba) {
  const uint32_t shift = digit_shift(pass), mask = digit_mask(pass);
  if (state->listed <= CANDIDATES) {
    uint32_t i;
    for (i = 0; i < state->listed; ++i) {
      const uint32_t bits = parked_bits(rgba, state->candidate[i]);
      if ((bits & state->prefix_mask) == state->prefix) ++state->histogram[(bits >> shift) & mask];
    }
  } else {
    const uint32_t area = size * size;
    uint32_t f, k;
    for (f = 0; f < faces; ++f)
      for (k = f * area + 1u; k < (f + 1u) * area; ++k) {
        const uint32_t bits = parked_bits(rgba, k);
        if ((bits & state->prefix_mask) == state->prefix)
          ++state->histogram[(bits >> shift) & mask];
      }
  }
}

/* After a histogram pass: the digit of the M-th largest weight among those matching. */
static void choose_digit(uint32_t pass, selection* state) {
  uint32_t digit = digit_mask(pass) + 1u, above = 0u;
  while (digit > 0u) {
    --digit;
    if (above + state->histogram[digit] >= state->remaining) break;
    above += state->histogram[digit];
  }
  state->remaining -= above;
  state->prefix |= digit << digit_shift(pass);
  state->prefix_mask |= digit_mask(pass) << digit_shift(pass);
}

/* The last pass, in index order: keeps the weights above the threshold and the first
 * `remaining` equal to it (their padding float back to 0), zeroes the rest. */
static void keep_pass(uint32_t faces, uint32_t size, selection* state, float* rgba) {
  const uint32_t area = size * size;
  uint32_t f, k;
  for (f = 0; f < faces; ++f)
    for (k = f * area + 1u; k < (f + 1u) * area; ++k) {
      float* coefficient = rgba + 4u * (size_t)k;
      const uint32_t bits = parked_bits(rgba, k);
      if (bits > state->prefix || (bits == state->prefix && state->remaining > 0u)) {
        if (bits == state->prefix) --state->remaining;
        coefficient[3] = 0.0f;
      } else {
        memset(coefficient, 0, 4u * sizeof(float));
      }
    }
}

prt_result prt_wavelet_select_light(prt_wavelet_param param, uint32_t size, uint32_t m,
                                    float* rgba) {
  const uint32_t faces = prt_wavelet_face_count(param);
  selection state;
  uint32_t pass, f;
  if (!prt_wavelet_domain_valid(param, size) || !rgba) return PRT_ERROR_INVALID_ARGUMENT;
  if (m >= faces * (size * size - 1u)) return PRT_OK;
  if (m == 0u) { /* keep only the scaling coefficients */
    for (f = 0; f < faces; ++f)
      memset(rgba + 4u * ((size_t)f * size * size + 1u), 0,
             4u * sizeof(float) * ((size_t)size * size - 1u));
    return PRT_OK;
  }
  state.prefix = 0u;
  state.prefix_mask = 0u;
  state.remaining = m;
  tabulate_areas(size, state.area);
  memset(state.histogram, 0, sizeof state.histogram);
  first_pass(faces, size, &state, rgba);
  choose_digit(0u, &state);
  list_candidates(faces, size, &state, rgba);
  for (pass = 1u; pass < 3u; ++pass) {
    memset(state.histogram, 0, sizeof state.histogram);
    digit_pass(faces, size, pass, &state, rgba);
    choose_digit(pass, &state);
  }
  keep_pass(faces, size, &state, rgba);
  return PRT_OK;
}
