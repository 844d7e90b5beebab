/* SPDX-License-Identifier: MIT */
/* The AVX2 + FMA backend of `cloth` shading (docs/cloth/method.md): the scalar reference
 * (cloth_shade.c, cloth_integrals.c, cloth_tables.c) followed step by step in float, eight samples
 * per iteration. Lanes are samples: what depends only on a tangent or a lobe is uniform and looped
 * over; a decision the scalar code makes per sample (a hidden lobe, a window that straddles
 * theta = 0, a pinched end, a wide or sharp phi profile) is a mask, and work is skipped only when
 * no lane needs it, so a lane's bits never depend on its neighbours.
 *
 * Float care: angles come from atan2 of components (asin and acos lose digits near +-1);
 * cos(x) - 1 is -2 sin^2(x / 2) (lambda up to 1e4 multiplies it); each theta node's trigonometry
 * comes from one sincos of half its offset from the lobe; the lobe's ratio to the window's
 * Gaussian is one exp of a sum of terms of moderate size; probability masses are taken in the
 * tail they lie in (prt_v8_normal_cdf_diff, and phi nodes placed from the nearer tail).
 *
 * Frame cache: what a (tangent, lobe) pair needs that the frame alone decides -- the lobe in the
 * fibre's angles, the table's lobe factors for both mirrors of the view, and the lobe's own theta
 * window (its pieces, nodes, profile, Gaussian moments, phi nodes and weights) -- is the same in
 * every lane of a batch whose eight samples share one frame. Such a batch keeps one float of each
 * (filled lazily, pair by pair) and the following batches of the same frame read them back. Both
 * paths run the same code on the same values, so the cache changes no bit.
 *
 * Within a batch, what a lobe's terms owe to the frame and not to the tangent's offset -- the
 * lobe's axis along u, v, n, and per thread and mirror the table cells of the lobe and the view --
 * is computed once and shared by the tangents (lobe_share); also bit for bit. The switches
 * PRT_CLOTH_NO_FRAME_CACHE, PRT_CLOTH_NO_LOBE_SHARING and PRT_CLOTH_TANGENT_COPIES (each copy of
 * a tangent shaded apart) undo the savings, for measuring them. */
#include <math.h>
#include <string.h>

#include "cloth_shade_simd.h"
#include "cloth_simd_math.h"

typedef __m256 v8;

#define C8(c) _mm256_set1_ps((float)(c))
#define LANES 8u
#define PI 3.14159265358979323846
#define HALF_PI 1.57079632679489661923
#define SQRT_2PI 2.50662827463100050242
#define WINDOW_SIGMAS 4.0f /* as cloth_integrals.c */
#define PHI_SIGMAS 6.0f
#define MERGE_WIDTH 1.5
#define MAX_Q PRT_CLOTH_MAX_PHI_NODES
#define MAX_NODES (2u * PRT_CLOTH_MAX_THETA_SEGMENTS + 1u)
#define MAX_CHUNKS (PRT_BLOB_CLTH_MAX_RANK / 8u)
/* Tangents shaded per sample: the distinct ones, or with PRT_CLOTH_TANGENT_COPIES up to this many
 * copies (past it a tangent gets fewer copies, each weighing its share). */
#define MAX_TANGENTS 64u
/* The frame cache's floats (on the stack): pairs past it are computed every batch. */
#define CACHE_FLOATS 16384u

/* Gauss-Legendre nodes and weights on [-1, 1], n = 1..8 (cloth_integrals.c's table). */
static const float kNodes[MAX_Q][MAX_Q] = {
    {0.0f},
    {-0.5773502691896257f, 0.5773502691896257f},
    {-0.7745966692414834f, 0.0f, 0.7745966692414834f},
    {-0.8611363115940526f, -0.3399810435848563f, 0.3399810435848563f, 0.8611363115940526f},
    {-0.9061798459386640f, -0.5384693101056831f, 0.0f, 0.5384693101056831f, 0.9061798459386640f},
    {-0.9324695142031521f, -0.6612093864662645f, -0.2386191860831969f, 0.2386191860831969f,
     0.6612093864662645f, 0.9324695142031521f},
    {-0.9491079123427585f, -0.7415311855993945f, -0.4058451513773972f, 0.0f, 0.4058451513773972f,
     0.7415311855993945f, 0.9491079123427585f},
    {-0.9602898564975363f, -0.7966664774136267f, -0.5255324099163290f, -0.1834346424956498f,
     0.1834346424956498f, 0.5255324099163290f, 0.7966664774136267f, 0.9602898564975363f},
};
static const float kWeights[MAX_Q][MAX_Q] = {
    {2.0f},
    {1.0f, 1.0f},
    {0.5555555555555556f, 0.8888888888888888f, 0.5555555555555556f},
    {0.3478548451374538f, 0.6521451548625461f, 0.6521451548625461f, 0.3478548451374538f},
    {0.2369268850561891f, 0.4786286704993665f, 0.5688888888888889f, 0.4786286704993665f,
     0.2369268850561891f},
    {0.1713244923791704f, 0.3607615730481386f, 0.4679139345726910f, 0.4679139345726910f,
     0.3607615730481386f, 0.1713244923791704f},
    {0.1294849661688697f, 0.2797053914892766f, 0.3818300505051189f, 0.4179591836734694f,
     0.3818300505051189f, 0.2797053914892766f, 0.1294849661688697f},
    {0.1012285362903763f, 0.2223810344533745f, 0.3137066458778873f, 0.3626837833783620f,
     0.3626837833783620f, 0.3137066458778873f, 0.2223810344533745f, 0.1012285362903763f},
};

/* ---- Lane helpers ------------------------------------------------------------------------------
 */

static inline v8 add8(v8 a, v8 b) {
  return _mm256_add_ps(a, b);
}
static inline v8 sub8(v8 a, v8 b) {
  return _mm256_sub_ps(a, b);
}
static inline v8 mul8(v8 a, v8 b) {
  return _mm256_mul_ps(a, b);
}
static inline v8 div8(v8 a, v8 b) {
  return _mm256_div_ps(a, b);
}
static inline v8 fma8(v8 a, v8 b, v8 c) {
  return _mm256_fmadd_ps(a, b, c);
}
static inline v8 and8(v8 a, v8 b) {
  return _mm256_and_ps(a, b);
}
static inline v8 andnot8(v8 a, v8 b) { /* ~a & b */
  return _mm256_andnot_ps(a, b);
}
static inline v8 lt8(v8 a, v8 b) {
  return _mm256_cmp_ps(a, b, _CMP_LT_OQ);
}
static inline v8 le8(v8 a, v8 b) {
  return _mm256_cmp_ps(a, b, _CMP_LE_OQ);
}
static inline v8 gt8(v8 a, v8 b) {
  return _mm256_cmp_ps(a, b, _CMP_GT_OQ);
}
static inline v8 ge8(v8 a, v8 b) {
  return _mm256_cmp_ps(a, b, _CMP_GE_OQ);
}
static inline v8 sel8(v8 mask, v8 a, v8 b) {
  return _mm256_blendv_ps(b, a, mask);
}
static inline int any8(v8 mask) {
  return _mm256_movemask_ps(mask) != 0;
}
static inline v8 all_ones(void) {
  return _mm256_castsi256_ps(_mm256_set1_epi32(-1));
}
static inline v8 bool8(int b) {
  return b ? all_ones() : _mm256_setzero_ps();
}
static inline float lane0(v8 x) {
  return _mm256_cvtss_f32(x);
}
/* The lanes whose bit is set in `bits`. */
static inline v8 mask_of_bits(unsigned bits) {
  const __m256i lane_bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_castsi256_ps(
      _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)bits), lane_bits), lane_bits));
}
/* Lane l of the result is the sum of the eight lanes of x[l]. */
static inline v8 sum_each(const v8 x[LANES]) {
  const v8 s01 = _mm256_hadd_ps(x[0], x[1]), s23 = _mm256_hadd_ps(x[2], x[3]);
  const v8 s45 = _mm256_hadd_ps(x[4], x[5]), s67 = _mm256_hadd_ps(x[6], x[7]);
  const v8 s0123 = _mm256_hadd_ps(s01, s23), s4567 = _mm256_hadd_ps(s45, s67);
  return add8(_mm256_permute2f128_ps(s0123, s4567, 0x20),
              _mm256_permute2f128_ps(s0123, s4567, 0x31));
}

/* ---- The call's uniform data -------------------------------------------------------------------
 */

typedef struct factor_info {
  const uint8_t* u;
  const uint8_t* v;
  const uint8_t* u_scale;
  const uint8_t* v_scale;
  uint32_t rank, chunks, bits;
  uint64_t u_safe, v_safe; /* rows below these can be read in whole chunks */
} factor_info;

typedef struct thread_c {
  float nu; /* eta^2 - 1 */
  int fresnel;
  float kd, lobed, albedo[3];
  float inv2g2[2], log_g[2]; /* parts 0, 1: 1 / (2 gamma^2), log(gamma sqrt(2 pi)) */
} thread_c;

