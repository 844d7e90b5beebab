/* SPDX-License-Identifier: MIT */
/* The GL backend of `cloth` shading (prt_cloth_asset.h): per call, the light and the fabric are
 * prepared on the CPU by the scalar reference's own functions (prt_cloth_prepare_light,
 * prt_cloth_prepare_fabric, prt_cloth_method_of) and packed into a uniform block; per pixel, a
 * fragment shader (cloth_gl_glsl.c) drawn as one full-screen triangle over the caller's G-buffer
 * evaluates the method in float. The tables (every T and T_c factorisation) are one 2D integer
 * texture holding the section's table data as stored, one 32-bit word per texel in rows of a
 * power of two: the shader fetches texels, dequantises the 8- or 16-bit values exactly and
 * computes every lookup's bilinear (and across levels linear) weights as cloth_tables.c does, with
 * no dependence on a GPU's filtering precision. */
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
/* Texture units: the G-buffer's normal, warp and view, then the tables. */
#define TABLE_UNIT 3u
#define UNITS 4u
/* Mesa's llvmpipe ends a fragment's loops after 65535 iterations in all (one counter for every
 * loop of the shader), which a light of many lobes reaches: a call draws in passes, each over a
 * range of tangents and lobes whose loop iterations, counted as the shader's loops run at most,
 * stay within this budget, and the passes after the first add to the first by blending. */
#define PASS_ITERATIONS 60000u
/* The shader's uniforms (explicit locations): the pass's tangent and lobe ranges. */
enum { UNIFORM_FIRST_TANGENT, UNIFORM_END_TANGENT, UNIFORM_FIRST_LOBE, UNIFORM_END_LOBE };

struct prt_gl_cloth_shader {
  prt_allocator allocator; /* the asset's */
  prt_gl_functions gl;
  const prt_cloth_view* view;
  prt_GLuint program;
  prt_GLuint vertex_array;
  prt_GLuint call_buffer;
  prt_GLuint table_texture;
  uint32_t table_shift; /* the table texture is 2^table_shift words wide */
  uint32_t max_rank;    /* the largest rank of a factorisation (the shader's arrays) */
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
           "#define MAX_TANGENTS %u\n#define MAX_LOBES %u\n#define TABLE_SHIFT %u\n"
           "#define SERIES_TERMS %u\n",
           (unsigned)h->bits, (unsigned)s->max_rank, (unsigned)h->xi_size, (unsigned)h->levels,
           (unsigned)h->view_theta, (unsigned)h->view_phi, (unsigned)PRT_CLOTH_GL_MAX_TANGENTS,
           (unsigned)PRT_CLOTH_MAX_LOBES, (unsigned)s->table_shift,
           (unsigned)PRT_CLOTH_GL_SERIES_TERMS);
  vertex[0] = prt_cloth_gl_vertex_source;
  fragment[0] = header;
  for (i = 0; i < PRT_CLOTH_GL_FRAGMENT_PARTS; ++i)
    fragment[1 + i] = prt_cloth_gl_fragment_sources[i];
  return prt_gl_compile_draw(context, &s->gl, FUNCTION_CREATE, vertex, 1, fragment,
                             1 + PRT_CLOTH_GL_FRAGMENT_PARTS, &s->program);
}

/* The table texture's width, 2^shift: the least power of two whose square holds the words;
 * UNSUPPORTED_BACKEND when this GL's textures are narrower. */
static prt_result choose_table_shape(prt_context* context, const prt_gl_functions* gl, size_t words,
                                     uint32_t* out_shift) {
  prt_GLint max_size = 0;
  uint32_t shift = 0;
  while (((uint64_t)1 << (2u * shift)) < (uint64_t)words) ++shift;
  gl->GetIntegerv(PRT_GL_MAX_TEXTURE_SIZE, &max_size);
  if (max_size <= 0 || ((uint64_t)1 << shift) > (uint64_t)max_size)
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             FUNCTION_CREATE
                             ": the tables (%zu bytes) need a texture %llu texels "
                             "wide; this GL allows %d",
                             4u * words, (unsigned long long)1 << shift, (int)max_size);
  *out_shift = shift;
  return PRT_OK;
}

