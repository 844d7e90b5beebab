/* SPDX-License-Identifier: MIT */
/* The GL backend of `wavelet` shading (prt_wavelet_asset.h): a compute shader over the sparse
 * rows of the WVLT section (formats/SPEC.md §7.2), uploaded as stored, at the offsets of the view
 * the load decoded. */
#include "internal.h"

#if !defined(PRT_HAS_GL)
prt_result prt_gl_wavelet_create(prt_context* context, const prt_asset* asset,
                                 prt_gl_loader_fn loader, void* loader_user,
                                 prt_gl_wavelet_shader** out_shader) {
  (void)asset, (void)loader, (void)loader_user;
  if (out_shader) *out_shader = NULL;
  return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                           "prt_gl_wavelet_create: compiled out (PRT_ENABLE_GL=OFF)");
}
void prt_gl_wavelet_destroy(prt_gl_wavelet_shader* shader) {
  (void)shader;
}
prt_result prt_gl_wavelet_shade(prt_gl_wavelet_shader* shader, const float* prepared_rgba,
                                uint32_t first_vertex, uint32_t vertex_count) {
  (void)shader, (void)prepared_rgba, (void)first_vertex, (void)vertex_count;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
uint32_t prt_gl_wavelet_output_buffer(const prt_gl_wavelet_shader* shader) {
  (void)shader;
  return 0;
}
prt_result prt_gl_wavelet_read(prt_gl_wavelet_shader* shader, uint32_t first_vertex,
                               uint32_t vertex_count, float* out_rgb) {
  (void)shader, (void)first_vertex, (void)vertex_count, (void)out_rgb;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
#else /* PRT_HAS_GL */

#include <stdio.h>
#include <string.h>

#include "gl_common.h"
#include "techniques.h"
#include "wavelet_internal.h"

/* Invocations per vertex (one work group each), and vertices per dispatch (GL guarantees 65535
 * groups in x). */
#define LANES 8u
#define MAX_GROUPS_PER_DISPATCH 65535u

/* buffers[]: the prepared light followed by the WVLT section (SSBO binding 0) and the radiance
 * (SSBO binding 2). The light shares the transfer's buffer so that the GL state touched stays
 * the one prt_wavelet_asset.h documents (SSBO bindings 0 and 2); it is rewritten by each shade
 * call. */
enum { BUFFER_DATA = 0, BUFFER_RADIANCE = 1, BUFFER_COUNT = 2 };
enum { BINDING_DATA = 0, BINDING_RADIANCE = 2 };
enum { UNIFORM_FIRST_VERTEX = 0 };

/* Where the WVLT arrays are, in 32-bit words from the section's start (§7.2; every array starts
 * on a word: the header, scales and row starts are words, and the counts are an even number of
 * u16 per vertex since B is even). */
typedef struct wavelet_words {
  uint32_t coefficients; /* F S²: the light's length in RGBA quadruples */
  uint32_t blocks;       /* B = F S² / 256 per row */
  uint32_t vertices;     /* V */
  uint32_t pairs;        /* P */
  uint32_t vertex_scale_word, row_start_word, count_word, pair_word;
} wavelet_words;

struct prt_gl_wavelet_shader {
  prt_allocator allocator; /* the asset's */
  prt_gl_functions gl;
  wavelet_words layout;
  const uint8_t* section;
  size_t section_bytes;
  prt_GLuint program;
  prt_GLuint buffers[BUFFER_COUNT];
};

static const char kCreate[] = "prt_gl_wavelet_create";

/* The word offsets of the view's layout; the section must fit the shaders' uint indexing. */
static prt_result read_layout(prt_context* context, const prt_wavelet_view* view,
                              wavelet_words* out) {
  const prt_blob_wvlt_layout* l = &view->layout;
  if (l->raw_size > UINT32_MAX)
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "%s: the WVLT section's %llu bytes exceed what GL can index", kCreate,
                             (unsigned long long)l->raw_size);
  out->coefficients = l->coefficients;
  out->blocks = l->blocks;
  out->vertices = view->info.vertex_count;
  out->pairs = view->info.pair_count;
  out->vertex_scale_word = (uint32_t)(l->vertex_scale / 4u);
  out->row_start_word = (uint32_t)(l->row_start / 4u);
  out->count_word = (uint32_t)(l->counts / 4u);
  out->pair_word = (uint32_t)(l->pairs / 4u);
  return PRT_OK;
}

/* ---- the compute shader ---------------------------------------------------------------- */

/* One work group of LANES invocations per vertex: lane t sums q * prepared[j] over the row's
 * pairs t, t + LANES, ... (adjacent lanes read adjacent pairs), finding each pair's block by
 * walking the block counts forward; the lanes' partial sums are added in shared memory and
 * multiplied by the vertex scale: radiance = vs * sum (§7.2 with the band scales folded into the
 * light by prt_wavelet_prepare_light). 8 lanes per vertex measured faster on Mesa llvmpipe than
 * 16 or 32, and than one invocation summing a row alone. The data is read as stored: 16-bit block
 * counts and (index, value) pairs two to a uint word (little-endian), the value's sign extended by
 * bitfieldExtract. Every read is clamped to its array (row starts to P, each block to 256 and
 * the blocks to the row's end), so corrupt rows give wrong sums, never reads outside the buffer;
 * a pair's coefficient 256 k + i is below F S² by construction. */
static const char kShaderSource[] =
    "layout(local_size_x = LANES) in;\n"
    "layout(std430, binding = 0) readonly restrict buffer Data {\n"
    "  vec4 light[COEFFICIENTS];\n"
    "  uint words[];\n"
    "};\n"
    "layout(std430, binding = 2) writeonly restrict buffer Radiance { float radiance[]; };\n"
    "layout(location = 0) uniform uint first_vertex;\n"
    "shared vec3 partial[LANES];\n"
    "\n"
    "uint half_word(uint first_word, uint i) {\n"
    "  return bitfieldExtract(words[first_word + (i >> 1u)], int((i & 1u) << 4u), 16);\n"
    "}\n"
    "uint block_count(uint i) { return min(half_word(COUNT_WORD, i), 256u); }\n"
    "\n"
    "vec3 lane_sum(uint v, uint lane) {\n"
    "  uint p0 = min(words[ROW_START_WORD + v], PAIRS);\n"
    "  uint end = clamp(words[ROW_START_WORD + v + 1u], p0, PAIRS);\n"
    "  uint counts = v * BLOCKS, k = 0u, block_end = p0 + block_count(counts);\n"
    "  vec3 sum = vec3(0.0);\n"
    "  for (uint p = p0 + lane; p < end; p += LANES) {\n"
    "    while (p >= block_end && k + 1u < BLOCKS) block_end += block_count(counts + ++k);\n"
    "    if (p >= block_end) break; /* the counts end before the row: corrupt */\n"
    "    uint pair = half_word(PAIR_WORD, p);\n"
    "    sum += float(bitfieldExtract(int(pair), 8, 8)) * light[(k << 8u) + (pair & 0xFFu)].rgb;\n"
    "  }\n"
    "  return sum;\n"
    "}\n"
    "\n"
    "void main() {\n"
    "  uint v = first_vertex + gl_WorkGroupID.x, lane = gl_LocalInvocationID.x;\n"
    "  partial[lane] = lane_sum(v, lane);\n"
    "  barrier();\n"
    "  if (lane != 0u) return;\n"
    "  vec3 sum = partial[0];\n"
    "  for (uint i = 1u; i < LANES; ++i) sum += partial[i];\n"
    "  uint s = VERTEX_SCALE_WORD + 3u * v;\n"
    "  vec3 rgb = uintBitsToFloat(uvec3(words[s], words[s + 1u], words[s + 2u])) * sum;\n"
    "  radiance[3u * v + 0u] = rgb.x;\n"
    "  radiance[3u * v + 1u] = rgb.y;\n"
    "  radiance[3u * v + 2u] = rgb.z;\n"
    "}\n";

static prt_result compile_program(prt_context* context, prt_gl_wavelet_shader* s) {
  const wavelet_words* l = &s->layout;
  char header[512];
  const prt_GLchar* sources[2];
  snprintf(header, sizeof header,
           "#version 430 core\n#define LANES %uu\n#define COEFFICIENTS %u\n#define BLOCKS %uu\n"
           "#define PAIRS %uu\n#define VERTEX_SCALE_WORD %uu\n#define ROW_START_WORD %uu\n"
           "#define COUNT_WORD %uu\n#define PAIR_WORD %uu\n",
           LANES, l->coefficients, l->blocks, l->pairs, l->vertex_scale_word, l->row_start_word,
           l->count_word, l->pair_word);
  sources[0] = header;
  sources[1] = kShaderSource;
  return prt_gl_compile_compute(context, &s->gl, kCreate, sources, 2, &s->program);
}

/* ---- buffers --------------------------------------------------------------------------- */

static size_t light_bytes(const prt_gl_wavelet_shader* s) {
  return 16u * (size_t)s->layout.coefficients;
}

/* Creates the two buffers (bound to the generic SSBO target only while filling them): the data
 * buffer's light part is left for the first shade call to fill. */
static prt_result create_buffers(prt_context* context, prt_gl_wavelet_shader* s,
                                 size_t radiance_bytes) {
  const prt_gl_functions* gl = &s->gl;
  const size_t data_bytes = light_bytes(s) + s->section_bytes;
  prt_result r;
  prt_gl_drain_errors(gl);
  gl->GenBuffers(BUFFER_COUNT, s->buffers);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[BUFFER_DATA]);
  gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)data_bytes, NULL,
                 PRT_GL_DYNAMIC_DRAW);
  r = prt_gl_upload_le_words(context, &s->allocator, gl, kCreate, PRT_GL_SHADER_STORAGE_BUFFER, 1,
                             light_bytes(s), s->section, s->section_bytes);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[BUFFER_RADIANCE]);
  gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)radiance_bytes, NULL,
                 PRT_GL_DYNAMIC_COPY);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  if (r != PRT_OK) return r;
  return prt_gl_check_upload(context, gl, kCreate, (uint64_t)data_bytes + radiance_bytes);
}

