/* SPDX-License-Identifier: MIT */
/* The GL backend of `cloth` shading (prt_cloth_asset.h): per call, the light and the fabric are
 * prepared on the CPU by the scalar reference's own functions (prt_cloth_prepare_light,
 * prt_cloth_prepare_fabric, prt_cloth_method_of) and packed into a uniform block; per pixel, a
 * fragment shader (cloth_gl_glsl.c) drawn as one full-screen triangle over the caller's G-buffer
 * evaluates the method in float. The tables are one shader storage buffer holding the section's
 * table data as stored: the 8- or 16-bit values are dequantised exactly in the shader and every
 * lookup's bilinear (and across levels linear) weights are computed there as in cloth_tables.c,
 * with no dependence on a GPU's filtering precision and no texture-size limit. */
#include "internal.h"

#if !defined(PRT_HAS_GL)
prt_result prt_gl_cloth_create(prt_context* context, const prt_asset* asset,
                               prt_gl_loader_fn loader, void* loader_user,
                               prt_gl_cloth_shader** out_shader) {
  (void)asset, (void)loader, (void)loader_user;
  if (out_shader) *out_shader = NULL;
  return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                           "prt_gl_cloth_create: compiled out (PRT_ENABLE_GL=OFF)");
}
void prt_gl_cloth_destroy(prt_gl_cloth_shader* shader) {
  (void)shader;
}
prt_result prt_gl_cloth_shade(prt_gl_cloth_shader* shader, uint32_t fabric,
                              const prt_cloth_params* params, const prt_cloth_light* light,
                              const prt_cloth_settings* settings,
                              const prt_gl_cloth_gbuffer* gbuffer) {
  (void)shader, (void)fabric, (void)params, (void)light, (void)settings, (void)gbuffer;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
#else /* PRT_HAS_GL */

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cloth_gl_internal.h"
#include "gl_common.h"
#include "techniques.h"

#define FUNCTION_CREATE "prt_gl_cloth_create"
#define HALF_PI 1.57079632679489661923
/* cloth_integrals.c's MERGE_WIDTH: a lobed part at least this many times wider than the light's
 * lobe shares the lobe's theta window. */
#define MERGE_WIDTH 1.5
/* G-buffer texture units: normal, warp, view. */
#define GBUFFER_UNITS 3u

enum { BUFFER_TABLES = 0, BUFFER_CALL = 1, BUFFER_COUNT = 2 };

struct prt_gl_cloth_shader {
  prt_allocator allocator; /* the asset's */
  prt_gl_functions gl;
  const prt_cloth_view* view;
  prt_GLuint program;
  prt_GLuint vertex_array;
  prt_GLuint buffers[BUFFER_COUNT];
  /* Per-call scratch, kept here rather than on the render thread's stack. */
  prt_cloth_light_prep light;
  prt_cloth_fabric_prep fabric;
  prt_cloth_gl_block block;
};

/* ---- create / destroy ------------------------------------------------------------------ */

static uint32_t largest_rank(const prt_cloth_view* view) {
  uint32_t q, c, rank = 1;
  for (q = 0; q < view->header.tables; ++q)
    for (c = 0; c < 2; ++c)
      if (view->factor_rank[q][c] > rank) rank = view->factor_rank[q][c];
  return rank;
}

/* The fragment shader's header: the #version line and the asset's grid constants. */
static prt_result compile_program(prt_context* context, prt_gl_cloth_shader* s) {
  const prt_blob_clth_header* h = &s->view->header;
  const prt_GLchar* vertex[1];
  const prt_GLchar* fragment[1 + PRT_CLOTH_GL_FRAGMENT_PARTS];
  char header[512];
  int i;
  snprintf(header, sizeof header,
           "#version 430 core\n#define BITS %u\n#define MAX_RANK %u\n#define XI_SIZE %u\n"
           "#define LEVELS %u\n#define VIEW_THETA %u\n#define VIEW_PHI %u\n"
           "#define MAX_TANGENTS %u\n#define MAX_LOBES %u\n",
           (unsigned)h->bits, (unsigned)largest_rank(s->view), (unsigned)h->xi_size,
           (unsigned)h->levels, (unsigned)h->view_theta, (unsigned)h->view_phi,
           (unsigned)PRT_CLOTH_GL_MAX_TANGENTS, (unsigned)PRT_CLOTH_MAX_LOBES);
  vertex[0] = prt_cloth_gl_vertex_source;
  fragment[0] = header;
  for (i = 0; i < PRT_CLOTH_GL_FRAGMENT_PARTS; ++i)
    fragment[1 + i] = prt_cloth_gl_fragment_sources[i];
  return prt_gl_compile_draw(context, &s->gl, FUNCTION_CREATE, vertex, 1, fragment,
                             1 + PRT_CLOTH_GL_FRAGMENT_PARTS, &s->program);
}

/* The tables' words (the section's bytes from the first factorisation on, a multiple of 4) and
 * the call's uniform block. */
static prt_result create_buffers(prt_context* context, prt_gl_cloth_shader* s) {
  const prt_gl_functions* gl = &s->gl;
  const size_t table_bytes = s->view->info.table_bytes;
  prt_result r;
  prt_gl_drain_errors(gl);
  gl->GenVertexArrays(1, &s->vertex_array);
  gl->GenBuffers(BUFFER_COUNT, s->buffers);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[BUFFER_TABLES]);
  r = prt_gl_upload_le_words(context, &s->allocator, gl, FUNCTION_CREATE,
                             PRT_GL_SHADER_STORAGE_BUFFER, 0, 0,
                             s->view->data + s->view->layout.data, table_bytes);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  if (r != PRT_OK) return r;
  gl->BindBuffer(PRT_GL_UNIFORM_BUFFER, s->buffers[BUFFER_CALL]);
  gl->BufferData(PRT_GL_UNIFORM_BUFFER, (prt_GLsizeiptr)sizeof s->block, NULL, PRT_GL_DYNAMIC_DRAW);
  gl->BindBuffer(PRT_GL_UNIFORM_BUFFER, 0);
  return prt_gl_check_upload(context, gl, FUNCTION_CREATE, table_bytes + sizeof s->block);
}

