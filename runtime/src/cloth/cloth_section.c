/* SPDX-License-Identifier: MIT */
/* Technique `cloth` in the runtime's technique table: the CLTH header, every fabric, thread,
 * tangent and table record and the exact size checked against the section at load (either
 * validation level; F <= 64 and G, Q <= 1024 keep this bounded), in the formats checker's order
 * and words; the view every `cloth` function reads (each factorisation's offset and rank); and
 * the ties of the `cloth` constants to the formats layer's. */
#include <inttypes.h>
#include <stdio.h>

#include "cloth_internal.h"
#include "techniques.h"

PRT_STATIC_ASSERT(PRT_SECTION_CLTH == PRT_BLOB_TAG_CLTH, tag_clth);
PRT_STATIC_ASSERT(PRT_CLOTH_MAX_THREAD_TANGENTS == PRT_BLOB_CLTH_MAX_THREAD_TANGENTS,
                  cloth_thread_tangents);
PRT_STATIC_ASSERT(PRT_CLOTH_MAX_MULTIPLICITY == PRT_BLOB_CLTH_MAX_MULTIPLICITY, cloth_multiplicity);

static prt_result corrupt(char* msg, size_t capacity, const char* what) {
  snprintf(msg, capacity, "'CLTH': %s", what);
  return PRT_ERROR_CORRUPT;
}

static int reserved_ok(const uint8_t* p, uint32_t size) {
  uint32_t i;
  for (i = 0; i < size; ++i)
    if (p[i] != 0) return 0;
  return 1;
}

/* The count fields and the sharpness range. */
static int counts_ok(const prt_blob_clth_header* h, char* what, size_t size) {
  if (h->fabrics < 1u || h->fabrics > PRT_BLOB_CLTH_MAX_FABRICS)
    snprintf(what, size, "%" PRIu32 " fabrics (must be 1..64)", h->fabrics);
  else if (h->tangents < 1u || h->tangents > PRT_BLOB_CLTH_MAX_TANGENTS)
    snprintf(what, size, "%" PRIu32 " tangent records (must be 1..1024)", h->tangents);
  else if (h->tables < 1u || h->tables > PRT_BLOB_CLTH_MAX_TABLES)
    snprintf(what, size, "%" PRIu32 " table records (must be 1..1024)", h->tables);
  else if (h->xi_size < 2u || h->xi_size > PRT_BLOB_CLTH_MAX_GRID)
    snprintf(what, size, "%" PRIu32 " lobe nodes per side (must be 2..256)", h->xi_size);
  else if (h->levels < 1u || h->levels > PRT_BLOB_CLTH_MAX_LEVELS)
    snprintf(what, size, "%" PRIu32 " sharpness levels (must be 1..64)", h->levels);
  else if (!isfinite(h->lambda_min))
    snprintf(what, size, "lambda_min is not finite");
  else if (!(h->lambda_min > 0.0f))
    snprintf(what, size, "lambda_min %g is not positive", (double)h->lambda_min);
  else if (!isfinite(h->lambda_max))
    snprintf(what, size, "lambda_max is not finite");
  else if (h->lambda_max < h->lambda_min)
    snprintf(what, size, "lambda_max %g is below lambda_min %g", (double)h->lambda_max,
             (double)h->lambda_min);
  else if (h->levels == 1u && h->lambda_max != h->lambda_min)
    snprintf(what, size, "lambda_max %g differs from lambda_min %g with one level",
             (double)h->lambda_max, (double)h->lambda_min);
  else
    return 1;
  return 0;
}

/* The view grid, bits, flags, reserved words and the element count. */
static int fields_ok(const prt_blob_clth_header* h, const uint8_t* p, uint64_t element_count,
                     char* what, size_t size) {
  if (h->view_theta < 2u || h->view_theta > PRT_BLOB_CLTH_MAX_GRID)
    snprintf(what, size, "%" PRIu32 " view theta nodes (must be 2..256)", h->view_theta);
  else if (h->view_phi < 2u || h->view_phi > PRT_BLOB_CLTH_MAX_GRID)
    snprintf(what, size, "%" PRIu32 " view phi nodes (must be 2..256)", h->view_phi);
  else if (h->bits != 8u && h->bits != 16u)
    snprintf(what, size, "%" PRIu32 " bits (must be 8 or 16)", h->bits);
  else if (h->flags != 0u)
    snprintf(what, size, "unknown flags 0x%" PRIx32, h->flags);
  else if (!reserved_ok(p + PRT_BLOB_CLTH_OFF_RESERVED, PRT_BLOB_CLTH_RESERVED_SIZE))
    snprintf(what, size, "reserved header fields are not zero");
  else if ((uint64_t)h->fabrics != element_count)
    snprintf(what, size, "header says %" PRIu32 " fabrics, element count %" PRIu64, h->fabrics,
             element_count);
  else
    return 1;
  return 0;
}

