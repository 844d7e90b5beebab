/* SPDX-License-Identifier: MIT */
/* Technique `shadowfield`'s evaluation on the CPU, scalar (docs/shadowfield/design.md, "At run
 * time", steps 2 to 4): gather a pass's incident light per receiver vertex, project a source's
 * radiance onto its basis and cast its field, and the outgoing radiance towards the eye. */
#include <math.h>
#include <string.h>

#include "../internal.h"
#include "shadowfield_scene.h"

#define SF_PI 3.14159265358979323846

/* ---- Reading fields ------------------------------------------------------------------------- */

/* `planes` planes of a field (points x width floats each) read at a located cell of its grid
 * (cell->count > 0). */
static void read_cell(const prt_sf_kernels* kernels, const prt_sf_shells* grid, const float* field,
                      uint32_t width, uint32_t planes, const prt_sf_cell* cell, float* out) {
  prt_sf_lookup lookup;
  prt_sf_cell_lookup(grid, cell, &lookup);
  kernels->read_rows(field, prt_sf_point_count(grid) * width, planes, width, &lookup, out);
}

void prt_sf_point_in_other(const prt_sf_pair* pair, const float x[3], float p[3]) {
  for (int r = 0; r < 3; ++r)
    p[r] = pair->to_other[3 * r] * x[0] + pair->to_other[3 * r + 1] * x[1] +
           pair->to_other[3 * r + 2] * x[2] + pair->offset[r];
}

/* Vertex v's row of cells: one per pair of its receiver. */
static prt_sf_cell* cell_row(const prt_shadowfield_scene* scene, const prt_sf_instance* receiver,
                             uint32_t v) {
  return scene->cells + receiver->cell_first + (size_t)v * receiver->pair_count;
}

/* Vertex v's transfer turned into the source of its pair q (receivers of fewer terms than
 * colours only). */
static float* turned_transfer(const prt_shadowfield_scene* scene, const prt_sf_instance* receiver,
                              uint32_t v, uint32_t q, uint32_t terms) {
  const uint32_t n2 = scene->order * scene->order;
  return scene->turned + receiver->turned_first +
         ((size_t)v * receiver->pair_count + q) * terms * n2;
}

/* ---- Gather --------------------------------------------------------------------------------- */

/* a += b in the lanes of `mask` (lane-interleaved, n2 coefficients). */
static void add_lanes(uint32_t n2, float* a, const float* b, uint32_t mask) {
  for (uint32_t k = 0; k < n2; ++k)
    for (uint32_t lane = 0; lane < PRT_SF_LANES; ++lane)
      if (mask >> lane & 1u) a[k * PRT_SF_LANES + lane] += b[k * PRT_SF_LANES + lane];
}

/* Step 2 for vertices [first, first + count) (count <= PRT_SF_LANES), one lane each: the
 * environment times every blocker's visibility, in the receiver's frame, into
 * light[lane][c n^2 + k] (one plane of coefficients per colour). Each lane's visibilities are
 * multiplied in the pairs' order, as vertex by vertex, or with the log-space product their logs
 * summed and exponentiated once; each blocker's reads are turned for all lanes by one rotation.
 * With `locate_sources`, also locates each vertex in every source's SRF grid into its row of cells,
 * which the bounces read, and for a receiver of fewer terms than colours turns its transfer into
 * each source's frame that reaches it. */
