/* SPDX-License-Identifier: MIT */
/* The readers of the CLTH view (cloth_internal.h): records and factorisations at the offsets the
 * load checked (cloth_section.c), so they read inside the section whatever the validation level. */
#include "cloth_internal.h"

static const uint8_t* fabric_at(const prt_cloth_view* view, uint32_t fabric) {
  return view->data + view->layout.fabrics + (uint64_t)PRT_BLOB_CLTH_FABRIC_SIZE * fabric;
}

static void read_thread(const uint8_t* t, prt_cloth_thread* out) {
  int c;
  out->eta = prt_blob_clth_load_f32(t + PRT_BLOB_CLTH_THREAD_OFF_ETA);
  for (c = 0; c < 3; ++c)
    out->albedo[c] = prt_blob_clth_load_f32(t + PRT_BLOB_CLTH_THREAD_OFF_ALBEDO + 4u * c);
  out->kd = prt_blob_clth_load_f32(t + PRT_BLOB_CLTH_THREAD_OFF_KD);
  out->gamma_s = prt_blob_clth_load_f32(t + PRT_BLOB_CLTH_THREAD_OFF_GAMMA_S);
  out->gamma_v = prt_blob_clth_load_f32(t + PRT_BLOB_CLTH_THREAD_OFF_GAMMA_V);
  out->coverage = prt_blob_clth_load_f32(t + PRT_BLOB_CLTH_THREAD_OFF_COVERAGE);
}

void prt_cloth_read_fabric(const prt_cloth_view* view, uint32_t fabric,
                           prt_cloth_fabric_record* out) {
  const uint8_t* p = fabric_at(view, fabric);
  int j;
  memset(out, 0, sizeof *out);
  memcpy(out->name, p + PRT_BLOB_CLTH_FABRIC_OFF_NAME, PRT_BLOB_CLTH_NAME_SIZE);
  out->params.struct_size = sizeof out->params;
  for (j = 0; j < 2; ++j) {
    const uint8_t* t = p + PRT_BLOB_CLTH_FABRIC_OFF_THREADS + PRT_BLOB_CLTH_THREAD_SIZE * j;
    read_thread(t, &out->params.threads[j]);
    out->first_tangent[j] = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_FIRST);
    out->tangent_count[j] = prt_le_load_u32(t + PRT_BLOB_CLTH_THREAD_OFF_COUNT);
  }
}

void prt_cloth_read_tangent(const prt_cloth_view* view, uint32_t tangent,
                            prt_cloth_tangent_record* out) {
  const uint8_t* t =
      view->data + view->layout.tangents + (uint64_t)PRT_BLOB_CLTH_TANGENT_SIZE * tangent;
  out->offset = prt_blob_clth_load_f32(t + PRT_BLOB_CLTH_TANGENT_OFF_OFFSET);
  out->multiplicity = prt_le_load_u32(t + PRT_BLOB_CLTH_TANGENT_OFF_MULTIPLICITY);
  out->table = prt_le_load_u32(t + PRT_BLOB_CLTH_TANGENT_OFF_TABLE);
  out->mirror = prt_le_load_u32(t + PRT_BLOB_CLTH_TANGENT_OFF_MIRROR);
}

void prt_cloth_read_factor(const prt_cloth_view* view, uint32_t table, int cone,
                           prt_cloth_factor* out) {
  const uint32_t rank = view->factor_rank[table][cone ? 1 : 0];
  const uint8_t* at = view->data + view->factor_offset[table][cone ? 1 : 0];
  const uint64_t v_bytes = view->layout.columns * rank * view->layout.value_size;
  out->rank = rank;
  out->bits = view->header.bits;
  out->u_scale = at;
  out->v_scale = at + 4u * rank;
  out->v_values = at + 8u * rank;
  out->u_values = at + 8u * rank + ((v_bytes + 3u) & ~(uint64_t)3u);
}

void prt_cloth_fabric_weave(const prt_cloth_view* view, const prt_cloth_fabric_record* fabric,
                            prt_cloth_weave* out) {
  uint32_t j, k;
  memset(out, 0, sizeof *out);
  out->struct_size = sizeof *out;
  for (j = 0; j < 2u; ++j) {
    out->tangent_count[j] = fabric->tangent_count[j];
    for (k = 0; k < fabric->tangent_count[j]; ++k) {
      prt_cloth_tangent_record t;
      prt_cloth_read_tangent(view, fabric->first_tangent[j] + k, &t);
      out->offsets[j][k] = t.offset;
      out->multiplicity[j][k] = t.multiplicity;
    }
  }
}
