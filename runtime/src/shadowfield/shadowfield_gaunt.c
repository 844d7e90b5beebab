/* SPDX-License-Identifier: MIT */
/* The SH triple-product tensor (shadowfield_gaunt.h), by exact quadrature. */
#include "shadowfield_gaunt.h"

#include <math.h>
#include <string.h>

#include "../internal.h"

#define SF_PI 3.14159265358979323846
#define SF_COEFFS (PRT_SF_GAUNT_MAX_ORDER * PRT_SF_GAUNT_MAX_ORDER)
/* Below this a coefficient is the quadrature's float rounding of an exact zero (every true
 * non-zero coefficient up to order 6 is orders of magnitude above it). */
#define SF_GAUNT_TINY 1e-5

void prt_sf_gauss_legendre(uint32_t count, double* nodes, double* weights) {
  for (uint32_t r = 0; r < count; ++r) {
    double x = cos(SF_PI * (r + 0.75) / (count + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (uint32_t l = 2; l <= count; ++l) {
        const double p2 = ((2.0 * l - 1.0) * x * p1 - (l - 1.0) * p0) / l;
        p0 = p1;
        p1 = p2;
      }
      derivative = count * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (fabs(step) < 1e-15) break;
    }
    nodes[r] = x;
    weights[r] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
}

/* Accumulates every C_ijk (k < n^2, all i, j < n^2) into dense[(k n^2 + i) n^2 + j]. */
static void integrate(uint32_t order, double* dense) {
  const uint32_t n2 = order * order;
  /* y_i y_j y_k has degree 3 (n - 1) in (x, y, z): so many Gauss-Legendre nodes in cos(theta)
   * and uniform nodes in phi integrate it exactly. */
  const uint32_t degree = 3u * (order - 1u);
  const uint32_t z_nodes = degree / 2u + 1u, phi_nodes = degree + 1u;
  double nodes[PRT_SF_GAUNT_MAX_ORDER * 2u], weights[PRT_SF_GAUNT_MAX_ORDER * 2u];
  prt_sf_gauss_legendre(z_nodes, nodes, weights);
  for (uint32_t a = 0; a < z_nodes; ++a) {
    const double z = nodes[a], sin_theta = sqrt(1.0 - z * z);
    for (uint32_t b = 0; b < phi_nodes; ++b) {
      const double phi = 2.0 * SF_PI * b / phi_nodes, w = weights[a] * 2.0 * SF_PI / phi_nodes;
      /* SH frame (x, y, z) = world (X, -Z, Y): prt_sh_eval takes world directions. */
      const float world[3] = {(float)(sin_theta * cos(phi)), (float)z,
                              (float)(-sin_theta * sin(phi))};
      float y[SF_COEFFS];
      prt_sh_eval(order, world, y);
      for (uint32_t k = 0; k < n2; ++k)
        for (uint32_t i = 0; i < n2; ++i) {
          const double yki = w * y[k] * y[i];
          double* row = dense + ((size_t)k * n2 + i) * n2;
          for (uint32_t j = 0; j < n2; ++j) row[j] += yki * y[j];
        }
    }
  }
}

prt_result prt_sf_gaunt_build(const prt_allocator* allocator, uint32_t order, prt_sf_gaunt* out) {
  memset(out, 0, sizeof *out);
  if (order == 0u || order > PRT_SF_GAUNT_MAX_ORDER) return PRT_ERROR_INVALID_ARGUMENT;
  const uint32_t n2 = order * order;
  const size_t dense_count = (size_t)n2 * n2 * n2;
  double* dense = (double*)prt_internal_alloc(allocator, dense_count * sizeof(double), 8);
  if (!dense) return PRT_ERROR_OUT_OF_MEMORY;
  memset(dense, 0, dense_count * sizeof(double));
  integrate(order, dense);
  uint32_t count = 0;
  for (size_t e = 0; e < dense_count; ++e)
    if (fabs(dense[e]) > SF_GAUNT_TINY) ++count;
  out->i = (uint8_t*)prt_internal_alloc(allocator, count, 1);
  out->j = (uint8_t*)prt_internal_alloc(allocator, count, 1);
  out->value = (float*)prt_internal_alloc(allocator, (size_t)count * sizeof(float), 4);
  if (!out->i || !out->j || !out->value) {
    out->count = count;
    prt_sf_gaunt_free(allocator, out);
    prt_internal_free(allocator, dense, dense_count * sizeof(double));
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  out->order = order;
  out->count = count;
  uint32_t e = 0;
  for (uint32_t k = 0; k < n2; ++k) {
    out->k_start[k] = e;
    for (uint32_t i = 0; i < n2; ++i)
      for (uint32_t j = 0; j < n2; ++j) {
        const double c = dense[((size_t)k * n2 + i) * n2 + j];
        if (fabs(c) <= SF_GAUNT_TINY) continue;
        out->i[e] = (uint8_t)i;
        out->j[e] = (uint8_t)j;
        out->value[e] = (float)c;
        ++e;
      }
  }
  out->k_start[n2] = e;
  prt_internal_free(allocator, dense, dense_count * sizeof(double));
  return PRT_OK;
}

void prt_sf_gaunt_free(const prt_allocator* allocator, prt_sf_gaunt* gaunt) {
  if (gaunt->i) prt_internal_free(allocator, gaunt->i, gaunt->count);
  if (gaunt->j) prt_internal_free(allocator, gaunt->j, gaunt->count);
  if (gaunt->value)
    prt_internal_free(allocator, gaunt->value, (size_t)gaunt->count * sizeof(float));
  memset(gaunt, 0, sizeof *gaunt);
}

void prt_sf_sh_multiply(const prt_sf_gaunt* gaunt, const float* a, const float* b, float* out) {
  const uint32_t n2 = gaunt->order * gaunt->order;
  for (uint32_t k = 0; k < n2; ++k) {
    float sum = 0.0f;
    for (uint32_t e = gaunt->k_start[k]; e < gaunt->k_start[k + 1u]; ++e)
      sum += gaunt->value[e] * a[gaunt->i[e]] * b[gaunt->j[e]];
    out[k] = sum;
  }
}