static void shadowed_light(const prt_shadowfield_scene* scene, const prt_sf_instance* receiver,
                           uint32_t first, uint32_t count, int locate_sources,
                           float light[][PRT_SF_MAX_COEFFS * 3u]) {
  const prt_sf_kernels* kernels = scene->kernels;
  const prt_sf_object* object = scene->objects[receiver->object];
  const uint32_t order = scene->order, n2 = order * order, terms = object->terms;
  const int turn_transfer = locate_sources && terms < 3u;
  const int log_product = scene->product == PRT_SHADOWFIELD_PRODUCT_LOG;
  float visibility[PRT_SF_MAX_COEFFS * PRT_SF_LANES], next[PRT_SF_MAX_COEFFS * PRT_SF_LANES];
  float unturned[PRT_SF_MAX_COEFFS * PRT_SF_LANES], local[PRT_SF_MAX_COEFFS];
  /* The SIMD product and rotation compute every lane: the idle ones hold zeros, not garbage. */
  memset(visibility, 0, (size_t)n2 * PRT_SF_LANES * sizeof(float));
  memset(next, 0, (size_t)n2 * PRT_SF_LANES * sizeof(float));
  memset(unturned, 0, (size_t)n2 * PRT_SF_LANES * sizeof(float));
  uint32_t blocked = 0u; /* lanes with a visibility so far */
  for (uint32_t q = 0; q < receiver->pair_count; ++q) {
    const prt_sf_pair* pair = &scene->pairs[receiver->pair_first + q];
    const uint32_t other_object = scene->instances[pair->other].object;
    const prt_sf_object* other = scene->objects[other_object];
    const float* oof = log_product ? scene->log_fields[other_object].values : other->oof;
    uint32_t multiply = 0u;      /* lanes whose visibility this blocker multiplies */
    uint32_t first_blocked = 0u; /* lanes this blocker is the first to shadow */
    for (uint32_t lane = 0; lane < count; ++lane) {
      const uint32_t v = first + lane;
      float p[3];
      prt_sf_point_in_other(pair, object->positions + 3u * v, p);
      prt_sf_cell cell;
      prt_sf_cell* source_cell = locate_sources ? &cell_row(scene, receiver, v)[q] : NULL;
      if (source_cell && pair->fields_share_sphere) {
        prt_sf_cell_locate_two(&other->oof_shells, pair->oof_log_span, &other->srf_shells,
                               pair->srf_log_span, p, &cell, source_cell);
      } else if (source_cell && pair->lights) {
        prt_sf_cell_locate(&other->srf_shells, pair->srf_log_span, p, source_cell);
      }
      if (turn_transfer && pair->lights && source_cell->count > 0u)
        kernels->rotate_back(pair, order, object->transfer + (size_t)v * terms * n2,
                             turned_transfer(scene, receiver, v, q, terms), terms);
      if (!pair->occludes) continue;
      if (!(source_cell && pair->fields_share_sphere))
        prt_sf_cell_locate(&other->oof_shells, pair->oof_log_span, p, &cell);
      if (cell.count == 0u) continue;
      read_cell(kernels, &other->oof_shells, oof, n2, 1u, &cell, local);
      for (uint32_t k = 0; k < n2; ++k) unturned[k * PRT_SF_LANES + lane] = local[k];
      if (blocked >> lane & 1u)
        multiply |= 1u << lane;
      else
        first_blocked |= 1u << lane;
    }
    /* A lane's first blocker is its visibility, a later one multiplies it. */
    if (first_blocked) kernels->rotate_lanes(pair, order, unturned, visibility, first_blocked);
    if (multiply) {
      kernels->rotate_lanes(pair, order, unturned, next, multiply);
      if (log_product)
        add_lanes(n2, visibility, next, multiply);
      else
        kernels->multiply_lanes(&scene->gaunt, visibility, next, multiply);
    }
    blocked |= first_blocked;
  }
  if (log_product && blocked) kernels->exp_lanes(&scene->exp_rule, visibility, blocked);
  for (uint32_t lane = 0; lane < count; ++lane) {
    if (!(blocked >> lane & 1u)) {
      for (uint32_t c = 0; c < 3u; ++c)
        for (uint32_t k = 0; k < n2; ++k) light[lane][c * n2 + k] = receiver->light[3u * k + c];
      continue;
    }
    for (uint32_t k = 0; k < n2; ++k) local[k] = visibility[k * PRT_SF_LANES + lane];
    kernels->light_times(receiver->light_product, n2, local, light[lane]);
  }
}