/* ---- create / destroy ------------------------------------------------------------------ */

prt_result prt_gl_wavelet_create(prt_context* context, const prt_asset* asset,
                                 prt_gl_loader_fn loader, void* loader_user,
                                 prt_gl_wavelet_shader** out_shader) {
  prt_gl_wavelet_shader local;
  prt_gl_wavelet_shader* s;
  const prt_wavelet_view* view;
  uint64_t bytes[2];
  const char* const names[2] = {"light and transfer", "radiance"};
  prt_result r;
  if (out_shader) *out_shader = NULL;
  r = prt_gl_check_create(context, kCreate, asset, (const void*)loader, out_shader,
                          PRT_TECHNIQUE_WAVELET, "WVLT", (const void**)&view);
  if (r != PRT_OK) return r;
  memset(&local, 0, sizeof local);
  local.allocator = asset->allocator;
  local.section = view->section;
  local.section_bytes = (size_t)view->layout.raw_size;
  r = read_layout(context, view, &local.layout);
  if (r != PRT_OK) return r;
  r = prt_gl_open(context, kCreate, loader, loader_user, &local.gl);
  bytes[0] = (uint64_t)light_bytes(&local) + local.section_bytes;
  bytes[1] = local.layout.vertices ? 12u * (uint64_t)local.layout.vertices : 12u;
  if (r == PRT_OK) r = prt_gl_check_block_sizes(context, &local.gl, kCreate, bytes, names, 2);
  if (r != PRT_OK) return r;

  s = (prt_gl_wavelet_shader*)prt_internal_alloc(&local.allocator, sizeof *s, 16);
  if (!s) return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory", kCreate);
  *s = local;
  r = compile_program(context, s);
  if (r == PRT_OK) r = create_buffers(context, s, (size_t)bytes[1]);
  if (r != PRT_OK) {
    prt_gl_wavelet_destroy(s);
    return r;
  }
  *out_shader = s;
  return PRT_OK;
}

