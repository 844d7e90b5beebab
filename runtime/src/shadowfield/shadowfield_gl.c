/* SPDX-License-Identifier: MIT */
/* The GL backend of technique `shadowfield` (prt/prt_shadowfield.h, prt_gl_shadowfield_*): the
 * per-vertex work of a frame in a compute shader (shadowfield_gl_glsl.c): the direct light, the
 * bounces and the outgoing radiance. This file creates the program and the buffers (the objects
 * uploaded once); shadowfield_gl_frame.c runs a frame. The CPU keeps the small work: the frame's
 * preparation (the light in each instance's frame, the pairs and their rotations,
 * prt_shadowfield_prepare) and, between two passes, nothing: each source's basis projection and the
 * field it casts are shader stages too, so a frame reads nothing back. */
#include <prt/prt_shadowfield.h>

#include "../internal.h"
#include "shadowfield_gl_internal.h"

#if !defined(PRT_HAS_GL)
prt_result prt_gl_shadowfield_create(prt_shadowfield_scene* scene, prt_gl_loader_fn loader,
                                     void* loader_user, prt_gl_shadowfield** out_shader) {
  (void)loader, (void)loader_user;
  if (out_shader) *out_shader = NULL;
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  return prt_internal_fail(scene->context, PRT_ERROR_UNSUPPORTED_BACKEND,
                           "prt_gl_shadowfield_create: compiled out (PRT_ENABLE_GL=OFF)");
}
void prt_gl_shadowfield_destroy(prt_gl_shadowfield* shader) {
  (void)shader;
}
prt_result prt_gl_shadowfield_shade(prt_gl_shadowfield* shader, const float* light_sh_rgb,
                                    const float eye[3], const prt_shadowfield_settings* settings) {
  (void)shader, (void)light_sh_rgb, (void)eye, (void)settings;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
uint32_t prt_gl_shadowfield_output_buffer(const prt_gl_shadowfield* shader) {
  (void)shader;
  return 0u;
}
uint32_t prt_gl_shadowfield_output_first(const prt_gl_shadowfield* shader, uint32_t instance) {
  (void)shader, (void)instance;
  return 0u;
}
prt_result prt_gl_shadowfield_read(prt_gl_shadowfield* shader, uint32_t instance,
                                   uint32_t first_vertex, uint32_t vertex_count, float* out_rgb) {
  (void)shader, (void)instance, (void)first_vertex, (void)vertex_count, (void)out_rgb;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
#else /* PRT_HAS_GL */

#include <stdio.h>
#include <string.h>

#include "../gl_common.h"

#define FUNCTION_CREATE "prt_gl_shadowfield_create"

/* ---- create ------------------------------------------------------------------------------- */

/* Words of the Gaunt buffer's tensor (k_start, then two words a coefficient): where the
 * exponential's rule starts. */
static uint32_t tensor_words(const prt_shadowfield_scene* scene) {
  return scene->order * scene->order + 1u + 2u * scene->gaunt.count;
}

/* Words of the Gaunt buffer: the tensor, then with the log-space product the exponential's
 * rule (its eval, then its project table). */
static uint64_t gaunt_words(const prt_shadowfield_scene* scene) {
  const uint64_t n2 = (uint64_t)scene->order * scene->order;
  return tensor_words(scene) + 2u * (uint64_t)scene->exp_rule.directions * n2;
}

static prt_result compile_program(prt_context* context, prt_gl_shadowfield* s) {
  const uint32_t n2 = s->scene->order * s->scene->order, directions = s->scene->exp_rule.directions;
  const uint32_t exp_eval = tensor_words(s->scene);
  char header[2048];
  snprintf(header, sizeof header,
           "#version 430 core\n#define LOCAL_SIZE %u\n"
           "#define VERTICES %uu\n#define TERMS %uu\n#define GLOSSY %uu\n#define BRDF_GRID %uu\n"
           "#define POSITIONS %uu\n#define NORMALS %uu\n#define ALBEDO %uu\n#define TRANSFER %uu\n"
           "#define G_TABLE %uu\n#define INCIDENT %uu\n#define OUTPUT %uu\n"
           "#define PAIR_COUNT %uu\n#define ROTATION %uu\n#define TRANSLATION %uu\n"
           "#define SCALE %uu\n#define EYE %uu\n#define LIGHT %uu\n#define PRODUCT %uu\n"
           "#define HEADER %uu\n#define OCCLUDES %uu\n#define LIGHTS %uu\n#define TO_OTHER %uu\n"
           "#define OFFSET %uu\n#define OOF_GRID %uu\n#define OOF %uu\n#define SRF_GRID %uu\n"
           "#define FIELD %uu\n#define FIELD_PLANE %uu\n#define SH_ROTATION %uu\n"
           "#define PAIR_FLOATS %uu\n#define SRF %uu\n#define BASIS %uu\n#define OWN_FIELD %uu\n"
           "#define FIELD_POINTS %uu\n#define BASIS_VALUES %uu\n"
           "#define VERTEX_WEIGHTS %uu\n#define BASIS_INVERSE %uu\n"
           "#define LOG_PRODUCT %u\n#define EXP_DIRECTIONS %uu\n#define EXP_EVAL %uu\n"
           "#define EXP_PROJECT %uu\n#define PROBE_COUNT %uu\n#define PROBE_POSITIONS %uu\n"
           "#define PROBE_LOOKUPS %uu\n#define PROBE_LIGHT %uu\n",
           PRT_SF_GL_LOCAL_SIZE, PRT_SF_GL_VERTICES, PRT_SF_GL_TERMS, PRT_SF_GL_GLOSSY,
           PRT_SF_GL_BRDF_GRID, PRT_SF_GL_POSITIONS, PRT_SF_GL_NORMALS, PRT_SF_GL_ALBEDO,
           PRT_SF_GL_TRANSFER, PRT_SF_GL_G_TABLE, PRT_SF_GL_INCIDENT, PRT_SF_GL_OUTPUT,
           PRT_SF_GL_PAIR_COUNT, PRT_SF_GL_ROTATION, PRT_SF_GL_TRANSLATION, PRT_SF_GL_SCALE,
           PRT_SF_GL_EYE, PRT_SF_GL_LIGHT, PRT_SF_GL_PRODUCT, PRT_SF_GL_HEADER, PRT_SF_GL_OCCLUDES,
           PRT_SF_GL_LIGHTS, PRT_SF_GL_TO_OTHER, PRT_SF_GL_OFFSET, PRT_SF_GL_OOF_GRID,
           PRT_SF_GL_OOF, PRT_SF_GL_SRF_GRID, PRT_SF_GL_FIELD, PRT_SF_GL_FIELD_PLANE,
           PRT_SF_GL_SH_ROTATION, PRT_SF_GL_PAIR_FLOATS, PRT_SF_GL_SRF, PRT_SF_GL_BASIS,
           PRT_SF_GL_OWN_FIELD, PRT_SF_GL_FIELD_POINTS, PRT_SF_GL_BASIS_VALUES,
           PRT_SF_GL_VERTEX_WEIGHTS, PRT_SF_GL_BASIS_INVERSE,
           s->product == PRT_SHADOWFIELD_PRODUCT_LOG ? 1u : 0u, directions, exp_eval,
           exp_eval + directions * n2, PRT_SF_GL_PROBE_COUNT, PRT_SF_GL_PROBE_POSITIONS,
           PRT_SF_GL_PROBE_LOOKUPS, PRT_SF_GL_PROBE_LIGHT);
  const prt_GLchar* sources[2] = {header, prt_sf_gl_shader_source};
  const prt_result r =
      prt_gl_compile_compute(context, &s->gl, FUNCTION_CREATE, sources, 2, &s->program);
  if (r == PRT_OK) s->gl.ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_ORDER, s->scene->order);
  return r;
}

static uint64_t srf_floats(const prt_sf_object* o) {
  return (uint64_t)o->basis_size * o->terms * prt_sf_point_count(&o->srf_shells) * o->order *
         o->order;
}

static uint64_t object_floats(const prt_sf_object* o, prt_sf_gl_object* at, uint64_t start) {
  const uint64_t n2 = (uint64_t)o->order * o->order, v = o->vertex_count;
  uint64_t next = start;
  at->positions = (uint32_t)next;
  next += 3u * v;
  at->normals = (uint32_t)next;
  next += 3u * v;
  at->albedo = (uint32_t)next;
  next += 3u * v;
  at->transfer = (uint32_t)next;
  next += v * o->terms * n2;
  at->g_table = (uint32_t)next;
  if (o->glossy) next += (uint64_t)o->terms * o->brdf_grid * o->brdf_grid;
  at->oof = (uint32_t)next;
  next += prt_sf_point_count(&o->oof_shells) * n2;
  at->srf = (uint32_t)next;
  next += srf_floats(o);
  at->basis = (uint32_t)next;
  next += (uint64_t)o->basis_size * v;
  at->vertex_weights = (uint32_t)next;
  if (o->basis_size) next += v;
  at->basis_inverse = (uint32_t)next;
  next += (uint64_t)o->basis_size * o->basis_size;
  return next;
}

/* Lays out every buffer; the sizes in bytes (at least 4 each) in bytes[] by buffer. */
static void lay_out(prt_gl_shadowfield* s, uint64_t bytes[PRT_SF_GL_BUFFER_COUNT]) {
  const prt_shadowfield_scene* scene = s->scene;
  uint64_t objects = 0u, fields = 0u, incident = 0u, radiance = 0u, most_vertices = 0u;
  uint64_t most_weights = 0u; /* a projection and its weights, in the scratch rows */
  for (uint32_t o = 0; o < s->object_count; ++o) {
    const prt_sf_object* object = scene->objects[o];
    objects = object_floats(object, &s->objects[o], objects);
    const uint64_t weights = 2u * 3u * (uint64_t)object->basis_size * object->terms;
    if (weights > most_weights) most_weights = weights;
  }
  for (uint32_t i = 0; i < s->instance_count; ++i) {
    const prt_sf_instance* instance = &scene->instances[i];
    s->instances[i].incident = (uint32_t)incident;
    s->instances[i].field = (uint32_t)fields;
    s->instances[i].radiance_vertex = (uint32_t)radiance;
    incident += instance->incident_floats;
    if (instance->field) fields += instance->field_floats;
    const uint32_t vertices = scene->objects[instance->object]->vertex_count;
    radiance += vertices;
    if (vertices > most_vertices) most_vertices = vertices;
  }
  const uint64_t invocations =
      (most_vertices < PRT_SF_GL_CHUNK_VERTICES ? most_vertices : PRT_SF_GL_CHUNK_VERTICES) +
      PRT_SF_GL_LOCAL_SIZE;
  s->radiance_vertices = (uint32_t)radiance;
  bytes[PRT_SF_GL_BUFFER_OBJECTS] = 4u * objects;
  bytes[PRT_SF_GL_BUFFER_GAUNT] = 4u * gaunt_words(scene);
  bytes[PRT_SF_GL_BUFFER_FIELDS] = 4u * fields;
  bytes[PRT_SF_GL_BUFFER_INCIDENT] = 4u * incident;
  bytes[PRT_SF_GL_BUFFER_RADIANCE] = 12u * radiance;
  bytes[PRT_SF_GL_BUFFER_FRAME] = 4u * (uint64_t)s->instance_count * PRT_SF_GL_HEADER;
  /* Sized when a frame asks for probes (shadowfield_gl_frame.c); a float until then. */
  bytes[PRT_SF_GL_BUFFER_PROBES] = 4u;
  bytes[PRT_SF_GL_BUFFER_SCRATCH] = 4u * invocations * PRT_SF_GL_SCRATCH_FLOATS(scene->order);
  if (bytes[PRT_SF_GL_BUFFER_SCRATCH] < 4u * most_weights)
    bytes[PRT_SF_GL_BUFFER_SCRATCH] = 4u * most_weights;
  for (int b = 0; b < PRT_SF_GL_BUFFER_COUNT; ++b)
    if (bytes[b] == 0u) bytes[b] = 4u; /* empty parts still get valid buffers */
}

void prt_sf_gl_upload(const prt_gl_functions* gl, uint32_t at, const float* values,
                      uint64_t count) {
  if (count)
    gl->BufferSubData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLintptr)(4u * (uint64_t)at),
                      (prt_GLsizeiptr)(4u * count), values);
}