static int host_is_little_endian(void) {
  const uint32_t one = 1;
  uint8_t first;
  memcpy(&first, &one, 1);
  return first == 1;
}

/* The pixel-unpack state a texture upload reads (an application may have left any of it set),
 * saved and put back around the upload. */
static const prt_GLenum kUnpackState[] = {
    PRT_GL_PIXEL_UNPACK_BUFFER_BINDING, PRT_GL_UNPACK_SWAP_BYTES,
    PRT_GL_UNPACK_ROW_LENGTH,           PRT_GL_UNPACK_SKIP_ROWS,
    PRT_GL_UNPACK_SKIP_PIXELS,          PRT_GL_UNPACK_ALIGNMENT};
#define UNPACK_STATE (sizeof kUnpackState / sizeof kUnpackState[0])

static void set_unpack_state(const prt_gl_functions* gl, const prt_GLint* values) {
  size_t i;
  gl->BindBuffer(PRT_GL_PIXEL_UNPACK_BUFFER, (prt_GLuint)values[0]);
  for (i = 1; i < UNPACK_STATE; ++i) gl->PixelStorei(kUnpackState[i], values[i]);
}

/* Writes `count` host-order words into the texture bound to TEXTURE_2D, in rows of 2^shift. */
static void upload_words(const prt_gl_functions* gl, const uint32_t* words, size_t count,
                         uint32_t shift) {
  static const prt_GLint kPlain[UNPACK_STATE] = {0, 0, 0, 0, 0, 4};
  const size_t rows = count >> shift, rest = count - (rows << shift);
  prt_GLint saved[UNPACK_STATE];
  size_t i;
  for (i = 0; i < UNPACK_STATE; ++i) gl->GetIntegerv(kUnpackState[i], &saved[i]);
  set_unpack_state(gl, kPlain);
  if (rows)
    gl->TexSubImage2D(PRT_GL_TEXTURE_2D, 0, 0, 0, (prt_GLsizei)1 << shift, (prt_GLsizei)rows,
                      PRT_GL_RED_INTEGER, PRT_GL_UNSIGNED_INT, words);
  if (rest)
    gl->TexSubImage2D(PRT_GL_TEXTURE_2D, 0, 0, (prt_GLint)rows, (prt_GLsizei)rest, 1,
                      PRT_GL_RED_INTEGER, PRT_GL_UNSIGNED_INT, words + (rows << shift));
  set_unpack_state(gl, saved);
}

/* The table texture (the section's table bytes from the first factorisation on, a multiple of 4,
 * as little-endian words; bound to no unit afterwards, unit 0 active) and the call's uniform
 * buffer. */
