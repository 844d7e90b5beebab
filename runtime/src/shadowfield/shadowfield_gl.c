/* SPDX-License-Identifier: MIT */
/* The GL backend of technique `shadowfield` (prt/prt_shadowfield.h, prt_gl_shadowfield_*): the
 * per-vertex work of a frame in a compute shader (shadowfield_gl_glsl.c): the direct light, the
 * bounces and the outgoing radiance. The CPU keeps the small work: the frame's preparation (the
 * light in each instance's frame, the pairs and their rotations, prt_shadowfield_prepare) and,
 * between two passes, nothing: each source's basis projection and the field it casts are
 * shader stages too, so a frame reads nothing back. */
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
#define FUNCTION_SHADE "prt_gl_shadowfield_shade"

/* The buffers, by their binding in the shader. */
enum {
  BUFFER_OBJECTS = 0,  /* every object's vertices, transfer, g table and OOF */
  BUFFER_GAUNT = 1,    /* the triple-product tensor */
  BUFFER_FIELDS = 2,   /* every source's field of the last projected pass */
  BUFFER_INCIDENT = 3, /* every instance's light per pass, vertex and term */
  BUFFER_RADIANCE = 4, /* every instance's outgoing radiance */
  BUFFER_FRAME = 5,    /* every instance's record of the frame */
  BUFFER_SCRATCH = 6,  /* each invocation's SH vectors (shadowfield_gl_glsl.c) */
  BUFFER_COUNT = 7
};
enum {
  UNIFORM_RECORD = 0,
  UNIFORM_STAGE = 1,
  UNIFORM_PASS = 2,
  UNIFORM_FIRST_VERTEX = 3,
  UNIFORM_ORDER = 4
};

/* Vertices per dispatch: each has its scratch rows, so this bounds the scratch buffer. */
#define CHUNK_VERTICES 16384u

/* Where an object's arrays start in the object buffer (floats). */
typedef struct object_offsets {
  uint32_t positions, normals, albedo, transfer, g_table, oof, srf;
  uint32_t basis, vertex_weights, basis_inverse;
} object_offsets;

/* Where an instance's arrays start: incident and field (floats), radiance (vertices), and its
 * record in the frame buffer (floats, set per frame). */
typedef struct instance_offsets {
  uint32_t incident, field, radiance_vertex, record;
} instance_offsets;

struct prt_gl_shadowfield {
  prt_allocator allocator; /* the scene's context's */
  prt_gl_functions gl;
  prt_shadowfield_scene* scene;
  uint32_t object_count, instance_count; /* the scene's when created */
  prt_GLuint program;
  prt_GLuint buffers[BUFFER_COUNT];
  object_offsets* objects;
  instance_offsets* instances;
  uint32_t radiance_vertices;
  float* frame;               /* the records, uploaded to BUFFER_FRAME */
  size_t frame_capacity;      /* floats in `frame` */
  size_t frame_buffer_floats; /* floats in BUFFER_FRAME */
};

static void put_uint(float* words, uint32_t at, uint32_t value) {
  memcpy(words + at, &value, sizeof value);
}

/* ---- create ------------------------------------------------------------------------------- */

static prt_result compile_program(prt_context* context, prt_gl_shadowfield* s) {
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
           "#define VERTEX_WEIGHTS %uu\n#define BASIS_INVERSE %uu\n",
           PRT_SF_GL_LOCAL_SIZE, PRT_SF_GL_VERTICES, PRT_SF_GL_TERMS, PRT_SF_GL_GLOSSY,
           PRT_SF_GL_BRDF_GRID, PRT_SF_GL_POSITIONS, PRT_SF_GL_NORMALS, PRT_SF_GL_ALBEDO,
           PRT_SF_GL_TRANSFER, PRT_SF_GL_G_TABLE, PRT_SF_GL_INCIDENT, PRT_SF_GL_OUTPUT,
           PRT_SF_GL_PAIR_COUNT, PRT_SF_GL_ROTATION, PRT_SF_GL_TRANSLATION, PRT_SF_GL_SCALE,
           PRT_SF_GL_EYE, PRT_SF_GL_LIGHT, PRT_SF_GL_PRODUCT, PRT_SF_GL_HEADER, PRT_SF_GL_OCCLUDES,
           PRT_SF_GL_LIGHTS, PRT_SF_GL_TO_OTHER, PRT_SF_GL_OFFSET, PRT_SF_GL_OOF_GRID,
           PRT_SF_GL_OOF, PRT_SF_GL_SRF_GRID, PRT_SF_GL_FIELD, PRT_SF_GL_FIELD_PLANE,
           PRT_SF_GL_SH_ROTATION, PRT_SF_GL_PAIR_FLOATS, PRT_SF_GL_SRF, PRT_SF_GL_BASIS,
           PRT_SF_GL_OWN_FIELD, PRT_SF_GL_FIELD_POINTS, PRT_SF_GL_BASIS_VALUES,
           PRT_SF_GL_VERTEX_WEIGHTS, PRT_SF_GL_BASIS_INVERSE);
  const prt_GLchar* sources[2] = {header, prt_sf_gl_shader_source};
  const prt_result r =
      prt_gl_compile_compute(context, &s->gl, FUNCTION_CREATE, sources, 2, &s->program);
  if (r == PRT_OK) s->gl.ProgramUniform1ui(s->program, UNIFORM_ORDER, s->scene->order);
  return r;
}