/* Step 3: L_k(v) from every source's field of the previous pass; 0 when no source reaches
 * vertex v (at x). The sources' cells come from v's direct pass when it ran this frame.
 * T_k . R f = R^T T_k . f: a receiver of fewer terms than colours dots each source's field with
 * its transfer turned into the source's frame (by its direct pass, or here when that did not
 * run), others turn each source's field (3 rotations a pass) and dot the sum once. */
static void bounced_light(const prt_shadowfield_scene* scene, const prt_sf_instance* receiver,
                          uint32_t v, const float x[3], const float* transfer, uint32_t terms,
                          float* out) {
  const prt_sf_kernels* kernels = scene->kernels;
  const uint32_t order = scene->order, n2 = order * order;
  /* Without pairs the frame has no cells for this receiver (the buffer may be NULL). */
  const prt_sf_cell* row = receiver->pair_count > 0u && receiver->located[v] == scene->frame
                               ? cell_row(scene, receiver, v)
                               : NULL;
  const int turn_transfer = terms < 3u;
  float light[PRT_SF_MAX_COEFFS * 3u], local[PRT_SF_MAX_COEFFS * 3u],
      turned[PRT_SF_MAX_COEFFS * 3u], partial[3u * 2u * PRT_SF_LANES];
  int lit = 0;
  if (turn_transfer)
    memset(partial, 0, sizeof partial);
  else
    memset(light, 0, (size_t)n2 * 3u * sizeof(float));
  for (uint32_t q = 0; q < receiver->pair_count; ++q) {
    const prt_sf_pair* pair = &scene->pairs[receiver->pair_first + q];
    if (!pair->lights) continue;
    const prt_sf_instance* source = &scene->instances[pair->other];
    const prt_sf_object* object = scene->objects[source->object];
    prt_sf_cell cell;
    if (row) {
      cell = row[q];
    } else {
      float p[3];
      prt_sf_point_in_other(pair, x, p);
      prt_sf_cell_locate(&object->srf_shells, pair->srf_log_span, p, &cell);
    }
    if (cell.count == 0u) continue;
    prt_sf_lookup lookup;
    prt_sf_cell_lookup(&object->srf_shells, &cell, &lookup);
    const uint64_t plane = prt_sf_point_count(&object->srf_shells) * n2;
    if (turn_transfer) {
      const float* turned_back = turned;
      if (row)
        turned_back = turned_transfer(scene, receiver, v, q, terms);
      else
        kernels->rotate_back(pair, order, transfer, turned, terms);
      kernels->read_dot(source->field, plane, n2, &lookup, turned_back, terms, partial);
    } else {
      kernels->read_rows(source->field, plane, 3u, n2, &lookup, local);
      kernels->rotate(pair, order, local, turned, 3u);
      for (uint32_t e = 0; e < 3u * n2; ++e) light[e] += turned[e];
    }
    lit = 1;
  }
  if (turn_transfer) {
    kernels->reduce_lanes(partial, 3u * terms, out);
    return;
  }
  if (lit)
    kernels->transfer_dot(transfer, n2, terms, light, out);
  else
    memset(out, 0, (size_t)terms * 3u * sizeof(float));
}

