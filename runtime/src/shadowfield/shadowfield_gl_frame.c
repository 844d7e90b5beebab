/* SPDX-License-Identifier: MIT */
/* The GL backend of technique `shadowfield`, a frame (prt_gl_shadowfield_shade, _read): the
 * CPU prepares it (prt_shadowfield_prepare) and writes every instance's record (its placement,
 * light and pairs, shadowfield_gl_internal.h); the compute shader's stages then run the direct
 * light, and per bounce each source's projection, its field and the gather, then the outgoing
 * radiance, with a barrier between two stages. Only compiled with PRT_HAS_GL. */
#include "../internal.h"

#if defined(PRT_HAS_GL)

#include <string.h>

#include "../gl_common.h"
#include "shadowfield_gl_internal.h"

#define FUNCTION_SHADE "prt_gl_shadowfield_shade"

static void put_uint(float* words, uint32_t at, uint32_t value) {
  memcpy(words + at, &value, sizeof value);
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
  const prt_sf_gl_object* at = &s->objects[instance->object];
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
  put_uint(words, PRT_SF_GL_PROBE_COUNT, instance->probe_count);
  put_uint(words, PRT_SF_GL_PROBE_POSITIONS, at->probe_positions);
  put_uint(words, PRT_SF_GL_PROBE_LOOKUPS, at->probe_lookups);
  put_uint(words, PRT_SF_GL_PROBE_LIGHT, s->instances[i].probe_light);
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

/* Every instance's record of the prepared frame, uploaded to PRT_SF_GL_BUFFER_FRAME. */
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
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[PRT_SF_GL_BUFFER_FRAME]);
  if (floats > s->frame_buffer_floats) {
    gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)(floats * sizeof(float)), NULL,
                   PRT_GL_DYNAMIC_DRAW);
    s->frame_buffer_floats = floats;
  }
  prt_sf_gl_upload(gl, 0u, s->frame, floats);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  return PRT_OK;
}

/* ---- bounce probes: the layouts at the prepared spacing, laid out again when it changes ---- */

/* Where each object's layout and each instance's probe light go in the probe buffer; its
 * floats. */
static uint64_t place_probes(prt_gl_shadowfield* s) {
  const prt_shadowfield_scene* scene = s->scene;
  const uint64_t n2 = (uint64_t)scene->order * scene->order;
  uint64_t floats = 1u; /* never empty */
  for (uint32_t o = 0; o < s->object_count; ++o) {
    const uint64_t count = scene->probes[o].count;
    s->objects[o].probe_positions = (uint32_t)floats;
    floats += 3u * count;
    s->objects[o].probe_lookups = (uint32_t)floats;
    floats += 16u * (uint64_t)scene->probes[o].lookup_count;
  }
  for (uint32_t i = 0; i < s->instance_count; ++i) {
    s->instances[i].probe_light = (uint32_t)floats;
    floats += scene->probes[scene->instances[i].object].count * 3u * n2;
  }
  return floats;
}

/* The objects' probe positions and vertex lookups into `words` (probe light left as it is). */
static void write_probes(const prt_gl_shadowfield* s, float* words) {
  const prt_shadowfield_scene* scene = s->scene;
  for (uint32_t o = 0; o < s->object_count; ++o) {
    const prt_sf_probes* probes = &scene->probes[o];
    if (probes->count == 0u) continue;
    memcpy(words + s->objects[o].probe_positions, probes->positions,
           (size_t)probes->count * 3u * sizeof(float));
    for (uint32_t v = 0; v < probes->lookup_count; ++v) {
      const prt_sf_lookup* lookup = &probes->lookups[v];
      float* at = words + s->objects[o].probe_lookups + 16u * (size_t)v;
      for (uint32_t e = 0; e < 8u; ++e) {
        put_uint(at, e, e < lookup->count ? (uint32_t)lookup->index[e] : 0u);
        at[8u + e] = e < lookup->count ? lookup->weight[e] : 0.0f;
      }
    }
  }
}

/* The probe buffer for the prepared spacing's layouts, when they changed since the last frame. */
static prt_result upload_probes(prt_gl_shadowfield* s) {
  const prt_shadowfield_scene* scene = s->scene;
  const float spacing = s->object_count > 0u ? scene->probes[0].spacing : 0.0f;
  if (spacing == s->probe_spacing) return PRT_OK;
  const uint64_t floats = place_probes(s);
  if (floats > UINT32_MAX) return PRT_ERROR_OUT_OF_MEMORY;
  float* words = (float*)prt_internal_alloc(&s->allocator, (size_t)floats * sizeof(float), 16);
  if (!words) return PRT_ERROR_OUT_OF_MEMORY;
  memset(words, 0, (size_t)floats * sizeof(float));
  write_probes(s, words);
  const prt_gl_functions* gl = &s->gl;
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[PRT_SF_GL_BUFFER_PROBES]);
  gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)(floats * sizeof(float)), words,
                 PRT_GL_DYNAMIC_COPY);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  prt_internal_free(&s->allocator, words, (size_t)floats * sizeof(float));
  s->probe_spacing = spacing;
  return PRT_OK;
}

/* Invocations [0, count) of the bound stage on instance i's record, in chunks (each chunk's
 * invocations have their own scratch rows, which the next chunk reuses). */