static uint64_t srf_floats(const prt_sf_object* o) {
  return (uint64_t)o->basis_size * o->terms * prt_sf_point_count(&o->srf_shells) * o->order *
         o->order;
}

static uint64_t object_floats(const prt_sf_object* o, object_offsets* at, uint64_t start) {
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
static void lay_out(prt_gl_shadowfield* s, uint64_t bytes[BUFFER_COUNT]) {
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
      (most_vertices < CHUNK_VERTICES ? most_vertices : CHUNK_VERTICES) + PRT_SF_GL_LOCAL_SIZE;
  s->radiance_vertices = (uint32_t)radiance;
  bytes[BUFFER_OBJECTS] = 4u * objects;
  bytes[BUFFER_GAUNT] = 4u * (scene->order * scene->order + 1u + 2u * (uint64_t)scene->gaunt.count);
  bytes[BUFFER_FIELDS] = 4u * fields;
  bytes[BUFFER_INCIDENT] = 4u * incident;
  bytes[BUFFER_RADIANCE] = 12u * radiance;
  bytes[BUFFER_FRAME] = 4u * (uint64_t)s->instance_count * PRT_SF_GL_HEADER;
  bytes[BUFFER_SCRATCH] = 4u * invocations * PRT_SF_GL_SCRATCH_FLOATS(scene->order);
  if (bytes[BUFFER_SCRATCH] < 4u * most_weights) bytes[BUFFER_SCRATCH] = 4u * most_weights;
  for (int b = 0; b < BUFFER_COUNT; ++b)
    if (bytes[b] == 0u) bytes[b] = 4u; /* empty parts still get valid buffers */
}

static void upload(const prt_gl_functions* gl, uint32_t at, const float* values, uint64_t count) {
  if (count)
    gl->BufferSubData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLintptr)(4u * (uint64_t)at),
                      (prt_GLsizeiptr)(4u * count), values);
}

static void upload_objects(const prt_gl_shadowfield* s) {
  const prt_gl_functions* gl = &s->gl;
  for (uint32_t o = 0; o < s->object_count; ++o) {
    const prt_sf_object* object = s->scene->objects[o];
    const object_offsets* at = &s->objects[o];
    const uint64_t n2 = (uint64_t)object->order * object->order, v = object->vertex_count;
    upload(gl, at->positions, object->positions, 3u * v);
    upload(gl, at->normals, object->normals, 3u * v);
    upload(gl, at->albedo, object->albedo, 3u * v);
    upload(gl, at->transfer, object->transfer, v * object->terms * n2);
    if (object->glossy)
      upload(gl, at->g_table, object->g_table,
             (uint64_t)object->terms * object->brdf_grid * object->brdf_grid);
    upload(gl, at->oof, object->oof, prt_sf_point_count(&object->oof_shells) * n2);
    if (!object->basis_size) continue;
    upload(gl, at->srf, object->srf, srf_floats(object));
    upload(gl, at->basis, object->basis, (uint64_t)object->basis_size * v);
    upload(gl, at->vertex_weights, object->vertex_weights, v);
    upload(gl, at->basis_inverse, object->basis_inverse,
           (uint64_t)object->basis_size * object->basis_size);
  }
}

