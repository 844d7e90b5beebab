/* SPDX-License-Identifier: MIT */
/* The `cloth` section CLTH, layout version 1 (formats/SPEC.md §7.4): woven fabrics for the
 * microcylinder model (docs/cloth/model.md), each a record of its two threads' default live
 * parameters and tangent offsets, and the precomputed shadowing/masking convolution tables of its
 * tangents, SVD-factored and quantised. Element = material (one fabric); the section counts the
 * material domain. A 64-byte header, the fabric records, the tangent records, the table records,
 * then each table's data; the size follows from the header and the table ranks
 * (prt_blob_clth_layout_of). Plain C99, pure functions. */
#ifndef PRT_FORMAT_CLOTH_LAYOUT_H
#define PRT_FORMAT_CLOTH_LAYOUT_H

#include <prt/format/blob_layout.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRT_BLOB_TAG_CLTH PRT_BLOB_TAG('C', 'L', 'T', 'H')

#define PRT_BLOB_CLTH_HEADER_SIZE 64u
#define PRT_BLOB_CLTH_MAX_FABRICS 64u
#define PRT_BLOB_CLTH_MAX_TANGENTS 1024u        /* tangent records, all fabrics */
#define PRT_BLOB_CLTH_MAX_TABLES 1024u          /* table records */
#define PRT_BLOB_CLTH_MAX_THREAD_TANGENTS 16u   /* distinct offsets of one thread */
#define PRT_BLOB_CLTH_MAX_MULTIPLICITY 64u      /* repeats of one offset in a thread's multiset */
#define PRT_BLOB_CLTH_MAX_GRID 256u             /* xi_size, view_theta, view_phi */
#define PRT_BLOB_CLTH_MAX_LEVELS 64u            /* lambda_levels */
#define PRT_BLOB_CLTH_MAX_RANK 64u              /* rank of one factorisation */
/* a_1 + a_2 <= 1 + this, in double: float pairs whose decimal sum is 1 (0.86f + 0.14f) pass. */
#define PRT_BLOB_CLTH_COVERAGE_SLACK 1e-6

/* pi and pi/2 as the f32 nearest them (each just above the real number), the bounds the ranges
 * below are checked against: a stored f32 x is in (0, pi] when 0 < x <= PRT_BLOB_CLTH_PI_F32. */
#define PRT_BLOB_CLTH_PI_F32 3.14159274f
#define PRT_BLOB_CLTH_HALF_PI_F32 1.57079637f

/* Header, 64 bytes. */
#define PRT_BLOB_CLTH_OFF_FABRICS 0u       /* u32: F, 1..64 = the section's element count */
#define PRT_BLOB_CLTH_OFF_TANGENTS 4u      /* u32: G, 1..1024 tangent records */
#define PRT_BLOB_CLTH_OFF_TABLES 8u        /* u32: Q, 1..1024 table records */
#define PRT_BLOB_CLTH_OFF_XI_SIZE 12u      /* u32: N_xi, 2..256 octahedral nodes per side */
#define PRT_BLOB_CLTH_OFF_LEVELS 16u       /* u32: L, 1..64 lobe-sharpness levels */
#define PRT_BLOB_CLTH_OFF_LAMBDA_MIN 20u   /* f32: sharpness of level 0, finite, > 0 */
#define PRT_BLOB_CLTH_OFF_LAMBDA_MAX 24u   /* f32: of level L-1, finite, >= min (= min if L = 1) */
#define PRT_BLOB_CLTH_OFF_VIEW_THETA 28u   /* u32: N_theta, 2..256 view nodes over [0, pi/2] */
#define PRT_BLOB_CLTH_OFF_VIEW_PHI 32u     /* u32: N_phi, 2..256 view nodes over [0, pi] */
#define PRT_BLOB_CLTH_OFF_BITS 36u         /* u32: 8 or 16 bits per stored factor value */
#define PRT_BLOB_CLTH_OFF_FLAGS 40u        /* u32: 0 (no flag is defined in layout 1) */
#define PRT_BLOB_CLTH_OFF_RESERVED 44u     /* u32[5], zero */
#define PRT_BLOB_CLTH_RESERVED_SIZE 20u

/* A fabric record, 160 bytes: a name, then thread 1 (warp) and thread 2 (weft). */
#define PRT_BLOB_CLTH_FABRIC_SIZE 160u
#define PRT_BLOB_CLTH_NAME_SIZE 32u /* UTF-8, at least one byte, NUL-padded to 32 */
#define PRT_BLOB_CLTH_FABRIC_OFF_NAME 0u
#define PRT_BLOB_CLTH_FABRIC_OFF_THREADS 32u