static void dispatch(const prt_gl_shadowfield* s, uint32_t i, uint32_t count) {
  const prt_gl_functions* gl = &s->gl;
  gl->ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_RECORD, s->instances[i].record);
  for (uint32_t first = 0; first < count; first += PRT_SF_GL_CHUNK_VERTICES) {
    const uint32_t chunk =
        count - first < PRT_SF_GL_CHUNK_VERTICES ? count - first : PRT_SF_GL_CHUNK_VERTICES;
    gl->ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_FIRST_VERTEX, first);
    gl->DispatchCompute((chunk + PRT_SF_GL_LOCAL_SIZE - 1u) / PRT_SF_GL_LOCAL_SIZE, 1, 1);
    /* The next dispatch reuses the scratch rows; a later stage reads these writes. */
    gl->MemoryBarrier(PRT_GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

/* One stage over every vertex of every instance. */
static void run_stage(const prt_gl_shadowfield* s, uint32_t stage, uint32_t pass) {
  s->gl.ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_STAGE, stage);
  s->gl.ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_PASS, pass);
  for (uint32_t i = 0; i < s->instance_count; ++i)
    dispatch(s, i, prt_shadowfield_instance_vertex_count(s->scene, i));
}

/* Between pass - 1 and pass: each source's radiance of pass - 1 projected on its basis, then
 * the field it casts from the weights, one source after another (the weights are in the
 * scratch rows). */
static void project_sources(const prt_gl_shadowfield* s, uint32_t pass) {
  const prt_gl_functions* gl = &s->gl;
  const prt_shadowfield_scene* scene = s->scene;
  gl->ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_PASS, pass - 1u);
  for (uint32_t i = 0; i < s->instance_count; ++i) {
    const prt_sf_instance* source = &scene->instances[i];
    if (!source->is_source || !source->field) continue;
    const prt_sf_object* object = scene->objects[source->object];
    const uint32_t weights = object->basis_size * object->terms * 3u;
    gl->ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_STAGE, PRT_SF_GL_STAGE_PROJECT);
    dispatch(s, i, weights);
    gl->ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_STAGE, PRT_SF_GL_STAGE_WEIGHTS);
    dispatch(s, i, weights);
    gl->ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_STAGE, PRT_SF_GL_STAGE_CAST);
    dispatch(s, i, (uint32_t)(prt_sf_field_points(scene, i) * scene->order * scene->order));
  }
}

/* Each instance's bounce probes gather their light of `pass`. */
static void gather_probes(const prt_gl_shadowfield* s, uint32_t pass) {
  s->gl.ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_STAGE, PRT_SF_GL_STAGE_PROBES);
  s->gl.ProgramUniform1ui(s->program, PRT_SF_GL_UNIFORM_PASS, pass);
  for (uint32_t i = 0; i < s->instance_count; ++i)
    if (s->scene->instances[i].probe_count > 0u) dispatch(s, i, s->scene->instances[i].probe_count);
}

static void bind_buffers(const prt_gl_shadowfield* s, int bind) {
  for (uint32_t b = 0; b < PRT_SF_GL_BUFFER_COUNT; ++b)
    s->gl.BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, b, bind ? s->buffers[b] : 0u);
}

/* The settings for prt_shadowfield_prepare: a GL backend asked for becomes AUTO there (the
 * preparation is the CPU's); a CPU or SIMD one is refused. Others go to prepare as they are, so
 * that it refuses them as it does for prt_shadowfield_shade. */
static prt_result prepare_settings(prt_context* context, const prt_shadowfield_settings* settings,
                                   prt_shadowfield_settings* copy,
                                   const prt_shadowfield_settings** out) {
  *out = settings;
  if (!settings || !prt_internal_struct_size_ok(settings, PRT_SF_SETTINGS_1_0_SIZE)) return PRT_OK;
  if (settings->backend == PRT_BACKEND_CPU || settings->backend == PRT_BACKEND_SIMD)
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "%s: settings ask for a CPU backend (use prt_shadowfield_shade)",
                             FUNCTION_SHADE);
  if (settings->backend == PRT_BACKEND_GL) {
    /* As far as the caller's struct reaches; the rest as a zeroed struct has it. */
    memset(copy, 0, sizeof *copy);
    memcpy(copy, settings,
           settings->struct_size < sizeof *copy ? settings->struct_size : sizeof *copy);
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
  if (scene->product != shader->product)
    return prt_internal_fail(scene->context, PRT_ERROR_INVALID_OPERATION,
                             "%s: the scene's product changed since the create call (create the "
                             "shader again)",
                             FUNCTION_SHADE);
  prt_shadowfield_settings copy;
  const prt_shadowfield_settings* cpu_settings;
  prt_result r = prepare_settings(scene->context, settings, &copy, &cpu_settings);
  if (r == PRT_OK) r = prt_shadowfield_prepare(scene, light_sh_rgb, eye, cpu_settings);
  if (r != PRT_OK) return r;
  if (upload_probes(shader) != PRT_OK || upload_frame(shader) != PRT_OK) {
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
    gather_probes(shader, pass);
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
  return shader ? shader->buffers[PRT_SF_GL_BUFFER_RADIANCE] : 0u;
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
    prt_gl_read_radiance(&shader->gl, shader->buffers[PRT_SF_GL_BUFFER_RADIANCE],
                         shader->instances[instance].radiance_vertex + first_vertex, vertex_count,
                         out_rgb);
  return PRT_OK;
}

#endif /* PRT_HAS_GL */