/* k_start, then per coefficient i | j << 8 and the value's bits. */
static prt_result upload_gaunt(prt_context* context, prt_gl_shadowfield* s, uint64_t bytes) {
  const prt_sf_gaunt* gaunt = &s->scene->gaunt;
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
  s->gl.BufferSubData(PRT_GL_SHADER_STORAGE_BUFFER, 0, (prt_GLsizeiptr)bytes, words);
  prt_internal_free(&s->allocator, words, (size_t)bytes);
  return PRT_OK;
}

static prt_result create_buffers(prt_context* context, prt_gl_shadowfield* s,
                                 const uint64_t bytes[BUFFER_COUNT]) {
  const prt_gl_functions* gl = &s->gl;
  prt_result r = PRT_OK;
  prt_gl_drain_errors(gl);
  gl->GenBuffers(BUFFER_COUNT, s->buffers);
  uint64_t total = 0u;
  for (int b = 0; b < BUFFER_COUNT; ++b) {
    gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[b]);
    gl->BufferData(
        PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)bytes[b], NULL,
        b == BUFFER_OBJECTS || b == BUFFER_GAUNT ? PRT_GL_STATIC_DRAW : PRT_GL_DYNAMIC_COPY);
    if (b == BUFFER_OBJECTS) upload_objects(s);
    if (b == BUFFER_GAUNT && r == PRT_OK) r = upload_gaunt(context, s, bytes[b]);
    total += bytes[b];
  }
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  s->frame_buffer_floats = (size_t)(bytes[BUFFER_FRAME] / 4u);
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
  s->objects =
      (object_offsets*)allocate_zeroed(&s->allocator, s->object_count * sizeof(object_offsets));
  s->instances = (instance_offsets*)allocate_zeroed(&s->allocator,
                                                    s->instance_count * sizeof(instance_offsets));
  uint64_t bytes[BUFFER_COUNT];
  if (!s->objects || !s->instances) {
    r = prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory", FUNCTION_CREATE);
  } else {
    lay_out(s, bytes);
    static const char* const kNames[BUFFER_COUNT] = {"objects",  "gaunt", "fields", "incident",
                                                     "radiance", "frame", "scratch"};
    r = prt_gl_check_block_sizes(context, &s->gl, FUNCTION_CREATE, bytes, kNames, BUFFER_COUNT);
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
  if (shader->buffers[0]) shader->gl.DeleteBuffers(BUFFER_COUNT, shader->buffers);
  if (shader->program) shader->gl.DeleteProgram(shader->program);
  prt_allocator allocator = shader->allocator;
  if (shader->frame) prt_internal_free(&allocator, shader->frame, shader->frame_capacity * 4u);
  if (shader->objects)
    prt_internal_free(&allocator, shader->objects,
                      (shader->object_count ? shader->object_count * sizeof(object_offsets) : 1u));
  if (shader->instances)
    prt_internal_free(
        &allocator, shader->instances,
        (shader->instance_count ? shader->instance_count * sizeof(instance_offsets) : 1u));
  prt_internal_free(&allocator, shader, sizeof *shader);
}

/* ---- per frame ---------------------------------------------------------------------------- */

static void put_grid(float* words, uint32_t at, const prt_sf_shells* grid) {
  memcpy(words + at, grid->centre, sizeof grid->centre);
  words[at + 3u] = grid->radius;
  words[at + 4u] = grid->inner;
  words[at + 5u] = grid->outer;
  put_uint(words, at + 6u, grid->shells);
  put_uint(words, at + 7u, grid->face_size);
}

static void write_pair(const prt_gl_shadowfield* s, const prt_sf_pair* pair, float* words) {
  const prt_shadowfield_scene* scene = s->scene;
  const prt_sf_instance* other = &scene->instances[pair->other];
  const prt_sf_object* object = scene->objects[other->object];
  const uint32_t n2 = scene->order * scene->order;
  put_uint(words, PRT_SF_GL_OCCLUDES, pair->occludes);
  put_uint(words, PRT_SF_GL_LIGHTS, pair->lights && other->field ? 1u : 0u);
  memcpy(words + PRT_SF_GL_TO_OTHER, pair->to_other, sizeof pair->to_other);
  memcpy(words + PRT_SF_GL_OFFSET, pair->offset, sizeof pair->offset);
  put_grid(words, PRT_SF_GL_OOF_GRID, &object->oof_shells);
  put_uint(words, PRT_SF_GL_OOF, s->objects[other->object].oof);
  put_grid(words, PRT_SF_GL_SRF_GRID, &object->srf_shells);
  put_uint(words, PRT_SF_GL_FIELD, s->instances[pair->other].field);
  put_uint(words, PRT_SF_GL_FIELD_PLANE,
           object->basis_size ? (uint32_t)(prt_sf_point_count(&object->srf_shells) * n2) : 0u);
  memcpy(words + PRT_SF_GL_SH_ROTATION, pair->sh_rotation, sizeof pair->sh_rotation);
}

