/* SPDX-License-Identifier: MIT */
/* The CLTH content check (formats/SPEC.md §7.4, full validation). The runtime's load
 * (runtime/src/cloth/cloth_section.c) restates the header, record and size checks in the same
 * order and words; the names' UTF-8, distinct names and offsets and the tables' data are checked
 * here only. */
#include "cloth_section.h"

#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include <prt/format/cloth_layout.h>

#include "../mesh/mesh_sections.h"
#include "../reader_internal.h"

#define FAIL_CORRUPT(...) prt_blob_fail(PRT_BLOB_CORRUPT, msg, cap, "'CLTH': " __VA_ARGS__)
#define FAIL_NON_FINITE(...) prt_blob_fail(PRT_BLOB_NON_FINITE, msg, cap, "'CLTH': " __VA_ARGS__)

/* The count fields, each in its range. */
static prt_blob_status check_counts(const prt_blob_clth_header* h, char* msg, size_t cap) {
  if (h->fabrics < 1u || h->fabrics > PRT_BLOB_CLTH_MAX_FABRICS)
    return FAIL_CORRUPT("%" PRIu32 " fabrics (must be 1..64)", h->fabrics);
  if (h->tangents < 1u || h->tangents > PRT_BLOB_CLTH_MAX_TANGENTS)
    return FAIL_CORRUPT("%" PRIu32 " tangent records (must be 1..1024)", h->tangents);
  if (h->tables < 1u || h->tables > PRT_BLOB_CLTH_MAX_TABLES)
    return FAIL_CORRUPT("%" PRIu32 " table records (must be 1..1024)", h->tables);
  if (h->xi_size < 2u || h->xi_size > PRT_BLOB_CLTH_MAX_GRID)
    return FAIL_CORRUPT("%" PRIu32 " lobe nodes per side (must be 2..256)", h->xi_size);
  if (h->levels < 1u || h->levels > PRT_BLOB_CLTH_MAX_LEVELS)
    return FAIL_CORRUPT("%" PRIu32 " sharpness levels (must be 1..64)", h->levels);
  return PRT_BLOB_OK;
}

/* The sharpness range of the lobe grid. */
static prt_blob_status check_sharpness(const prt_blob_clth_header* h, char* msg, size_t cap) {
  if (!prt_blob_f32_is_finite(h->lambda_min)) return FAIL_NON_FINITE("lambda_min is not finite");
  if (!(h->lambda_min > 0.0f))
    return FAIL_CORRUPT("lambda_min %g is not positive", (double)h->lambda_min);
  if (!prt_blob_f32_is_finite(h->lambda_max)) return FAIL_NON_FINITE("lambda_max is not finite");
  if (h->lambda_max < h->lambda_min)
    return FAIL_CORRUPT("lambda_max %g is below lambda_min %g", (double)h->lambda_max,
                        (double)h->lambda_min);
  if (h->levels == 1u && h->lambda_max != h->lambda_min)
    return FAIL_CORRUPT("lambda_max %g differs from lambda_min %g with one level",
                        (double)h->lambda_max, (double)h->lambda_min);
  return PRT_BLOB_OK;
}

/* Every header field in the table's order, then the element count; on success *h and *l are
 * filled. */