typedef struct tangent_c {
  int thread, mirror, tilted, vertical, sign;
  float sin_tau, cos_tau, lo, hi, tan_coef, weight;
  factor_info full, cone;
} tangent_c;

/* A lobed part's own theta window (per thread and lobe): sd, 1 / sd, log(sd sqrt(2 pi)), and the
 * weights of the lobe's and the band's means in the product's mean. */
typedef struct part_window {
  float sd, inv_sd, log_root, wl, wb;
} part_window;

typedef struct lobe_c {
  float axis[3], lambda, rgb[3];
  double cull; /* visible where n . axis >= 0 or sqrt(1 - d^2) >= cull */
  uint32_t level;
  float level_frac;
  float sd, inv_sd, log_root; /* the lobe's own window */
  unsigned merged[2];         /* per thread: parts on the lobe's window */
  part_window part[2][2];     /* [thread][part] */
  float blend[2][2];          /* [thread][part]: the weight of T_c */
} lobe_c;

typedef struct call_c {
  const prt_cloth_view* view;
  uint32_t lobes, tangents, nodes, q, levels, xi, nt, np;
  int cone, keep_hidden;
  /* node fractions: even, graded to the low end, to the high end; and the fraction left to the
   * high end when graded there */
  float frac[4][MAX_NODES];
  float gl_x[MAX_Q], gl_g[MAX_Q], gl_hw[MAX_Q]; /* nodes, (x + 1) / 2, weights / 2 */
  size_t record;                                /* cache floats per pair */
  thread_c threads[2];
  tangent_c tan[MAX_TANGENTS];
  lobe_c lobe[PRT_CLOTH_MAX_LOBES];
} call_c;

static uint64_t safe_rows(uint64_t rows, uint32_t rank, uint32_t chunks) {
  const uint64_t values = rows * rank, read = 8u * (uint64_t)chunks;
  return values >= read ? (values - read) / rank + 1u : 0u;
}

static void factor_of(const call_c* cc, const prt_cloth_factor* f, factor_info* out) {
  const prt_blob_clth_header* h = &cc->view->header;
  out->u = (const uint8_t*)f->u_values;
  out->v = (const uint8_t*)f->v_values;
  out->u_scale = f->u_scale;
  out->v_scale = f->v_scale;
  out->rank = f->rank;
  out->chunks = (f->rank + 7u) / 8u;
  out->bits = f->bits;
  out->u_safe = safe_rows((uint64_t)h->levels * h->xi_size * h->xi_size, f->rank, out->chunks);
  out->v_safe = safe_rows((uint64_t)h->view_theta * h->view_phi, f->rank, out->chunks);
}

static void prepare_lobe(const call_c* cc, const prt_cloth_lobe_prep* lp,
                         const prt_cloth_params* params, uint32_t flags, lobe_c* out) {
  const double lambda = lp->lambda, lobe_sd = 1.0 / sqrt(lambda);
  int i, j, part;
  for (i = 0; i < 3; ++i) {
    out->axis[i] = (float)lp->axis[i];
    out->rgb[i] = (float)lp->rgb[i];
  }
  out->lambda = (float)lambda;
  /* exp(lambda (s - 1)) >= PRT_CLOTH_HIDDEN_LOBE as a bound on s */
  out->cull =
      (flags & PRT_CLOTH_KEEP_HIDDEN_LOBES) ? -INFINITY : 1.0 + log(PRT_CLOTH_HIDDEN_LOBE) / lambda;
  out->level = 0;
  out->level_frac = 0.0f;
  if (cc->levels > 1) {
    double fl;
    prt_cloth_grid_cell(lp->level / (double)(cc->levels - 1), cc->levels, &out->level, &fl);
    out->level_frac = (float)fl;
  }
  out->sd = (float)lobe_sd;
  out->inv_sd = (float)sqrt(lambda);
  out->log_root = (float)log(lobe_sd * SQRT_2PI);
  for (j = 0; j < 2; ++j) {
    const prt_cloth_thread* t = &params->threads[j];
    out->merged[j] = 4u;
    for (part = 0; part < 2; ++part) {
      const double gamma = part == 0 ? t->gamma_s : t->gamma_v;
      const double band = 1.0 / (4.0 * gamma * gamma), precision = lambda + band;
      const double sd = 1.0 / sqrt(precision);
      part_window* w = &out->part[j][part];
      if (2.0 * gamma >= MERGE_WIDTH * lobe_sd) out->merged[j] |= 1u << part;
      w->sd = (float)sd;
      w->inv_sd = (float)sqrt(precision);
      w->log_root = (float)log(sd * SQRT_2PI);
      w->wl = (float)(lambda / precision);
      w->wb = (float)(band / precision);
      out->blend[j][part] = (flags & PRT_CLOTH_NO_CONE_TABLE)
                                ? 0.0f
                                : (float)((1.0 / lambda) / (1.0 / lambda + 4.0 * gamma * gamma));
    }
  }
}

static void prepare_tangent(const call_c* cc, const prt_cloth_tangent_prep* tp, tangent_c* out) {
  const double tilt = asin(fmin(1.0, fabs(tp->sin_tau)));
  out->thread = tp->thread;
  out->mirror = tp->mirror;
  out->tilted = tp->sin_tau != 0.0;
  out->vertical = tp->cos_tau < 1e-9;
  out->sign = tp->sin_tau > 0.0 ? 1 : tp->sin_tau < 0.0 ? -1 : 0;
  out->sin_tau = (float)tp->sin_tau;
  out->cos_tau = (float)tp->cos_tau;
  out->lo = (float)(tp->sin_tau > 0.0 ? -(HALF_PI - tilt) : -HALF_PI);
  out->hi = (float)(tp->sin_tau < 0.0 ? HALF_PI - tilt : HALF_PI);
  out->tan_coef = out->vertical ? 0.0f : (float)(-tp->sin_tau / tp->cos_tau);
  out->weight = (float)tp->weight;
  factor_of(cc, &tp->full, &out->full);
  factor_of(cc, &tp->cone, &out->cone);
}

/* A tangent's multiplicity: its weight is the thread's coverage times it, exactly in double. */
static uint32_t multiplicity_of(const prt_cloth_fabric_prep* fabric,
                                const prt_cloth_tangent_prep* tp) {
  const double coverage = fabric->params.threads[tp->thread].coverage;
  const double m = coverage > 0.0 ? floor(tp->weight / coverage + 0.5) : 1.0;
  return m >= 1.0 ? (uint32_t)m : 1u;
}

static void prepare_call(const prt_cloth_view* view, const prt_cloth_fabric_prep* fabric,
                         const prt_cloth_light_prep* light, const prt_cloth_method* method,
                         call_c* cc) {
  uint32_t i, s, j;
  uint32_t max_chunks = 1;
  cc->view = view;
  cc->lobes = light->count;
  cc->nodes = 2u * method->theta_segments;
  cc->q = method->phi_nodes;
  cc->levels = view->header.levels;
  cc->xi = view->header.xi_size;
  cc->nt = view->header.view_theta;
  cc->np = view->header.view_phi;
  cc->cone = !(method->flags & PRT_CLOTH_NO_CONE_TABLE);
  cc->keep_hidden = (method->flags & PRT_CLOTH_KEEP_HIDDEN_LOBES) != 0;
  for (s = 0; s <= cc->nodes; ++s) {
    const double f = (double)s / cc->nodes;
    cc->frac[0][s] = (float)f;
    cc->frac[1][s] = (float)(f * f);
    cc->frac[2][s] = (float)(1.0 - (1.0 - f) * (1.0 - f));
    cc->frac[3][s] = (float)((1.0 - f) * (1.0 - f));
  }
  for (i = 0; i < cc->q; ++i) {
    cc->gl_x[i] = kNodes[cc->q - 1][i];
    cc->gl_g[i] = 0.5f * (kNodes[cc->q - 1][i] + 1.0f);
    cc->gl_hw[i] = 0.5f * kWeights[cc->q - 1][i];
  }
  for (j = 0; j < 2; ++j) {
    const prt_cloth_thread* t = &fabric->params.threads[j];
    thread_c* th = &cc->threads[j];
    int c, part;
    th->nu = (float)((double)t->eta * t->eta - 1.0);
    th->fresnel = t->eta != 1.0f;
    th->kd = t->kd;
    th->lobed = (float)(1.0 - t->kd);
    for (c = 0; c < 3; ++c) th->albedo[c] = t->albedo[c];
    for (part = 0; part < 2; ++part) {
      const double gamma = part == 0 ? t->gamma_s : t->gamma_v;
      th->inv2g2[part] = (float)(1.0 / (2.0 * gamma * gamma));
      th->log_g[part] = (float)log(gamma * SQRT_2PI);
    }
  }
  cc->tangents = 0;
  for (i = 0; i < fabric->tangent_count; ++i) {
    const prt_cloth_tangent_prep* tp = &fabric->tangents[i];
    const uint32_t left = MAX_TANGENTS - cc->tangents - (fabric->tangent_count - 1u - i);
    uint32_t copies = 1, c;
    if (method->flags & PRT_CLOTH_TANGENT_COPIES) copies = multiplicity_of(fabric, tp);
    if (copies > left) copies = left;
    for (c = 0; c < copies; ++c) {
      tangent_c* tc = &cc->tan[cc->tangents++];
      prepare_tangent(cc, tp, tc);
      tc->weight = (float)(tp->weight / copies);
      if (tc->full.chunks > max_chunks) max_chunks = tc->full.chunks;
      if (tc->cone.chunks > max_chunks) max_chunks = tc->cone.chunks;
    }
  }
  for (i = 0; i < cc->lobes; ++i)
    prepare_lobe(cc, &light->lobes[i], &fabric->params, method->flags, &cc->lobe[i]);
  /* A pair's record: the lobe's angles, its lobe factors (two mirrors, two tables), then the
   * lobe's window: two pieces, each a flag, its nodes and its panels. */
  cc->record = 4u + 2u * 2u * 8u * max_chunks +
               2u * (1u + (cc->nodes + 1u) * (5u + 3u * cc->q) + (cc->nodes / 2u) * 6u);
}