/* The header of instance i's record: its object, buffers, placement and prepared light. */
static void write_header(const prt_gl_shadowfield* s, uint32_t i, float* words) {
  const prt_shadowfield_scene* scene = s->scene;
  const prt_sf_instance* instance = &scene->instances[i];
  const prt_sf_object* object = scene->objects[instance->object];
  const object_offsets* at = &s->objects[instance->object];
  const uint32_t n2 = scene->order * scene->order;
  memset(words, 0, PRT_SF_GL_HEADER * sizeof(float));
  put_uint(words, PRT_SF_GL_VERTICES, object->vertex_count);
  put_uint(words, PRT_SF_GL_TERMS, object->terms);
  put_uint(words, PRT_SF_GL_GLOSSY, object->glossy);
  put_uint(words, PRT_SF_GL_BRDF_GRID, object->brdf_grid);
  put_uint(words, PRT_SF_GL_POSITIONS, at->positions);
  put_uint(words, PRT_SF_GL_NORMALS, at->normals);
  put_uint(words, PRT_SF_GL_ALBEDO, at->albedo);
  put_uint(words, PRT_SF_GL_TRANSFER, at->transfer);
  put_uint(words, PRT_SF_GL_G_TABLE, at->g_table);
  put_uint(words, PRT_SF_GL_INCIDENT, s->instances[i].incident);
  put_uint(words, PRT_SF_GL_OUTPUT, 3u * s->instances[i].radiance_vertex);
  put_uint(words, PRT_SF_GL_PAIR_COUNT, instance->pair_count);
  put_uint(words, PRT_SF_GL_SRF, at->srf);
  put_uint(words, PRT_SF_GL_BASIS, instance->field ? object->basis_size : 0u);
  put_uint(words, PRT_SF_GL_OWN_FIELD, s->instances[i].field);
  put_uint(words, PRT_SF_GL_FIELD_POINTS,
           instance->field ? (uint32_t)prt_sf_point_count(&object->srf_shells) : 0u);
  put_uint(words, PRT_SF_GL_BASIS_VALUES, at->basis);
  put_uint(words, PRT_SF_GL_VERTEX_WEIGHTS, at->vertex_weights);
  put_uint(words, PRT_SF_GL_BASIS_INVERSE, at->basis_inverse);
  memcpy(words + PRT_SF_GL_ROTATION, instance->rotation, sizeof instance->rotation);
  memcpy(words + PRT_SF_GL_TRANSLATION, instance->translation, sizeof instance->translation);
  words[PRT_SF_GL_SCALE] = instance->scale;
  memcpy(words + PRT_SF_GL_EYE, scene->eye, sizeof scene->eye);
  memcpy(words + PRT_SF_GL_LIGHT, instance->light, (size_t)3u * n2 * sizeof(float));
  memcpy(words + PRT_SF_GL_PRODUCT, instance->light_product, (size_t)3u * n2 * n2 * sizeof(float));
}

static int reserve_frame(prt_gl_shadowfield* s, size_t floats) {
  if (floats > s->frame_capacity) {
    float* frame = (float*)prt_internal_alloc(&s->allocator, floats * sizeof(float), 16);
    if (!frame) return 0;
    if (s->frame) prt_internal_free(&s->allocator, s->frame, s->frame_capacity * sizeof(float));
    s->frame = frame;
    s->frame_capacity = floats;
  }
  return 1;
}