/* A thread's float parameters: where, what and the range (formats/SPEC.md §7.4). */
typedef struct thread_field {
  uint32_t offset;
  const char* name;
  float lo, hi;
  int lo_open; /* 1: lo itself is out of range */
  const char* range;
} thread_field;

static const thread_field kThreadFields[] = {
    {PRT_BLOB_CLTH_THREAD_OFF_ETA, "eta", 1.0f, 4.0f, 0, "[1, 4]"},
    {PRT_BLOB_CLTH_THREAD_OFF_ALBEDO, "albedo red", 0.0f, 1.0f, 0, "[0, 1]"},
    {PRT_BLOB_CLTH_THREAD_OFF_ALBEDO + 4u, "albedo green", 0.0f, 1.0f, 0, "[0, 1]"},
    {PRT_BLOB_CLTH_THREAD_OFF_ALBEDO + 8u, "albedo blue", 0.0f, 1.0f, 0, "[0, 1]"},
    {PRT_BLOB_CLTH_THREAD_OFF_KD, "k_d", 0.0f, 1.0f, 0, "[0, 1]"},
    {PRT_BLOB_CLTH_THREAD_OFF_GAMMA_S, "gamma_s", 0.0f, PRT_BLOB_CLTH_PI_F32, 1, "(0, pi]"},
    {PRT_BLOB_CLTH_THREAD_OFF_GAMMA_V, "gamma_v", 0.0f, PRT_BLOB_CLTH_PI_F32, 1, "(0, pi]"},
    {PRT_BLOB_CLTH_THREAD_OFF_COVERAGE, "coverage", 0.0f, 1.0f, 0, "[0, 1]"},
};

#define THREAD_FIELD_COUNT (sizeof kThreadFields / sizeof kThreadFields[0])

/* Thread j (0, 1) of fabric f: parameters, tangent record range, reserved words. */
static int thread_ok(const uint8_t* fabric, const prt_blob_clth_header* h, uint32_t f, uint32_t j,
                     char* what, size_t size) {
  const uint8_t* t = fabric + PRT_BLOB_CLTH_FABRIC_OFF_THREADS + PRT_BLOB_CLTH_THREAD_SIZE * j;
  const uint32_t first = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_FIRST);
  const uint32_t count = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_COUNT);
  size_t i;
  for (i = 0; i < THREAD_FIELD_COUNT; ++i) {
    const thread_field* field = &kThreadFields[i];
    const float x = prt_blob_clth_load_f32(t + field->offset);
    if (!isfinite(x)) {
      snprintf(what, size, "fabric %" PRIu32 " thread %" PRIu32 ": %s is not finite", f, j + 1u,
               field->name);
      return 0;
    }
    if (x < field->lo || x > field->hi || (field->lo_open && x == field->lo)) {
      snprintf(what, size, "fabric %" PRIu32 " thread %" PRIu32 ": %s %g is not in %s", f, j + 1u,
               field->name, (double)x, field->range);
      return 0;
    }
  }
  if (count < 1u || count > PRT_BLOB_CLTH_MAX_THREAD_TANGENTS)
    snprintf(what, size,
             "fabric %" PRIu32 " thread %" PRIu32 " has %" PRIu32
             " tangent records (must be 1..16)",
             f, j + 1u, count);
  else if ((uint64_t)first + count > h->tangents)
    snprintf(what, size,
             "fabric %" PRIu32 " thread %" PRIu32 ": tangent records %" PRIu32 "..%" PRIu64
             " are not below %" PRIu32,
             f, j + 1u, first, (uint64_t)first + count - 1u, h->tangents);
  else if (!reserved_ok(t + PRT_BLOB_CLTH_THREAD_OFF_RESERVED,
                        PRT_BLOB_CLTH_THREAD_SIZE - PRT_BLOB_CLTH_THREAD_OFF_RESERVED))
    snprintf(what, size, "fabric %" PRIu32 " thread %" PRIu32 ": reserved fields are not zero", f,
             j + 1u);
  else
    return 1;
  return 0;
}