static void upload_objects(const prt_gl_shadowfield* s) {
  const prt_gl_functions* gl = &s->gl;
  for (uint32_t o = 0; o < s->object_count; ++o) {
    const prt_sf_object* object = s->scene->objects[o];
    const prt_sf_gl_object* at = &s->objects[o];
    const uint64_t n2 = (uint64_t)object->order * object->order, v = object->vertex_count;
    prt_sf_gl_upload(gl, at->positions, object->positions, 3u * v);
    prt_sf_gl_upload(gl, at->normals, object->normals, 3u * v);
    prt_sf_gl_upload(gl, at->albedo, object->albedo, 3u * v);
    prt_sf_gl_upload(gl, at->transfer, object->transfer, v * object->terms * n2);
    if (object->glossy)
      prt_sf_gl_upload(gl, at->g_table, object->g_table,
                       (uint64_t)object->terms * object->brdf_grid * object->brdf_grid);
    const float* oof =
        s->product == PRT_SHADOWFIELD_PRODUCT_LOG ? s->scene->log_fields[o].values : object->oof;
    prt_sf_gl_upload(gl, at->oof, oof, prt_sf_point_count(&object->oof_shells) * n2);
    if (!object->basis_size) continue;
    prt_sf_gl_upload(gl, at->srf, object->srf, srf_floats(object));
    prt_sf_gl_upload(gl, at->basis, object->basis, (uint64_t)object->basis_size * v);
    prt_sf_gl_upload(gl, at->vertex_weights, object->vertex_weights, v);
    prt_sf_gl_upload(gl, at->basis_inverse, object->basis_inverse,
                     (uint64_t)object->basis_size * object->basis_size);
  }
}