prt_result prt_gl_cloth_create(prt_context* context, const prt_asset* asset,
                               prt_gl_loader_fn loader, void* loader_user,
                               prt_gl_cloth_shader** out_shader) {
  prt_gl_functions gl;
  prt_gl_cloth_shader* s;
  const prt_cloth_view* view;
  prt_result r;
  if (out_shader) *out_shader = NULL;
  r = prt_gl_check_create(context, FUNCTION_CREATE, asset, (const void*)loader, out_shader,
                          PRT_TECHNIQUE_CLOTH, "CLTH", (const void**)&view);
  if (r != PRT_OK) return r;
  memset(&gl, 0, sizeof gl);
  r = prt_gl_open(context, FUNCTION_CREATE, loader, loader_user, &gl);
  if (r == PRT_OK) {
    const uint64_t bytes[1] = {view->info.table_bytes};
    const char* const names[1] = {"tables"};
    r = prt_gl_check_block_sizes(context, &gl, FUNCTION_CREATE, bytes, names, 1);
  }
  if (r != PRT_OK) return r;

  s = (prt_gl_cloth_shader*)prt_internal_alloc(&asset->allocator, sizeof *s, 16);
  if (!s)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, FUNCTION_CREATE ": out of memory");
  memset(s, 0, sizeof *s);
  s->allocator = asset->allocator;
  s->gl = gl;
  s->view = view;
  r = compile_program(context, s);
  if (r == PRT_OK) r = create_buffers(context, s);
  if (r != PRT_OK) {
    prt_gl_cloth_destroy(s);
    return r;
  }
  *out_shader = s;
  return PRT_OK;
}

void prt_gl_cloth_destroy(prt_gl_cloth_shader* shader) {
  prt_allocator allocator;
  if (!shader) return;
  if (shader->buffers[0]) shader->gl.DeleteBuffers(BUFFER_COUNT, shader->buffers);
  if (shader->vertex_array) shader->gl.DeleteVertexArrays(1, &shader->vertex_array);
  if (shader->program) shader->gl.DeleteProgram(shader->program);
  allocator = shader->allocator;
  prt_internal_free(&allocator, shader, sizeof *shader);
}

/* ---- the call's uniform block ------------------------------------------------------------- */

/* cloth_tables.c's grid_cell: the lower of n nodes at x in [0, 1] and the weight of the upper. */
static void grid_cell(double x, uint32_t n, uint32_t* lower, double* frac) {
  double g = x * (double)(n - 1);
  uint32_t i;
  if (!(g > 0.0)) g = 0.0;
  if (g > (double)(n - 1)) g = (double)(n - 1);
  i = (uint32_t)g;
  if (i >= n - 1) i = n - 2;
  *lower = i;
  *frac = g - (double)i;
}

static uint32_t word_offset(const prt_cloth_view* view, const void* at) {
  return (uint32_t)(((const uint8_t*)at - (view->data + view->layout.data)) / 4u);
}

