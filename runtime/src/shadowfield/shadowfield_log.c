/* SPDX-License-Identifier: MIT */
/* The log-space product's fields and quadratures (shadowfield_log.h). */
#include "shadowfield_log.h"

#include "../internal.h"
#include "shadowfield_gaunt.h"

#define SF_PI 3.14159265358979323846
#define SF_MAX_COEFFS (PRT_SF_GAUNT_MAX_ORDER * PRT_SF_GAUNT_MAX_ORDER)
#define SF_MAX_Z_NODES 64u

prt_result prt_sf_sphere_rule_build(const prt_allocator* allocator, uint32_t order,
                                    uint32_t z_nodes, uint32_t phi_nodes, prt_sf_sphere_rule* out) {
  memset(out, 0, sizeof *out);
  if (order == 0u || order > PRT_SF_GAUNT_MAX_ORDER || z_nodes == 0u || z_nodes > SF_MAX_Z_NODES ||
      phi_nodes == 0u)
    return PRT_ERROR_INVALID_ARGUMENT;
  const uint32_t n2 = order * order, directions = z_nodes * phi_nodes;
  const size_t bytes = (size_t)directions * n2 * sizeof(float);
  out->eval = (float*)prt_internal_alloc(allocator, bytes, 32);
  out->project = (float*)prt_internal_alloc(allocator, bytes, 32);
  out->order = order;
  out->directions = directions;
  if (!out->eval || !out->project) {
    prt_sf_sphere_rule_free(allocator, out);
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  double nodes[SF_MAX_Z_NODES], weights[SF_MAX_Z_NODES];
  prt_sf_gauss_legendre(z_nodes, nodes, weights);
  for (uint32_t a = 0; a < z_nodes; ++a) {
    const double z = nodes[a], sin_theta = sqrt(1.0 - z * z);
    for (uint32_t b = 0; b < phi_nodes; ++b) {
      const double phi = 2.0 * SF_PI * (b + 0.5) / phi_nodes;
      const double weight = weights[a] * 2.0 * SF_PI / phi_nodes;
      /* SH frame (x, y, z) = world (X, -Z, Y): prt_sh_eval takes world directions. */
      const float world[3] = {(float)(sin_theta * cos(phi)), (float)z,
                              (float)(-sin_theta * sin(phi))};
      const uint32_t d = a * phi_nodes + b;
      float y[SF_MAX_COEFFS];
      prt_sh_eval(order, world, y);
      for (uint32_t i = 0; i < n2; ++i) {
        out->eval[(size_t)d * n2 + i] = y[i];
        out->project[(size_t)i * directions + d] = (float)(weight * y[i]);
      }
    }
  }
  return PRT_OK;
}

void prt_sf_sphere_rule_free(const prt_allocator* allocator, prt_sf_sphere_rule* rule) {
  const size_t bytes = (size_t)rule->directions * rule->order * rule->order * sizeof(float);
  if (rule->eval) prt_internal_free(allocator, rule->eval, bytes);
  if (rule->project) prt_internal_free(allocator, rule->project, bytes);
  memset(rule, 0, sizeof *rule);
}

prt_result prt_sf_exp_rule_build(const prt_allocator* allocator, uint32_t order,
                                 prt_sf_sphere_rule* out) {
  return prt_sf_sphere_rule_build(allocator, order, order + 2u, 2u * order + 3u, out);
}

prt_result prt_sf_log_rule_build(const prt_allocator* allocator, uint32_t order,
                                 prt_sf_sphere_rule* out) {
  return prt_sf_sphere_rule_build(allocator, order, 16u, 32u, out);
}

void prt_sf_log_of_field(const prt_sf_sphere_rule* fine, const float* field, uint64_t points,
                         float floor_value, float* out) {
  const uint32_t n2 = fine->order * fine->order, directions = fine->directions;
  for (uint64_t p = 0; p < points; ++p) {
    const float* in = field + p * n2;
    double sums[SF_MAX_COEFFS] = {0.0};
    for (uint32_t d = 0; d < directions; ++d) {
      const float* y = fine->eval + (size_t)d * n2;
      float visibility = 0.0f;
      for (uint32_t i = 0; i < n2; ++i) visibility += in[i] * y[i];
      visibility = visibility > floor_value ? visibility : floor_value;
      const double value = log((double)visibility);
      for (uint32_t i = 0; i < n2; ++i)
        sums[i] += value * fine->project[(size_t)i * directions + d];
    }
    for (uint32_t i = 0; i < n2; ++i) out[p * n2 + i] = (float)sums[i];
  }
}