/* Fabric f's record: name (at least one byte, NUL-padded), threads, coverages; keeps the name. */
static int fabric_ok(prt_cloth_view* view, const prt_blob_clth_header* h, uint32_t f, char* what,
                     size_t size) {
  const uint8_t* fabric =
      view->data + view->layout.fabrics + (uint64_t)PRT_BLOB_CLTH_FABRIC_SIZE * f;
  const uint8_t* threads = fabric + PRT_BLOB_CLTH_FABRIC_OFF_THREADS;
  uint32_t n = 0, j;
  float a1, a2;
  while (n < PRT_BLOB_CLTH_NAME_SIZE && fabric[n] != 0) ++n;
  if (n == 0) {
    snprintf(what, size, "fabric %" PRIu32 " has an empty name", f);
    return 0;
  }
  if (!reserved_ok(fabric + n, PRT_BLOB_CLTH_NAME_SIZE - n)) {
    snprintf(what, size, "fabric %" PRIu32 ": name is not NUL-padded", f);
    return 0;
  }
  for (j = 0; j < 2u; ++j)
    if (!thread_ok(fabric, h, f, j, what, size)) return 0;
  a1 = prt_blob_clth_load_f32(threads + PRT_BLOB_CLTH_THREAD_OFF_COVERAGE);
  a2 = prt_blob_clth_load_f32(threads + PRT_BLOB_CLTH_THREAD_SIZE +
                              PRT_BLOB_CLTH_THREAD_OFF_COVERAGE);
  if ((double)a1 + (double)a2 > 1.0 + PRT_BLOB_CLTH_COVERAGE_SLACK) {
    snprintf(what, size, "fabric %" PRIu32 ": coverages %g and %g add up to more than 1", f,
             (double)a1, (double)a2);
    return 0;
  }
  memcpy(view->names[f], fabric, n);
  view->names[f][n] = '\0';
  return 1;
}

/* Tangent record g. */
static int tangent_ok(const prt_cloth_view* view, const prt_blob_clth_header* h, uint32_t g,
                      char* what, size_t size) {
  prt_cloth_tangent_record t;
  prt_cloth_read_tangent(view, g, &t);
  if (!isfinite(t.offset))
    snprintf(what, size, "tangent %" PRIu32 ": offset is not finite", g);
  else if (t.offset < -PRT_BLOB_CLTH_HALF_PI_F32 || t.offset > PRT_BLOB_CLTH_HALF_PI_F32)
    snprintf(what, size, "tangent %" PRIu32 ": offset %g is not in [-pi/2, pi/2]", g,
             (double)t.offset);
  else if (t.multiplicity < 1u || t.multiplicity > PRT_BLOB_CLTH_MAX_MULTIPLICITY)
    snprintf(what, size, "tangent %" PRIu32 ": multiplicity %" PRIu32 " (must be 1..64)", g,
             t.multiplicity);
  else if (t.table >= h->tables)
    snprintf(what, size, "tangent %" PRIu32 ": table %" PRIu32 " is not below %" PRIu32 " tables",
             g, t.table, h->tables);
  else if (t.mirror > 1u)
    snprintf(what, size, "tangent %" PRIu32 ": mirror %" PRIu32 " is not 0 or 1", g, t.mirror);
  else
    return 1;
  return 0;
}