/* A thread record, 64 bytes: the default live parameters and the thread's tangent records
 * [first, first + count) (distinct offsets, each with its multiplicity). */
#define PRT_BLOB_CLTH_THREAD_SIZE 64u
#define PRT_BLOB_CLTH_THREAD_OFF_ETA 0u        /* f32: index of refraction, finite, in [1, 4] */
#define PRT_BLOB_CLTH_THREAD_OFF_ALBEDO 4u     /* f32[3]: volume albedo A, finite, in [0, 1] */
#define PRT_BLOB_CLTH_THREAD_OFF_KD 16u        /* f32: isotropic fraction k_d, in [0, 1] */
#define PRT_BLOB_CLTH_THREAD_OFF_GAMMA_S 20u   /* f32: surface lobe width, radians, (0, pi] */
#define PRT_BLOB_CLTH_THREAD_OFF_GAMMA_V 24u   /* f32: volume lobe width, radians, (0, pi] */
#define PRT_BLOB_CLTH_THREAD_OFF_COVERAGE 28u  /* f32: area fraction a_j, in [0, 1] */
#define PRT_BLOB_CLTH_THREAD_OFF_FIRST 32u     /* u32: first tangent record */
#define PRT_BLOB_CLTH_THREAD_OFF_COUNT 36u     /* u32: 1..16 tangent records */
#define PRT_BLOB_CLTH_THREAD_OFF_RESERVED 40u  /* u32[6], zero */

/* A tangent record, 16 bytes: one distinct offset of a thread's multiset. */
#define PRT_BLOB_CLTH_TANGENT_SIZE 16u
#define PRT_BLOB_CLTH_TANGENT_OFF_OFFSET 0u       /* f32: tau, radians, finite, |tau| <= pi/2 */
#define PRT_BLOB_CLTH_TANGENT_OFF_MULTIPLICITY 4u /* u32: 1..64 repeats in the multiset */
#define PRT_BLOB_CLTH_TANGENT_OFF_TABLE 8u        /* u32: table record, < Q */
#define PRT_BLOB_CLTH_TANGENT_OFF_MIRROR 12u      /* u32: 0, or 1: read the table with x -> -x */

/* A table record, 16 bytes: the ranks of the table's two factorisations (the lobe-weighted
 * convolution T, then its restriction to the specular cone T_c). */
#define PRT_BLOB_CLTH_TABLE_SIZE 16u
#define PRT_BLOB_CLTH_TABLE_OFF_RANK 0u      /* u32: R of T, 1..64 */
#define PRT_BLOB_CLTH_TABLE_OFF_CONE_RANK 4u /* u32: R of T_c, 1..64 */
#define PRT_BLOB_CLTH_TABLE_OFF_RESERVED 8u  /* u32[2], zero */

/* The header fields, as stored. */
typedef struct prt_blob_clth_header {
  uint32_t fabrics;
  uint32_t tangents;
  uint32_t tables;
  uint32_t xi_size;
  uint32_t levels;
  float lambda_min;
  float lambda_max;
  uint32_t view_theta;
  uint32_t view_phi;
  uint32_t bits;
  uint32_t flags;
} prt_blob_clth_header;

/* A little-endian f32 (the bits of prt_le_load_u32). */
static inline float prt_blob_clth_load_f32(const uint8_t* p) {
  union {
    uint32_t u;
    float f;
  } v;
  v.u = prt_le_load_u32(p);
  return v.f;
}

/* Reads the header from the section's first PRT_BLOB_CLTH_HEADER_SIZE bytes (the caller checks
 * that they are there). The reserved words are not part of it. */
static inline void prt_blob_clth_read_header(const uint8_t* p, prt_blob_clth_header* out) {
  out->fabrics = prt_le_load_u32(p + PRT_BLOB_CLTH_OFF_FABRICS);
  out->tangents = prt_le_load_u32(p + PRT_BLOB_CLTH_OFF_TANGENTS);
  out->tables = prt_le_load_u32(p + PRT_BLOB_CLTH_OFF_TABLES);
  out->xi_size = prt_le_load_u32(p + PRT_BLOB_CLTH_OFF_XI_SIZE);
  out->levels = prt_le_load_u32(p + PRT_BLOB_CLTH_OFF_LEVELS);
  out->lambda_min = prt_blob_clth_load_f32(p + PRT_BLOB_CLTH_OFF_LAMBDA_MIN);
  out->lambda_max = prt_blob_clth_load_f32(p + PRT_BLOB_CLTH_OFF_LAMBDA_MAX);
  out->view_theta = prt_le_load_u32(p + PRT_BLOB_CLTH_OFF_VIEW_THETA);
  out->view_phi = prt_le_load_u32(p + PRT_BLOB_CLTH_OFF_VIEW_PHI);
  out->bits = prt_le_load_u32(p + PRT_BLOB_CLTH_OFF_BITS);
  out->flags = prt_le_load_u32(p + PRT_BLOB_CLTH_OFF_FLAGS);
}