static prt_blob_status check_header(const prt_blob_content* content, prt_blob_clth_header* h,
                                    prt_blob_clth_layout* l, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  prt_blob_status st;
  prt_blob_clth_read_header(p, h);
  st = check_counts(h, msg, cap);
  if (st == PRT_BLOB_OK) st = check_sharpness(h, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  if (h->view_theta < 2u || h->view_theta > PRT_BLOB_CLTH_MAX_GRID)
    return FAIL_CORRUPT("%" PRIu32 " view theta nodes (must be 2..256)", h->view_theta);
  if (h->view_phi < 2u || h->view_phi > PRT_BLOB_CLTH_MAX_GRID)
    return FAIL_CORRUPT("%" PRIu32 " view phi nodes (must be 2..256)", h->view_phi);
  if (h->bits != 8u && h->bits != 16u)
    return FAIL_CORRUPT("%" PRIu32 " bits (must be 8 or 16)", h->bits);
  if (h->flags != 0u) return FAIL_CORRUPT("unknown flags 0x%" PRIx32, h->flags);
  if (!prt_blob_bytes_are_zero(p + PRT_BLOB_CLTH_OFF_RESERVED, PRT_BLOB_CLTH_RESERVED_SIZE))
    return FAIL_CORRUPT("reserved header fields are not zero");
  if ((uint64_t)h->fabrics != content->section->element_count)
    return FAIL_CORRUPT("header says %" PRIu32 " fabrics, element count %" PRIu64, h->fabrics,
                        content->section->element_count);
  prt_blob_clth_layout_of(h, l); /* valid counts */
  return PRT_BLOB_OK;
}

/* A thread's float parameters: where, what and the range (SPEC.md §7.4). */
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

/* Thread j of fabric f: its parameters, its tangent record range and its reserved words. */
static prt_blob_status check_thread(const uint8_t* fabric, const prt_blob_clth_header* h,
                                    uint32_t f, uint32_t j, char* msg, size_t cap) {
  const uint8_t* t = fabric + PRT_BLOB_CLTH_FABRIC_OFF_THREADS + PRT_BLOB_CLTH_THREAD_SIZE * j;
  const uint32_t first = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_FIRST);
  const uint32_t count = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_COUNT);
  size_t i;
  for (i = 0; i < THREAD_FIELD_COUNT; ++i) {
    const thread_field* field = &kThreadFields[i];
    const float x = prt_blob_load_f32(t + field->offset);
    if (!prt_blob_f32_is_finite(x))
      return FAIL_NON_FINITE("fabric %" PRIu32 " thread %" PRIu32 ": %s is not finite", f, j + 1u,
                             field->name);
    if (x < field->lo || x > field->hi || (field->lo_open && x == field->lo))
      return FAIL_CORRUPT("fabric %" PRIu32 " thread %" PRIu32 ": %s %g is not in %s", f, j + 1u,
                          field->name, (double)x, field->range);
  }
  if (count < 1u || count > PRT_BLOB_CLTH_MAX_THREAD_TANGENTS)
    return FAIL_CORRUPT("fabric %" PRIu32 " thread %" PRIu32 " has %" PRIu32
                        " tangent records (must be 1..16)",
                        f, j + 1u, count);
  if ((uint64_t)first + count > h->tangents)
    return FAIL_CORRUPT("fabric %" PRIu32 " thread %" PRIu32 ": tangent records %" PRIu32
                        "..%" PRIu64 " are not below %" PRIu32,
                        f, j + 1u, first, (uint64_t)first + count - 1u, h->tangents);
  if (!prt_blob_bytes_are_zero(t + PRT_BLOB_CLTH_THREAD_OFF_RESERVED,
                               PRT_BLOB_CLTH_THREAD_SIZE - PRT_BLOB_CLTH_THREAD_OFF_RESERVED))
    return FAIL_CORRUPT("fabric %" PRIu32 " thread %" PRIu32 ": reserved fields are not zero", f,
                        j + 1u);
  return PRT_BLOB_OK;
}

/* The length of a stored name (bytes before the first NUL, at most 32). */
static size_t name_length(const uint8_t* name) {
  size_t n = 0;
  while (n < PRT_BLOB_CLTH_NAME_SIZE && name[n] != 0) ++n;
  return n;
}

/* Fabric f's record: its name's padding, both threads and their coverages. */
static prt_blob_status check_fabric(const uint8_t* p, const prt_blob_clth_header* h,
                                    const prt_blob_clth_layout* l, uint32_t f, char* msg,
                                    size_t cap) {
  const uint8_t* fabric = p + l->fabrics + (uint64_t)PRT_BLOB_CLTH_FABRIC_SIZE * f;
  const size_t n = name_length(fabric);
  const uint8_t* threads = fabric + PRT_BLOB_CLTH_FABRIC_OFF_THREADS;
  float a1, a2;
  uint32_t j;
  if (n == 0) return FAIL_CORRUPT("fabric %" PRIu32 " has an empty name", f);
  if (!prt_blob_bytes_are_zero(fabric + n, PRT_BLOB_CLTH_NAME_SIZE - n))
    return FAIL_CORRUPT("fabric %" PRIu32 ": name is not NUL-padded", f);
  for (j = 0; j < 2u; ++j) {
    const prt_blob_status st = check_thread(fabric, h, f, j, msg, cap);
    if (st != PRT_BLOB_OK) return st;
  }
  a1 = prt_blob_load_f32(threads + PRT_BLOB_CLTH_THREAD_OFF_COVERAGE);
  a2 = prt_blob_load_f32(threads + PRT_BLOB_CLTH_THREAD_SIZE + PRT_BLOB_CLTH_THREAD_OFF_COVERAGE);
  /* The slack admits float pairs whose decimal sum is 1 (0.86f + 0.14f > 1). */
  if ((double)a1 + (double)a2 > 1.0 + PRT_BLOB_CLTH_COVERAGE_SLACK)
    return FAIL_CORRUPT("fabric %" PRIu32 ": coverages %g and %g add up to more than 1", f,
                        (double)a1, (double)a2);
  return PRT_BLOB_OK;
}