/* k_start, then per coefficient i | j << 8 and the value's bits; then the exponential's rule
 * (gaunt_words). */
static prt_result upload_gaunt(prt_context* context, prt_gl_shadowfield* s, uint64_t bytes) {
  const prt_sf_gaunt* gaunt = &s->scene->gaunt;
  const prt_sf_sphere_rule* rule = &s->scene->exp_rule;
  const uint32_t n2 = gaunt->order * gaunt->order;
  uint32_t* words = (uint32_t*)prt_internal_alloc(&s->allocator, (size_t)bytes, 16);
  if (!words)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory",
                             FUNCTION_CREATE);
  memset(words, 0, (size_t)bytes);
  for (uint32_t k = 0; k <= n2; ++k) words[k] = gaunt->k_start[k];
  for (uint32_t e = 0; e < gaunt->count; ++e) {
    words[n2 + 1u + 2u * e] = (uint32_t)gaunt->i[e] | (uint32_t)gaunt->j[e] << 8u;
    memcpy(&words[n2 + 2u + 2u * e], &gaunt->value[e], sizeof(float));
  }
  const size_t rule_floats = (size_t)rule->directions * n2;
  if (rule_floats) {
    uint32_t* at = &words[tensor_words(s->scene)];
    memcpy(at, rule->eval, rule_floats * sizeof(float));
    memcpy(at + rule_floats, rule->project, rule_floats * sizeof(float));
  }
  s->gl.BufferSubData(PRT_GL_SHADER_STORAGE_BUFFER, 0, (prt_GLsizeiptr)bytes, words);
  prt_internal_free(&s->allocator, words, (size_t)bytes);
  return PRT_OK;
}