static prt_result create_objects(prt_context* context, prt_gl_cloth_shader* s) {
  const prt_gl_functions* gl = &s->gl;
  const size_t bytes = s->view->info.table_bytes, count = bytes / 4u;
  const uint8_t* data = s->view->data + s->view->layout.data;
  const size_t width = (size_t)1 << s->table_shift;
  const size_t height = count ? (count + width - 1) >> s->table_shift : 1;
  uint32_t* swapped = NULL;
  size_t i;
  if (!host_is_little_endian() && count) {
    swapped = (uint32_t*)prt_internal_alloc(&s->allocator, bytes, 16);
    if (!swapped)
      return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY,
                               FUNCTION_CREATE ": out of memory (%zu bytes)", bytes);
    for (i = 0; i < count; ++i) swapped[i] = prt_le_load_u32(data + 4u * i);
  }
  prt_gl_drain_errors(gl);
  gl->GenVertexArrays(1, &s->vertex_array);
  gl->GenTextures(1, &s->table_texture);
  gl->ActiveTexture(PRT_GL_TEXTURE0 + TABLE_UNIT);
  gl->BindTexture(PRT_GL_TEXTURE_2D, s->table_texture);
  gl->TexStorage2D(PRT_GL_TEXTURE_2D, 1, PRT_GL_R32UI, (prt_GLsizei)width, (prt_GLsizei)height);
  /* an integer texture is complete only with nearest filtering */
  gl->TexParameteri(PRT_GL_TEXTURE_2D, PRT_GL_TEXTURE_MIN_FILTER, (prt_GLint)PRT_GL_NEAREST);
  gl->TexParameteri(PRT_GL_TEXTURE_2D, PRT_GL_TEXTURE_MAG_FILTER, (prt_GLint)PRT_GL_NEAREST);
  upload_words(gl, swapped ? swapped : (const uint32_t*)(const void*)data, count, s->table_shift);
  gl->BindTexture(PRT_GL_TEXTURE_2D, 0);
  gl->ActiveTexture(PRT_GL_TEXTURE0);
  if (swapped) prt_internal_free(&s->allocator, swapped, bytes);
  gl->GenBuffers(1, &s->call_buffer);
  gl->BindBuffer(PRT_GL_UNIFORM_BUFFER, s->call_buffer);
  gl->BufferData(PRT_GL_UNIFORM_BUFFER, (prt_GLsizeiptr)sizeof s->block, NULL, PRT_GL_DYNAMIC_DRAW);
  gl->BindBuffer(PRT_GL_UNIFORM_BUFFER, 0);
  return prt_gl_check_upload(context, gl, FUNCTION_CREATE, 4u * width * height + sizeof s->block);
}

prt_result prt_gl_cloth_create(prt_context* context, const prt_asset* asset,
                               prt_gl_loader_fn loader, void* loader_user,
                               prt_gl_cloth_shader** out_shader) {
  prt_gl_functions gl;
  prt_gl_cloth_shader* s;
  const prt_cloth_view* view;
  uint32_t shift = 0;
  prt_result r;
  if (out_shader) *out_shader = NULL;
  r = prt_gl_check_create(context, FUNCTION_CREATE, asset, (const void*)loader, out_shader,
                          PRT_TECHNIQUE_CLOTH, "CLTH", (const void**)&view);
  if (r != PRT_OK) return r;
  memset(&gl, 0, sizeof gl);
  r = prt_gl_open(context, FUNCTION_CREATE, loader, loader_user, &gl);
  if (r == PRT_OK) r = choose_table_shape(context, &gl, view->info.table_bytes / 4u, &shift);
  if (r != PRT_OK) return r;

  s = (prt_gl_cloth_shader*)prt_internal_alloc(&asset->allocator, sizeof *s, 16);
  if (!s)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, FUNCTION_CREATE ": out of memory");
  memset(s, 0, sizeof *s);
  s->allocator = asset->allocator;
  s->gl = gl;
  s->view = view;
  s->table_shift = shift;
  s->max_rank = largest_rank(view);
  r = compile_program(context, s);
  if (r == PRT_OK) r = create_objects(context, s);
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
  if (shader->call_buffer) shader->gl.DeleteBuffers(1, &shader->call_buffer);
  if (shader->table_texture) shader->gl.DeleteTextures(1, &shader->table_texture);
  if (shader->vertex_array) shader->gl.DeleteVertexArrays(1, &shader->vertex_array);
  if (shader->program) shader->gl.DeleteProgram(shader->program);
  allocator = shader->allocator;
  prt_internal_free(&allocator, shader, sizeof *shader);
}

/* ---- the call's uniform block ------------------------------------------------------------- */