/* Tangent record g. */
static prt_blob_status check_tangent(const uint8_t* p, const prt_blob_clth_header* h,
                                     const prt_blob_clth_layout* l, uint32_t g, char* msg,
                                     size_t cap) {
  const uint8_t* t = p + l->tangents + (uint64_t)PRT_BLOB_CLTH_TANGENT_SIZE * g;
  const float offset = prt_blob_load_f32(t + PRT_BLOB_CLTH_TANGENT_OFF_OFFSET);
  const uint32_t multiplicity = prt_le_load_u32(t + PRT_BLOB_CLTH_TANGENT_OFF_MULTIPLICITY);
  const uint32_t table = prt_le_load_u32(t + PRT_BLOB_CLTH_TANGENT_OFF_TABLE);
  const uint32_t mirror = prt_le_load_u32(t + PRT_BLOB_CLTH_TANGENT_OFF_MIRROR);
  if (!prt_blob_f32_is_finite(offset))
    return FAIL_NON_FINITE("tangent %" PRIu32 ": offset is not finite", g);
  if (offset < -PRT_BLOB_CLTH_HALF_PI_F32 || offset > PRT_BLOB_CLTH_HALF_PI_F32)
    return FAIL_CORRUPT("tangent %" PRIu32 ": offset %g is not in [-pi/2, pi/2]", g,
                        (double)offset);
  if (multiplicity < 1u || multiplicity > PRT_BLOB_CLTH_MAX_MULTIPLICITY)
    return FAIL_CORRUPT("tangent %" PRIu32 ": multiplicity %" PRIu32 " (must be 1..64)", g,
                        multiplicity);
  if (table >= h->tables)
    return FAIL_CORRUPT("tangent %" PRIu32 ": table %" PRIu32 " is not below %" PRIu32 " tables", g,
                        table, h->tables);
  if (mirror > 1u)
    return FAIL_CORRUPT("tangent %" PRIu32 ": mirror %" PRIu32 " is not 0 or 1", g, mirror);
  return PRT_BLOB_OK;
}

/* Table record q; adds the bytes of its two factorisations to *size. */
static prt_blob_status check_table(const uint8_t* p, const prt_blob_clth_layout* l, uint32_t q,
                                   uint64_t* size, char* msg, size_t cap) {
  const uint8_t* t = p + l->tables + (uint64_t)PRT_BLOB_CLTH_TABLE_SIZE * q;
  const uint32_t rank = prt_le_load_u32(t + PRT_BLOB_CLTH_TABLE_OFF_RANK);
  const uint32_t cone_rank = prt_le_load_u32(t + PRT_BLOB_CLTH_TABLE_OFF_CONE_RANK);
  if (rank < 1u || rank > PRT_BLOB_CLTH_MAX_RANK)
    return FAIL_CORRUPT("table %" PRIu32 ": rank %" PRIu32 " (must be 1..64)", q, rank);
  if (cone_rank < 1u || cone_rank > PRT_BLOB_CLTH_MAX_RANK)
    return FAIL_CORRUPT("table %" PRIu32 ": cone rank %" PRIu32 " (must be 1..64)", q, cone_rank);
  if (!prt_blob_bytes_are_zero(t + PRT_BLOB_CLTH_TABLE_OFF_RESERVED,
                               PRT_BLOB_CLTH_TABLE_SIZE - PRT_BLOB_CLTH_TABLE_OFF_RESERVED))
    return FAIL_CORRUPT("table %" PRIu32 ": reserved fields are not zero", q);
  *size += prt_blob_clth_factor_size(l, rank) + prt_blob_clth_factor_size(l, cone_rank);
  return PRT_BLOB_OK;
}

