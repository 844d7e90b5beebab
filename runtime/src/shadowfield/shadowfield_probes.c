/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield`'s bounce probes (docs/shadowfield/design.md, "Bounce probes"): a
 * bounce's light gathered at the corners of a grid over each object, in its own frame, and
 * taken by each vertex trilinearly from the corners of its cell before its own transfer dots
 * it. The light arriving at a point does not depend on the surface there, so far fewer points
 * read the sources' fields than there are vertices. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../internal.h"
#include "shadowfield_scene.h"

/* ---- Layout --------------------------------------------------------------------------------- */

/* One corner of a vertex's cell: its index in the grid's corners (UINT64_MAX when the vertex
 * weighs it 0) and the vertex's slot for it, 8 v + j. */
typedef struct sf_corner_ref {
  uint64_t key;
  uint32_t slot;
} sf_corner_ref;

static int compare_refs(const void* a, const void* b) {
  const sf_corner_ref* x = (const sf_corner_ref*)a;
  const sf_corner_ref* y = (const sf_corner_ref*)b;
  if (x->key != y->key) return x->key < y->key ? -1 : 1;
  return (x->slot > y->slot) - (x->slot < y->slot);
}

/* Reads no object: a scene may be destroyed after its assets. */
static void free_layout(const prt_allocator* allocator, prt_sf_probes* probes) {
  if (probes->positions)
    prt_internal_free(allocator, probes->positions, (size_t)probes->count * 3u * sizeof(float));
  if (probes->lookups)
    prt_internal_free(allocator, probes->lookups,
                      (size_t)probes->lookup_count * sizeof(prt_sf_lookup));
  memset(probes, 0, sizeof *probes);
}

/* The grid's origin (the vertices' lower corner), its cells per axis and its corners in all;
 * 0 corners when they would not fit in 2^53 (a spacing far finer than the object). */
static double grid_of(const prt_sf_object* object, double spacing, double origin[3],
                      uint64_t cells[3]) {
  double high[3];
  for (int a = 0; a < 3; ++a) origin[a] = high[a] = object->positions[a];
  for (uint32_t v = 1; v < object->vertex_count; ++v)
    for (int a = 0; a < 3; ++a) {
      const double x = object->positions[3u * v + a];
      if (x < origin[a]) origin[a] = x;
      if (x > high[a]) high[a] = x;
    }
  double corners = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double along = floor((high[a] - origin[a]) / spacing) + 1.0;
    if (!(along < 9.0e15)) return 0.0;
    cells[a] = (uint64_t)along;
    corners *= along + 1.0;
  }
  return corners < 9.0e15 ? corners : 0.0;
}

/* Each vertex's 8 corners and trilinear weights into refs and lookups (indices still to be
 * given). */
static void weigh_corners(const prt_sf_object* object, double spacing, const double origin[3],
                          const uint64_t cells[3], sf_corner_ref* refs, prt_sf_lookup* lookups) {
  for (uint32_t v = 0; v < object->vertex_count; ++v) {
    uint64_t cell[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
      const double at = (object->positions[3u * v + a] - origin[a]) / spacing;
      const double whole = floor(at);
      cell[a] = whole < (double)cells[a] ? (uint64_t)whole : cells[a] - 1u;
      f[a] = at - (double)cell[a];
      if (f[a] > 1.0) f[a] = 1.0;
    }
    prt_sf_lookup* lookup = &lookups[v];
    memset(lookup, 0, sizeof *lookup);
    for (uint32_t j = 0; j < 8u; ++j) {
      double weight = 1.0;
      uint64_t key = 0u;
      for (int a = 2; a >= 0; --a) {
        const uint32_t up = j >> a & 1u;
        weight *= up ? f[a] : 1.0 - f[a];
        key = key * (cells[a] + 1u) + cell[a] + up;
      }
      lookup->weight[j] = (float)weight;
      refs[8u * v + j].key = lookup->weight[j] > 0.0f ? key : UINT64_MAX;
      refs[8u * v + j].slot = 8u * v + j;
    }
  }
}

/* Numbers the distinct corners in refs (sorted) into the lookups' indices; their count. */
static uint32_t number_corners(const sf_corner_ref* refs, size_t ref_count,
                               prt_sf_lookup* lookups) {
  uint32_t count = 0u;
  for (size_t e = 0; e < ref_count && refs[e].key != UINT64_MAX; ++e) {
    if (e > 0u && refs[e].key != refs[e - 1u].key) ++count;
    lookups[refs[e].slot / 8u].index[refs[e].slot % 8u] = count;
  }
  return ref_count > 0u && refs[0].key != UINT64_MAX ? count + 1u : 0u;
}

/* The corner of grid index `key`. */
static void corner_position(uint64_t key, const double origin[3], const uint64_t cells[3],
                            double spacing, float* out) {
  for (int a = 0; a < 3; ++a) {
    out[a] = (float)(origin[a] + spacing * (double)(key % (cells[a] + 1u)));
    key /= cells[a] + 1u;
  }
}

/* Drops each lookup's corners of weight 0, keeping the others in order. */
static void compact_lookups(prt_sf_lookup* lookups, uint32_t vertex_count) {
  for (uint32_t v = 0; v < vertex_count; ++v) {
    prt_sf_lookup* lookup = &lookups[v];
    uint32_t kept = 0u;
    for (uint32_t j = 0; j < 8u; ++j) {
      if (!(lookup->weight[j] > 0.0f)) continue;
      lookup->index[kept] = lookup->index[j];
      lookup->weight[kept++] = lookup->weight[j];
    }
    lookup->count = kept;
  }
}

/* The object's probes at `spacing` > 0; count 0 (per vertex) when the grid has as many corners
 * with weight as the object has vertices. */
static prt_result lay_out(const prt_allocator* allocator, const prt_sf_object* object,
                          float spacing, prt_sf_probes* probes) {
  const uint32_t vertices = object->vertex_count;
  double origin[3];
  uint64_t cells[3];
  memset(probes, 0, sizeof *probes);
  probes->spacing = spacing;
  if (grid_of(object, spacing, origin, cells) == 0.0) return PRT_OK;
  const size_t ref_count = (size_t)vertices * 8u;
  sf_corner_ref* refs =
      (sf_corner_ref*)prt_internal_alloc(allocator, ref_count * sizeof(sf_corner_ref), 16);
  prt_sf_lookup* lookups =
      (prt_sf_lookup*)prt_internal_alloc(allocator, (size_t)vertices * sizeof(prt_sf_lookup), 16);
  if (!refs || !lookups) {
    if (refs) prt_internal_free(allocator, refs, ref_count * sizeof(sf_corner_ref));
    if (lookups) prt_internal_free(allocator, lookups, (size_t)vertices * sizeof(prt_sf_lookup));
    return PRT_ERROR_OUT_OF_MEMORY;
  }
  weigh_corners(object, spacing, origin, cells, refs, lookups);
  qsort(refs, ref_count, sizeof *refs, compare_refs);
  const uint32_t count = number_corners(refs, ref_count, lookups);
  float* positions = count < vertices ? (float*)prt_internal_alloc(
                                            allocator, (size_t)count * 3u * sizeof(float), 16)
                                      : NULL;
  if (positions) {
    for (size_t e = 0; e < ref_count && refs[e].key != UINT64_MAX; ++e) {
      const prt_sf_lookup* lookup = &lookups[refs[e].slot / 8u];
      corner_position(refs[e].key, origin, cells, spacing,
                      positions + 3u * lookup->index[refs[e].slot % 8u]);
    }
    compact_lookups(lookups, vertices);
    probes->count = count;
    probes->positions = positions;
    probes->lookups = lookups;
    probes->lookup_count = vertices;
  }
  prt_internal_free(allocator, refs, ref_count * sizeof(sf_corner_ref));
  if (!positions) prt_internal_free(allocator, lookups, (size_t)vertices * sizeof(prt_sf_lookup));
  return positions || count >= vertices ? PRT_OK : PRT_ERROR_OUT_OF_MEMORY;
}

/* ---- The frame's buffers ------------------------------------------------------------------- */

static int lit_by_some_pair(const prt_shadowfield_scene* scene, const prt_sf_instance* receiver) {
  for (uint32_t q = 0; q < receiver->pair_count; ++q)
    if (scene->pairs[receiver->pair_first + q].lights) return 1;
  return 0;
}

/* Grows *data (capacity *capacity elements of `size` bytes) to hold `count`. */
static int reserve(const prt_allocator* allocator, void** data, size_t* capacity, size_t count,
                   size_t size) {
  if (count <= *capacity) return 1;
  void* grown = prt_internal_alloc(allocator, count * size, 16);
  if (!grown) return 0;
  if (*data) prt_internal_free(allocator, *data, *capacity * size);
  *data = grown;
  *capacity = count;
  return 1;
}

static prt_result lay_out_objects(prt_shadowfield_scene* scene, float spacing) {
  for (uint32_t o = 0; o < scene->object_count; ++o) {
    prt_sf_probes* probes = &scene->probes[o];
    if (probes->spacing == spacing) continue;
    free_layout(&scene->allocator, probes);
    if (spacing > 0.0f && lay_out(&scene->allocator, scene->objects[o], spacing, probes) != PRT_OK)
      return prt_internal_fail(scene->context, PRT_ERROR_OUT_OF_MEMORY, "shadowfield probes");
  }
  return PRT_OK;
}

prt_result prt_sf_prepare_probes(prt_shadowfield_scene* scene, float spacing, uint32_t bounces) {
  const prt_result laid = lay_out_objects(scene, spacing);
  if (laid != PRT_OK) return laid;
  const uint32_t n2 = scene->order * scene->order;
  size_t cells = 0;
  for (uint32_t i = 0; i < scene->instance_count; ++i) {
    prt_sf_instance* instance = &scene->instances[i];
    const prt_sf_probes* probes = &scene->probes[instance->object];
    instance->probe_count = bounces > 0u && lit_by_some_pair(scene, instance) ? probes->count : 0u;
    instance->probe_cell_first = cells;
    cells += (size_t)instance->probe_count * instance->pair_count;
    if (!reserve(&scene->allocator, (void**)&instance->probe_light, &instance->probe_light_capacity,
                 (size_t)instance->probe_count * n2 * 3u, sizeof(float)) ||
        !reserve(&scene->allocator, (void**)&instance->probe_located,
                 &instance->probe_located_capacity, instance->probe_count, sizeof(uint32_t)))
      return prt_internal_fail(scene->context, PRT_ERROR_OUT_OF_MEMORY, "shadowfield probes");
  }
  if (!reserve(&scene->allocator, (void**)&scene->probe_cells, &scene->probe_cell_capacity, cells,
               sizeof(prt_sf_cell)))
    return prt_internal_fail(scene->context, PRT_ERROR_OUT_OF_MEMORY, "shadowfield probe cells");
  return PRT_OK;
}

void prt_sf_free_probes(prt_shadowfield_scene* scene) {
  const prt_allocator* allocator = &scene->allocator;
  for (uint32_t i = 0; i < scene->instance_count; ++i) {
    prt_sf_instance* instance = &scene->instances[i];
    if (instance->probe_light)
      prt_internal_free(allocator, instance->probe_light,
                        instance->probe_light_capacity * sizeof(float));
    if (instance->probe_located)
      prt_internal_free(allocator, instance->probe_located,
                        instance->probe_located_capacity * sizeof(uint32_t));
  }
  if (scene->probes)
    for (uint32_t o = 0; o < scene->object_count; ++o) free_layout(allocator, &scene->probes[o]);
  if (scene->probe_cells)
    prt_internal_free(allocator, scene->probe_cells,
                      scene->probe_cell_capacity * sizeof(prt_sf_cell));
}

/* ---- Gathering ------------------------------------------------------------------------------ */

static prt_sf_cell* probe_cell_row(const prt_shadowfield_scene* scene,
                                   const prt_sf_instance* receiver, uint32_t p) {
  return scene->probe_cells + receiver->probe_cell_first + (size_t)p * receiver->pair_count;
}

/* Probe p's row of cells in its sources' SRF grids. */
static void locate_probe(const prt_shadowfield_scene* scene, const prt_sf_instance* receiver,
                         const float* position, prt_sf_cell* row) {
  for (uint32_t q = 0; q < receiver->pair_count; ++q) {
    const prt_sf_pair* pair = &scene->pairs[receiver->pair_first + q];
    if (!pair->lights) continue;
    const prt_sf_object* source = scene->objects[scene->instances[pair->other].object];
    float p[3];
    prt_sf_point_in_other(pair, position, p);
    prt_sf_cell_locate(&source->srf_shells, pair->srf_log_span, p, &row[q]);
  }
}

/* Probe p's light from every source's field of the previous pass, in the receiver's frame
 * (3 planes of n^2), each field turned by its pair's rotation. */
static void probe_light(const prt_shadowfield_scene* scene, const prt_sf_instance* receiver,
                        const prt_sf_cell* row, float* light) {
  const prt_sf_kernels* kernels = scene->kernels;
  const uint32_t order = scene->order, n2 = order * order;
  float local[PRT_SF_MAX_COEFFS * 3u], turned[PRT_SF_MAX_COEFFS * 3u];
  memset(light, 0, (size_t)n2 * 3u * sizeof(float));
  for (uint32_t q = 0; q < receiver->pair_count; ++q) {
    const prt_sf_pair* pair = &scene->pairs[receiver->pair_first + q];
    if (!pair->lights || row[q].count == 0u) continue;
    const prt_sf_instance* source = &scene->instances[pair->other];
    const prt_sf_shells* grid = &scene->objects[source->object]->srf_shells;
    prt_sf_lookup lookup;
    prt_sf_cell_lookup(grid, &row[q], &lookup);
    kernels->read_rows(source->field, prt_sf_point_count(grid) * n2, 3u, n2, &lookup, local);
    kernels->rotate(pair, order, local, turned, 3u);
    for (uint32_t e = 0; e < 3u * n2; ++e) light[e] += turned[e];
  }
}

void prt_sf_gather_probes_range(const prt_shadowfield_scene* scene, uint32_t pass,
                                uint32_t instance, uint32_t first, uint32_t count) {
  const prt_sf_instance* receiver = &scene->instances[instance];
  const prt_sf_probes* probes = &scene->probes[receiver->object];
  const uint32_t n2 = scene->order * scene->order;
  const size_t plane = (size_t)receiver->probe_count * n2;
  float light[PRT_SF_MAX_COEFFS * 3u];
  for (uint32_t p = first; p < first + count; ++p) {
    prt_sf_cell* row = probe_cell_row(scene, receiver, p);
    if (pass == 0u) {
      locate_probe(scene, receiver, probes->positions + 3u * p, row);
      receiver->probe_located[p] = scene->frame;
      continue;
    }
    /* Without pass 0's probe stage this frame, locate now (the projections then cast every
     * point). */
    if (receiver->probe_located[p] != scene->frame)
      locate_probe(scene, receiver, probes->positions + 3u * p, row);
    probe_light(scene, receiver, row, light);
    for (uint32_t c = 0; c < 3u; ++c)
      memcpy(receiver->probe_light + c * plane + (size_t)p * n2, light + c * n2,
             n2 * sizeof(float));
  }
}

void prt_sf_probed_light(const prt_shadowfield_scene* scene, const prt_sf_instance* receiver,
                         uint32_t v, const float* transfer, uint32_t terms, float* out) {
  const prt_sf_kernels* kernels = scene->kernels;
  const uint32_t n2 = scene->order * scene->order;
  const prt_sf_lookup* lookup = &scene->probes[receiver->object].lookups[v];
  const uint64_t plane = (uint64_t)receiver->probe_count * n2;
  if (terms < 3u) {
    /* As a source's field with a turned transfer: the same kernels, on a small field. */
    float partial[3u * 2u * PRT_SF_LANES];
    memset(partial, 0, sizeof partial);
    kernels->read_dot(receiver->probe_light, plane, n2, lookup, transfer, terms, partial);
    kernels->reduce_lanes(partial, 3u * terms, out);
    return;
  }
  float light[PRT_SF_MAX_COEFFS * 3u];
  kernels->read_rows(receiver->probe_light, plane, 3u, n2, lookup, light);
  kernels->transfer_dot(transfer, n2, terms, light, out);
}

/* ---- The stage's entry points --------------------------------------------------------------- */

uint32_t prt_shadowfield_instance_probe_count(const prt_shadowfield_scene* scene,
                                              uint32_t instance) {
  if (!scene || !scene->prepared || instance >= scene->instance_count) return 0u;
  return scene->instances[instance].probe_count;
}

prt_result prt_shadowfield_gather_probes(prt_shadowfield_scene* scene, uint32_t pass,
                                         uint32_t instance, uint32_t first_probe,
                                         uint32_t probe_count) {
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (!scene->prepared) return PRT_ERROR_INVALID_OPERATION;
  if (pass > scene->bounces || instance >= scene->instance_count) return PRT_ERROR_INVALID_ARGUMENT;
  const uint32_t size = scene->instances[instance].probe_count;
  if (first_probe > size || probe_count > size - first_probe) return PRT_ERROR_INVALID_ARGUMENT;
  prt_sf_gather_probes_range(scene, pass, instance, first_probe, probe_count);
  return PRT_OK;
}