/* Offset in words from the first table byte (the table texture's first texel). */
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
  const double lo = tp->sin_tau > 0.0 ? -(HALF_PI - tilt) : -HALF_PI;
  const double hi = tp->sin_tau < 0.0 ? HALF_PI - tilt : HALF_PI;
  b->tangent_angles[g][0] = (float)tp->sin_tau;
  b->tangent_angles[g][1] = (float)tp->cos_tau;
  b->tangent_angles[g][2] = (float)tp->weight;
  b->tangent_angles[g][3] = vertical ? 0.0f : (float)(-tp->sin_tau / tp->cos_tau);
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
  if (levels > 1) prt_cloth_grid_cell(lobe->level / (double)(levels - 1), levels, &level, &frac);
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
  const prt_GLuint textures[UNITS] = {
      bind ? gbuffer->normal_texture : 0u, bind ? gbuffer->warp_texture : 0u,
      bind ? gbuffer->view_texture : 0u, bind ? s->table_texture : 0u};
  uint32_t unit;
  gl->UseProgram(bind ? s->program : 0u);
  gl->BindVertexArray(bind ? s->vertex_array : 0u);
  for (unit = UNITS; unit-- > 0;) { /* ends on unit 0, the active unit left */
    gl->ActiveTexture(PRT_GL_TEXTURE0 + unit);
    gl->BindTexture(PRT_GL_TEXTURE_2D, textures[unit]);
    gl->BindSampler(unit, 0u);
  }
  gl->BindBufferBase(PRT_GL_UNIFORM_BUFFER, 0, bind ? s->call_buffer : 0u);
}

/* Per-call functions write no context (prt_gl.h): a bad argument is reported by the result. */
static prt_result check_call(const prt_gl_cloth_shader* shader, uint32_t fabric,
                             const prt_cloth_params* params, const prt_cloth_light* light,
                             const prt_cloth_settings* settings,
                             const prt_gl_cloth_gbuffer* gbuffer, prt_cloth_method* method) {
  prt_result r;
  if (!shader || !light || !gbuffer ||
      !prt_internal_struct_size_ok(gbuffer, PRT_GL_CLOTH_GBUFFER_SIZE_1_0))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (fabric >= shader->view->header.fabrics) return PRT_ERROR_NOT_FOUND;
  if (params && prt_cloth_params_validate(params) != PRT_OK) return PRT_ERROR_INVALID_ARGUMENT;
  if (prt_cloth_light_validate(light) != PRT_OK) return PRT_ERROR_INVALID_ARGUMENT;
  r = prt_cloth_method_of(settings, method);
  if (r != PRT_OK) return r;
  /* the paper's study switches are the scalar reference's alone */
  return (method->flags & PRT_CLOTH_PAPER_FLAGS) ? PRT_ERROR_UNSUPPORTED_BACKEND : PRT_OK;
}

/* Upper bounds of the shader's loop iterations (cloth_gl_glsl.c: no early exit taken, no loop
 * unrolled): per tangent, its two view factors; per lobe of a tangent, its two table reads and
 * its three theta windows of up to two pieces, each of 2 segments + 1 theta nodes (a phi integral
 * of phi_nodes each) and `segments` panels (a series of up to SERIES_TERMS terms each). */
static uint32_t tangent_iterations(uint32_t max_rank) {
  return 1u + 2u * max_rank;
}

static uint32_t lobe_iterations(const prt_cloth_method* method, uint32_t max_rank) {
  const uint32_t segments = method->theta_segments, nodes = method->phi_nodes;
  const uint32_t tables = 2u * (2u + 8u * (1u + max_rank));
  const uint32_t piece =
      (2u * segments + 1u) * (1u + nodes) + segments * PRT_CLOTH_GL_SERIES_TERMS + 1u;
  return 1u + tables + 3u + 3u * (2u + 2u * piece);
}

/* How many tangents and lobes one pass takes within PASS_ITERATIONS. */
static void pass_sizes(const prt_gl_cloth_shader* s, const prt_cloth_method* method,
                       uint32_t* out_tangents, uint32_t* out_lobes) {
  const uint32_t per_tangent = tangent_iterations(s->max_rank);
  const uint32_t per_lobe = lobe_iterations(method, s->max_rank);
  uint32_t tangents = PASS_ITERATIONS / (per_tangent + per_lobe), lobes;
  if (tangents > s->fabric.tangent_count) tangents = s->fabric.tangent_count;
  if (tangents < 1u) tangents = 1u;
  lobes = PASS_ITERATIONS / tangents > per_tangent
              ? (PASS_ITERATIONS / tangents - per_tangent) / per_lobe
              : 1u;
  *out_tangents = tangents;
  *out_lobes = lobes < 1u ? 1u : lobes;
}

