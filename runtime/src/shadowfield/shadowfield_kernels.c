/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield`'s inner loops, scalar: the reference the SIMD table is checked
 * against (shadowfield_kernels.h). */
#include <string.h>

#include "shadowfield_kernels.h"
#include "shadowfield_scene.h"

static void read_rows_scalar(const float* field, uint64_t plane, uint32_t planes, uint32_t width,
                             const prt_sf_lookup* lookup, float* out) {
  memset(out, 0, (size_t)width * planes * sizeof(float));
  for (uint32_t c = 0; c < planes; ++c) {
    float* o = out + c * width;
    for (uint32_t e = 0; e < lookup->count; ++e) {
      const float w = lookup->weight[e];
      const float* row = field + c * plane + lookup->index[e] * width;
      for (uint32_t i = 0; i < width; ++i) o[i] += w * row[i];
    }
  }
}

/* The dots whole, in lane 0. */
static void read_dot_scalar(const float* field, uint64_t plane, uint32_t width,
                            const prt_sf_lookup* lookup, const float* transfer, uint32_t terms,
                            float* partial) {
  float local[3u * PRT_SF_MAX_COEFFS];
  read_rows_scalar(field, plane, 3u, width, lookup, local);
  for (uint32_t k = 0; k < terms; ++k)
    for (uint32_t c = 0; c < 3u; ++c) {
      float sum = 0.0f;
      for (uint32_t i = 0; i < width; ++i) sum += transfer[k * width + i] * local[c * width + i];
      partial[(3u * k + c) * PRT_SF_LANES] += sum;
    }
}

static void reduce_lanes_scalar(const float* partial, uint32_t count, float* out) {
  for (uint32_t r = 0; r < count; ++r) {
    float sum = 0.0f;
    for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane) sum += partial[r * PRT_SF_LANES + lane];
    out[r] = sum;
  }
}

static void rotate_scalar(const prt_sf_pair* pair, uint32_t order, const float* in, float* out,
                          uint32_t planes) {
  const uint32_t n2 = order * order;
  for (uint32_t c = 0; c < planes; ++c)
    prt_sf_rotate_apply(order, pair->sh_rotation, in + c * n2, out + c * n2, 1u);
}

/* The column-major blocks read row-major are the transpose's, the inverse rotation. */
static void rotate_back_scalar(const prt_sf_pair* pair, uint32_t order, const float* in, float* out,
                               uint32_t planes) {
  const uint32_t n2 = order * order;
  for (uint32_t c = 0; c < planes; ++c)
    prt_sf_rotate_apply(order, pair->sh_rotation_columns, in + c * n2, out + c * n2, 1u);
}

static void rotate_lanes_scalar(const prt_sf_pair* pair, uint32_t order, const float* in,
                                float* out, uint32_t mask) {
  const uint32_t n2 = order * order;
  float local[PRT_SF_MAX_COEFFS], turned[PRT_SF_MAX_COEFFS];
  for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane) {
    if (!(mask >> lane & 1u)) continue;
    for (uint32_t k = 0; k < n2; ++k) local[k] = in[k * PRT_SF_LANES + lane];
    prt_sf_rotate_apply(order, pair->sh_rotation, local, turned, 1u);
    for (uint32_t k = 0; k < n2; ++k) out[k * PRT_SF_LANES + lane] = turned[k];
  }
}

static void light_times_scalar(const float* matrix, uint32_t n2, const float* visibility,
                               float* light) {
  for (uint32_t c = 0; c < 3u; ++c)
    for (uint32_t k = 0; k < n2; ++k) {
      const float* row = matrix + ((size_t)c * n2 + k) * n2;
      float sum = 0.0f;
      for (uint32_t j = 0; j < n2; ++j) sum += row[j] * visibility[j];
      light[c * n2 + k] = sum;
    }
}

static void multiply_lanes_scalar(const prt_sf_gaunt* gaunt, float* a, const float* b,
                                  uint32_t mask) {
  const uint32_t n2 = gaunt->order * gaunt->order;
  float left[PRT_SF_MAX_COEFFS], right[PRT_SF_MAX_COEFFS], product[PRT_SF_MAX_COEFFS];
  for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane) {
    if (!(mask >> lane & 1u)) continue;
    for (uint32_t k = 0; k < n2; ++k) {
      left[k] = a[k * PRT_SF_LANES + lane];
      right[k] = b[k * PRT_SF_LANES + lane];
    }
    prt_sf_sh_multiply(gaunt, left, right, product);
    for (uint32_t k = 0; k < n2; ++k) a[k * PRT_SF_LANES + lane] = product[k];
  }
}

static void transfer_dot_scalar(const float* transfer, uint32_t n2, uint32_t terms,
                                const float* light, float* out) {
  for (uint32_t k = 0; k < terms; ++k) {
    const float* t = transfer + (size_t)k * n2;
    float sum[3] = {0.0f, 0.0f, 0.0f};
    for (uint32_t i = 0; i < n2; ++i)
      for (uint32_t c = 0; c < 3u; ++c) sum[c] += t[i] * light[c * n2 + i];
    for (uint32_t c = 0; c < 3u; ++c) out[3u * k + c] = sum[c];
  }
}

/* Per block of points, every SRF row in turn adds to the block's three planes; each value's
 * sum runs over (i, k) in order, as a row-by-row sum over the whole field would. */
static void cast_field_scalar(const prt_sf_object* object, const float* weights, float* field,
                              uint64_t first, uint64_t count) {
  const uint32_t n2 = object->order * object->order, rows = object->basis_size * object->terms;
  const uint64_t points = prt_sf_point_count(&object->srf_shells);
  for (uint64_t start = first; start < first + count; start += PRT_SF_FIELD_BLOCK) {
    const uint64_t end =
        start + PRT_SF_FIELD_BLOCK < first + count ? start + PRT_SF_FIELD_BLOCK : first + count;
    const size_t length = (size_t)(end - start) * n2;
    float* restrict red = field + (size_t)start * n2;
    float* restrict green = field + ((size_t)points + start) * n2;
    float* restrict blue = field + ((size_t)2u * points + start) * n2;
    memset(red, 0, length * sizeof(float));
    memset(green, 0, length * sizeof(float));
    memset(blue, 0, length * sizeof(float));
    for (uint32_t r = 0; r < rows; ++r) {
      const float w0 = weights[3u * r], w1 = weights[3u * r + 1u], w2 = weights[3u * r + 2u];
      const float* restrict srf = object->srf + ((size_t)r * points + start) * n2;
      for (size_t e = 0; e < length; ++e) {
        red[e] += w0 * srf[e];
        green[e] += w1 * srf[e];
        blue[e] += w2 * srf[e];
      }
    }
  }
}

static void exp_lanes_scalar(const prt_sf_sphere_rule* rule, float* lanes, uint32_t mask) {
  const uint32_t n2 = rule->order * rule->order, directions = rule->directions;
  for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane) {
    if (!(mask >> lane & 1u)) continue;
    float out[PRT_SF_MAX_COEFFS] = {0.0f};
    for (uint32_t d = 0; d < directions; ++d) {
      const float* y = rule->eval + (size_t)d * n2;
      float value = 0.0f;
      for (uint32_t i = 0; i < n2; ++i) value += y[i] * lanes[i * PRT_SF_LANES + lane];
      const float e = prt_sf_exp(value);
      for (uint32_t i = 0; i < n2; ++i) out[i] += rule->project[(size_t)i * directions + d] * e;
    }
    for (uint32_t i = 0; i < n2; ++i) lanes[i * PRT_SF_LANES + lane] = out[i];
  }
}

const prt_sf_kernels prt_sf_kernels_scalar = {
    read_rows_scalar,    rotate_scalar,         rotate_back_scalar, rotate_lanes_scalar,
    light_times_scalar,  multiply_lanes_scalar, read_dot_scalar,    reduce_lanes_scalar,
    transfer_dot_scalar, cast_field_scalar,     exp_lanes_scalar};
