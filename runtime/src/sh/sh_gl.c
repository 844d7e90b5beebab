/* SPDX-License-Identifier: MIT */
/* The GL backend of `sh` shading (prt_sh_asset.h): a compute shader over the quantised transfer,
 * read through the SHTR view the load decoded. */
#include "internal.h"

#if !defined(PRT_HAS_GL)
prt_result prt_gl_sh_create(prt_context* context, const prt_asset* asset, prt_gl_loader_fn loader,
                            void* loader_user, prt_gl_sh_shader** out_shader) {
  (void)asset, (void)loader, (void)loader_user;
  if (out_shader) *out_shader = NULL;
  return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                           "prt_gl_sh_create: compiled out (PRT_ENABLE_GL=OFF)");
}
void prt_gl_sh_destroy(prt_gl_sh_shader* shader) {
  (void)shader;
}
prt_result prt_gl_sh_shade(prt_gl_sh_shader* shader, const float* light_rgb, uint32_t first_vertex,
                           uint32_t vertex_count) {
  (void)shader, (void)light_rgb, (void)first_vertex, (void)vertex_count;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
uint32_t prt_gl_sh_output_buffer(const prt_gl_sh_shader* shader) {
  (void)shader;
  return 0;
}
prt_result prt_gl_sh_read(prt_gl_sh_shader* shader, uint32_t first_vertex, uint32_t vertex_count,
                          float* out_rgb) {
  (void)shader, (void)first_vertex, (void)vertex_count, (void)out_rgb;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
#else /* PRT_HAS_GL */

#include <stdio.h>
#include <string.h>

#include "gl_common.h"
#include "sh_internal.h"
#include "techniques.h"

/* Vertices per work group, and per dispatch (GL guarantees 65535 groups in x). */
#define LOCAL_SIZE 64u
#define MAX_GROUPS_PER_DISPATCH 65535u
/* The light block: vec4 base, then 3 order² weights rounded up to whole vec4s. */
#define MAX_LIGHT_FLOATS (4u + 3u * PRT_BLOB_SHTR_MAX_ORDER * PRT_BLOB_SHTR_MAX_ORDER + 3u)

/* buffers[]: the quantised transfer (SSBO binding 0), the folded light (uniform block binding 0)
 * and the radiance (SSBO binding 2). */
enum { BINDING_QUANTISED = 0, BINDING_LIGHT = 1, BINDING_RADIANCE = 2, BINDING_COUNT = 3 };
enum { UNIFORM_FIRST_VERTEX = 0, UNIFORM_VERTEX_COUNT = 1 };

struct prt_gl_sh_shader {
  prt_allocator allocator; /* the asset's */
  prt_gl_functions gl;
  prt_sh_info info;
  uint32_t coefficients; /* channels * order² per vertex */
  const uint8_t* params; /* (offset, scale) f32 pairs in the asset, `coefficients` of them */
  uint32_t light_floats; /* floats uploaded per shade call */
  prt_GLuint program;
  prt_GLuint buffers[BINDING_COUNT];
};

/* ---- the compute shader ---------------------------------------------------------------- */

/* One invocation per vertex: radiance = base + sum_j q_j weight_j, where the CPU folded the
 * dequantisation into the light (base = sum_j offset_j L_j, weight_j = scale_j L_j), so the
 * GPU reads the stored 8/16-bit values as they are, packed in uint words (little-endian).
 * The folded light is a uniform block (the same for every invocation): vec4 base, then the
 * weights channel-major (R: order² floats, then G, then B) packed four to a vec4.
 * Even orders have order² divisible by 4, so every row starts on a word and every group of
 * four coefficients fills one word (8-bit) or two (16-bit) and one weight vec4: the loop reads
 * each word once and sums with dot(). Odd orders take the general path, one value at a time. */
static const char kShaderDeclarations[] =
    "layout(local_size_x = LOCAL_SIZE) in;\n"
    "layout(std430, binding = 0) readonly restrict buffer Quantised { uint words[]; };\n"
    "layout(std140, binding = 0) uniform Light { vec4 base; vec4 weight[WEIGHT_VEC4S]; };\n"
    "layout(std430, binding = 2) writeonly restrict buffer Radiance { float radiance[]; };\n"
    "layout(location = 0) uniform uint first_vertex;\n"
    "layout(location = 1) uniform uint vertex_count;\n"
    "const uint N2 = uint(ORDER2);\n"
    "\n"
    "#if ORDER2 % 4 == 0\n"
    "const uint GROUPS = N2 / 4u; /* vec4 groups per channel */\n"
    "vec4 group_at(uint g) {\n"
    "#if BITS == 8\n"
    "  uint w = words[g];\n"
    "  return vec4(uvec4(w & 0xFFu, (w >> 8u) & 0xFFu, (w >> 16u) & 0xFFu, w >> 24u));\n"
    "#else\n"
    "  uint a = words[2u * g], b = words[2u * g + 1u];\n"
    "  return vec4(uvec4(a & 0xFFFFu, a >> 16u, b & 0xFFFFu, b >> 16u));\n"
    "#endif\n"
    "}\n"
    "\n"
    "vec3 shade(uint v) {\n"
    "  uint g0 = v * uint(CHANNELS) * GROUPS;\n"
    "  vec3 sum = base.xyz;\n"
    "#if CHANNELS == 1\n"
    "  for (uint g = 0u; g < GROUPS; ++g) {\n"
    "    vec4 q = group_at(g0 + g);\n"
    "    sum += vec3(dot(q, weight[g]), dot(q, weight[GROUPS + g]),\n"
    "                dot(q, weight[2u * GROUPS + g]));\n"
    "  }\n"
    "#else\n"
    "  for (uint c = 0u; c < 3u; ++c) {\n"
    "    float s = 0.0;\n"
    "    for (uint g = 0u; g < GROUPS; ++g)\n"
    "      s += dot(group_at(g0 + c * GROUPS + g), weight[c * GROUPS + g]);\n"
    "    sum[c] += s;\n"
    "  }\n"
    "#endif\n"
    "  return sum;\n"
    "}\n"
    "#else\n"
    "float quantised(uint index) {\n"
    "#if BITS == 8\n"
    "  return float(bitfieldExtract(words[index >> 2u], int((index & 3u) << 3u), 8));\n"
    "#else\n"
    "  return float(bitfieldExtract(words[index >> 1u], int((index & 1u) << 4u), 16));\n"
    "#endif\n"
    "}\n"
    "float weight_at(uint i) { return weight[i >> 2u][i & 3u]; }\n"
    "\n"
    "vec3 shade(uint v) {\n"
    "  uint row = v * uint(CHANNELS) * N2;\n"
    "  vec3 sum = base.xyz;\n"
    "#if CHANNELS == 1\n"
    "  for (uint k = 0u; k < N2; ++k)\n"
    "    sum += quantised(row + k) *\n"
    "           vec3(weight_at(k), weight_at(N2 + k), weight_at(2u * N2 + k));\n"
    "#else\n"
    "  for (uint c = 0u; c < 3u; ++c) {\n"
    "    float s = 0.0;\n"
    "    for (uint k = 0u; k < N2; ++k)\n"
    "      s += quantised(row + c * N2 + k) * weight_at(c * N2 + k);\n"
    "    sum[c] += s;\n"
    "  }\n"
    "#endif\n"
    "  return sum;\n"
    "}\n"
    "#endif\n";

static const char kShaderMain[] =
    "void main() {\n"
    "  uint i = gl_GlobalInvocationID.x;\n"
    "  if (i >= vertex_count) return;\n"
    "  uint v = first_vertex + i;\n"
    "  vec3 rgb = shade(v);\n"
    "  radiance[3u * v + 0u] = rgb.x;\n"
    "  radiance[3u * v + 1u] = rgb.y;\n"
    "  radiance[3u * v + 2u] = rgb.z;\n"
    "}\n";

static prt_result compile_program(prt_context* context, prt_gl_sh_shader* s) {
  char header[256];
  const prt_GLchar* sources[3];
  snprintf(header, sizeof header,
           "#version 430 core\n#define LOCAL_SIZE %u\n#define ORDER2 %u\n#define CHANNELS %u\n"
           "#define BITS %u\n#define WEIGHT_VEC4S %u\n",
           LOCAL_SIZE, s->info.order * s->info.order, s->info.channels, s->info.bits,
           (s->light_floats - 4u) / 4u);
  sources[0] = header;
  sources[1] = kShaderDeclarations;
  sources[2] = kShaderMain;
  return prt_gl_compile_compute(context, &s->gl, "prt_gl_sh_create", sources, 3, &s->program);
}

/* ---- buffers --------------------------------------------------------------------------- */

/* Creates the three buffers (bound to the generic SSBO target only while filling them). */
static prt_result create_buffers(prt_context* context, prt_gl_sh_shader* s, const uint8_t* values,
                                 size_t value_bytes, size_t radiance_bytes) {
  const prt_gl_functions* gl = &s->gl;
  prt_result r;
  prt_gl_drain_errors(gl);
  gl->GenBuffers(BINDING_COUNT, s->buffers);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[BINDING_QUANTISED]);
  r = prt_gl_upload_le_words(context, &s->allocator, gl, "prt_gl_sh_create",
                             PRT_GL_SHADER_STORAGE_BUFFER, 0, 0, values, value_bytes);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[BINDING_LIGHT]);
  gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)(4u * s->light_floats), NULL,
                 PRT_GL_DYNAMIC_DRAW);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[BINDING_RADIANCE]);
  gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)radiance_bytes, NULL,
                 PRT_GL_DYNAMIC_COPY);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  if (r != PRT_OK) return r;
  return prt_gl_check_upload(context, gl, "prt_gl_sh_create",
                             (uint64_t)value_bytes + radiance_bytes);
}