void prt_sf_gather_range(const prt_shadowfield_scene* scene, uint32_t pass, uint32_t instance,
                         uint32_t first_vertex, uint32_t vertex_count) {
  const prt_sf_instance* receiver = &scene->instances[instance];
  const prt_sf_object* object = scene->objects[receiver->object];
  const uint32_t n2 = scene->order * scene->order, terms = object->terms;
  float* incident = receiver->incident + (size_t)pass * object->vertex_count * terms * 3u;
  const uint32_t end = first_vertex + vertex_count;
  if (pass > 0u && receiver->probe_count > 0u) {
    for (uint32_t v = first_vertex; v < end; ++v)
      prt_sf_probed_light(scene, receiver, v, object->transfer + (size_t)v * terms * n2, terms,
                          incident + (size_t)v * terms * 3u);
    return;
  }
  if (pass > 0u) {
    for (uint32_t v = first_vertex; v < end; ++v)
      bounced_light(scene, receiver, v, object->positions + 3u * v,
                    object->transfer + (size_t)v * terms * n2, terms,
                    incident + (size_t)v * terms * 3u);
    return;
  }
  /* A receiver with probes reads the sources at its probes, not at its vertices. */
  const int locate_sources = scene->bounces > 0u && receiver->probe_count == 0u;
  float light[PRT_SF_LANES][PRT_SF_MAX_COEFFS * 3u];
  for (uint32_t first = first_vertex; first < end; first += PRT_SF_LANES) {
    const uint32_t count = end - first < PRT_SF_LANES ? end - first : PRT_SF_LANES;
    shadowed_light(scene, receiver, first, count, locate_sources, light);
    for (uint32_t lane = 0; lane < count; ++lane) {
      const uint32_t v = first + lane;
      if (locate_sources) receiver->located[v] = scene->frame;
      /* L_k(x) = T_k(x) . L */
      scene->kernels->transfer_dot(object->transfer + (size_t)v * terms * n2, n2, terms,
                                   light[lane], incident + (size_t)v * terms * 3u);
    }
  }
}

/* ---- Project -------------------------------------------------------------------------------- */

/* w_ikc = (A^-1 B W r_kc)_i with r_kc(v) = albedo_c(v) L_k,c(v) of `pass`. */
static void basis_weights(const prt_sf_object* object, const float* incident, float* weights,
                          float* projected) {
  const uint32_t basis = object->basis_size, terms = object->terms, width = terms * 3u;
  const uint32_t vertices = object->vertex_count;
  memset(projected, 0, (size_t)basis * width * sizeof(float));
  /* Vertex by vertex, so its radiance is formed once and every basis row adds it in a loop the
   * compiler vectorises; each row's sum still runs over the vertices in order. */
  float radiance[PRT_SF_MAX_TERMS * 3u];
  for (uint32_t v = 0; v < vertices; ++v) {
    const float* albedo = object->albedo + 3u * v;
    const float* l = incident + (size_t)v * width;
    for (uint32_t k = 0; k < terms; ++k)
      for (uint32_t c = 0; c < 3u; ++c) radiance[3u * k + c] = albedo[c] * l[3u * k + c];
    for (uint32_t m = 0; m < basis; ++m) {
      const float bw = object->basis[(size_t)m * vertices + v] * object->vertex_weights[v];
      float* restrict row = projected + (size_t)m * width;
      for (uint32_t e = 0; e < width; ++e) row[e] += bw * radiance[e];
    }
  }
  for (uint32_t i = 0; i < basis; ++i)
    for (uint32_t e = 0; e < width; ++e) {
      float sum = 0.0f;
      for (uint32_t m = 0; m < basis; ++m)
        sum += object->basis_inverse[(size_t)i * basis + m] * projected[(size_t)m * width + e];
      weights[(size_t)i * width + e] = sum;
    }
}

/* Marks the points of `grid` that rows [0, rows) of cells (row r's cell of the pair at
 * rows_at[r pair_count + q]) read; 0, marking nothing more, when a row has no cells this frame
 * (its stamp is not `frame`). */
static int mark_rows(const prt_sf_shells* grid, const prt_sf_cell* rows_at, uint32_t rows,
                     uint32_t pair_count, uint32_t q, const uint32_t* stamps, uint32_t frame,
                     uint8_t* needed) {
  for (uint32_t r = 0; r < rows; ++r) {
    if (stamps[r] != frame) return 0;
    const prt_sf_cell* cell = &rows_at[(size_t)r * pair_count + q];
    if (cell->count == 0u) continue;
    prt_sf_lookup lookup;
    prt_sf_cell_lookup(grid, cell, &lookup);
    for (uint32_t e = 0; e < lookup.count; ++e) needed[lookup.index[e]] = 1u;
  }
  return 1;
}

/* Marks the source's SRF points some receiver's cell reads this frame (a vertex's, or a probe's
 * for a receiver with probes), or every point when a row that it reaches has no cells this
 * frame (the bounces locate afresh). */