static prt_result create_buffers(prt_context* context, prt_gl_shadowfield* s,
                                 const uint64_t bytes[PRT_SF_GL_BUFFER_COUNT]) {
  const prt_gl_functions* gl = &s->gl;
  prt_result r = PRT_OK;
  prt_gl_drain_errors(gl);
  gl->GenBuffers(PRT_SF_GL_BUFFER_COUNT, s->buffers);
  uint64_t total = 0u;
  for (int b = 0; b < PRT_SF_GL_BUFFER_COUNT; ++b) {
    gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[b]);
    gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)bytes[b], NULL,
                   b == PRT_SF_GL_BUFFER_OBJECTS || b == PRT_SF_GL_BUFFER_GAUNT
                       ? PRT_GL_STATIC_DRAW
                       : PRT_GL_DYNAMIC_COPY);
    if (b == PRT_SF_GL_BUFFER_OBJECTS) upload_objects(s);
    if (b == PRT_SF_GL_BUFFER_GAUNT && r == PRT_OK) r = upload_gaunt(context, s, bytes[b]);
    total += bytes[b];
  }
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  s->frame_buffer_floats = (size_t)(bytes[PRT_SF_GL_BUFFER_FRAME] / 4u);
  if (r != PRT_OK) return r;
  return prt_gl_check_upload(context, gl, FUNCTION_CREATE, total);
}