/* ---- create / destroy ------------------------------------------------------------------ */

prt_result prt_gl_sh_create(prt_context* context, const prt_asset* asset, prt_gl_loader_fn loader,
                            void* loader_user, prt_gl_sh_shader** out_shader) {
  prt_gl_sh_shader local;
  prt_gl_sh_shader* s;
  const prt_sh_view* view;
  uint64_t value_bytes, radiance_bytes;
  prt_result r;
  if (out_shader) *out_shader = NULL;
  r = prt_gl_check_create(context, "prt_gl_sh_create", asset, (const void*)loader, out_shader,
                          PRT_TECHNIQUE_SH, "SHTR", (const void**)&view);
  if (r != PRT_OK) return r;
  memset(&local, 0, sizeof local);
  local.allocator = asset->allocator;
  local.info = view->info;
  local.params = view->params;
  local.coefficients = view->coefficients;
  local.light_floats = 4u + (3u * local.info.order * local.info.order + 3u) / 4u * 4u;
  r = prt_gl_open(context, "prt_gl_sh_create", loader, loader_user, &local.gl);
  /* Whole uint words: the section is padded to 4 bytes, so the last word is inside it. */
  value_bytes = ((uint64_t)view->value_bytes + 3u) & ~(uint64_t)3u;
  radiance_bytes = 12u * (uint64_t)local.info.vertex_count;
  if (value_bytes == 0) value_bytes = 4; /* empty assets still get valid buffers */
  if (radiance_bytes == 0) radiance_bytes = 12;
  if (r == PRT_OK) {
    const uint64_t bytes[2] = {value_bytes, radiance_bytes};
    const char* const names[2] = {"transfer", "radiance"};
    r = prt_gl_check_block_sizes(context, &local.gl, "prt_gl_sh_create", bytes, names, 2);
  }
  if (r != PRT_OK) return r;

  s = (prt_gl_sh_shader*)prt_internal_alloc(&local.allocator, sizeof *s, 16);
  if (!s)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "prt_gl_sh_create: out of memory");
  *s = local;
  r = compile_program(context, s);
  if (r == PRT_OK)
    r = create_buffers(context, s, s->info.vertex_count ? view->values : NULL, (size_t)value_bytes,
                       (size_t)radiance_bytes);
  if (r != PRT_OK) {
    prt_gl_sh_destroy(s);
    return r;
  }
  *out_shader = s;
  return PRT_OK;
}

