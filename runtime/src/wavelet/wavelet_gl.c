/* SPDX-License-Identifier: MIT */
/* The GL backend of `wavelet` shading (prt_gl.h): a compute shader over the sparse rows of the
 * WVLT section (formats/SPEC.md §7.2), uploaded as stored. */
#include "internal.h"

#if !defined(PRT_HAS_GL)
prt_result prt_gl_wavelet_create(const prt_asset* asset, prt_gl_loader_fn loader, void* loader_user,
                                 prt_gl_wavelet_shader** out_shader) {
  (void)asset, (void)loader, (void)loader_user;
  if (out_shader) *out_shader = NULL;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
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

/* Invocations per vertex (one work group each), and vertices per dispatch (GL guarantees 65535
 * groups in x). */
#define LANES 8u
#define MAX_GROUPS_PER_DISPATCH 65535u

/* buffers[]: the prepared light followed by the WVLT section (SSBO binding 0) and the radiance
 * (SSBO binding 2). The light shares the transfer's buffer so that the GL state touched stays
 * the one prt_gl.h documents (SSBO bindings 0 and 2); it is rewritten by each shade call. */
enum { BUFFER_DATA = 0, BUFFER_RADIANCE = 1, BUFFER_COUNT = 2 };
enum { BINDING_DATA = 0, BINDING_RADIANCE = 2 };
enum { UNIFORM_FIRST_VERTEX = 0 };

/* Where the WVLT arrays are, in 32-bit words from the section's start (§7.2). */
typedef struct wavelet_layout {
  uint32_t coefficients; /* F S²: the light's length in RGBA quadruples */
  uint32_t blocks;       /* B = F S² / 256 per row */
  uint32_t vertices;     /* V */
  uint32_t pairs;        /* P */
  uint32_t vertex_scale_word, row_start_word, count_word, pair_word;
} wavelet_layout;

struct prt_gl_wavelet_shader {
  const prt_asset* asset;
  prt_gl_functions gl;
  wavelet_layout layout;
  const uint8_t* section;
  size_t section_bytes;
  prt_GLuint program;
  prt_GLuint buffers[BUFFER_COUNT];
};

static const char kCreate[] = "prt_gl_wavelet_create";

/* ---- the section ----------------------------------------------------------------------- */

static int log2_exact(uint32_t size) {
  int log = 0;
  while (size > 1u && (size & 1u) == 0) size >>= 1, ++log;
  return size == 1u ? log : -1;
}

/* Reads the header and checks that every array it implies lies inside the section, exactly
 * (§7.2 raw_size), so that the shader's word offsets are in bounds whatever the validation
 * level the asset was loaded at. The rows' contents are not checked here: the shader clamps
 * every read to its array. */
static prt_result read_layout(prt_context* context, const uint8_t* data, size_t bytes,
                              wavelet_layout* out) {
  uint32_t param, size, faces, levels;
  uint64_t expected, counts_bytes;
  int log;
  if (!data || bytes < PRT_BLOB_WVLT_HEADER_SIZE)
    return prt_internal_fail(context, PRT_ERROR_CORRUPT, "%s: the WVLT section is %zu bytes",
                             kCreate, bytes);
  param = prt_le_load_u32(data);
  size = prt_le_load_u32(data + 4);
  log = log2_exact(size);
  if (param > 1u || log < 4 || log > 7)
    return prt_internal_fail(context, PRT_ERROR_CORRUPT,
                             "%s: bad WVLT header (param %u, face size %u)", kCreate, param, size);
  faces = param == 0u ? 6u : 2u;
  levels = (uint32_t)log + 1u;
  out->coefficients = faces * size * size;
  out->blocks = out->coefficients / PRT_BLOB_WVLT_BLOCK;
  out->vertices = prt_le_load_u32(data + 8);
  out->pairs = prt_le_load_u32(data + 24);
  counts_bytes = 2u * (uint64_t)out->vertices * out->blocks; /* a multiple of 4: B is even */
  expected = PRT_BLOB_WVLT_HEADER_SIZE + 4u * (uint64_t)faces * levels +
             12u * (uint64_t)out->vertices + 4u * ((uint64_t)out->vertices + 1u) + counts_bytes +
             2u * (uint64_t)out->pairs;
  expected = (expected + 3u) & ~(uint64_t)3u;
  if (expected != bytes || bytes > UINT32_MAX)
    return prt_internal_fail(context, PRT_ERROR_CORRUPT,
                             "%s: the WVLT section is %zu bytes; its header implies %llu", kCreate,
                             bytes, (unsigned long long)expected);
  out->vertex_scale_word = PRT_BLOB_WVLT_HEADER_SIZE / 4u + faces * levels;
  out->row_start_word = out->vertex_scale_word + 3u * out->vertices;
  out->count_word = out->row_start_word + out->vertices + 1u;
  out->pair_word = out->count_word + (uint32_t)(counts_bytes / 4u);
  if (prt_le_load_u32(data + 4u * (size_t)(out->row_start_word + out->vertices)) != out->pairs)
    return prt_internal_fail(context, PRT_ERROR_CORRUPT,
                             "%s: the WVLT row starts do not end at the pair count %u", kCreate,
                             out->pairs);
  return PRT_OK;
}

static prt_result open_asset(const prt_asset* asset, prt_gl_wavelet_shader* s) {
  const void* data = NULL;
  size_t size = 0;
  prt_result r = prt_asset_section_data(asset, PRT_SECTION_WVLT, &data, &size);
  if (r == PRT_ERROR_NOT_FOUND)
    return prt_internal_fail(asset->context, r, "%s: the asset has no WVLT section", kCreate);
  if (r != PRT_OK)
    return prt_internal_fail(asset->context, r, "%s: no WVLT data: %s", kCreate,
                             prt_result_string(r));
  s->section = (const uint8_t*)data;
  s->section_bytes = size;
  return read_layout(asset->context, s->section, size, &s->layout);
}

/* ---- the compute shader ---------------------------------------------------------------- */

/* One work group of LANES invocations per vertex: lane t sums q * prepared[j] over the row's
 * pairs t, t + LANES, ... (adjacent lanes read adjacent pairs), finding each pair's block by
 * walking the block counts forward; the lanes' partial sums are added in shared memory and
 * multiplied by the vertex scale: radiance = vs * sum (§7.2 with the band scales folded into the
 * light by prt_wavelet_prepare_light). Measured on Mesa llvmpipe (prt_bench_wavelet_gl, 35,947
 * vertices of ~1000 pairs): 8 lanes per vertex beat 16 and 32, and beat one invocation per vertex
 * summing its row alone by ~30 %. The data is read as stored: 16-bit block counts and
 * (index, value) pairs two to a uint word (little-endian), the value's sign extended by
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

static prt_result compile_program(prt_gl_wavelet_shader* s) {
  const wavelet_layout* l = &s->layout;
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
  return prt_gl_compile_compute(s->asset->context, &s->gl, kCreate, sources, 2, &s->program);
}

/* ---- buffers --------------------------------------------------------------------------- */

static size_t light_bytes(const prt_gl_wavelet_shader* s) {
  return 16u * (size_t)s->layout.coefficients;
}

/* Creates the two buffers (bound to the generic SSBO target only while filling them): the data
 * buffer's light part is left for the first shade call to fill. */
static prt_result create_buffers(prt_gl_wavelet_shader* s, size_t radiance_bytes) {
  const prt_gl_functions* gl = &s->gl;
  prt_context* context = s->asset->context;
  const size_t data_bytes = light_bytes(s) + s->section_bytes;
  prt_result r;
  prt_gl_drain_errors(gl);
  gl->GenBuffers(BUFFER_COUNT, s->buffers);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[BUFFER_DATA]);
  gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)data_bytes, NULL,
                 PRT_GL_DYNAMIC_DRAW);
  r = prt_gl_upload_le_words(context, &s->asset->allocator, gl, kCreate,
                             PRT_GL_SHADER_STORAGE_BUFFER, 1, light_bytes(s), s->section,
                             s->section_bytes);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[BUFFER_RADIANCE]);
  gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)radiance_bytes, NULL,
                 PRT_GL_DYNAMIC_COPY);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  if (r != PRT_OK) return r;
  return prt_gl_check_upload(context, gl, kCreate, (uint64_t)data_bytes + radiance_bytes);
}

