/* SPDX-License-Identifier: MIT */
/* Private to the runtime: technique `cloth`'s shared pieces. The CLTH view the load keeps
 * (cloth_section.c: header, records and size checked, so every accessor below reads inside the
 * section whatever the validation level), the exact model in double (cloth_model.c, the terms of
 * docs/cloth/model.md that the kernel, the reference and the shading share) and the struct-size
 * constants of prt_cloth.h / prt_cloth_asset.h. */
#ifndef PRT_RUNTIME_CLOTH_INTERNAL_H
#define PRT_RUNTIME_CLOTH_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include <prt/format/cloth_layout.h>
#include <prt/prt_cloth.h>
#include <prt/prt_cloth_asset.h>

#include "internal.h"

#define PRT_CLOTH_PARAMS_SIZE_1_0 PRT_SIZE_THROUGH(prt_cloth_params, threads)
#define PRT_CLOTH_WEAVE_SIZE_1_0 PRT_SIZE_THROUGH(prt_cloth_weave, multiplicity)
#define PRT_CLOTH_ENV_TEXELS_SIZE_1_0 PRT_SIZE_THROUGH(prt_cloth_env_texels, power)
#define PRT_CLOTH_PIXELS_SIZE_1_0 PRT_SIZE_THROUGH(prt_cloth_pixels, views)
#define PRT_CLOTH_LIGHT_SIZE_1_0 PRT_SIZE_THROUGH(prt_cloth_light, lobes)
#define PRT_CLOTH_FIT_DESC_SIZE_1_0 PRT_SIZE_THROUGH(prt_cloth_fit_desc, iterations)
#define PRT_CLOTH_FIT_REPORT_SIZE_1_0 PRT_SIZE_THROUGH(prt_cloth_fit_report, power_error)
#define PRT_CLOTH_INFO_SIZE_1_0 PRT_SIZE_THROUGH(prt_cloth_info, table_bytes)
#define PRT_CLOTH_SETTINGS_SIZE_1_0 PRT_SIZE_THROUGH(prt_cloth_settings, phi_nodes)
#define PRT_GL_CLOTH_GBUFFER_SIZE_1_0 PRT_SIZE_THROUGH(prt_gl_cloth_gbuffer, view_texture)

/* ---- The CLTH view ------------------------------------------------------------------------- */

/* One factorisation of a table (T or its cone restriction T_c): value(row, column) =
 * sum_r u_scale[r] u[row][r] * v_scale[r] v[column][r], with u, v signed 8- or 16-bit. */
typedef struct prt_cloth_factor {
  uint32_t rank;
  uint32_t bits;        /* 8 or 16 */
  const uint8_t* u_scale; /* f32[rank], little-endian, 4-byte aligned in the section */
  const uint8_t* v_scale; /* f32[rank] */
  const void* u_values;   /* [rows][rank]: row = level xi_size^2 + j xi_size + i */
  const void* v_values;   /* [columns][rank]: column = a view_phi + b */
} prt_cloth_factor;

/* The CLTH section of a loaded asset. */
typedef struct prt_cloth_view {
  prt_cloth_info info;
  prt_blob_clth_header header;
  prt_blob_clth_layout layout;
  const uint8_t* data; /* the section's bytes */
  /* Each fabric's name, NUL-terminated (what prt_cloth_get_fabric hands out: a stored name of 32
   * bytes has no NUL of its own). */
  char names[PRT_BLOB_CLTH_MAX_FABRICS][PRT_BLOB_CLTH_NAME_SIZE + 1];
  /* Offset of each table's two factorisations' data ([q][0]: T, [q][1]: T_c) from data, and
   * their ranks, summed from the table records at load. */
  uint64_t factor_offset[PRT_BLOB_CLTH_MAX_TABLES][2];
  uint32_t factor_rank[PRT_BLOB_CLTH_MAX_TABLES][2];
} prt_cloth_view;

/* A fabric of the view: name (NUL-terminated copy), default parameters and each thread's tangent
 * record range. */
typedef struct prt_cloth_fabric_record {
  char name[PRT_BLOB_CLTH_NAME_SIZE + 1];
  prt_cloth_params params;
  uint32_t first_tangent[2];
  uint32_t tangent_count[2];
} prt_cloth_fabric_record;

typedef struct prt_cloth_tangent_record {
  float offset; /* tau, radians */
  uint32_t multiplicity;
  uint32_t table;
  uint32_t mirror;
} prt_cloth_tangent_record;

/* Readers of a view's records (index below the header's count: the caller checks). */
void prt_cloth_read_fabric(const prt_cloth_view* view, uint32_t fabric,
                           prt_cloth_fabric_record* out);
void prt_cloth_read_tangent(const prt_cloth_view* view, uint32_t tangent,
                            prt_cloth_tangent_record* out);
void prt_cloth_read_factor(const prt_cloth_view* view, uint32_t table, int cone,
                           prt_cloth_factor* out);
/* The fabric's weave as prt_cloth_weave (offsets and multiplicities of its tangent records). */
void prt_cloth_fabric_weave(const prt_cloth_view* view, const prt_cloth_fabric_record* fabric,
                            prt_cloth_weave* out);

/* ---- The exact model (cloth_model.c), double precision ------------------------------------- */

/* A surface frame: unit normal n, warp u (orthogonal to n), weft v = n x u. */
typedef struct prt_cloth_frame {
  double n[3], u[3], v[3];
} prt_cloth_frame;

/* Builds the frame from a normal and a warp (normalised, warp made orthogonal to the normal);
 * returns 0 for a zero or non-finite vector or a warp parallel to the normal. */
int prt_cloth_make_frame(const float normal[3], const float warp[3], prt_cloth_frame* out);

/* The tilted fibre frame (t, n', b) of thread j (0 warp, 1 weft) at offset tau
 * (docs/cloth/model.md, Frames). */
typedef struct prt_cloth_fibre {
  double t[3], n[3], b[3];
} prt_cloth_fibre;
void prt_cloth_fibre_frame(const prt_cloth_frame* frame, int thread, double tau,
                           prt_cloth_fibre* out);

/* Exact unpolarised Fresnel reflectance from air into relative index eta at incidence cosine c
 * (clamped to [0, 1]). */
double prt_cloth_fresnel(double eta, double c);

/* f_s(t, w_i, w_o) cos(theta_i) of one fibre (RGB) and its M and P, for unit w_i, w_o. */
void prt_cloth_fibre_scatter(const prt_cloth_thread* thread, const prt_cloth_fibre* fibre,
                             const double wi[3], const double wo[3], double out_rgb[3],
                             double* out_m, double* out_p);

/* The kernel k(w_i, w_o) of the whole cloth (RGB), 0 below the surface. */
void prt_cloth_kernel_d(const prt_cloth_params* params, const prt_cloth_weave* weave,
                        const prt_cloth_frame* frame, const double wi[3], const double wo[3],
                        double out_rgb[3]);

#endif /* PRT_RUNTIME_CLOTH_INTERNAL_H */