void prt_gl_wavelet_destroy(prt_gl_wavelet_shader* shader) {
  prt_allocator allocator;
  if (!shader) return;
  if (shader->buffers[0]) shader->gl.DeleteBuffers(BUFFER_COUNT, shader->buffers);
  if (shader->program) shader->gl.DeleteProgram(shader->program);
  allocator = shader->allocator;
  prt_internal_free(&allocator, shader, sizeof *shader);
}

/* ---- per frame ------------------------------------------------------------------------- */

/* Per-frame calls write no context (prt_gl.h): a bad range is reported by the result alone. */
static int range_inside(const prt_gl_wavelet_shader* s, uint32_t first, uint32_t count) {
  return first <= s->layout.vertices && count <= s->layout.vertices - first;
}

static void dispatch(const prt_gl_wavelet_shader* s, uint32_t first_vertex, uint32_t vertex_count) {
  const prt_gl_functions* gl = &s->gl;
  uint32_t done;
  for (done = 0; done < vertex_count;) {
    uint32_t chunk = vertex_count - done;
    if (chunk > MAX_GROUPS_PER_DISPATCH) chunk = MAX_GROUPS_PER_DISPATCH;
    gl->ProgramUniform1ui(s->program, UNIFORM_FIRST_VERTEX, first_vertex + done);
    gl->DispatchCompute(chunk, 1, 1);
    done += chunk;
  }
}