/* Table record q; places its two factorisations at *at and moves *at past them. */
static int table_ok(prt_cloth_view* view, uint32_t q, uint64_t* at, char* what, size_t size) {
  const uint8_t* t = view->data + view->layout.tables + (uint64_t)PRT_BLOB_CLTH_TABLE_SIZE * q;
  const uint32_t rank = prt_le_load_u32(t + PRT_BLOB_CLTH_TABLE_OFF_RANK);
  const uint32_t cone_rank = prt_le_load_u32(t + PRT_BLOB_CLTH_TABLE_OFF_CONE_RANK);
  if (rank < 1u || rank > PRT_BLOB_CLTH_MAX_RANK)
    snprintf(what, size, "table %" PRIu32 ": rank %" PRIu32 " (must be 1..64)", q, rank);
  else if (cone_rank < 1u || cone_rank > PRT_BLOB_CLTH_MAX_RANK)
    snprintf(what, size, "table %" PRIu32 ": cone rank %" PRIu32 " (must be 1..64)", q, cone_rank);
  else if (!reserved_ok(t + PRT_BLOB_CLTH_TABLE_OFF_RESERVED,
                        PRT_BLOB_CLTH_TABLE_SIZE - PRT_BLOB_CLTH_TABLE_OFF_RESERVED))
    snprintf(what, size, "table %" PRIu32 ": reserved fields are not zero", q);
  else {
    view->factor_rank[q][0] = rank;
    view->factor_rank[q][1] = cone_rank;
    view->factor_offset[q][0] = *at;
    *at += prt_blob_clth_factor_size(&view->layout, rank);
    view->factor_offset[q][1] = *at;
    *at += prt_blob_clth_factor_size(&view->layout, cone_rank);
    return 1;
  }
  return 0;
}

/* Every record in section order, then the exact size the ranks imply. */
static int records_ok(prt_cloth_view* view, uint64_t size, char* what, size_t what_size) {
  const prt_blob_clth_header* h = &view->header;
  uint64_t end = view->layout.data;
  uint32_t i;
  if (size < view->layout.data) {
    snprintf(what, what_size,
             "%" PRIu64 " raw bytes cannot hold the header and records (%" PRIu64 " bytes)", size,
             view->layout.data);
    return 0;
  }
  for (i = 0; i < h->fabrics; ++i)
    if (!fabric_ok(view, h, i, what, what_size)) return 0;
  for (i = 0; i < h->tangents; ++i)
    if (!tangent_ok(view, h, i, what, what_size)) return 0;
  for (i = 0; i < h->tables; ++i)
    if (!table_ok(view, i, &end, what, what_size)) return 0;
  if (end != size) {
    snprintf(what, what_size, "%" PRIu64 " raw bytes, the header and ranks imply %" PRIu64, size,
             end);
    return 0;
  }
  return 1;
}

static void fill_info(prt_cloth_view* view, uint64_t size) {
  const prt_blob_clth_header* h = &view->header;
  prt_cloth_info* info = &view->info;
  info->struct_size = sizeof *info;
  info->fabric_count = h->fabrics;
  info->table_count = h->tables;
  info->xi_size = h->xi_size;
  info->lambda_levels = h->levels;
  info->lambda_min = h->lambda_min;
  info->lambda_max = h->lambda_max;
  info->view_theta = h->view_theta;
  info->view_phi = h->view_phi;
  info->bits = h->bits;
  info->table_bytes = (size_t)(size - view->layout.data);
}

static prt_result open_clth(const prt_asset_section* section, void* out, char* msg,
                            size_t capacity) {
  prt_cloth_view* view = (prt_cloth_view*)out;
  const uint8_t* p = section->data;
  const uint64_t size = section->entry.raw_size;
  char what[160];
  if (!p || size < PRT_BLOB_CLTH_HEADER_SIZE) {
    snprintf(what, sizeof what, "%" PRIu64 " bytes cannot hold the 64-byte header", size);
    return corrupt(msg, capacity, what);
  }
  memset(view, 0, sizeof *view);
  view->data = p;
  prt_blob_clth_read_header(p, &view->header);
  if (!counts_ok(&view->header, what, sizeof what) ||
      !fields_ok(&view->header, p, section->entry.element_count, what, sizeof what))
    return corrupt(msg, capacity, what);
  prt_blob_clth_layout_of(&view->header, &view->layout); /* valid counts */
  if (!records_ok(view, size, what, sizeof what)) return corrupt(msg, capacity, what);
  fill_info(view, size);
  return PRT_OK;
}

extern const struct prt_scene_hooks prt_cloth_scene_hooks; /* cloth/cloth_scene_hooks.c */

const prt_technique_entry prt_cloth_technique_entry = {
    PRT_TECHNIQUE_CLOTH,
    "cloth",
    PRT_BLOB_TAG_CLTH,
    sizeof(prt_cloth_view),
    open_clth,
    NULL,
    NULL,
    &prt_cloth_scene_hooks,
};