/* Blend state a pass after the first sets, saved to be put back. */
typedef struct blend_state {
  prt_GLint src_rgb, dst_rgb, src_alpha, dst_alpha, equation_rgb, equation_alpha;
} blend_state;

static void save_blend(const prt_gl_functions* gl, blend_state* b) {
  gl->GetIntegerv(PRT_GL_BLEND_SRC_RGB, &b->src_rgb);
  gl->GetIntegerv(PRT_GL_BLEND_DST_RGB, &b->dst_rgb);
  gl->GetIntegerv(PRT_GL_BLEND_SRC_ALPHA, &b->src_alpha);
  gl->GetIntegerv(PRT_GL_BLEND_DST_ALPHA, &b->dst_alpha);
  gl->GetIntegerv(PRT_GL_BLEND_EQUATION_RGB, &b->equation_rgb);
  gl->GetIntegerv(PRT_GL_BLEND_EQUATION_ALPHA, &b->equation_alpha);
}

static void restore_blend(const prt_gl_functions* gl, const blend_state* b) {
  gl->BlendFuncSeparate((prt_GLenum)b->src_rgb, (prt_GLenum)b->dst_rgb, (prt_GLenum)b->src_alpha,
                        (prt_GLenum)b->dst_alpha);
  gl->BlendEquationSeparate((prt_GLenum)b->equation_rgb, (prt_GLenum)b->equation_alpha);
}

/* The draws, pass by pass over the tangents' and lobes' ranges: the first writes (alpha 1), the
 * others add to it (alpha 0) with the caller's blend functions put back afterwards. */
static void draw_passes(const prt_gl_cloth_shader* s, const prt_cloth_method* method) {
  const prt_gl_functions* gl = &s->gl;
  const uint32_t tangent_count = s->fabric.tangent_count, lobe_count = s->light.count;
  uint32_t tangents, lobes, t = 0, k = 0, pass = 0;
  blend_state saved;
  pass_sizes(s, method, &tangents, &lobes);
  do {
    const uint32_t t_end = t + tangents < tangent_count ? t + tangents : tangent_count;
    const uint32_t k_end = k + lobes < lobe_count ? k + lobes : lobe_count;
    if (pass++ == 1) {
      save_blend(gl, &saved);
      gl->BlendFuncSeparate(PRT_GL_ONE, PRT_GL_ONE, PRT_GL_ONE, PRT_GL_ONE);
      gl->BlendEquationSeparate(PRT_GL_FUNC_ADD, PRT_GL_FUNC_ADD);
      gl->Enable(PRT_GL_BLEND);
    }
    gl->ProgramUniform1ui(s->program, UNIFORM_FIRST_TANGENT, t);
    gl->ProgramUniform1ui(s->program, UNIFORM_END_TANGENT, t_end);
    gl->ProgramUniform1ui(s->program, UNIFORM_FIRST_LOBE, k);
    gl->ProgramUniform1ui(s->program, UNIFORM_END_LOBE, k_end);
    gl->DrawArrays(PRT_GL_TRIANGLES, 0, 3);
    k = k_end;
    if (k >= lobe_count) k = 0, t = t_end;
  } while (t < tangent_count && lobe_count > 0);
  if (pass > 1) {
    restore_blend(gl, &saved);
    gl->Disable(PRT_GL_BLEND);
  }
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
  gl->BindBuffer(PRT_GL_UNIFORM_BUFFER, shader->call_buffer);
  gl->BufferSubData(PRT_GL_UNIFORM_BUFFER, 0, (prt_GLsizeiptr)sizeof shader->block, &shader->block);
  gl->BindBuffer(PRT_GL_UNIFORM_BUFFER, 0);
  bind_all(shader, gbuffer, 1);
  gl->Disable(PRT_GL_DEPTH_TEST);
  gl->Disable(PRT_GL_BLEND);
  gl->Disable(PRT_GL_CULL_FACE);
  draw_passes(shader, &method);
  bind_all(shader, gbuffer, 0);
  return PRT_OK;
}

#endif /* PRT_HAS_GL */