/* Where the fixed parts of a CLTH section lie (offsets in bytes from the section's first byte,
 * each a multiple of 4), and how big one factorisation's data is per unit of rank:
 *   fabrics  F records of PRT_BLOB_CLTH_FABRIC_SIZE
 *   tangents G records of PRT_BLOB_CLTH_TANGENT_SIZE
 *   tables   Q records of PRT_BLOB_CLTH_TABLE_SIZE
 *   data     table 0's T, table 0's T_c, table 1's T, ... each factorisation of rank R being
 *              f32 u_scale[R], f32 v_scale[R],
 *              V values  [N_theta N_phi][R]   (column c = a N_phi + b: view node (a, b))
 *              U values  [L N_xi^2][R]        (row = level N_xi^2 + j N_xi + i: lobe node)
 *            with the value blocks (signed 8- or 16-bit) each padded with zeros to 4 bytes. */
typedef struct prt_blob_clth_layout {
  uint32_t value_size; /* bytes per stored factor value: bits / 8 */
  uint64_t rows;       /* L N_xi^2 */
  uint64_t columns;    /* N_theta N_phi */
  uint64_t fabrics;
  uint64_t tangents;
  uint64_t tables;
  uint64_t data; /* the first factorisation's u_scale */
} prt_blob_clth_layout;

/* Fills *out for a header whose counts are within the limits above and returns 1; returns 0
 * (out untouched) otherwise. The data's size needs the ranks: prt_blob_clth_factor_size. */
static inline int prt_blob_clth_layout_of(const prt_blob_clth_header* h,
                                          prt_blob_clth_layout* out) {
  uint64_t at;
  if (h->fabrics < 1u || h->fabrics > PRT_BLOB_CLTH_MAX_FABRICS) return 0;
  if (h->tangents < 1u || h->tangents > PRT_BLOB_CLTH_MAX_TANGENTS) return 0;
  if (h->tables < 1u || h->tables > PRT_BLOB_CLTH_MAX_TABLES) return 0;
  if (h->xi_size < 2u || h->xi_size > PRT_BLOB_CLTH_MAX_GRID) return 0;
  if (h->levels < 1u || h->levels > PRT_BLOB_CLTH_MAX_LEVELS) return 0;
  if (h->view_theta < 2u || h->view_theta > PRT_BLOB_CLTH_MAX_GRID) return 0;
  if (h->view_phi < 2u || h->view_phi > PRT_BLOB_CLTH_MAX_GRID) return 0;
  if (h->bits != 8u && h->bits != 16u) return 0;
  out->value_size = h->bits / 8u;
  out->rows = (uint64_t)h->levels * h->xi_size * h->xi_size;
  out->columns = (uint64_t)h->view_theta * h->view_phi;
  at = PRT_BLOB_CLTH_HEADER_SIZE;
  out->fabrics = at;
  at += (uint64_t)PRT_BLOB_CLTH_FABRIC_SIZE * h->fabrics;
  out->tangents = at;
  at += (uint64_t)PRT_BLOB_CLTH_TANGENT_SIZE * h->tangents;
  out->tables = at;
  at += (uint64_t)PRT_BLOB_CLTH_TABLE_SIZE * h->tables;
  out->data = at;
  return 1;
}

/* Bytes of one factorisation of rank R (1..64) in a section of this layout: the two scale
 * arrays and the two padded value blocks. At most 8 + 2 (256^2 + 64 256^2) 64 bytes each, so a
 * sum over 2048 factorisations stays far below 2^64. */
static inline uint64_t prt_blob_clth_factor_size(const prt_blob_clth_layout* l, uint32_t rank) {
  uint64_t v = (l->columns * rank * l->value_size + 3u) & ~(uint64_t)3u;
  uint64_t u = (l->rows * rank * l->value_size + 3u) & ~(uint64_t)3u;
  return 8u * (uint64_t)rank + v + u;
}

#ifdef __cplusplus
}
#endif

#endif /* PRT_FORMAT_CLOTH_LAYOUT_H */