/* Every record in section order, then the exact size the ranks imply. */
static prt_blob_status check_records(const prt_blob_content* content, const prt_blob_clth_header* h,
                                     const prt_blob_clth_layout* l, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  uint64_t size = l->data;
  prt_blob_status st = PRT_BLOB_OK;
  uint32_t i;
  if ((uint64_t)content->size < l->data)
    return FAIL_CORRUPT("%zu raw bytes cannot hold the header and records (%" PRIu64 " bytes)",
                        content->size, l->data);
  for (i = 0; i < h->fabrics && st == PRT_BLOB_OK; ++i) st = check_fabric(p, h, l, i, msg, cap);
  for (i = 0; i < h->tangents && st == PRT_BLOB_OK; ++i) st = check_tangent(p, h, l, i, msg, cap);
  for (i = 0; i < h->tables && st == PRT_BLOB_OK; ++i) st = check_table(p, l, i, &size, msg, cap);
  if (st != PRT_BLOB_OK) return st;
  if ((uint64_t)content->size != size)
    return FAIL_CORRUPT("%zu raw bytes, the header and ranks imply %" PRIu64, content->size, size);
  return PRT_BLOB_OK;
}

/* Names are UTF-8 and distinct. */
static prt_blob_status check_names(const uint8_t* p, const prt_blob_clth_header* h,
                                   const prt_blob_clth_layout* l, char* msg, size_t cap) {
  uint32_t f, other;
  for (f = 0; f < h->fabrics; ++f) {
    const uint8_t* name = p + l->fabrics + (uint64_t)PRT_BLOB_CLTH_FABRIC_SIZE * f;
    const size_t n = name_length(name);
    if (prt_blob_utf8_error(name, n) < n)
      return FAIL_CORRUPT("fabric %" PRIu32 ": name is not UTF-8", f);
    for (other = 0; other < f; ++other) {
      const uint8_t* earlier = p + l->fabrics + (uint64_t)PRT_BLOB_CLTH_FABRIC_SIZE * other;
      if (memcmp(earlier, name, PRT_BLOB_CLTH_NAME_SIZE) == 0)
        return FAIL_CORRUPT("fabrics %" PRIu32 " and %" PRIu32 " have the same name", other, f);
    }
  }
  return PRT_BLOB_OK;
}

/* The offsets of each thread's tangent records are distinct. */
static prt_blob_status check_offsets(const uint8_t* p, const prt_blob_clth_header* h,
                                     const prt_blob_clth_layout* l, char* msg, size_t cap) {
  uint32_t f, j, a, b;
  for (f = 0; f < h->fabrics; ++f)
    for (j = 0; j < 2u; ++j) {
      const uint8_t* t = p + l->fabrics + (uint64_t)PRT_BLOB_CLTH_FABRIC_SIZE * f +
                         PRT_BLOB_CLTH_FABRIC_OFF_THREADS + PRT_BLOB_CLTH_THREAD_SIZE * j;
      const uint32_t first = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_FIRST);
      const uint32_t count = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_COUNT);
      for (a = 1; a < count; ++a)
        for (b = 0; b < a; ++b) {
          const uint64_t at = l->tangents + (uint64_t)PRT_BLOB_CLTH_TANGENT_SIZE * (first + a);
          const uint64_t bt = l->tangents + (uint64_t)PRT_BLOB_CLTH_TANGENT_SIZE * (first + b);
          const float offset = prt_blob_load_f32(p + at + PRT_BLOB_CLTH_TANGENT_OFF_OFFSET);
          if (offset == prt_blob_load_f32(p + bt + PRT_BLOB_CLTH_TANGENT_OFF_OFFSET))
            return FAIL_CORRUPT("fabric %" PRIu32 " thread %" PRIu32 ": offset %g appears twice", f,
                                j + 1u, (double)offset);
        }
    }
  return PRT_BLOB_OK;
}