static void mark_needed(const prt_shadowfield_scene* scene, uint32_t instance) {
  prt_sf_instance* source = &scene->instances[instance];
  const prt_sf_shells* grid = &scene->objects[source->object]->srf_shells;
  const uint64_t points = prt_sf_point_count(grid);
  memset(source->needed, 0, points);
  for (uint32_t i = 0; i < scene->instance_count; ++i) {
    const prt_sf_instance* receiver = &scene->instances[i];
    const int probed = receiver->probe_count > 0u;
    const prt_sf_cell* rows_at = probed ? scene->probe_cells + receiver->probe_cell_first
                                        : scene->cells + receiver->cell_first;
    const uint32_t rows =
        probed ? receiver->probe_count : scene->objects[receiver->object]->vertex_count;
    const uint32_t* stamps = probed ? receiver->probe_located : receiver->located;
    for (uint32_t q = 0; q < receiver->pair_count; ++q) {
      const prt_sf_pair* pair = &scene->pairs[receiver->pair_first + q];
      if (pair->other != instance || !pair->lights) continue;
      if (!mark_rows(grid, rows_at, rows, receiver->pair_count, q, stamps, scene->frame,
                     source->needed)) {
        memset(source->needed, 1, points);
        return;
      }
    }
  }
}

void prt_sf_project_weights(const prt_shadowfield_scene* scene, uint32_t pass, uint32_t instance) {
  prt_sf_instance* source = &scene->instances[instance];
  if (!source->is_source) return;
  /* The cells are the frame's from its direct pass on, so the marks serve every pass. */
  if (source->needed_frame != scene->frame) {
    mark_needed(scene, instance);
    source->needed_frame = scene->frame;
  }
  const prt_sf_object* object = scene->objects[source->object];
  const float* incident =
      source->incident + (size_t)pass * object->vertex_count * object->terms * 3u;
  float* projected = source->weights + (size_t)object->basis_size * object->terms * 3u;
  basis_weights(object, incident, source->weights, projected);
}

uint64_t prt_sf_field_points(const prt_shadowfield_scene* scene, uint32_t instance) {
  const prt_sf_instance* source = &scene->instances[instance];
  if (!source->is_source) return 0u;
  return prt_sf_point_count(&scene->objects[source->object]->srf_shells);
}

/* Only the points prt_sf_project_weights marked: the others are never read this frame. Each
 * point's value is the same whatever run it is cast in. */
void prt_sf_cast_field(const prt_shadowfield_scene* scene, uint32_t instance, uint64_t first,
                       uint64_t count) {
  const prt_sf_instance* source = &scene->instances[instance];
  if (!source->is_source) return;
  const prt_sf_object* object = scene->objects[source->object];
  const uint64_t end = first + count;
  for (uint64_t p = first; p < end;) {
    while (p < end && !source->needed[p]) ++p;
    const uint64_t start = p;
    while (p < end && source->needed[p]) ++p;
    if (p > start)
      scene->kernels->cast_field(object, source->weights, source->field, start, p - start);
  }
}

void prt_sf_project_instance(const prt_shadowfield_scene* scene, uint32_t pass, uint32_t instance) {
  prt_sf_project_weights(scene, pass, instance);
  prt_sf_cast_field(scene, instance, 0u, prt_sf_field_points(scene, instance));
}

/* ---- Output --------------------------------------------------------------------------------- */