/* ---- The frame cache ---------------------------------------------------------------------------
 */

enum { CACHE_NONE, CACHE_FILL, CACHE_READ };

typedef struct cursor {
  float* at;
  int mode;
} cursor;

static inline void put8(cursor* c, v8 x) {
  *c->at++ = lane0(x);
}
static inline v8 get8(cursor* c) {
  return _mm256_broadcast_ss(c->at++);
}
static inline void put_flag(cursor* c, int flag) {
  *c->at++ = flag ? 1.0f : 0.0f;
}
static inline int get_flag(cursor* c) {
  return *c->at++ != 0.0f;
}

/* ---- Tables (cloth_tables.c) -------------------------------------------------------------------
 */

/* Values [8 c, 8 c + 8) of row `row` as floats; past the rank they belong to the next rows (the
 * caller multiplies them by zero) or, at the array's end, are 0. */
static inline v8 load_values(const factor_info* f, const uint8_t* base, uint64_t row, uint32_t c,
                             uint64_t safe) {
  const uint64_t at = row * f->rank + 8u * c;
  if (row < safe) {
    if (f->bits == 16)
      return _mm256_cvtepi32_ps(
          _mm256_cvtepi16_epi32(_mm_loadu_si128((const __m128i*)(base + 2u * at))));
    return _mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(_mm_loadl_epi64((const __m128i*)(base + at))));
  } else {
    const uint32_t n = f->rank - 8u * c < 8u ? f->rank - 8u * c : 8u;
    if (f->bits == 16) {
      int16_t tmp[8] = {0, 0, 0, 0, 0, 0, 0, 0};
      memcpy(tmp, base + 2u * at, 2u * n);
      return _mm256_cvtepi32_ps(_mm256_cvtepi16_epi32(_mm_loadu_si128((const __m128i*)tmp)));
    } else {
      int8_t tmp[8] = {0, 0, 0, 0, 0, 0, 0, 0};
      memcpy(tmp, base + at, n);
      return _mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(_mm_loadl_epi64((const __m128i*)tmp)));
    }
  }
}