static void fill_factor(const prt_cloth_view* view, const prt_cloth_factor* f,
                        prt_cloth_gl_factor* out) {
  out->u_scale = word_offset(view, f->u_scale);
  out->v_scale = word_offset(view, f->v_scale);
  out->v_values = word_offset(view, f->v_values);
  out->u_values = word_offset(view, f->u_values);
}

/* A tangent as the shader reads it: its tilt (and cloth_integrals.c's theta support, computed
 * here in double), weight, thread, mirror and factorisations. */
static void fill_tangent(prt_gl_cloth_shader* s, uint32_t g) {
  const prt_cloth_tangent_prep* tp = &s->fabric.tangents[g];
  prt_cloth_gl_block* b = &s->block;
  const int vertical = tp->cos_tau < 1e-9;
  const double tilt = asin(fmin(1.0, fabs(tp->sin_tau)));
  b->tangent_angles[g][0] = (float)tp->sin_tau;
  b->tangent_angles[g][1] = (float)tp->cos_tau;
  b->tangent_angles[g][2] = (float)tp->weight;
  b->tangent_angles[g][3] = vertical ? 0.0f : (float)(-tp->sin_tau / tp->cos_tau);
  const double lo = tp->sin_tau > 0.0 ? -(HALF_PI - tilt) : -HALF_PI;
  const double hi = tp->sin_tau < 0.0 ? HALF_PI - tilt : HALF_PI;
  b->tangent_support[g][0] = (float)lo;
  b->tangent_support[g][1] = (float)hi;
  b->tangent_support[g][2] = b->tangent_support[g][3] = 0.0f;
  b->tangent_bits[g][0] = (tp->thread ? PRT_CLOTH_GL_TANGENT_WEFT : 0u) |
                          (tp->mirror ? PRT_CLOTH_GL_TANGENT_MIRROR : 0u) |
                          (vertical ? PRT_CLOTH_GL_TANGENT_VERTICAL : 0u);
  b->tangent_bits[g][1] = tp->full.rank;
  b->tangent_bits[g][2] = tp->cone.rank;
  b->tangent_bits[g][3] = 0u;
  fill_factor(s->view, &tp->full, &b->tangent_full[g]);
  fill_factor(s->view, &tp->cone, &b->tangent_cone[g]);
}

/* A lobe: axis, sharpness, amplitude, its sharpness levels (cloth_tables.c's cell in double) and
 * which lobed parts of each thread share its theta window (cloth_integrals.c's test, in
 * double as there). */
static void fill_lobe(prt_gl_cloth_shader* s, uint32_t k) {
  const prt_cloth_lobe_prep* lobe = &s->light.lobes[k];
  const uint32_t levels = s->view->header.levels;
  const double lobe_sd = 1.0 / sqrt(lobe->lambda);
  prt_cloth_gl_block* b = &s->block;
  uint32_t level = 0, bits = 0, j, i;
  double frac = 0.0;
  if (levels > 1) grid_cell(lobe->level / (double)(levels - 1), levels, &level, &frac);
  for (j = 0; j < 2; ++j) {
    const prt_cloth_thread* t = &s->fabric.params.threads[j];
    if (2.0 * (double)t->gamma_s >= MERGE_WIDTH * lobe_sd) bits |= 1u << (2u * j);
    if (2.0 * (double)t->gamma_v >= MERGE_WIDTH * lobe_sd) bits |= 2u << (2u * j);
  }
  b->lobe_bits[k] = bits | level << PRT_CLOTH_GL_LEVEL_SHIFT;
  for (i = 0; i < 3; ++i) {
    b->lobe_axis[k][i] = (float)lobe->axis[i];
    b->lobe_rgb[k][i] = (float)lobe->rgb[i];
  }
  b->lobe_axis[k][3] = (float)lobe->lambda;
  b->lobe_rgb[k][3] = (float)frac;
}

static void fill_block(prt_gl_cloth_shader* s, const prt_cloth_method* method,
                       const prt_GLint viewport[4]) {
  prt_cloth_gl_block* b = &s->block;
  uint32_t j, i;
  memset(b, 0, sizeof *b);
  b->counts[0] = s->light.count;
  b->counts[1] = s->fabric.tangent_count;
  b->counts[2] = method->theta_segments;
  b->counts[3] = method->phi_nodes;
  b->misc[0] = method->flags;
  b->misc[1] = (uint32_t)viewport[0];
  b->misc[2] = (uint32_t)viewport[1];
  for (j = 0; j < 2; ++j) {
    const prt_cloth_thread* t = &s->fabric.params.threads[j];
    b->thread_scatter[j][0] = t->eta;
    b->thread_scatter[j][1] = t->kd;
    b->thread_scatter[j][2] = t->gamma_s;
    b->thread_scatter[j][3] = t->gamma_v;
    for (i = 0; i < 3; ++i) b->thread_albedo[j][i] = t->albedo[i];
  }
  for (i = 0; i < s->fabric.tangent_count; ++i) fill_tangent(s, i);
  for (i = 0; i < s->light.count; ++i) fill_lobe(s, i);
}