void prt_gl_sh_destroy(prt_gl_sh_shader* shader) {
  prt_allocator allocator;
  if (!shader) return;
  if (shader->buffers[0]) shader->gl.DeleteBuffers(BINDING_COUNT, shader->buffers);
  if (shader->program) shader->gl.DeleteProgram(shader->program);
  allocator = shader->allocator;
  prt_internal_free(&allocator, shader, sizeof *shader);
}

/* ---- per frame ------------------------------------------------------------------------- */

/* The folded light as the shader reads it: vec4 (bias r, g, b, 0), then weight[ch order² + k]
 * (prt_sh_fold_light), zero up to whole vec4s. */
static void fold_light(const prt_gl_sh_shader* s, const float* light_rgb, float* out) {
  const uint32_t n2 = s->info.order * s->info.order;
  uint32_t k;
  prt_sh_fold_light(s->params, s->info.order, s->info.channels, light_rgb, n2, out + 4, n2, out);
  out[3] = 0.0f;
  for (k = 4u + 3u * n2; k < s->light_floats; ++k) out[k] = 0.0f;
}

/* Per-frame calls write no context (prt_gl.h): a bad range is reported by the result alone. */
static int range_inside(const prt_gl_sh_shader* s, uint32_t first, uint32_t count) {
  return first <= s->info.vertex_count && count <= s->info.vertex_count - first;
}