/* Every instance's record of the prepared frame, uploaded to BUFFER_FRAME. */
static prt_result upload_frame(prt_gl_shadowfield* s) {
  const prt_shadowfield_scene* scene = s->scene;
  size_t floats = 0u;
  for (uint32_t i = 0; i < s->instance_count; ++i)
    floats += PRT_SF_GL_HEADER + (size_t)scene->instances[i].pair_count * PRT_SF_GL_PAIR_FLOATS;
  if (!reserve_frame(s, floats)) return PRT_ERROR_OUT_OF_MEMORY;
  size_t at = 0u;
  for (uint32_t i = 0; i < s->instance_count; ++i) {
    const prt_sf_instance* instance = &scene->instances[i];
    s->instances[i].record = (uint32_t)at;
    write_header(s, i, s->frame + at);
    at += PRT_SF_GL_HEADER;
    for (uint32_t q = 0; q < instance->pair_count; ++q, at += PRT_SF_GL_PAIR_FLOATS)
      write_pair(s, &scene->pairs[instance->pair_first + q], s->frame + at);
  }
  const prt_gl_functions* gl = &s->gl;
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[BUFFER_FRAME]);
  if (floats > s->frame_buffer_floats) {
    gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)(floats * sizeof(float)), NULL,
                   PRT_GL_DYNAMIC_DRAW);
    s->frame_buffer_floats = floats;
  }
  upload(gl, 0u, s->frame, floats);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  return PRT_OK;
}

/* Invocations [0, count) of the bound stage on instance i's record, in chunks (each chunk's
 * invocations have their own scratch rows, which the next chunk reuses). */