void prt_sf_square_from_hemisphere(const double direction[3], double* a, double* b) {
  const double z = direction[2] > 0.0 ? direction[2] : 0.0;
  const double length = sqrt(direction[0] * direction[0] + direction[1] * direction[1] + z * z);
  if (!(length > 0.0)) { /* straight below the surface: read at the normal */
    *a = *b = 0.0;
    return;
  }
  const double dz = z / length;
  const double r = sqrt(1.0 - dz > 0.0 ? 1.0 - dz : 0.0);
  if (r == 0.0) {
    *a = *b = 0.0;
    return;
  }
  double phi = atan2(direction[1] / length, direction[0] / length);
  if (phi < -SF_PI / 4.0) phi += 2.0 * SF_PI;
  const double to_square = 4.0 / SF_PI;
  if (phi < SF_PI / 4.0) {
    *a = r;
    *b = phi * to_square * r;
  } else if (phi < 3.0 * SF_PI / 4.0) {
    *a = (SF_PI / 2.0 - phi) * to_square * r;
    *b = r;
  } else if (phi < 5.0 * SF_PI / 4.0) {
    *a = -r;
    *b = -(phi - SF_PI) * to_square * r;
  } else {
    *a = (phi - 3.0 * SF_PI / 2.0) * to_square * r;
    *b = -r;
  }
}

/* The two cells along one square axis around `coordinate` in [-1, 1] and the second's weight,
 * clamped to the outermost centres. */
static void axis_span(double coordinate, uint32_t size, uint32_t* first, uint32_t* second,
                      double* weight) {
  double at = (coordinate + 1.0) * 0.5 * size - 0.5;
  if (!(at > 0.0)) at = 0.0;
  if (at > size - 1.0) at = size - 1.0;
  *first = (uint32_t)at < size - 1u ? (uint32_t)at : size - 1u;
  *second = *first + 1u < size ? *first + 1u : size - 1u;
  *weight = at - *first;
}

float prt_sf_outgoing_at(const prt_sf_object* object, uint32_t term, const double wo[3]) {
  const uint32_t size = object->brdf_grid;
  double a, b, wx, wy;
  uint32_t x0, x1, y0, y1;
  prt_sf_square_from_hemisphere(wo, &a, &b);
  axis_span(a, size, &x0, &x1, &wx);
  axis_span(b, size, &y0, &y1, &wy);
  const float* g = object->g_table + (size_t)term * size * size;
  return (float)((1.0 - wx) * (1.0 - wy) * g[y0 * size + x0] + wx * (1.0 - wy) * g[y0 * size + x1] +
                 (1.0 - wx) * wy * g[y1 * size + x0] + wx * wy * g[y1 * size + x1]);
}

void prt_sf_tangent_frame(const float n[3], float t[3], float b[3]) {
  const float sign = copysignf(1.0f, n[2]);
  const float a = -1.0f / (sign + n[2]);
  const float b_ = n[0] * n[1] * a;
  t[0] = 1.0f + sign * n[0] * n[0] * a;
  t[1] = sign * b_;
  t[2] = -sign * n[0];
  b[0] = b_;
  b[1] = sign + n[1] * n[1] * a;
  b[2] = -n[1];
}

/* The direction to the eye from object-frame vertex x, in x's tangent frame; the normal when the
 * eye is at the vertex. */
static void view_direction(const prt_shadowfield_scene* scene, const prt_sf_instance* instance,
                           const float x[3], const float normal[3], double wo[3]) {
  const float* r = instance->rotation;
  float to_eye_world[3], to_eye[3], t[3], b[3];
  for (int c = 0; c < 3; ++c)
    to_eye_world[c] =
        scene->eye[c] - instance->translation[c] -
        instance->scale * (r[3 * c] * x[0] + r[3 * c + 1] * x[1] + r[3 * c + 2] * x[2]);
  for (int c = 0; c < 3; ++c)
    to_eye[c] = r[c] * to_eye_world[0] + r[3 + c] * to_eye_world[1] + r[6 + c] * to_eye_world[2];
  prt_sf_tangent_frame(normal, t, b);
  wo[0] = (double)t[0] * to_eye[0] + (double)t[1] * to_eye[1] + (double)t[2] * to_eye[2];
  wo[1] = (double)b[0] * to_eye[0] + (double)b[1] * to_eye[1] + (double)b[2] * to_eye[2];
  wo[2] =
      (double)normal[0] * to_eye[0] + (double)normal[1] * to_eye[1] + (double)normal[2] * to_eye[2];
  if (wo[0] == 0.0 && wo[1] == 0.0 && wo[2] == 0.0) wo[2] = 1.0;
}