prt_result prt_gl_sh_shade(prt_gl_sh_shader* shader, const float* light_rgb, uint32_t first_vertex,
                           uint32_t vertex_count) {
  float light[MAX_LIGHT_FLOATS];
  const prt_gl_functions* gl;
  uint32_t done;
  if (!shader || !light_rgb || !range_inside(shader, first_vertex, vertex_count))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (vertex_count == 0) return PRT_OK;
  gl = &shader->gl;
  fold_light(shader, light_rgb, light);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, shader->buffers[BINDING_LIGHT]);
  gl->BufferSubData(PRT_GL_SHADER_STORAGE_BUFFER, 0, (prt_GLsizeiptr)(4u * shader->light_floats),
                    light);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, BINDING_QUANTISED,
                     shader->buffers[BINDING_QUANTISED]);
  gl->BindBufferBase(PRT_GL_UNIFORM_BUFFER, 0, shader->buffers[BINDING_LIGHT]);
  gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, BINDING_RADIANCE,
                     shader->buffers[BINDING_RADIANCE]);
  gl->UseProgram(shader->program);
  for (done = 0; done < vertex_count;) {
    uint32_t chunk = vertex_count - done;
    if (chunk > MAX_GROUPS_PER_DISPATCH * LOCAL_SIZE) chunk = MAX_GROUPS_PER_DISPATCH * LOCAL_SIZE;
    gl->ProgramUniform1ui(shader->program, UNIFORM_FIRST_VERTEX, first_vertex + done);
    gl->ProgramUniform1ui(shader->program, UNIFORM_VERTEX_COUNT, chunk);
    gl->DispatchCompute((chunk + LOCAL_SIZE - 1u) / LOCAL_SIZE, 1, 1);
    done += chunk;
  }
  gl->UseProgram(0);
  gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, BINDING_QUANTISED, 0);
  gl->BindBufferBase(PRT_GL_UNIFORM_BUFFER, 0, 0);
  gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, BINDING_RADIANCE, 0);
  /* Make the writes visible to whatever reads the output next: vertex fetch, shaders, copies. */
  gl->MemoryBarrier(PRT_GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | PRT_GL_SHADER_STORAGE_BARRIER_BIT |
                    PRT_GL_BUFFER_UPDATE_BARRIER_BIT);
  return PRT_OK;
}

uint32_t prt_gl_sh_output_buffer(const prt_gl_sh_shader* shader) {
  return shader ? shader->buffers[BINDING_RADIANCE] : 0u;
}

prt_result prt_gl_sh_read(prt_gl_sh_shader* shader, uint32_t first_vertex, uint32_t vertex_count,
                          float* out_rgb) {
  if (!shader || (!out_rgb && vertex_count > 0) ||
      !range_inside(shader, first_vertex, vertex_count))
    return PRT_ERROR_INVALID_ARGUMENT;
  if (vertex_count > 0)
    prt_gl_read_radiance(&shader->gl, shader->buffers[BINDING_RADIANCE], first_vertex, vertex_count,
                         out_rgb);
  return PRT_OK;
}

#endif /* PRT_HAS_GL */