/* One block of `count` stored values at p (then its padding): no -128 / -32768, zero padding. */
static prt_blob_status check_values(const uint8_t* p, uint64_t count, uint32_t value_size,
                                    const char* where, const char* block, char* msg, size_t cap) {
  const uint64_t bytes = count * value_size;
  const uint64_t padded = (bytes + 3u) & ~(uint64_t)3u;
  uint64_t i;
  for (i = 0; i < count; ++i) {
    const int bad = value_size == 1u ? p[i] == 0x80u : prt_le_load_u16(p + 2u * i) == 0x8000u;
    if (bad)
      return FAIL_CORRUPT("%s: %s value %" PRIu64 " is %s", where, block, i,
                          value_size == 1u ? "-128" : "-32768");
  }
  if (!prt_blob_bytes_are_zero(p + bytes, (size_t)(padded - bytes)))
    return FAIL_CORRUPT("%s: padding after the %s values is not zero", where, block);
  return PRT_BLOB_OK;
}

/* One factorisation's data at `at`: scales finite and >= 0, then the V and the U values. */
static prt_blob_status check_factor(const uint8_t* p, const prt_blob_clth_layout* l, uint64_t at,
                                    uint32_t rank, const char* where, char* msg, size_t cap) {
  const uint64_t v_values = at + 8u * (uint64_t)rank;
  const uint64_t u_values = v_values + ((l->columns * rank * l->value_size + 3u) & ~(uint64_t)3u);
  prt_blob_status st;
  uint32_t r;
  for (r = 0; r < 2u * rank; ++r) {
    const float scale = prt_blob_load_f32(p + at + 4u * r);
    const char* which = r < rank ? "u_scale" : "v_scale";
    if (!prt_blob_f32_is_finite(scale))
      return FAIL_NON_FINITE("%s: %s[%" PRIu32 "] is not finite", where, which, r % rank);
    if (scale < 0.0f)
      return FAIL_CORRUPT("%s: %s[%" PRIu32 "] is negative", where, which, r % rank);
  }
  st = check_values(p + v_values, l->columns * rank, l->value_size, where, "V", msg, cap);
  if (st != PRT_BLOB_OK) return st;
  return check_values(p + u_values, l->rows * rank, l->value_size, where, "U", msg, cap);
}

/* Every table's two factorisations, in section order. */
static prt_blob_status check_data(const uint8_t* p, const prt_blob_clth_header* h,
                                  const prt_blob_clth_layout* l, char* msg, size_t cap) {
  uint64_t at = l->data;
  uint32_t q;
  int cone;
  for (q = 0; q < h->tables; ++q)
    for (cone = 0; cone < 2; ++cone) {
      const uint8_t* record = p + l->tables + (uint64_t)PRT_BLOB_CLTH_TABLE_SIZE * q;
      const uint32_t rank = prt_le_load_u32(
          record + (cone ? PRT_BLOB_CLTH_TABLE_OFF_CONE_RANK : PRT_BLOB_CLTH_TABLE_OFF_RANK));
      char where[32];
      prt_blob_status st;
      snprintf(where, sizeof where, "table %" PRIu32 " %s", q, cone ? "T_c" : "T");
      st = check_factor(p, l, at, rank, where, msg, cap);
      if (st != PRT_BLOB_OK) return st;
      at += prt_blob_clth_factor_size(l, rank);
    }
  return PRT_BLOB_OK;
}

prt_blob_status prt_blob_check_clth(const prt_blob_content* content, char* msg, size_t cap) {
  const uint8_t* p = content->bytes;
  prt_blob_clth_header h;
  prt_blob_clth_layout l = {0};
  prt_blob_status st;
  if (content->size < PRT_BLOB_CLTH_HEADER_SIZE)
    return FAIL_CORRUPT("%zu bytes cannot hold the 64-byte header", content->size);
  st = check_header(content, &h, &l, msg, cap);
  if (st == PRT_BLOB_OK) st = check_records(content, &h, &l, msg, cap);
  if (st == PRT_BLOB_OK) st = check_names(p, &h, &l, msg, cap);
  if (st == PRT_BLOB_OK) st = check_offsets(p, &h, &l, msg, cap);
  if (st == PRT_BLOB_OK) st = check_data(p, &h, &l, msg, cap);
  return st;
}