void prt_sf_output_range(const prt_shadowfield_scene* scene, uint32_t instance,
                         uint32_t through_pass, uint32_t first_vertex, uint32_t vertex_count,
                         float* out_rgb) {
  const prt_sf_instance* receiver = &scene->instances[instance];
  const prt_sf_object* object = scene->objects[receiver->object];
  const uint32_t terms = object->terms;
  const size_t pass_floats = (size_t)object->vertex_count * terms * 3u;
  for (uint32_t v = first_vertex; v < first_vertex + vertex_count; ++v) {
    float g[PRT_SF_MAX_TERMS];
    if (object->glossy) {
      double wo[3];
      view_direction(scene, receiver, object->positions + 3u * v, object->normals + 3u * v, wo);
      /* A glossy surface seen from behind reflects nothing towards the eye (as the reference
       * renderer and the baked source fields have it); the table would read its horizon. */
      for (uint32_t k = 0; k < terms; ++k)
        g[k] = wo[2] > 0.0 ? prt_sf_outgoing_at(object, k, wo) : 0.0f;
    } else {
      g[0] = 1.0f;
    }
    float sum[3] = {0.0f, 0.0f, 0.0f};
    for (uint32_t pass = 0; pass <= through_pass; ++pass) {
      const float* l = receiver->incident + pass * pass_floats + (size_t)v * terms * 3u;
      for (uint32_t k = 0; k < terms; ++k)
        for (uint32_t c = 0; c < 3u; ++c) sum[c] += g[k] * l[3u * k + c];
    }
    float* out = out_rgb + (size_t)(v - first_vertex) * 3u;
    for (uint32_t c = 0; c < 3u; ++c) out[c] = object->albedo[3u * v + c] * sum[c];
  }
}

/* ---- The stages' entry points --------------------------------------------------------------- */

static int range_ok(uint32_t first, uint32_t count, uint32_t size) {
  return first <= size && count <= size - first;
}

prt_result prt_shadowfield_gather(prt_shadowfield_scene* scene, uint32_t pass, uint32_t instance,
                                  uint32_t first_vertex, uint32_t vertex_count) {
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (!scene->prepared) return PRT_ERROR_INVALID_OPERATION;
  if (pass > scene->bounces || instance >= scene->instance_count ||
      !range_ok(first_vertex, vertex_count, prt_shadowfield_instance_vertex_count(scene, instance)))
    return PRT_ERROR_INVALID_ARGUMENT;
  prt_sf_gather_range(scene, pass, instance, first_vertex, vertex_count);
  return PRT_OK;
}

prt_result prt_shadowfield_project(prt_shadowfield_scene* scene, uint32_t pass,
                                   uint32_t first_instance, uint32_t instance_count) {
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  if (!scene->prepared) return PRT_ERROR_INVALID_OPERATION;
  if (pass >= scene->bounces || !range_ok(first_instance, instance_count, scene->instance_count))
    return PRT_ERROR_INVALID_ARGUMENT;
  for (uint32_t i = first_instance; i < first_instance + instance_count; ++i)
    prt_sf_project_instance(scene, pass, i);
  return PRT_OK;
}

prt_result prt_shadowfield_output(const prt_shadowfield_scene* scene, uint32_t instance,
                                  uint32_t through_pass, uint32_t first_vertex,
                                  uint32_t vertex_count, float* out_rgb) {
  if (!scene || !out_rgb) return PRT_ERROR_INVALID_ARGUMENT;
  if (!scene->prepared) return PRT_ERROR_INVALID_OPERATION;
  if (through_pass > scene->bounces || instance >= scene->instance_count ||
      !range_ok(first_vertex, vertex_count, prt_shadowfield_instance_vertex_count(scene, instance)))
    return PRT_ERROR_INVALID_ARGUMENT;
  prt_sf_output_range(scene, instance, through_pass, first_vertex, vertex_count, out_rgb);
  return PRT_OK;
}