/* ---- per call -------------------------------------------------------------------------- */

/* Binds everything the draw reads (or, bind = 0, unbinds it all: the state prt_cloth_asset.h
 * lists, left at 0 / off). */
static void bind_all(const prt_gl_cloth_shader* s, const prt_gl_cloth_gbuffer* gbuffer, int bind) {
  const prt_gl_functions* gl = &s->gl;
  const prt_GLuint textures[GBUFFER_UNITS] = {bind ? gbuffer->normal_texture : 0u,
                                              bind ? gbuffer->warp_texture : 0u,
                                              bind ? gbuffer->view_texture : 0u};
  uint32_t unit;
  gl->UseProgram(bind ? s->program : 0u);
  gl->BindVertexArray(bind ? s->vertex_array : 0u);
  for (unit = GBUFFER_UNITS; unit-- > 0;) {
    gl->ActiveTexture(PRT_GL_TEXTURE0 + unit);
    gl->BindTexture(PRT_GL_TEXTURE_2D, textures[unit]);
    gl->BindSampler(unit, 0u);
  }
  gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, 0, bind ? s->buffers[BUFFER_TABLES] : 0u);
  gl->BindBufferBase(PRT_GL_UNIFORM_BUFFER, 0, bind ? s->buffers[BUFFER_CALL] : 0u);
}

/* Per-call functions write no context (prt_gl.h): a bad argument is reported by the result. */
static prt_result check_call(const prt_gl_cloth_shader* shader, uint32_t fabric,
                             const prt_cloth_params* params, const prt_cloth_light* light,
                             const prt_cloth_settings* settings,
                             const prt_gl_cloth_gbuffer* gbuffer, prt_cloth_method* method) {
  if (!shader || !light || !gbuffer ||
      !prt_internal_struct_size_ok(gbuffer, PRT_GL_CLOTH_GBUFFER_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (fabric >= shader->view->header.fabrics) return PRT_ERROR_NOT_FOUND;
  if (params && prt_cloth_params_validate(params) != PRT_OK) return PRT_ERROR_INVALID_ARGUMENT;
  if (prt_cloth_light_validate(light) != PRT_OK) return PRT_ERROR_INVALID_ARGUMENT;
  return prt_cloth_method_of(settings, method);
}

prt_result prt_gl_cloth_shade(prt_gl_cloth_shader* shader, uint32_t fabric,
                              const prt_cloth_params* params, const prt_cloth_light* light,
                              const prt_cloth_settings* settings,
                              const prt_gl_cloth_gbuffer* gbuffer) {
  const prt_gl_functions* gl;
  prt_cloth_method method;
  prt_GLint viewport[4] = {0, 0, 0, 0};
  prt_result r = check_call(shader, fabric, params, light, settings, gbuffer, &method);
  if (r != PRT_OK) return r;
  gl = &shader->gl;
  prt_cloth_prepare_light(shader->view, light, &method, &shader->light);
  prt_cloth_prepare_fabric(shader->view, fabric, params, &shader->fabric);
  gl->GetIntegerv(PRT_GL_VIEWPORT, viewport);
  fill_block(shader, &method, viewport);
  gl->BindBuffer(PRT_GL_UNIFORM_BUFFER, shader->buffers[BUFFER_CALL]);
  gl->BufferSubData(PRT_GL_UNIFORM_BUFFER, 0, (prt_GLsizeiptr)sizeof shader->block, &shader->block);
  gl->BindBuffer(PRT_GL_UNIFORM_BUFFER, 0);
  bind_all(shader, gbuffer, 1);
  gl->Disable(PRT_GL_DEPTH_TEST);
  gl->Disable(PRT_GL_BLEND);
  gl->Disable(PRT_GL_CULL_FACE);
  gl->DrawArrays(PRT_GL_TRIANGLES, 0, 3);
  bind_all(shader, gbuffer, 0);
  return PRT_OK;
}

#endif /* PRT_HAS_GL */