/* Scales [8 c, 8 c + 8), 0 past the rank. */
static inline v8 load_scales(const uint8_t* scales, uint32_t rank, uint32_t c) {
  const int left = (int)(rank - 8u * c);
  const __m256i mask =
      _mm256_cmpgt_epi32(_mm256_set1_epi32(left), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  return _mm256_maskload_ps((const float*)(scales + 32u * c), mask);
}

/* The grid cells of x in [0, 1] over n nodes, as prt_cloth_grid_cell in double. */
static inline void grid_cells(v8 x, uint32_t n, int32_t lower[LANES], float frac[LANES]) {
  const v8 last = C8((float)(n - 1));
  v8 g = mul8(x, last);
  g = sel8(gt8(g, _mm256_setzero_ps()), g, _mm256_setzero_ps()); /* NaN too */
  g = _mm256_min_ps(g, last);
  __m256i i = _mm256_cvttps_epi32(g);
  i = _mm256_min_epi32(i, _mm256_set1_epi32((int)n - 2));
  _mm256_storeu_si256((__m256i*)lower, i);
  _mm256_storeu_ps(frac, sub8(g, _mm256_cvtepi32_ps(i)));
}

/* The view factor of one lane: the bilinear row of cell (a, b), times both scales (so that T is
 * its dot product with the lobe factor's unscaled row), 0 past the rank. */
static void view_row(const call_c* cc, const factor_info* f, uint32_t a, uint32_t b, float fa,
                     float fb, float* out) {
  const uint64_t r00 = (uint64_t)a * cc->np + b, r10 = r00 + cc->np;
  const v8 w00 = C8((1.0f - fa) * (1.0f - fb)), w01 = C8((1.0f - fa) * fb);
  const v8 w10 = C8(fa * (1.0f - fb)), w11 = C8(fa * fb);
  uint32_t c;
  for (c = 0; c < f->chunks; ++c) {
    v8 acc = mul8(w00, load_values(f, f->v, r00, c, f->v_safe));
    acc = fma8(w01, load_values(f, f->v, r00 + 1u, c, f->v_safe), acc);
    acc = fma8(w10, load_values(f, f->v, r10, c, f->v_safe), acc);
    acc = fma8(w11, load_values(f, f->v, r10 + 1u, c, f->v_safe), acc);
    acc = mul8(acc, mul8(load_scales(f->v_scale, f->rank, c), load_scales(f->u_scale, f->rank, c)));
    _mm256_store_ps(out + 8u * c, acc);
  }
}

/* The lobe factor's unscaled row at octahedral cell (i, j) and the lobe's level. */
static void lobe_row(const call_c* cc, const factor_info* f, const lobe_c* lobe, uint32_t i,
                     uint32_t j, float fi, float fj, v8* out) {
  const uint64_t plane = (uint64_t)cc->xi * cc->xi;
  const uint32_t levels = cc->levels > 1 ? 2u : 1u;
  v8 w[8];
  uint64_t rows[8];
  uint32_t k, c, corner;
  for (k = 0; k < levels; ++k) {
    const float wl = cc->levels > 1 ? (k ? lobe->level_frac : 1.0f - lobe->level_frac) : 1.0f;
    const uint64_t base = (lobe->level + k) * plane + (uint64_t)j * cc->xi + i;
    w[4 * k + 0] = C8(wl * (1.0f - fi) * (1.0f - fj));
    w[4 * k + 1] = C8(wl * fi * (1.0f - fj));
    w[4 * k + 2] = C8(wl * (1.0f - fi) * fj);
    w[4 * k + 3] = C8(wl * fi * fj);
    rows[4 * k + 0] = base;
    rows[4 * k + 1] = base + 1u;
    rows[4 * k + 2] = base + cc->xi;
    rows[4 * k + 3] = base + cc->xi + 1u;
  }
  for (c = 0; c < f->chunks; ++c) {
    v8 acc = mul8(w[0], load_values(f, f->u, rows[0], c, f->u_safe));
    for (corner = 1; corner < 4u * levels; ++corner)
      acc = fma8(w[corner], load_values(f, f->u, rows[corner], c, f->u_safe), acc);
    out[c] = acc;
  }
}

/* Each lane's grid cells in two dimensions: lower nodes and fractions. */
typedef struct cells_l {
  int32_t i[LANES], j[LANES];
  float fi[LANES], fj[LANES];
} cells_l;

/* The octahedral cells of canonical lobe directions (formats/SPEC.md §7.4). */
static void octahedral_cells(const call_c* cc, v8 x, v8 y, v8 z, cells_l* out) {
  const v8 l1 = add8(add8(prt_v8_abs(x), prt_v8_abs(y)), prt_v8_abs(z));
  v8 px = div8(x, l1), py = div8(y, l1);
  const v8 below = lt8(z, _mm256_setzero_ps());
  const v8 one = C8(1.0f);
  const v8 sx = sel8(ge8(px, _mm256_setzero_ps()), one, C8(-1.0f));
  const v8 sy = sel8(ge8(py, _mm256_setzero_ps()), one, C8(-1.0f));
  const v8 fx = mul8(sub8(one, prt_v8_abs(py)), sx), fy = mul8(sub8(one, prt_v8_abs(px)), sy);
  px = sel8(below, fx, px);
  py = sel8(below, fy, py);
  grid_cells(mul8(C8(0.5f), add8(px, one)), cc->xi, out->i, out->fi);
  grid_cells(mul8(C8(0.5f), add8(py, one)), cc->xi, out->j, out->fj);
}

/* ---- Lanes of one batch ------------------------------------------------------------------------
 */

typedef struct batch {
  v8 n[3], u[3], v[3];
  v8 du, dv, dn; /* the view's components along u, v, n */
  v8 active;
  int uniform;                      /* all lanes share lane 0's frame */
  uint8_t vis[PRT_CLOTH_MAX_LOBES]; /* lanes that see each lobe */
  float key[6];                     /* lane 0's normal and warp */
} batch;

/* A tangent's view in each lane. */
typedef struct view_l {
  v8 theta_o, phi_o, cos_o;
  unsigned flip; /* lanes whose canonical view was mirrored to y >= 0 */
  float vf[LANES][PRT_BLOB_CLTH_MAX_RANK] __attribute__((aligned(32))); /* T's view rows */
  float vc[LANES][PRT_BLOB_CLTH_MAX_RANK] __attribute__((aligned(32))); /* T_c's */
} view_l;

/* What a batch's lobes and view share across its tangents: the lobe axes in the lanes' frames,
 * and per thread and mirror (index 2 thread + mirror) the table cells of each lobe and of the
 * view. Filled lazily; lobes past SHARED_LOBES are computed per tangent. Off
 * (PRT_CLOTH_NO_LOBE_SHARING), every tangent computes its own: the same values either way. */
#define SHARED_LOBES 32u
typedef struct lobe_share {
  int on;
  uint8_t have_axis[SHARED_LOBES];
  uint8_t have_cells[4][SHARED_LOBES];
  uint8_t have_view[4];
  v8 axis[SHARED_LOBES][3];
  cells_l cells[4][SHARED_LOBES];
  cells_l view[4];
} lobe_share;

static void reset_share(lobe_share* sh) {
  memset(sh->have_axis, 0, sizeof sh->have_axis);
  memset(sh->have_cells, 0, sizeof sh->have_cells);
  memset(sh->have_view, 0, sizeof sh->have_view);
}

/* The lobe's axis along each lane's u, v, n. */
static void lobe_axis_of(const lobe_c* lobe, const batch* b, v8 d[3]) {
  const v8 ax = C8(lobe->axis[0]), ay = C8(lobe->axis[1]), az = C8(lobe->axis[2]);
  d[0] = fma8(ax, b->u[0], fma8(ay, b->u[1], mul8(az, b->u[2])));
  d[1] = fma8(ax, b->v[0], fma8(ay, b->v[1], mul8(az, b->v[2])));
  d[2] = fma8(ax, b->n[0], fma8(ay, b->n[1], mul8(az, b->n[2])));
}

static const v8* lobe_axis(lobe_share* sh, const lobe_c* lobe, uint32_t k, const batch* b,
                           v8 own[3]) {
  if (!sh->on || k >= SHARED_LOBES) {
    lobe_axis_of(lobe, b, own);
    return own;
  }
  if (!sh->have_axis[k]) lobe_axis_of(lobe, b, sh->axis[k]);
  sh->have_axis[k] = 1;
  return sh->axis[k];
}

/* A direction's components along the tangent's canonical x_j, y_j and n from those along u, v, n.
 */
static inline void thread_axes(const tangent_c* tc, v8 du, v8 dv, v8* x, v8* y) {
  if (tc->thread == 0) {
    *x = du;
    *y = dv;
  } else {
    *x = dv;
    *y = _mm256_xor_ps(du, C8(-0.0f));
  }
}

/* theta = asin(w . t) as atan2 of the components (accurate near +-pi/2), its cosine and sine, and
 * phi = atan2(w . b, w . n') of a direction in the fibre frame of tangent tc. */
static inline void fibre_angles(const tangent_c* tc, v8 x, v8 y, v8 z, v8* theta, v8* phi,
                                v8* cos_theta, v8* sin_theta) {
  const v8 st = C8(tc->sin_tau), ct = C8(tc->cos_tau);
  const v8 wt = fma8(ct, x, mul8(st, z));
  const v8 wn = _mm256_fnmadd_ps(st, x, mul8(ct, z));
  const v8 r = _mm256_sqrt_ps(fma8(wn, wn, mul8(y, y)));
  const v8 norm = _mm256_sqrt_ps(fma8(wt, wt, mul8(r, r)));
  *theta = prt_v8_atan2(wt, r);
  *phi = prt_v8_atan2(y, wn);
  *cos_theta = div8(r, norm);
  if (sin_theta) *sin_theta = div8(wt, norm);
}

/* The view's cells in the tables of a thread's canonical frame (after the mirror). */
static void view_cells(const call_c* cc, v8 x, v8 y, v8 dn, int mirror, cells_l* out) {
  const v8 cx = mirror ? _mm256_xor_ps(x, C8(-0.0f)) : x;
  const v8 cy = prt_v8_abs(y);
  const v8 cz = _mm256_max_ps(dn, _mm256_setzero_ps());
  /* theta = acos(z) and phi = atan2(|y|, x), as angles of the components */
  const v8 theta = prt_v8_atan2(_mm256_sqrt_ps(fma8(cx, cx, mul8(cy, cy))), cz);
  const v8 phi = prt_v8_atan2(cy, cx);
  grid_cells(mul8(theta, C8(1.0 / HALF_PI)), cc->nt, out->i, out->fi);
  grid_cells(mul8(phi, C8(1.0 / PI)), cc->np, out->j, out->fj);
}

static void tangent_view(const call_c* cc, const tangent_c* tc, const batch* b, unsigned lanes,
                         lobe_share* sh, view_l* out) {
  const int group = 2 * tc->thread + tc->mirror;
  cells_l own;
  const cells_l* vc = &own;
  v8 x, y;
  uint32_t l;
  thread_axes(tc, b->du, b->dv, &x, &y);
  fibre_angles(tc, x, y, b->dn, &out->theta_o, &out->phi_o, &out->cos_o, NULL);
  out->flip = (unsigned)_mm256_movemask_ps(lt8(y, _mm256_setzero_ps()));
  if (sh->on) {
    if (!sh->have_view[group]) view_cells(cc, x, y, b->dn, tc->mirror, &sh->view[group]);
    sh->have_view[group] = 1;
    vc = &sh->view[group];
  } else {
    view_cells(cc, x, y, b->dn, tc->mirror, &own);
  }
  for (l = 0; l < LANES; ++l) {
    const uint32_t a = (uint32_t)vc->i[l], c = (uint32_t)vc->j[l];
    if (!(lanes >> l & 1u)) continue;
    view_row(cc, &tc->full, a, c, vc->fi[l], vc->fj[l], out->vf[l]);
    if (cc->cone) view_row(cc, &tc->cone, a, c, vc->fi[l], vc->fj[l], out->vc[l]);
  }
}

/* ---- One pair (tangent, lobe) across the lanes -------------------------------------------------
 */

typedef struct pair_l {
  float lambda;
  v8 theta_k, phi_k, cos_k, sin_k; /* the lobe in the fibre's angles (the frame's) */
  v8 cx, cy, cz;                   /* the lobe in the thread's canonical frame (the frame's) */
  v8 cos_b, sin_b;                 /* beta = (theta_k - theta_o) / 2 */
  v8 cos_hd, sin_hd;               /* (phi_k - phi_o) / 2 */
  v8 sum_ko;                       /* theta_k + theta_o */
  v8 cos_o;
} pair_l;

/* A theta window: mean, its offsets from theta_k and -theta_o, its sd and the parts on it. */
typedef struct window_l {
  v8 mu, y0, g0;
  float sd, inv_sd, log_root;
  unsigned parts;
} window_l;

/* What one theta node of a window needs that the view does not change. */
typedef struct node_static {
  v8 x;                              /* theta - mu */
  v8 ct;                             /* cos theta */
  v8 c1, s1;                         /* cos, sin of (theta - theta_k) / 2 */
  v8 lobe;                           /* the lobe's profile over the window's Gaussian */
  v8 dc[MAX_Q], ds[MAX_Q], w[MAX_Q]; /* phi nodes: cos, sin of (phi - phi_k) / 2; weights */
} node_static;

static void put_node(cursor* c, const node_static* ns, uint32_t q) {
  uint32_t i;
  put8(c, ns->x);
  put8(c, ns->ct);
  put8(c, ns->c1);
  put8(c, ns->s1);
  put8(c, ns->lobe);
  for (i = 0; i < q; ++i) {
    put8(c, ns->dc[i]);
    put8(c, ns->ds[i]);
    put8(c, ns->w[i]);
  }
}

static void get_node(cursor* c, node_static* ns, uint32_t q) {
  uint32_t i;
  ns->x = get8(c);
  ns->ct = get8(c);
  ns->c1 = get8(c);
  ns->s1 = get8(c);
  ns->lobe = get8(c);
  for (i = 0; i < q; ++i) {
    ns->dc[i] = get8(c);
    ns->ds[i] = get8(c);
    ns->w[i] = get8(c);
  }
}

/* The half-width of the phi range at theta (phi_half_width): acos(c), c = -tan(tau) tan(theta),
 * as atan2(sqrt((1 - c)(1 + c)), c) with both scaled by cos(tau) cos(theta), where
 * 1 - c ~ cos(theta - tau) and 1 + c ~ cos(theta + tau). At a pinched end cos(theta - tau)
 * vanishes like the distance to the end, and the half-width like its square root: there it is
 * sin(distance) (`end_cos`, in lanes `pinched`), the distance being known to its last bit where
 * theta is not. A vertical fibre's front opens on one side of theta = 0 only: the sign of theta
 * decides it (exact at the split node, theta = mu + (-mu)). */
static inline v8 phi_half_width(const tangent_c* tc, v8 theta, v8 ct, v8 st, v8 pinched,
                                v8 end_cos) {
  const v8 half_pi = C8(HALF_PI), zero = _mm256_setzero_ps();
  if (tc->vertical) return and8(gt8(mul8(C8(tc->sin_tau), theta), zero), half_pi);
  if (!tc->tilted) return half_pi;
  {
    const v8 s = C8(tc->sin_tau), c = C8(tc->cos_tau);
    const v8 num = _mm256_xor_ps(mul8(s, st), C8(-0.0f)); /* c cos(tau) cos(theta) */
    const v8 minus = sel8(pinched, end_cos, fma8(ct, c, mul8(st, s)));
    const v8 plus = _mm256_fmsub_ps(ct, c, mul8(st, s));
    const v8 a = prt_v8_atan2(_mm256_sqrt_ps(_mm256_max_ps(mul8(minus, plus), zero)), num);
    return sel8(le8(num, zero), half_pi, and8(gt8(minus, zero), a));
  }
}

/* The static parts of nodes x[0..count) of window w (node_static): the phi nodes of the lobe's
 * von Mises profile at each theta (phi_integrals' placement), their weights with the profile
 * folded in and the half-angle trigonometry of each node's offset from phi_k. `end[s]` is node
 * s's distance from the pinched end of its piece in lanes `pinched`. Each step runs over all the
 * nodes before the next, so that the nodes' independent chains of transcendental functions
 * overlap instead of each waiting on the last. */
#define STAGE_NODES 9u
static void nodes_static(const call_c* cc, const tangent_c* tc, const pair_l* p, const window_l* w,
                         uint32_t count, const v8* x, v8 pinched, const v8* end, node_static* ns) {
  const v8 zero = _mm256_setzero_ps();
  v8 theta[STAGE_NODES], st[STAGE_NODES], half[STAGE_NODES], kappa[STAGE_NODES];
  v8 sdp[STAGE_NODES], wide[STAGE_NODES], za[STAGE_NODES], zb[STAGE_NODES], live[STAGE_NODES];
  v8 sharp[STAGE_NODES], flip[STAGE_NODES], ua[STAGE_NODES], mass[STAGE_NODES];
  const int ends = tc->tilted && !tc->vertical && any8(pinched);
  v8 any_sharp = zero;
  uint32_t s, i;
  for (s = 0; s < count; ++s) {
    const v8 z = mul8(x[s], C8(w->inv_sd));
    v8 s1, c1, ct, end_sin = zero, end_c;
    theta[s] = add8(w->mu, x[s]);
    prt_v8_sincos(mul8(C8(0.5f), add8(x[s], w->y0)), &s1, &c1);
    prt_v8_sincos(theta[s], &st[s], &ct);
    if (ends) prt_v8_sincos(end[s], &end_sin, &end_c);
    ns[s].x = x[s];
    ns[s].ct = ct;
    ns[s].c1 = c1;
    ns[s].s1 = s1;
    /* lambda (cos(theta - theta_k) - 1) - log N(theta; mu, sd) */
    ns[s].lobe = prt_v8_exp(
        fma8(mul8(C8(-2.0f * p->lambda), s1), s1, fma8(mul8(C8(0.5f), z), z, C8(w->log_root))));
    half[s] = phi_half_width(tc, theta[s], ct, st[s], pinched, end_sin);
  }
  for (s = 0; s < count; ++s) {
    const v8 k = _mm256_max_ps(mul8(mul8(C8(p->lambda), ns[s].ct), p->cos_k), zero);
    const v8 rk = _mm256_sqrt_ps(k);
    kappa[s] = k;
    sdp[s] = div8(C8(1.0f), rk); /* +inf for kappa = 0 */
    wide[s] = ge8(mul8(C8(4.0f), sdp[s]), C8(HALF_PI));
    za[s] =
        _mm256_max_ps(mul8(sub8(_mm256_xor_ps(half[s], C8(-0.0f)), p->phi_k), rk), C8(-PHI_SIGMAS));
    zb[s] = _mm256_min_ps(mul8(sub8(half[s], p->phi_k), rk), C8(PHI_SIGMAS));
    live[s] = and8(gt8(half[s], zero), _mm256_or_ps(wide[s], gt8(zb[s], za[s])));
    sharp[s] = andnot8(wide[s], live[s]);
    flip[s] = ua[s] = mass[s] = zero;
    any_sharp = _mm256_or_ps(any_sharp, sharp[s]);
  }
  if (any8(any_sharp))
    for (s = 0; s < count; ++s) {
      const v8 f = gt8(add8(za[s], zb[s]), zero);
      const v8 zl = sel8(f, _mm256_xor_ps(zb[s], C8(-0.0f)), za[s]);
      const v8 zh = sel8(f, _mm256_xor_ps(za[s], C8(-0.0f)), zb[s]);
      flip[s] = f;
      ua[s] = prt_v8_normal_cdf(zl);
      mass[s] = sub8(prt_v8_normal_cdf(zh), ua[s]);
      sharp[s] = and8(sharp[s], gt8(mass[s], zero)); /* else plain nodes over [a, b] */
    }
  for (i = 0; i < cc->q; ++i) {
    const v8 xq = C8(cc->gl_x[i]), hw = C8(cc->gl_hw[i]), g = C8(cc->gl_g[i]);
    for (s = 0; s < count; ++s) {
      /* wide: plain nodes over [-half, half]; a sharp profile whose mass rounds to 0: over [a, b]
       */
      const v8 d_wide = _mm256_fmsub_ps(half[s], xq, p->phi_k);
      const v8 d_narrow =
          mul8(sdp[s], mul8(C8(0.5f), fma8(sub8(zb[s], za[s]), xq, add8(za[s], zb[s]))));
      v8 d = sel8(wide[s], d_wide, d_narrow);
      v8 pre = sel8(wide[s], mul8(mul8(half[s], C8(2.0f)), hw),
                    mul8(mul8(sdp[s], sub8(zb[s], za[s])), hw));
      v8 e = zero, sn, cs;
      if (any8(any_sharp)) {
        const v8 zq = prt_v8_normal_quantile(fma8(mass[s], g, ua[s]));
        const v8 z = sel8(flip[s], _mm256_xor_ps(zq, C8(-0.0f)), zq);
        d = sel8(sharp[s], mul8(sdp[s], z), d);
        pre = sel8(sharp[s], mul8(mul8(mass[s], hw), mul8(sdp[s], C8(SQRT_2PI))), pre);
        e = and8(sharp[s], mul8(mul8(C8(0.5f), z), z));
      }
      prt_v8_sincos(mul8(C8(0.5f), d), &sn, &cs);
      ns[s].dc[i] = cs;
      ns[s].ds[i] = sn;
      ns[s].w[i] =
          and8(live[s], mul8(pre, prt_v8_exp(fma8(mul8(mul8(kappa[s], C8(-2.0f)), sn), sn, e))));
    }
  }
}

/* Exact Fresnel reflectance at incidence cosine c in [0, 1] (prt_cloth_fresnel), eta > 1. */
static inline v8 fresnel(v8 nu, v8 c) {
  const v8 one = C8(1.0f);
  const v8 g = _mm256_sqrt_ps(fma8(c, c, nu));
  const v8 gp = add8(g, c), gm = sub8(g, c);
  const v8 den_b = fma8(c, gm, one);
  const v8 r = div8(one, mul8(gp, den_b));
  const v8 a = mul8(mul8(gm, den_b), r);
  const v8 b = mul8(mul8(_mm256_fmsub_ps(c, gp, one), gp), r);
  return mul8(mul8(C8(0.5f), mul8(a, a)), fma8(b, b, one));
}

/* The integrands over the window's Gaussian at one node (integrands_over_gaussian): h[part]. */
static void node_dynamic(const call_c* cc, const thread_c* th, const pair_l* p, const window_l* w,
                         const node_static* ns, v8 h[3]) {
  const v8 zero = _mm256_setzero_ps();
  const v8 cd = _mm256_fmsub_ps(ns->c1, p->cos_b, mul8(ns->s1, p->sin_b));
  const v8 live = and8(gt8(ns->ct, zero), gt8(cd, C8(1e-12f)));
  const v8 nu = C8(th->nu);
  v8 phi0 = zero, phi1 = zero, base, inv_sum;
  uint32_t i;
  for (i = 0; i < cc->q; ++i) {
    const v8 y = prt_v8_abs(_mm256_fmsub_ps(ns->dc[i], p->cos_hd, mul8(ns->ds[i], p->sin_hd)));
    if (th->fresnel) {
      const v8 f = fresnel(nu, _mm256_min_ps(mul8(cd, y), C8(1.0f)));
      const v8 t = sub8(C8(1.0f), f);
      phi0 = fma8(mul8(ns->w[i], f), y, phi0);
      phi1 = fma8(mul8(ns->w[i], t), t, phi1);
    } else {
      phi1 = add8(phi1, ns->w[i]);
    }
  }
  {
    const v8 r = div8(ns->ct, cd);
    base = mul8(mul8(r, r), ns->lobe);
  }
  inv_sum = div8(C8(1.0f), add8(ns->ct, p->cos_o));
  h[0] = h[1] = h[2] = zero;
  if (w->parts & 4u) h[2] = and8(live, mul8(mul8(base, phi1), inv_sum));
  if (w->parts & 3u) {
    const v8 hh = mul8(C8(0.5f), add8(ns->x, w->g0));
    const v8 hh2 = mul8(hh, hh);
    if (w->parts & 1u) {
      const v8 g = prt_v8_exp(_mm256_fnmadd_ps(hh2, C8(th->inv2g2[0]), C8(-th->log_g[0])));
      h[0] = and8(live, mul8(mul8(base, g), phi0));
    }
    if (w->parts & 2u) {
      const v8 g = prt_v8_exp(_mm256_fnmadd_ps(hh2, C8(th->inv2g2[1]), C8(-th->log_g[1])));
      h[1] = and8(live, mul8(mul8(mul8(base, g), phi1), inv_sum));
    }
  }
}

/* The Gaussian's moments over a panel about its middle node, and the reciprocals of the node
 * spacings (gaussian_moments). About the middle node the exact moments cancel by (d / w)^2 for a
 * panel of width w at d from the mean, which float cannot carry for a narrow panel: one narrower
 * than the sd takes its first and second moments by Gauss-Legendre quadrature instead (six
 * nodes: the Gaussian varies by at most e^(4.5) over it). */
typedef struct panel_static {
  v8 m0, m1, m2, i0, i2, i20;
} panel_static;

/* 1 / x, and 0 for x = 0: a piece narrower than float resolves at its place (next to a support
 * end a few ulp from theta = 0) collapses its nodes, and its panels are then worth nothing. */
static inline v8 reciprocal_or_zero(v8 x) {
  return and8(_mm256_cmp_ps(x, _mm256_setzero_ps(), _CMP_NEQ_OQ), div8(C8(1.0f), x));
}

static const float kPanelNodes[6] = {-0.9324695142031521f, -0.6612093864662645f,
                                     -0.2386191860831969f, 0.2386191860831969f,
                                     0.6612093864662645f,  0.9324695142031521f};
static const float kPanelWeights[6] = {0.1713244923791704f, 0.3607615730481386f,
                                       0.4679139345726910f, 0.4679139345726910f,
                                       0.3607615730481386f, 0.1713244923791704f};

static void panel_static_of(const window_l* w, v8 xa, v8 xm, v8 xb, panel_static* ps) {
  const v8 sd = C8(w->sd), inv = C8(w->inv_sd);
  const v8 za = mul8(xa, inv), zb = mul8(xb, inv);
  const v8 m0 = prt_v8_normal_cdf_diff(za, zb);
  const v8 width = sub8(xb, xa);
  const v8 narrow = lt8(width, sd);
  ps->m0 = m0;
  ps->m1 = ps->m2 = _mm256_setzero_ps();
  if (!_mm256_testc_ps(narrow, all_ones())) { /* some lane is wide: exact moments */
    const v8 pa = mul8(prt_v8_exp(mul8(mul8(C8(-0.5f), za), za)), C8(1.0 / SQRT_2PI));
    const v8 pb = mul8(prt_v8_exp(mul8(mul8(C8(-0.5f), zb), zb)), C8(1.0 / SQRT_2PI));
    const v8 m1 = mul8(sd, sub8(pa, pb));
    const v8 m2 = mul8(mul8(sd, sd), sub8(m0, _mm256_fmsub_ps(zb, pb, mul8(za, pa))));
    const v8 d = _mm256_xor_ps(xm, C8(-0.0f)); /* mu - c */
    ps->m1 = fma8(d, m0, m1);
    ps->m2 = fma8(mul8(d, d), m0, fma8(add8(d, d), m1, m2));
  }
  if (any8(narrow)) {
    const v8 half = mul8(C8(0.5f), width), mid = mul8(C8(0.5f), add8(xa, xb));
    const v8 scale = mul8(half, mul8(inv, C8(1.0 / SQRT_2PI)));
    v8 q1 = _mm256_setzero_ps(), q2 = _mm256_setzero_ps();
    int i;
    for (i = 0; i < 6; ++i) {
      const v8 x = fma8(half, C8(kPanelNodes[i]), mid);
      const v8 z = mul8(x, inv), t = sub8(x, xm);
      const v8 f = mul8(C8(kPanelWeights[i]), prt_v8_exp(mul8(mul8(C8(-0.5f), z), z)));
      q1 = fma8(f, t, q1);
      q2 = fma8(mul8(f, t), t, q2);
    }
    ps->m1 = sel8(narrow, mul8(q1, scale), ps->m1);
    ps->m2 = sel8(narrow, mul8(q2, scale), ps->m2);
  }
  ps->i0 = reciprocal_or_zero(sub8(xa, xm));
  ps->i2 = reciprocal_or_zero(sub8(xb, xm));
  ps->i20 = reciprocal_or_zero(width);
}

/* The parts of the window on piece [pl, ph] (integrate_piece), added to out where `live`. */
static void integrate_piece(const call_c* cc, const tangent_c* tc, const thread_c* th,
                            const pair_l* p, const window_l* w, v8 pl, v8 ph, v8 pinch_lo,
                            v8 pinch_hi, v8 live, cursor* cur, v8 out[3]) {
  const uint32_t n = cc->nodes;
  const v8 pinched = _mm256_or_ps(pinch_lo, pinch_hi);
  v8 x[MAX_NODES], h[MAX_NODES][3], acc[3];
  uint32_t s, first;
  int part;
  for (first = 0; first <= n; first += STAGE_NODES) {
    const uint32_t count = n + 1u - first < STAGE_NODES ? n + 1u - first : STAGE_NODES;
    node_static ns[STAGE_NODES];
    v8 end[STAGE_NODES];
    if (cur->mode == CACHE_READ) {
      for (s = 0; s < count; ++s) get_node(cur, &ns[s], cc->q);
    } else {
      const v8 width = sub8(ph, pl);
      for (s = first; s < first + count; ++s) {
        const v8 f = sel8(pinch_lo, C8(cc->frac[1][s]),
                          sel8(pinch_hi, C8(cc->frac[2][s]), C8(cc->frac[0][s])));
        x[s] = s == n ? ph : fma8(width, f, pl);
        end[s - first] = mul8(width, sel8(pinch_lo, C8(cc->frac[1][s]), C8(cc->frac[3][s])));
      }
      nodes_static(cc, tc, p, w, count, x + first, pinched, end, ns);
      if (cur->mode == CACHE_FILL)
        for (s = 0; s < count; ++s) put_node(cur, &ns[s], cc->q);
    }
    for (s = 0; s < count; ++s) {
      x[first + s] = ns[s].x;
      node_dynamic(cc, th, p, w, &ns[s], h[first + s]);
    }
  }
  acc[0] = acc[1] = acc[2] = _mm256_setzero_ps();
  for (s = 0; s < n; s += 2) {
    panel_static ps;
    if (cur->mode == CACHE_READ) {
      ps.m0 = get8(cur), ps.m1 = get8(cur), ps.m2 = get8(cur);
      ps.i0 = get8(cur), ps.i2 = get8(cur), ps.i20 = get8(cur);
    } else {
      panel_static_of(w, x[s], x[s + 1], x[s + 2], &ps);
      if (cur->mode == CACHE_FILL) {
        put8(cur, ps.m0), put8(cur, ps.m1), put8(cur, ps.m2);
        put8(cur, ps.i0), put8(cur, ps.i2), put8(cur, ps.i20);
      }
    }
    for (part = 0; part < 3; ++part) {
      if (!(w->parts & (1u << part))) continue;
      {
        /* the parabola through the three nodes, in powers of (theta - theta_mid) */
        const v8 d0 = mul8(sub8(h[s][part], h[s + 1][part]), ps.i0);
        const v8 d2 = mul8(sub8(h[s + 2][part], h[s + 1][part]), ps.i2);
        const v8 c2 = mul8(sub8(d2, d0), ps.i20);
        const v8 c1 = _mm256_fnmadd_ps(c2, sub8(x[s], x[s + 1]), d0);
        acc[part] = add8(acc[part], fma8(h[s + 1][part], ps.m0, fma8(c1, ps.m1, mul8(c2, ps.m2))));
      }
    }
  }
  for (part = 0; part < 3; ++part)
    if (w->parts & (1u << part)) out[part] = add8(out[part], and8(live, acc[part]));
}

/* The parts of window w (integrate_window): clipped to the support, split at theta = 0 for a
 * tilted fibre, each piece graded towards a pinched end. `lanes`: the lanes that take it. */
static void integrate_window(const call_c* cc, const tangent_c* tc, const thread_c* th,
                             const pair_l* p, const window_l* w, v8 lanes, cursor* cur, v8 out[3]) {
  const v8 zero = _mm256_setzero_ps();
  v8 pl1 = zero, ph1 = zero, pl2 = zero, ph2 = zero, lo1 = zero, hi1 = zero, hi2 = zero;
  v8 live1 = zero, live2 = zero;
  int run1, run2;
  if (cur->mode == CACHE_READ) {
    run1 = get_flag(cur);
    live1 = bool8(run1);
  } else {
    /* decided in theta, as the scalar code: the support's ends may lie closer to theta = 0 than
     * an ulp of mu, which x = theta - mu would lose */
    const v8 lo_s = C8(tc->lo), hi_s = C8(tc->hi), reach = C8(WINDOW_SIGMAS * w->sd);
    const v8 lo = _mm256_max_ps(lo_s, sub8(w->mu, reach));
    const v8 hi = _mm256_min_ps(hi_s, add8(w->mu, reach));
    const v8 neg_mu = _mm256_xor_ps(w->mu, C8(-0.0f));
    const v8 nonempty = gt8(hi, lo);
    const v8 split =
        tc->tilted ? and8(lt8(lo, zero), gt8(hi, zero)) : zero; /* nonempty with them */
    const v8 clip_lo = le8(lo, lo_s), clip_hi = ge8(hi, hi_s);
    pl1 = sub8(lo, w->mu);
    ph1 = sel8(split, neg_mu, sub8(hi, w->mu));
    lo1 = tc->sign > 0 ? clip_lo : zero;
    hi1 = tc->sign < 0 ? andnot8(split, clip_hi) : zero;
    live1 = nonempty;
    pl2 = neg_mu;
    ph2 = sub8(hi, w->mu);
    hi2 = tc->sign < 0 ? clip_hi : zero;
    live2 = split;
    run1 = any8(cur->mode == CACHE_FILL ? live1 : and8(live1, lanes));
    if (cur->mode == CACHE_FILL) put_flag(cur, run1);
  }
  if (run1) integrate_piece(cc, tc, th, p, w, pl1, ph1, lo1, hi1, and8(live1, lanes), cur, out);
  if (cur->mode == CACHE_READ) {
    run2 = get_flag(cur);
    live2 = bool8(run2);
  } else {
    run2 = any8(cur->mode == CACHE_FILL ? live2 : and8(live2, lanes));
    if (cur->mode == CACHE_FILL) put_flag(cur, run2);
  }
  if (run2) integrate_piece(cc, tc, th, p, w, pl2, ph2, zero, hi2, and8(live2, lanes), cur, out);
}

/* The three lobe integrals of a pair (prt_cloth_lobe_integrals): each lobed part narrower than
 * the lobe on its own window, then the lobe's own window (cacheable). */
static void lobe_integrals(const call_c* cc, const tangent_c* tc, const lobe_c* lobe,
                           const pair_l* p, v8 lanes, cursor* cur, v8 out[3]) {
  const thread_c* th = &cc->threads[tc->thread];
  const unsigned merged = lobe->merged[tc->thread];
  cursor none = {NULL, CACHE_NONE};
  window_l w;
  int part;
  out[0] = out[1] = out[2] = _mm256_setzero_ps();
  for (part = 0; part < 2; ++part) {
    const part_window* pw = &lobe->part[tc->thread][part];
    if (merged & (1u << part)) continue;
    /* mu = (lambda theta_k - band theta_o) / (lambda + band) */
    w.y0 = mul8(C8(-pw->wb), p->sum_ko);
    w.g0 = mul8(C8(pw->wl), p->sum_ko);
    w.mu = add8(p->theta_k, w.y0);
    w.sd = pw->sd;
    w.inv_sd = pw->inv_sd;
    w.log_root = pw->log_root;
    w.parts = 1u << part;
    integrate_window(cc, tc, th, p, &w, lanes, &none, out);
  }
  w.mu = p->theta_k;
  w.y0 = _mm256_setzero_ps();
  w.g0 = p->sum_ko;
  w.sd = lobe->sd;
  w.inv_sd = lobe->inv_sd;
  w.log_root = lobe->log_root;
  w.parts = merged;
  integrate_window(cc, tc, th, p, &w, lanes, cur, out);
  for (part = 0; part < 3; ++part) out[part] = _mm256_max_ps(out[part], _mm256_setzero_ps());
}

/* The lobe (its axis d along u, v, n) in the fibre's angles and the thread's canonical frame,
 * for every lane. */
static void pair_static(const tangent_c* tc, const v8 d[3], pair_l* p) {
  v8 x, y;
  thread_axes(tc, d[0], d[1], &x, &y);
  fibre_angles(tc, x, y, d[2], &p->theta_k, &p->phi_k, &p->cos_k, &p->sin_k);
  p->cx = tc->mirror ? _mm256_xor_ps(x, C8(-0.0f)) : x;
  p->cy = y;
  p->cz = d[2];
}

/* T and T_c of each lane in `lanes` (0 elsewhere): the lobe rows read at each lane's canonical
 * lobe (mirrored in y with the view), or for both mirrors from the cache. `shared`, when not
 * NULL, holds the lanes' cells if *have, else receives them. */
static void pair_tables(const call_c* cc, const tangent_c* tc, const lobe_c* lobe, const pair_l* p,
                        const view_l* vw, unsigned lanes, cursor* cur, cells_l* shared,
                        uint8_t* have, v8* t, v8* t_cone) {
  v8 prod_f[LANES], prod_c[LANES], rows[2][2][MAX_CHUNKS];
  const uint32_t cf = tc->full.chunks, ccn = tc->cone.chunks;
  uint32_t l, c, m;
  cells_l own;
  const cells_l* cl = &own;
  if (cur->mode == CACHE_READ) {
    for (m = 0; m < 2; ++m) {
      for (c = 0; c < cf; ++c) rows[m][0][c] = _mm256_loadu_ps(cur->at), cur->at += 8;
      for (c = 0; c < ccn; ++c) rows[m][1][c] = _mm256_loadu_ps(cur->at), cur->at += 8;
    }
  } else if (cur->mode == CACHE_FILL) {
    /* both mirrors of lane 0's lobe: lanes 0 and 1 of the cells */
    const v8 two = _mm256_setr_ps(1, -1, 1, 1, 1, 1, 1, 1);
    octahedral_cells(cc, p->cx, mul8(p->cy, two), p->cz, &own);
    for (m = 0; m < 2; ++m) {
      const uint32_t i = (uint32_t)own.i[m], j = (uint32_t)own.j[m];
      lobe_row(cc, &tc->full, lobe, i, j, own.fi[m], own.fj[m], rows[m][0]);
      if (cc->cone) lobe_row(cc, &tc->cone, lobe, i, j, own.fi[m], own.fj[m], rows[m][1]);
      for (c = 0; c < cf; ++c) _mm256_storeu_ps(cur->at, rows[m][0][c]), cur->at += 8;
      for (c = 0; c < ccn; ++c) _mm256_storeu_ps(cur->at, rows[m][1][c]), cur->at += 8;
    }
  } else if (shared && *have) {
    cl = shared;
  } else {
    const v8 flip = mask_of_bits(vw->flip);
    cells_l* fill = shared ? shared : &own;
    octahedral_cells(cc, p->cx, sel8(flip, _mm256_xor_ps(p->cy, C8(-0.0f)), p->cy), p->cz, fill);
    if (shared) *have = 1;
    cl = fill;
  }
  for (l = 0; l < LANES; ++l) {
    v8 lane_rows[2][MAX_CHUNKS];
    v8(*r)[MAX_CHUNKS] = lane_rows;
    v8 pf = _mm256_setzero_ps(), pc = _mm256_setzero_ps();
    if (lanes >> l & 1u) {
      if (cur->mode == CACHE_NONE) {
        const uint32_t i = (uint32_t)cl->i[l], j = (uint32_t)cl->j[l];
        lobe_row(cc, &tc->full, lobe, i, j, cl->fi[l], cl->fj[l], lane_rows[0]);
        if (cc->cone) lobe_row(cc, &tc->cone, lobe, i, j, cl->fi[l], cl->fj[l], lane_rows[1]);
      } else {
        r = rows[vw->flip >> l & 1u];
      }
      for (c = 0; c < cf; ++c) pf = fma8(r[0][c], _mm256_load_ps(vw->vf[l] + 8u * c), pf);
      if (cc->cone)
        for (c = 0; c < ccn; ++c) pc = fma8(r[1][c], _mm256_load_ps(vw->vc[l] + 8u * c), pc);
    }
    prod_f[l] = pf;
    prod_c[l] = pc;
  }
  /* a weight: quantisation must not push it outside [0, 1] */
  *t = _mm256_min_ps(C8(1.0f), _mm256_max_ps(_mm256_setzero_ps(), sum_each(prod_f)));
  *t_cone =
      cc->cone ? _mm256_min_ps(C8(1.0f), _mm256_max_ps(_mm256_setzero_ps(), sum_each(prod_c))) : *t;
}

/* The frame cache's state for one call. */
typedef struct frame_cache {
  float* floats;
  size_t pairs; /* pairs with a record */
  int valid;    /* records belong to key */
  float key[6];
  uint8_t filled[MAX_TANGENTS * PRT_CLOTH_MAX_LOBES / 8u];
} frame_cache;

static void shade_tangent(const call_c* cc, uint32_t ti, const batch* b, frame_cache* fc,
                          lobe_share* sh, v8 rgb[3]) {
  const tangent_c* tc = &cc->tan[ti];
  const thread_c* th = &cc->threads[tc->thread];
  const unsigned active = (unsigned)_mm256_movemask_ps(b->active);
  const int group = 2 * tc->thread + tc->mirror;
  view_l vw;
  uint32_t k;
  tangent_view(cc, tc, b, active, sh, &vw);
  for (k = 0; k < cc->lobes; ++k) {
    const lobe_c* lobe = &cc->lobe[k];
    const unsigned lanes = b->vis[k] & active;
    const size_t pair = (size_t)ti * cc->lobes + k;
    cursor cur = {NULL, CACHE_NONE};
    const int shared = sh->on && k < SHARED_LOBES;
    pair_l p;
    v8 t, t_cone, in[3], mask, ws, wv, sin_b, cos_b, own_axis[3];
    int c;
    if (!lanes) continue;
    mask = mask_of_bits(lanes);
    if (b->uniform && pair < fc->pairs) {
      cur.at = fc->floats + pair * cc->record;
      cur.mode = (fc->filled[pair / 8u] >> (pair % 8u) & 1u) ? CACHE_READ : CACHE_FILL;
      fc->filled[pair / 8u] |= (uint8_t)(1u << (pair % 8u));
    }
    p.lambda = lobe->lambda;
    if (cur.mode == CACHE_READ) {
      p.theta_k = get8(&cur), p.phi_k = get8(&cur), p.cos_k = get8(&cur), p.sin_k = get8(&cur);
    } else {
      pair_static(tc, lobe_axis(sh, lobe, k, b, own_axis), &p);
      if (cur.mode == CACHE_FILL)
        put8(&cur, p.theta_k), put8(&cur, p.phi_k), put8(&cur, p.cos_k), put8(&cur, p.sin_k);
    }
    pair_tables(cc, tc, lobe, &p, &vw, lanes, &cur, shared ? &sh->cells[group][k] : NULL,
                shared ? &sh->have_cells[group][k] : NULL, &t, &t_cone);
    p.sum_ko = add8(p.theta_k, vw.theta_o);
    p.cos_o = vw.cos_o;
    prt_v8_sincos(mul8(C8(0.5f), sub8(p.theta_k, vw.theta_o)), &sin_b, &cos_b);
    p.sin_b = sin_b;
    p.cos_b = cos_b;
    prt_v8_sincos(mul8(C8(0.5f), sub8(p.phi_k, vw.phi_o)), &p.sin_hd, &p.cos_hd);
    lobe_integrals(cc, tc, lobe, &p, mask, &cur, in);
    ws = fma8(C8(lobe->blend[tc->thread][0]), sub8(t_cone, t), t);
    wv = fma8(C8(lobe->blend[tc->thread][1]), sub8(t_cone, t), t);
    {
      const v8 surface = mul8(ws, in[0]);
      const v8 lobed = mul8(mul8(C8(th->lobed), wv), in[1]);
      const v8 volume = fma8(mul8(C8(th->kd), t), in[2], lobed);
      for (c = 0; c < 3; ++c) {
        const v8 v = fma8(C8(th->albedo[c]), volume, surface);
        rgb[c] = add8(rgb[c], and8(mask, mul8(C8(tc->weight * lobe->rgb[c]), v)));
      }
    }
  }
}

/* ---- Batches -----------------------------------------------------------------------------------
 */

/* The lanes of samples [at, at + n) (n <= 8; the others repeat the last sample, inactive): each
 * frame, view and the lobes it sees, in double as the scalar reference decides them. */
static void load_batch(const call_c* cc, const prt_cloth_lobe_prep* lobes,
                       const prt_cloth_pixels* pixels, size_t at, uint32_t n, batch* b) {
  float fn[3][LANES], fu[3][LANES], fv[3][LANES], fw[3][LANES], act[LANES];
  uint8_t hidden[PRT_CLOTH_MAX_LOBES];
  prt_cloth_frame frame;
  int frame_ok = 0;
  uint32_t l, i, k;
  const float* n0 = pixels->normals + 3u * at;
  const float* w0 = pixels->warps + 3u * at;
  b->uniform = 1;
  memset(b->vis, 0, cc->lobes);
  for (l = 0; l < LANES; ++l) {
    const size_t s = at + (l < n ? l : n - 1u);
    const float* nrm = pixels->normals + 3u * s;
    const float* wrp = pixels->warps + 3u * s;
    const float* view = pixels->views + 3u * s;
    double wo[3], len;
    int ok;
    const int same =
        l > 0 && memcmp(nrm, n0, 3 * sizeof(float)) == 0 && memcmp(wrp, w0, 3 * sizeof(float)) == 0;
    if (!same) {
      if (l > 0) b->uniform = 0;
      frame_ok = prt_cloth_make_frame(nrm, wrp, &frame);
      /* lobe_visible, as a bound on sqrt(1 - d^2) */
      for (k = 0; k < cc->lobes && frame_ok; ++k) {
        const double d = lobes[k].axis[0] * frame.n[0] + lobes[k].axis[1] * frame.n[1] +
                         lobes[k].axis[2] * frame.n[2];
        hidden[k] = !(d >= 0.0 || sqrt(1.0 - d * d) >= cc->lobe[k].cull);
      }
    }
    wo[0] = view[0], wo[1] = view[1], wo[2] = view[2];
    len = sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
    ok = frame_ok && l < n && len > 0.0 && isfinite(len);
    if (ok) {
      wo[0] /= len, wo[1] /= len, wo[2] /= len;
      ok = wo[0] * frame.n[0] + wo[1] * frame.n[1] + wo[2] * frame.n[2] > 0.0;
    }
    for (i = 0; i < 3; ++i) {
      fn[i][l] = frame_ok ? (float)frame.n[i] : (i == 2 ? 1.0f : 0.0f);
      fu[i][l] = frame_ok ? (float)frame.u[i] : (i == 0 ? 1.0f : 0.0f);
      fv[i][l] = frame_ok ? (float)frame.v[i] : (i == 1 ? 1.0f : 0.0f);
      fw[i][l] = ok ? (float)wo[i] : fn[i][l];
    }
    act[l] = ok ? 1.0f : 0.0f;
    if (ok)
      for (k = 0; k < cc->lobes; ++k)
        if (!hidden[k]) b->vis[k] |= (uint8_t)(1u << l);
  }
  if (!frame_ok) b->uniform = 0;
  for (i = 0; i < 3; ++i) {
    b->n[i] = _mm256_loadu_ps(fn[i]);
    b->u[i] = _mm256_loadu_ps(fu[i]);
    b->v[i] = _mm256_loadu_ps(fv[i]);
  }
  {
    const v8 wx = _mm256_loadu_ps(fw[0]), wy = _mm256_loadu_ps(fw[1]), wz = _mm256_loadu_ps(fw[2]);
    b->du = fma8(wx, b->u[0], fma8(wy, b->u[1], mul8(wz, b->u[2])));
    b->dv = fma8(wx, b->v[0], fma8(wy, b->v[1], mul8(wz, b->v[2])));
    b->dn = fma8(wx, b->n[0], fma8(wy, b->n[1], mul8(wz, b->n[2])));
  }
  b->active = gt8(_mm256_loadu_ps(act), _mm256_setzero_ps());
  memcpy(b->key, n0, 3 * sizeof(float));
  memcpy(b->key + 3, w0, 3 * sizeof(float));
}

void prt_cloth_shade_avx2(const prt_cloth_view* view, const prt_cloth_fabric_prep* fabric,
                          const prt_cloth_light_prep* light, const prt_cloth_method* method,
                          const prt_cloth_pixels* pixels, uint32_t first, uint32_t count,
                          float* out_rgb) {
  float cache_floats[CACHE_FLOATS];
  call_c cc;
  frame_cache fc;
  lobe_share share;
  batch b;
  uint32_t done;
  prepare_call(view, fabric, light, method, &cc);
  fc.floats = cache_floats;
  fc.pairs = (method->flags & PRT_CLOTH_NO_FRAME_CACHE) ? 0u : CACHE_FLOATS / cc.record;
  fc.valid = 0;
  share.on = !(method->flags & PRT_CLOTH_NO_LOBE_SHARING);
  for (done = 0; done < count; done += LANES) {
    const uint32_t n = count - done < LANES ? count - done : LANES;
    float lanes_rgb[3][LANES];
    v8 rgb[3];
    uint32_t i, l;
    load_batch(&cc, light->lobes, pixels, (size_t)first + done, n, &b);
    rgb[0] = rgb[1] = rgb[2] = _mm256_setzero_ps();
    if (any8(b.active)) {
      if (b.uniform && fc.pairs > 0 && !(fc.valid && memcmp(fc.key, b.key, sizeof fc.key) == 0)) {
        memcpy(fc.key, b.key, sizeof fc.key);
        memset(fc.filled, 0, sizeof fc.filled);
        fc.valid = 1;
      }
      reset_share(&share);
      for (i = 0; i < cc.tangents; ++i) shade_tangent(&cc, i, &b, &fc, &share, rgb);
    }
    for (i = 0; i < 3; ++i) _mm256_storeu_ps(lanes_rgb[i], and8(b.active, rgb[i]));
    for (l = 0; l < n; ++l)
      for (i = 0; i < 3; ++i) out_rgb[3u * (size_t)(done + l) + i] = lanes_rgb[i][l];
  }
}