prt_result prt_gl_wavelet_shade(prt_gl_wavelet_shader* shader, const float* prepared_rgba,
                                uint32_t first_vertex, uint32_t vertex_count) {
  const prt_gl_functions* gl;
  if (!shader || !prepared_rgba || !range_inside(shader, first_vertex, vertex_count))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (vertex_count == 0) return PRT_OK;
  gl = &shader->gl;
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, shader->buffers[BUFFER_DATA]);
  gl->BufferSubData(PRT_GL_SHADER_STORAGE_BUFFER, 0, (prt_GLsizeiptr)light_bytes(shader),
                    prepared_rgba);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, BINDING_DATA, shader->buffers[BUFFER_DATA]);
  gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, BINDING_RADIANCE,
                     shader->buffers[BUFFER_RADIANCE]);
  gl->UseProgram(shader->program);
  dispatch(shader, first_vertex, vertex_count);
  gl->UseProgram(0);
  gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, BINDING_DATA, 0);
  gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, BINDING_RADIANCE, 0);
  /* Make the writes visible to whatever reads the output next: vertex fetch, shaders, copies. */
  gl->MemoryBarrier(PRT_GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | PRT_GL_SHADER_STORAGE_BARRIER_BIT |
                    PRT_GL_BUFFER_UPDATE_BARRIER_BIT);
  return PRT_OK;
}

uint32_t prt_gl_wavelet_output_buffer(const prt_gl_wavelet_shader* shader) {
  return shader ? shader->buffers[BUFFER_RADIANCE] : 0u;
}

prt_result prt_gl_wavelet_read(prt_gl_wavelet_shader* shader, uint32_t first_vertex,
                               uint32_t vertex_count, float* out_rgb) {
  if (!shader || (!out_rgb && vertex_count > 0) ||
      !range_inside(shader, first_vertex, vertex_count))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (vertex_count > 0)
    prt_gl_read_radiance(&shader->gl, shader->buffers[BUFFER_RADIANCE], first_vertex, vertex_count,
                         out_rgb);
  return PRT_OK;
}

#endif /* PRT_HAS_GL */