static prt_result check_scene(prt_context* context, const prt_shadowfield_scene* scene,
                              prt_gl_loader_fn loader, prt_gl_shadowfield** out_shader) {
  if (!loader || !out_shader)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "%s: loader and out_shader must not be NULL", FUNCTION_CREATE);
  if (!prt_gl_allowed(context))
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "%s: the context's backend limit excludes gl", FUNCTION_CREATE);
  if (scene->instance_count == 0u)
    return prt_internal_fail(context, PRT_ERROR_INVALID_OPERATION,
                             "%s: the scene has no instance yet (add them first)", FUNCTION_CREATE);
  return PRT_OK;
}

static void* allocate_zeroed(const prt_allocator* allocator, size_t bytes) {
  void* p = prt_internal_alloc(allocator, bytes ? bytes : 1u, 16);
  if (p) memset(p, 0, bytes ? bytes : 1u);
  return p;
}

prt_result prt_gl_shadowfield_create(prt_shadowfield_scene* scene, prt_gl_loader_fn loader,
                                     void* loader_user, prt_gl_shadowfield** out_shader) {
  if (out_shader) *out_shader = NULL;
  if (!scene) return PRT_ERROR_INVALID_ARGUMENT;
  prt_context* context = scene->context;
  prt_result r = check_scene(context, scene, loader, out_shader);
  if (r != PRT_OK) return r;
  prt_gl_shadowfield local;
  memset(&local, 0, sizeof local);
  r = prt_gl_open(context, FUNCTION_CREATE, loader, loader_user, &local.gl);
  if (r != PRT_OK) return r;
  prt_gl_shadowfield* s =
      (prt_gl_shadowfield*)allocate_zeroed(&scene->allocator, sizeof(prt_gl_shadowfield));
  if (!s)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory",
                             FUNCTION_CREATE);
  *s = local;
  s->allocator = scene->allocator;
  s->scene = scene;
  s->object_count = scene->object_count;
  s->instance_count = scene->instance_count;
  s->product = scene->product;
  s->probe_spacing = -1.0f;
  s->objects =
      (prt_sf_gl_object*)allocate_zeroed(&s->allocator, s->object_count * sizeof(prt_sf_gl_object));
  s->instances = (prt_sf_gl_instance*)allocate_zeroed(
      &s->allocator, s->instance_count * sizeof(prt_sf_gl_instance));
  uint64_t bytes[PRT_SF_GL_BUFFER_COUNT];
  if (!s->objects || !s->instances) {
    r = prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory", FUNCTION_CREATE);
  } else {
    lay_out(s, bytes);
    static const char* const kNames[PRT_SF_GL_BUFFER_COUNT] = {
        "objects", "gaunt", "fields", "incident", "radiance", "frame", "scratch", "probes"};
    r = prt_gl_check_block_sizes(context, &s->gl, FUNCTION_CREATE, bytes, kNames,
                                 PRT_SF_GL_BUFFER_COUNT);
  }
  if (r == PRT_OK) r = compile_program(context, s);
  if (r == PRT_OK) r = create_buffers(context, s, bytes);
  if (r != PRT_OK) {
    prt_gl_shadowfield_destroy(s);
    return r;
  }
  *out_shader = s;
  return PRT_OK;
}

void prt_gl_shadowfield_destroy(prt_gl_shadowfield* shader) {
  if (!shader) return;
  if (shader->buffers[0]) shader->gl.DeleteBuffers(PRT_SF_GL_BUFFER_COUNT, shader->buffers);
  if (shader->program) shader->gl.DeleteProgram(shader->program);
  prt_allocator allocator = shader->allocator;
  if (shader->frame) prt_internal_free(&allocator, shader->frame, shader->frame_capacity * 4u);
  if (shader->objects)
    prt_internal_free(
        &allocator, shader->objects,
        (shader->object_count ? shader->object_count * sizeof(prt_sf_gl_object) : 1u));
  if (shader->instances)
    prt_internal_free(
        &allocator, shader->instances,
        (shader->instance_count ? shader->instance_count * sizeof(prt_sf_gl_instance) : 1u));
  prt_internal_free(&allocator, shader, sizeof *shader);
}

#endif /* PRT_HAS_GL */
