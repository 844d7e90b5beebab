/* SPDX-License-Identifier: MIT */
/* Technique `wavelet` in the runtime's technique table: the WVLT header decoded and checked
 * against the section at load (either validation level), the view every `wavelet` function
 * reads, and the ties of the `wavelet` constants to the formats layer's. */
#include <inttypes.h>
#include <stdio.h>

#include "internal.h"
#include "techniques.h"
#include "wavelet_internal.h"

PRT_STATIC_ASSERT(PRT_SECTION_WVLT == PRT_BLOB_TAG_WVLT, tag_wvlt);
PRT_STATIC_ASSERT(PRT_WAVELET_PARAM_CUBE == PRT_BLOB_WVLT_PARAM_CUBE, param_cube);
PRT_STATIC_ASSERT(PRT_WAVELET_PARAM_DUAL_PARABOLOID == PRT_BLOB_WVLT_PARAM_DUAL_PARABOLOID,
                  param_dual_paraboloid);
PRT_STATIC_ASSERT(PRT_WAVELET_QUANTIZER_VERTEX == PRT_BLOB_WVLT_QUANTIZER_VERTEX, quantizer_vertex);
PRT_STATIC_ASSERT(PRT_WAVELET_QUANTIZER_BAND == PRT_BLOB_WVLT_QUANTIZER_BAND, quantizer_band);
PRT_STATIC_ASSERT(PRT_WAVELET_MIN_SIZE == PRT_BLOB_WVLT_MIN_SIZE, wavelet_min_size);
PRT_STATIC_ASSERT(PRT_WAVELET_MAX_SIZE == PRT_BLOB_WVLT_MAX_SIZE, wavelet_max_size);
PRT_STATIC_ASSERT(PRT_WAVELET_MAX_BLOCKS ==
                      6u * PRT_BLOB_WVLT_MAX_SIZE * PRT_BLOB_WVLT_MAX_SIZE / PRT_BLOB_WVLT_BLOCK,
                  wavelet_max_blocks);

static prt_result corrupt(char* msg, size_t capacity, const char* what) {
  snprintf(msg, capacity, "'WVLT': %s", what);
  return PRT_ERROR_CORRUPT;
}

/* The header fields the formats checker checks, in its order and words, then rs[V] = P; the rows
 * themselves are for full validation (and are checked again as shading walks them). */
static prt_result open_wvlt(const prt_asset_section* section, void* out, char* msg,
                            size_t capacity) {
  prt_wavelet_view* view = (prt_wavelet_view*)out;
  prt_wavelet_info* info = &view->info;
  prt_blob_wvlt_layout* l = &view->layout;
  const uint8_t* p = section->data;
  const uint64_t size = section->entry.raw_size;
  prt_blob_wvlt_header header;
  uint32_t param, quantizer;
  char what[160];
  if (!p || size < PRT_BLOB_WVLT_HEADER_SIZE) {
    snprintf(what, sizeof what, "%" PRIu64 " bytes cannot hold the 32-byte header", size);
    return corrupt(msg, capacity, what);
  }
  memset(info, 0, sizeof *info);
  prt_blob_wvlt_read_header(p, &header);
  info->struct_size = sizeof *info;
  param = header.param;
  info->size = header.size;
  info->vertex_count = header.vertices;
  quantizer = header.quantizer;
  info->keep = header.keep;
  info->bounces = header.bounces;
  info->pair_count = header.pair_count;
  if (param != PRT_BLOB_WVLT_PARAM_CUBE && param != PRT_BLOB_WVLT_PARAM_DUAL_PARABOLOID) {
    snprintf(what, sizeof what, "param %" PRIu32 " is not 0 or 1", param);
    return corrupt(msg, capacity, what);
  }
  if (!prt_blob_wvlt_layout_of(param, info->size, info->vertex_count, info->pair_count, l)) {
    snprintf(what, sizeof what, "face size %" PRIu32 " is not a power of two in 16..128",
             info->size);
    return corrupt(msg, capacity, what);
  }
  if (quantizer != PRT_BLOB_WVLT_QUANTIZER_VERTEX && quantizer != PRT_BLOB_WVLT_QUANTIZER_BAND) {
    snprintf(what, sizeof what, "quantizer %" PRIu32 " is not 0 or 1", quantizer);
    return corrupt(msg, capacity, what);
  }
  if (header.reserved != 0) return corrupt(msg, capacity, "reserved header field is not zero");
  if ((uint64_t)info->vertex_count != section->entry.element_count) {
    snprintf(what, sizeof what, "header says %" PRIu32 " vertices, element count %" PRIu64,
             info->vertex_count, section->entry.element_count);
    return corrupt(msg, capacity, what);
  }
  if (l->raw_size != size) {
    snprintf(what, sizeof what, "%" PRIu64 " raw bytes, the header implies %" PRIu64, size,
             l->raw_size);
    return corrupt(msg, capacity, what);
  }
  if (prt_le_load_u32(p + l->row_start + 4u * (uint64_t)info->vertex_count) != info->pair_count) {
    snprintf(what, sizeof what, "the last row start is not the pair count %" PRIu32,
             info->pair_count);
    return corrupt(msg, capacity, what);
  }
  info->param = (prt_wavelet_param)param;
  info->quantizer = (prt_wavelet_quantizer)quantizer;
  info->faces = l->faces;
  info->coefficient_count = l->coefficients;
  info->block_count = l->blocks;
  view->section = p;
  view->band_scale = p + l->band_scale;
  view->rows.vertex_scale = p + l->vertex_scale;
  view->rows.row_start = p + l->row_start;
  view->rows.counts = p + l->counts;
  view->rows.pairs = p + l->pairs;
  view->rows.light = NULL;
  view->rows.skip = NULL;
  view->rows.blocks = l->blocks;
  view->rows.pair_count = info->pair_count;
  return PRT_OK;
}

extern const struct prt_scene_hooks prt_wavelet_scene_hooks; /* wavelet/wavelet_scene_hooks.c */

const prt_technique_entry prt_wavelet_technique_entry = {
    PRT_TECHNIQUE_WAVELET,
    "wavelet",
    PRT_BLOB_TAG_WVLT,
    sizeof(prt_wavelet_view),
    open_wvlt,
    prt_wavelet_attach_tiles,
    prt_wavelet_release_tiles,
    &prt_wavelet_scene_hooks,
};