static void dispatch(const prt_gl_shadowfield* s, uint32_t i, uint32_t count) {
  const prt_gl_functions* gl = &s->gl;
  gl->ProgramUniform1ui(s->program, UNIFORM_RECORD, s->instances[i].record);
  for (uint32_t first = 0; first < count; first += CHUNK_VERTICES) {
    const uint32_t chunk = count - first < CHUNK_VERTICES ? count - first : CHUNK_VERTICES;
    gl->ProgramUniform1ui(s->program, UNIFORM_FIRST_VERTEX, first);
    gl->DispatchCompute((chunk + PRT_SF_GL_LOCAL_SIZE - 1u) / PRT_SF_GL_LOCAL_SIZE, 1, 1);
    /* The next dispatch reuses the scratch rows; a later stage reads these writes. */
    gl->MemoryBarrier(PRT_GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

/* One stage over every vertex of every instance. */
static void run_stage(const prt_gl_shadowfield* s, uint32_t stage, uint32_t pass) {
  s->gl.ProgramUniform1ui(s->program, UNIFORM_STAGE, stage);
  s->gl.ProgramUniform1ui(s->program, UNIFORM_PASS, pass);
  for (uint32_t i = 0; i < s->instance_count; ++i)
    dispatch(s, i, prt_shadowfield_instance_vertex_count(s->scene, i));
}

/* Between pass - 1 and pass: each source's radiance of pass - 1 projected on its basis, then
 * the field it casts from the weights, one source after another (the weights are in the
 * scratch rows). */
static void project_sources(const prt_gl_shadowfield* s, uint32_t pass) {
  const prt_gl_functions* gl = &s->gl;
  const prt_shadowfield_scene* scene = s->scene;
  gl->ProgramUniform1ui(s->program, UNIFORM_PASS, pass - 1u);
  for (uint32_t i = 0; i < s->instance_count; ++i) {
    const prt_sf_instance* source = &scene->instances[i];
    if (!source->is_source || !source->field) continue;
    const prt_sf_object* object = scene->objects[source->object];
    const uint32_t weights = object->basis_size * object->terms * 3u;
    gl->ProgramUniform1ui(s->program, UNIFORM_STAGE, PRT_SF_GL_STAGE_PROJECT);
    dispatch(s, i, weights);
    gl->ProgramUniform1ui(s->program, UNIFORM_STAGE, PRT_SF_GL_STAGE_WEIGHTS);
    dispatch(s, i, weights);
    gl->ProgramUniform1ui(s->program, UNIFORM_STAGE, PRT_SF_GL_STAGE_CAST);
    dispatch(s, i, (uint32_t)(prt_sf_field_points(scene, i) * scene->order * scene->order));
  }
}

static void bind_buffers(const prt_gl_shadowfield* s, int bind) {
  for (uint32_t b = 0; b < BUFFER_COUNT; ++b)
    s->gl.BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, b, bind ? s->buffers[b] : 0u);
}

/* The settings for prt_shadowfield_prepare: a GL backend asked for becomes AUTO there (the
 * preparation is the CPU's); a CPU or SIMD one is refused. Others go to prepare as they are, so
 * that it refuses them as it does for prt_shadowfield_shade. */
static prt_result prepare_settings(prt_context* context, const prt_shadowfield_settings* settings,
                                   prt_shadowfield_settings* copy,
                                   const prt_shadowfield_settings** out) {
  *out = settings;
  if (!settings || !prt_internal_struct_size_ok(settings, sizeof *settings)) return PRT_OK;
  if (settings->backend == PRT_BACKEND_CPU || settings->backend == PRT_BACKEND_SIMD)
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "%s: settings ask for a CPU backend (use prt_shadowfield_shade)",
                             FUNCTION_SHADE);
  if (settings->backend == PRT_BACKEND_GL) {
    *copy = *settings;
    copy->backend = PRT_BACKEND_AUTO;
    *out = copy;
  }
  return PRT_OK;
}

prt_result prt_gl_shadowfield_shade(prt_gl_shadowfield* shader, const float* light_sh_rgb,
                                    const float eye[3], const prt_shadowfield_settings* settings) {
  if (!shader) return PRT_ERROR_INVALID_ARGUMENT;
  prt_shadowfield_scene* scene = shader->scene;
  if (scene->instance_count != shader->instance_count ||
      scene->object_count != shader->object_count)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_OPERATION,
                             "%s: the scene gained objects or instances since the create call",
                             FUNCTION_SHADE);
  prt_shadowfield_settings copy;
  const prt_shadowfield_settings* cpu_settings;
  prt_result r = prepare_settings(scene->context, settings, &copy, &cpu_settings);
  if (r == PRT_OK) r = prt_shadowfield_prepare(scene, light_sh_rgb, eye, cpu_settings);
  if (r != PRT_OK) return r;
  if (upload_frame(shader) != PRT_OK) {
    scene->prepared = 0u;
    return prt_internal_fail(scene->context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory",
                             FUNCTION_SHADE);
  }
  const prt_gl_functions* gl = &shader->gl;
  bind_buffers(shader, 1);
  gl->UseProgram(shader->program);
  run_stage(shader, PRT_SF_GL_STAGE_DIRECT, 0u);
  for (uint32_t pass = 1; pass <= scene->bounces; ++pass) {
    project_sources(shader, pass);
    run_stage(shader, PRT_SF_GL_STAGE_BOUNCE, pass);
  }
  run_stage(shader, PRT_SF_GL_STAGE_OUTPUT, scene->bounces);
  /* For what reads the output next: vertex fetch, copies, reads. */
  gl->MemoryBarrier(PRT_GL_BUFFER_UPDATE_BARRIER_BIT | PRT_GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
  gl->UseProgram(0);
  bind_buffers(shader, 0);
  /* The CPU's buffers do not hold this frame: its stages must be prepared again. */
  scene->prepared = 0u;
  return PRT_OK;
}

uint32_t prt_gl_shadowfield_output_buffer(const prt_gl_shadowfield* shader) {
  return shader ? shader->buffers[BUFFER_RADIANCE] : 0u;
}

uint32_t prt_gl_shadowfield_output_first(const prt_gl_shadowfield* shader, uint32_t instance) {
  if (!shader || instance >= shader->instance_count) return 0u;
  return shader->instances[instance].radiance_vertex;
}

prt_result prt_gl_shadowfield_read(prt_gl_shadowfield* shader, uint32_t instance,
                                   uint32_t first_vertex, uint32_t vertex_count, float* out_rgb) {
  if (!shader || instance >= shader->instance_count || (!out_rgb && vertex_count > 0u))
    return PRT_ERROR_INVALID_ARGUMENT;
  const uint32_t vertices = prt_shadowfield_instance_vertex_count(shader->scene, instance);
  if (first_vertex > vertices || vertex_count > vertices - first_vertex)
    return PRT_ERROR_INVALID_ARGUMENT;
  if (vertex_count > 0u)
    prt_gl_read_radiance(&shader->gl, shader->buffers[BUFFER_RADIANCE],
                         shader->instances[instance].radiance_vertex + first_vertex, vertex_count,
                         out_rgb);
  return PRT_OK;
}

#endif /* PRT_HAS_GL */