/* ---- create / destroy ------------------------------------------------------------------ */

prt_result prt_gl_wavelet_create(const prt_asset* asset, prt_gl_loader_fn loader, void* loader_user,
                                 prt_gl_wavelet_shader** out_shader) {
  prt_gl_wavelet_shader local;
  prt_gl_wavelet_shader* s;
  uint64_t bytes[2];
  const char* const names[2] = {"light and transfer", "radiance"};
  prt_result r;
  if (out_shader) *out_shader = NULL;
  if (!asset) return PRT_ERROR_INVALID_ARGUMENT;
  if (!loader || !out_shader)
    return prt_internal_fail(asset->context, PRT_ERROR_INVALID_ARGUMENT,
                             "%s: loader and out_shader must not be NULL", kCreate);
  if (!prt_gl_allowed(asset->context))
    return prt_internal_fail(asset->context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "%s: the context's backend limit (%s) excludes gl", kCreate,
                             prt_backend_name(asset->context->backend_limit));
  memset(&local, 0, sizeof local);
  local.asset = asset;
  r = open_asset(asset, &local);
  if (r != PRT_OK) return r;
  r = prt_gl_open(asset->context, kCreate, loader, loader_user, &local.gl);
  bytes[0] = (uint64_t)light_bytes(&local) + local.section_bytes;
  bytes[1] = local.layout.vertices ? 12u * (uint64_t)local.layout.vertices : 12u;
  if (r == PRT_OK)
    r = prt_gl_check_block_sizes(asset->context, &local.gl, kCreate, bytes, names, 2);
  if (r != PRT_OK) return r;

  s = (prt_gl_wavelet_shader*)prt_internal_alloc(&asset->allocator, sizeof *s, 16);
  if (!s)
    return prt_internal_fail(asset->context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory", kCreate);
  *s = local;
  r = compile_program(s);
  if (r == PRT_OK) r = create_buffers(s, (size_t)bytes[1]);
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
  allocator = shader->asset->allocator;
  prt_internal_free(&allocator, shader, sizeof *shader);
}

/* ---- per frame ------------------------------------------------------------------------- */

static prt_result check_range(const prt_gl_wavelet_shader* s, const char* function, uint32_t first,
                              uint32_t count) {
  if (first > s->layout.vertices || count > s->layout.vertices - first)
    return prt_internal_fail(s->asset->context, PRT_ERROR_INVALID_ARGUMENT,
                             "%s: vertices [%u, %u + %u) are outside the asset's %u", function,
                             first, first, count, s->layout.vertices);
  return PRT_OK;
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
  prt_result r;
  if (!shader) return PRT_ERROR_INVALID_ARGUMENT;
  if (!prepared_rgba)
    return prt_internal_fail(shader->asset->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_gl_wavelet_shade: prepared_rgba must not be NULL");
  r = check_range(shader, "prt_gl_wavelet_shade", first_vertex, vertex_count);
  if (r != PRT_OK || vertex_count == 0) return r;
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
  const prt_gl_functions* gl;
  prt_result r;
  if (!shader) return PRT_ERROR_INVALID_ARGUMENT;
  if (!out_rgb && vertex_count > 0)
    return prt_internal_fail(shader->asset->context, PRT_ERROR_INVALID_ARGUMENT,
                             "prt_gl_wavelet_read: out_rgb must not be NULL");
  r = check_range(shader, "prt_gl_wavelet_read", first_vertex, vertex_count);
  if (r != PRT_OK || vertex_count == 0) return r;
  gl = &shader->gl;
  gl->MemoryBarrier(PRT_GL_BUFFER_UPDATE_BARRIER_BIT);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, shader->buffers[BUFFER_RADIANCE]);
  gl->GetBufferSubData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLintptr)(12u * (size_t)first_vertex),
                       (prt_GLsizeiptr)(12u * (size_t)vertex_count), out_rgb);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  return PRT_OK;
}

#endif /* PRT_HAS_GL */
