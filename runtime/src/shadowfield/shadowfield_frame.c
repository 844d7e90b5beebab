/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield`'s frame (docs/shadowfield/design.md, "At run time"): the light in each
 * instance's frame, the pairs of instances that interact (step 1) with their rotations, and the
 * whole frame on one thread. */
#include <math.h>
#include <string.h>

#include "../internal.h"
#include "shadowfield_scene.h"

void prt_sf_rotate_apply(uint32_t order, const float* blocks, const float* in, float* out,
                         uint32_t channels) {
  const float* block = blocks;
  for (uint32_t l = 0; l < order; ++l) {
    const uint32_t width = 2u * l + 1u, base = l * l;
    for (uint32_t a = 0; a < width; ++a)
      for (uint32_t c = 0; c < channels; ++c) {
        float sum = 0.0f;
        for (uint32_t b = 0; b < width; ++b)
          sum += block[a * width + b] * in[(base + b) * channels + c];
        out[(base + a) * channels + c] = sum;
      }
    block += width * width;
  }
}

/* The band blocks of the SH rotation by `rotation` (row-major 3x3): prt_sh_rotate of the basis
 * vectors, one channel each, gives the matrix's columns. */
static void rotation_blocks(uint32_t order, const float rotation[9], float* blocks, float* columns,
                            float* padded, float* padded_back) {
  const uint32_t n2 = order * order;
  float identity[PRT_SF_MAX_COEFFS * PRT_SF_MAX_COEFFS],
      matrix[PRT_SF_MAX_COEFFS * PRT_SF_MAX_COEFFS];
  memset(identity, 0, sizeof identity);
  for (uint32_t i = 0; i < n2; ++i) identity[i * n2 + i] = 1.0f;
  prt_sh_rotate(order, rotation, identity, matrix, n2);
  float* block = blocks;
  memset(padded, 0, PRT_SF_PADDED_ROTATION_FLOATS * sizeof(float));
  memset(padded_back, 0, PRT_SF_PADDED_ROTATION_FLOATS * sizeof(float));
  for (uint32_t l = 0; l < order; ++l) {
    const uint32_t width = 2u * l + 1u, base = l * l, pad = (width + 7u) / 8u * 8u;
    for (uint32_t a = 0; a < width; ++a)
      for (uint32_t b = 0; b < width; ++b) {
        const float m = matrix[(base + a) * n2 + base + b];
        block[a * width + b] = m;
        columns[b * width + a] = m;
        padded[b * pad + a] = m;
        padded_back[a * pad + b] = m;
      }
    block += width * width;
    columns += width * width;
    padded += width * pad;
    padded_back += width * pad;
  }
}

static void transpose3(const float m[9], float out[9]) {
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out[3 * a + b] = m[3 * b + a];
}

static void multiply3(const float a[9], const float b[9], float out[9]) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out[3 * r + c] = a[3 * r] * b[c] + a[3 * r + 1] * b[3 + c] + a[3 * r + 2] * b[6 + c];
}

static void apply3(const float m[9], const float v[3], float out[3]) {
  for (int r = 0; r < 3; ++r) out[r] = m[3 * r] * v[0] + m[3 * r + 1] * v[1] + m[3 * r + 2] * v[2];
}

/* The world centre and radius of a grid's bounding sphere on an instance. */
static void world_sphere(const prt_sf_instance* instance, const prt_sf_shells* grid,
                         float centre[3], float* radius) {
  apply3(instance->rotation, grid->centre, centre);
  for (int c = 0; c < 3; ++c) centre[c] = instance->scale * centre[c] + instance->translation[c];
  *radius = instance->scale * grid->radius;
}

/* Step 1: does j's field reach receiver i's bounding sphere? */
static int reaches(const prt_sf_instance* receiver, const prt_sf_object* receiver_object,
                   const prt_sf_instance* other, const prt_sf_shells* other_grid) {
  float ci[3], cj[3], ri, rj;
  world_sphere(receiver, &receiver_object->oof_shells, ci, &ri);
  world_sphere(other, other_grid, cj, &rj);
  const float d[3] = {ci[0] - cj[0], ci[1] - cj[1], ci[2] - cj[2]};
  const float reach = rj * other_grid->outer + ri;
  return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < reach * reach;
}

static void fill_pair(const prt_shadowfield_scene* scene, uint32_t i, uint32_t j, uint32_t occludes,
                      uint32_t lights, prt_sf_pair* pair) {
  const prt_sf_instance* receiver = &scene->instances[i];
  const prt_sf_instance* other = &scene->instances[j];
  float other_t[9], rotation[9], receiver_t[9];
  const prt_sf_object* other_object = scene->objects[other->object];
  pair->other = j;
  pair->occludes = occludes;
  pair->lights = lights;
  pair->oof_log_span = prt_sf_log_span(&other_object->oof_shells);
  pair->srf_log_span = lights ? prt_sf_log_span(&other_object->srf_shells) : 0.0;
  pair->fields_share_sphere =
      occludes && lights &&
      prt_sf_shells_share_sphere(&other_object->oof_shells, &other_object->srf_shells);
  /* p = R_j^T (s_i R_i x + t_i - t_j) / s_j */
  transpose3(other->rotation, other_t);
  multiply3(other_t, receiver->rotation, rotation);
  const float ratio = receiver->scale / other->scale;
  for (int e = 0; e < 9; ++e) pair->to_other[e] = ratio * rotation[e];
  const float shift[3] = {receiver->translation[0] - other->translation[0],
                          receiver->translation[1] - other->translation[1],
                          receiver->translation[2] - other->translation[2]};
  apply3(other_t, shift, pair->offset);
  for (int c = 0; c < 3; ++c) pair->offset[c] /= other->scale;
  /* A field in j's frame seen in i's: rotation R_i^T R_j. */
  transpose3(receiver->rotation, receiver_t);
  multiply3(receiver_t, other->rotation, rotation);
  rotation_blocks(scene->order, rotation, pair->sh_rotation, pair->sh_rotation_columns,
                  pair->padded_columns, pair->padded_columns_back);
}

/* Visits every interacting pair in receiver order; with `pairs` NULL only counts them. */
static uint32_t find_pairs(prt_shadowfield_scene* scene, prt_sf_pair* pairs) {
  uint32_t count = 0;
  for (uint32_t i = 0; i < scene->instance_count; ++i) {
    prt_sf_instance* receiver = &scene->instances[i];
    const prt_sf_object* receiver_object = scene->objects[receiver->object];
    if (pairs) receiver->pair_first = count;
    for (uint32_t j = 0; j < scene->instance_count; ++j) {
      if (j == i) continue;
      const prt_sf_instance* other = &scene->instances[j];
      const prt_sf_object* other_object = scene->objects[other->object];
      const uint32_t occludes =
          (uint32_t)reaches(receiver, receiver_object, other, &other_object->oof_shells);
      const uint32_t lights = other_object->basis_size > 0u &&
                              reaches(receiver, receiver_object, other, &other_object->srf_shells);
      if (!occludes && !lights) continue;
      if (pairs) {
        fill_pair(scene, i, j, occludes, lights, &pairs[count]);
        if (lights) scene->instances[j].is_source = 1u;
      }
      ++count;
    }
    if (pairs) receiver->pair_count = count - receiver->pair_first;
  }
  return count;
}

static prt_result reserve_pairs(prt_shadowfield_scene* scene, uint32_t count) {
  if (count <= scene->pair_capacity) return PRT_OK;
  prt_sf_pair* pairs =
      (prt_sf_pair*)prt_internal_alloc(&scene->allocator, (size_t)count * sizeof(prt_sf_pair), 16);
  if (!pairs) return PRT_ERROR_OUT_OF_MEMORY;
  if (scene->pairs)
    prt_internal_free(&scene->allocator, scene->pairs, scene->pair_capacity * sizeof(prt_sf_pair));
  scene->pairs = pairs;
  scene->pair_capacity = count;
  return PRT_OK;
}

/* light x V = M . V for every V: M[(c n^2 + k) n^2 + j] = sum_i C_ijk light_i,c. A dense
 * matrix-vector product per blocked vertex costs less than the sparse triple product. */
static void light_product(const prt_sf_gaunt* gaunt, const float* light, float* matrix) {
  const uint32_t n2 = gaunt->order * gaunt->order;
  memset(matrix, 0, (size_t)3u * n2 * n2 * sizeof(float));
  for (uint32_t k = 0; k < n2; ++k)
    for (uint32_t e = gaunt->k_start[k]; e < gaunt->k_start[k + 1u]; ++e)
      for (uint32_t c = 0; c < 3u; ++c)
        matrix[((size_t)c * n2 + k) * n2 + gaunt->j[e]] +=
            gaunt->value[e] * light[3u * gaunt->i[e] + c];
}

/* Room for every receiver vertex's row of cells (prepare's pairs) and, for a receiver of fewer
 * terms than colours, of turned transfers; each receiver's start in both. */
static prt_result reserve_cells(prt_shadowfield_scene* scene) {
  size_t count = 0, floats = 0;
  const uint32_t n2 = scene->order * scene->order;
  for (uint32_t i = 0; i < scene->instance_count; ++i) {
    prt_sf_instance* instance = &scene->instances[i];
    const prt_sf_object* object = scene->objects[instance->object];
    const size_t row_count = (size_t)object->vertex_count * instance->pair_count;
    instance->cell_first = count;
    instance->turned_first = floats;
    count += row_count;
    if (object->terms < 3u) floats += row_count * object->terms * n2;
  }
  if (count > scene->cell_capacity) {
    prt_sf_cell* cells =
        (prt_sf_cell*)prt_internal_alloc(&scene->allocator, count * sizeof(prt_sf_cell), 16);
    if (!cells) return PRT_ERROR_OUT_OF_MEMORY;
    if (scene->cells)
      prt_internal_free(&scene->allocator, scene->cells,
                        scene->cell_capacity * sizeof(prt_sf_cell));
    scene->cells = cells;
    scene->cell_capacity = count;
  }
  if (floats > scene->turned_capacity) {
    float* turned = (float*)prt_internal_alloc(&scene->allocator, floats * sizeof(float), 16);
    if (!turned) return PRT_ERROR_OUT_OF_MEMORY;
    if (scene->turned)
      prt_internal_free(&scene->allocator, scene->turned, scene->turned_capacity * sizeof(float));
    scene->turned = turned;
    scene->turned_capacity = floats;
  }
  return PRT_OK;
}

/* A new stamp for the frame, so no cell located before it is read; after 2^32 - 1 frames the
 * stamps start again from cleared ones. */
static void next_frame(prt_shadowfield_scene* scene) {
  if (++scene->frame != 0u) return;
  for (uint32_t i = 0; i < scene->instance_count; ++i) {
    const prt_sf_instance* instance = &scene->instances[i];
    memset(instance->located, 0, scene->objects[instance->object]->vertex_count * sizeof(uint32_t));
    if (instance->probe_located)
      memset(instance->probe_located, 0, instance->probe_located_capacity * sizeof(uint32_t));
  }
  scene->frame = 1u;
}

static int all_finite(const float* values, size_t count) {
  for (size_t e = 0; e < count; ++e)
    if (!isfinite(values[e])) return 0;
  return 1;
}

/* The SIMD kernels when the context may use AVX2 + FMA, else NULL. */
static const prt_sf_kernels* simd_kernels(const prt_context* context) {
#if defined(PRT_HAS_X86_SIMD)
  const prt_simd_isa isa = prt_internal_simd_isa(context);
  if (isa == PRT_SIMD_ISA_AVX2 || isa == PRT_SIMD_ISA_AVX512) return &prt_sf_kernels_avx2;
#else
  (void)context;
#endif
  return NULL;
}

/* The settings' bounce count, probe spacing and backend's kernels (AUTO: SIMD when usable), or
 * a failure. */
static prt_result read_settings(prt_context* context, const prt_shadowfield_settings* settings,
                                uint32_t* bounces, float* probe_spacing,
                                const prt_sf_kernels** kernels) {
  const prt_sf_kernels* simd = simd_kernels(context);
  *bounces = PRT_SHADOWFIELD_DEFAULT_BOUNCES;
  *probe_spacing = 0.0f;
  *kernels = simd ? simd : &prt_sf_kernels_scalar;
  if (!settings) return PRT_OK;
  if (!prt_internal_struct_size_ok(settings, PRT_SF_SETTINGS_1_0_SIZE))
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "shadowfield settings: struct_size below 1.0's");
  if (prt_internal_struct_size_ok(settings, PRT_SF_SETTINGS_PROBES_SIZE)) {
    *probe_spacing = settings->bounce_probe_spacing;
    if (!(*probe_spacing >= 0.0f) || !isfinite(*probe_spacing))
      return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                               "shadowfield settings: bounce_probe_spacing %g (0, or finite > 0)",
                               (double)*probe_spacing);
  }
  if (settings->bounces > PRT_SHADOWFIELD_MAX_BOUNCES)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "shadowfield settings: %u bounces (at most %u)", settings->bounces,
                             PRT_SHADOWFIELD_MAX_BOUNCES);
  switch (settings->backend) {
    case PRT_BACKEND_AUTO:
      break;
    case PRT_BACKEND_CPU:
      *kernels = &prt_sf_kernels_scalar;
      break;
    case PRT_BACKEND_SIMD:
      if (!simd)
        return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                                 "shadowfield: the SIMD backend needs AVX2 and FMA");
      break;
    case PRT_BACKEND_GL:
      return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                               "shadowfield: GL shades through prt_gl_shadowfield_shade");
    default:
      return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                               "shadowfield settings: backend %d", (int)settings->backend);
  }
  *bounces = settings->bounces;
  return PRT_OK;
}

prt_result prt_shadowfield_prepare(prt_shadowfield_scene* scene, const float* light_sh_rgb,
                                   const float eye[3], const prt_shadowfield_settings* settings) {
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  prt_context* context = scene->context;
  scene->prepared = 0u;
  if (!light_sh_rgb || !eye)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT, "shadowfield: NULL light or eye");
  uint32_t bounces;
  float probe_spacing;
  const prt_sf_kernels* kernels;
  const prt_result read = read_settings(context, settings, &bounces, &probe_spacing, &kernels);
  if (read != PRT_OK) return read;
  const uint32_t n2 = scene->order * scene->order;
  if (!all_finite(light_sh_rgb, (size_t)n2 * 3u) || !all_finite(eye, 3u))
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "shadowfield: a light or eye that is not finite");
  for (uint32_t i = 0; i < scene->instance_count; ++i) {
    prt_sf_instance* instance = &scene->instances[i];
    float to_local[9];
    transpose3(instance->rotation, to_local);
    prt_sh_rotate(scene->order, to_local, light_sh_rgb, instance->light, 3u);
    light_product(&scene->gaunt, instance->light, instance->light_product);
    instance->is_source = 0u;
    instance->pair_first = instance->pair_count = 0u; /* find_pairs sets them only when it fills */
  }
  if (reserve_pairs(scene, find_pairs(scene, NULL)) != PRT_OK)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "shadowfield pairs");
  scene->pair_count = find_pairs(scene, scene->pairs);
  if (reserve_cells(scene) != PRT_OK)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "shadowfield cells");
  const prt_result probes = prt_sf_prepare_probes(scene, probe_spacing, bounces);
  if (probes != PRT_OK) return probes;
  next_frame(scene);
  memcpy(scene->eye, eye, sizeof scene->eye);
  scene->bounces = bounces;
  scene->kernels = kernels;
  scene->prepared = 1u;
  return PRT_OK;
}

prt_result prt_shadowfield_shade(prt_shadowfield_scene* scene, const float* light_sh_rgb,
                                 const float eye[3], const prt_shadowfield_settings* settings,
                                 float* const* out_rgb) {
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (!out_rgb)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_shadowfield_shade: NULL out_rgb");
  const prt_result prepared = prt_shadowfield_prepare(scene, light_sh_rgb, eye, settings);
  if (prepared != PRT_OK) return prepared;
  for (uint32_t pass = 0; pass <= scene->bounces; ++pass) {
    for (uint32_t i = 0; i < scene->instance_count; ++i)
      prt_sf_gather_probes_range(scene, pass, i, 0u, scene->instances[i].probe_count);
    for (uint32_t i = 0; i < scene->instance_count; ++i)
      prt_sf_gather_range(scene, pass, i, 0u, prt_shadowfield_instance_vertex_count(scene, i));
    if (pass < scene->bounces)
      for (uint32_t i = 0; i < scene->instance_count; ++i) prt_sf_project_instance(scene, pass, i);
  }
  for (uint32_t i = 0; i < scene->instance_count; ++i)
    if (out_rgb[i])
      prt_sf_output_range(scene, i, scene->bounces, 0u,
                          prt_shadowfield_instance_vertex_count(scene, i), out_rgb[i]);
  return PRT_OK;
}
