/* SPDX-License-Identifier: MIT */
/* The GL backend of `pose` shading (prt_pose_asset.h): the per-frame work that is small
 * (features, coefficients, the light folded into weights, the joints' skinning matrices) on the
 * CPU through the scalar code (prt_pose_fold_shading), the per-vertex work in a compute shader
 * over the basis values and skin records uploaded once at create. */
#include "internal.h"

#if !defined(PRT_HAS_GL)
prt_result prt_gl_pose_create(prt_context* context, const prt_asset* asset, prt_gl_loader_fn loader,
                              void* loader_user, prt_gl_pose_shader** out_shader) {
  (void)asset, (void)loader, (void)loader_user;
  if (out_shader) *out_shader = NULL;
  return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                           "prt_gl_pose_create: compiled out (PRT_ENABLE_GL=OFF)");
}
void prt_gl_pose_destroy(prt_gl_pose_shader* shader) {
  (void)shader;
}
prt_result prt_gl_pose_shade(prt_gl_pose_shader* shader, const prt_pose_input* pose,
                             const prt_pose_light* light, uint32_t first_vertex,
                             uint32_t vertex_count) {
  (void)shader, (void)pose, (void)light, (void)first_vertex, (void)vertex_count;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
uint32_t prt_gl_pose_output_buffer(const prt_gl_pose_shader* shader) {
  (void)shader;
  return 0;
}
prt_result prt_gl_pose_read(prt_gl_pose_shader* shader, uint32_t first_vertex,
                            uint32_t vertex_count, float* out_rgb) {
  (void)shader, (void)first_vertex, (void)vertex_count, (void)out_rgb;
  return PRT_ERROR_UNSUPPORTED_BACKEND;
}
#else /* PRT_HAS_GL */

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gl_common.h"
#include "pose_internal.h"
#include "techniques.h"

/* Vertices per work group, and per dispatch (GL guarantees 65535 groups in x). */
#define LOCAL_SIZE 64u
#define MAX_GROUPS_PER_DISPATCH 65535u
/* The light block: vec4 bias, the t_00 clamp's light and bounds (two vec4), one vec4 of RGB
 * weights (and the learned t_00's) per basis column, then one vec4 per coefficient of the exact
 * part (model 1). */
#define MAX_LIGHT_FLOATS (12u + 4u * PRT_POSE_MAX_BASIS_DIMS + 4u * PRT_POSE_MAX_COEFFICIENTS)
/* The skin record as uint words (PRT_BLOB_PSTR_SKIN_*): normal at 3..5, joints at 6,
 * weights at 7..8. */
#define SKIN_WORDS (PRT_BLOB_PSTR_SKIN_SIZE / 4u)

PRT_STATIC_ASSERT(PRT_BLOB_PSTR_SKIN_SIZE % 4u == 0, skin_words);
PRT_STATIC_ASSERT(PRT_BLOB_PSTR_SKIN_OFF_NORMAL == 12u && PRT_BLOB_PSTR_SKIN_OFF_JOINTS == 24u &&
                      PRT_BLOB_PSTR_SKIN_OFF_WEIGHTS == 28u,
                  skin_word_offsets);

/* buffers[]: SSBOs at the binding of their index (0 to 4), the light at uniform binding 0. The
 * skin, joint and normal buffers are only read by model 1's shader. */
enum {
  BUFFER_VALUES = 0,
  BUFFER_SKIN = 1,
  BUFFER_RADIANCE = 2,
  BUFFER_JOINTS = 3,
  BUFFER_NORMALS = 4,
  BUFFER_LIGHT = 5,
  BUFFER_COUNT = 6
};
enum { UNIFORM_FIRST_VERTEX = 0, UNIFORM_VERTEX_COUNT = 1, UNIFORM_GIVEN_NORMALS = 2 };

struct prt_gl_pose_shader {
  prt_allocator allocator; /* the asset's */
  prt_gl_functions gl;
  const prt_pose_view* view;
  uint32_t light_floats; /* floats uploaded to the light block per shade call */
  prt_GLuint program;
  prt_GLuint buffers[BUFFER_COUNT];
  /* Per-call scratch, kept here rather than on the render thread's stack. */
  prt_pose_folded folded;
  float light[MAX_LIGHT_FLOATS];
  float joints[12u * PRT_POSE_MAX_JOINTS];
};

static int residual(const prt_gl_pose_shader* s) {
  return s->view->info.model == PRT_POSE_MODEL_RESIDUAL;
}

/* ---- the compute shader ---------------------------------------------------------------- */

/* One invocation per vertex. The learned part is bias + sum_k value[v][k] weight[ch][k]: the CPU
 * folded the quantisation and the coefficients into the light (weight = scale_k w_k, bias =
 * sum_k offset_k w_k, as the SIMD kernels do), so the stored 8/16-bit values are read as they
 * are, packed in uint words. Model 1 adds the exact part sum_c y_c(n) exact[c] at the skinned
 * normal n, with the skinning of pose_model.c (weights normalised by their sum, joints at or past
 * J weigh 0, the identity when no weight is left; the normal through the cofactors with det's
 * sign, 0 where singular) and the SH recurrence of sh_eval.c, its constants from the header. */
static const char kShaderDeclarations[] =
    "layout(local_size_x = LOCAL_SIZE) in;\n"
    "layout(std430, binding = 0) readonly restrict buffer Values { uint words[]; };\n"
    "layout(std140, binding = 0) uniform Light {\n"
    "  vec4 bias;\n"
    "  vec4 dc_light;\n"
    "  vec4 dc_bounds;\n"
    "  vec4 weight[BASIS_DIMS];\n"
    "#if MODEL == 1\n"
    "  vec4 exact[ORDER * ORDER];\n"
    "#endif\n"
    "};\n"
    "layout(std430, binding = 2) writeonly restrict buffer Radiance { float radiance[]; };\n"
    "#if MODEL == 1\n"
    "layout(std430, binding = 1) readonly restrict buffer Skin { uint skin[]; };\n"
    "layout(std430, binding = 3) readonly restrict buffer Joints { vec4 joint_rows[]; };\n"
    "layout(std430, binding = 4) readonly restrict buffer Normals { float normals[]; };\n"
    "#endif\n"
    "layout(location = 0) uniform uint first_vertex;\n"
    "layout(location = 1) uniform uint vertex_count;\n"
    "layout(location = 2) uniform uint given_normals;\n"
    "const uint Q = uint(BASIS_DIMS);\n"
    "\n"
    "#if BITS == 8\n"
    "const uint PER_WORD_LOG2 = 2u, PER_WORD_MASK = 3u;\n"
    "#else\n"
    "const uint PER_WORD_LOG2 = 1u, PER_WORD_MASK = 1u;\n"
    "#endif\n"
    "\n"
    "/* Each word of the row is loaded once (rows need not start on a word). */\n"
    "vec4 learned(uint v) {\n"
    "  uint index = v * Q;\n"
    "  uint word = words[index >> PER_WORD_LOG2];\n"
    "  vec4 sum = bias;\n"
    "  for (uint k = 0u; k < Q; ++k, ++index) {\n"
    "    uint slot = index & PER_WORD_MASK;\n"
    "    if (k > 0u && slot == 0u) word = words[index >> PER_WORD_LOG2];\n"
    "    sum += float(bitfieldExtract(word, int(slot * uint(BITS)), BITS)) * weight[k];\n"
    "  }\n"
    "  return sum;\n"
    "}\n"
    "\n"
    "#if MODEL == 1\n"
    "vec3 skinned_normal(uint v) {\n"
    "  uint r = v * uint(SKIN_WORDS);\n"
    "  vec3 n = vec3(uintBitsToFloat(skin[r + 3u]), uintBitsToFloat(skin[r + 4u]),\n"
    "                uintBitsToFloat(skin[r + 5u]));\n"
    "  uint joints = skin[r + 6u], w01 = skin[r + 7u], w23 = skin[r + 8u];\n"
    "  float w[4] = float[4](float(w01 & 0xFFFFu), float(w01 >> 16u), float(w23 & 0xFFFFu),\n"
    "                        float(w23 >> 16u));\n"
    "  uint j[4];\n"
    "  float total = 0.0;\n"
    "  for (int k = 0; k < 4; ++k) {\n"
    "    j[k] = bitfieldExtract(joints, 8 * k, 8);\n"
    "    if (j[k] >= uint(JOINTS)) w[k] = 0.0;\n"
    "    total += w[k];\n"
    "  }\n"
    "  vec3 k0 = vec3(1.0, 0.0, 0.0), k1 = vec3(0.0, 1.0, 0.0), k2 = vec3(0.0, 0.0, 1.0);\n"
    "  if (total > 0.0) {\n"
    "    k0 = vec3(0.0), k1 = vec3(0.0), k2 = vec3(0.0);\n"
    "    for (int k = 0; k < 4; ++k) {\n"
    "      if (w[k] == 0.0) continue;\n"
    "      float a = w[k] / total;\n"
    "      uint b = 3u * j[k];\n"
    "      k0 += a * joint_rows[b].xyz;\n"
    "      k1 += a * joint_rows[b + 1u].xyz;\n"
    "      k2 += a * joint_rows[b + 2u].xyz;\n"
    "    }\n"
    "  }\n"
    "  /* cof(K) n: the cofactor rows of a matrix with rows k0, k1, k2 are cross products. */\n"
    "  vec3 c0 = cross(k1, k2), c1 = cross(k2, k0), c2 = cross(k0, k1);\n"
    "  float det = dot(k0, c0);\n"
    "  vec3 out_n = vec3(dot(c0, n), dot(c1, n), dot(c2, n)) * (det < 0.0 ? -1.0 : 1.0);\n"
    "  float len = length(out_n);\n"
    "  if (det == 0.0 || !(len > 0.0) || isinf(len) || isnan(len)) return vec3(0.0);\n"
    "  return out_n / len;\n"
    "}\n"
    "\n"
    "vec3 exact_part(vec3 n) {\n"
    "  float len = length(n);\n"
    "  if (!(len > 0.0) || isinf(len) || isnan(len)) return vec3(0.0);\n"
    "  /* SH frame (SPEC §13): x = X, y = -Z, z = Y. */\n"
    "  float x = n.x / len, y = -n.z / len, z = n.y / len;\n"
    "  vec3 sum = vec3(0.0);\n"
    "  float cos_m = 1.0, sin_m = 0.0;\n"
    "  for (uint m = 0u; m < uint(ORDER); ++m) {\n"
    "    float q2 = SH_DIAG[m];\n"
    "    float q1 = SH_SUB[m] * z * q2;\n"
    "    if (m > 0u) {\n"
    "      float c = cos_m * x - sin_m * y;\n"
    "      sin_m = sin_m * x + cos_m * y;\n"
    "      cos_m = c;\n"
    "    }\n"
    "    float scale_cos = m == 0u ? 1.0 : SQRT2 * cos_m;\n"
    "    float scale_sin = SQRT2 * sin_m;\n"
    "    for (uint l = m; l < uint(ORDER); ++l) {\n"
    "      float q;\n"
    "      if (l == m) {\n"
    "        q = q2;\n"
    "      } else if (l == m + 1u) {\n"
    "        q = q1;\n"
    "      } else {\n"
    "        uint k = l * (l + 1u) / 2u + m;\n"
    "        q = SH_A[k] * (z * q1 - SH_B[k] * q2);\n"
    "        q2 = q1;\n"
    "        q1 = q;\n"
    "      }\n"
    "      sum += (q * scale_cos) * exact[l * (l + 1u) + m].xyz;\n"
    "      if (m > 0u) sum += (q * scale_sin) * exact[l * (l + 1u) - m].xyz;\n"
    "    }\n"
    "  }\n"
    "  return sum;\n"
    "}\n"
    "#endif\n";

static const char kShaderMain[] =
    "void main() {\n"
    "  uint i = gl_GlobalInvocationID.x;\n"
    "  if (i >= vertex_count) return;\n"
    "  uint v = first_vertex + i;\n"
    "  vec4 sum = learned(v);\n"
    "  vec3 rgb = sum.xyz + (clamp(sum.w, dc_bounds.x, dc_bounds.y) - sum.w) * dc_light.xyz;\n"
    "#if MODEL == 1\n"
    "  vec3 n = given_normals != 0u\n"
    "               ? vec3(normals[3u * v], normals[3u * v + 1u], normals[3u * v + 2u])\n"
    "               : skinned_normal(v);\n"
    "  rgb += exact_part(n);\n"
    "#endif\n"
    "  radiance[3u * v + 0u] = rgb.x;\n"
    "  radiance[3u * v + 1u] = rgb.y;\n"
    "  radiance[3u * v + 2u] = rgb.z;\n"
    "}\n";

/* Appends `name` = float[](values) to the header; returns the new length. */
static size_t append_table(char* out, size_t used, size_t capacity, const char* name,
                           const double* values, uint32_t count) {
  uint32_t i;
  used +=
      (size_t)snprintf(out + used, capacity - used, "const float %s[%u] = float[](", name, count);
  for (i = 0; i < count && used < capacity; ++i)
    used += (size_t)snprintf(out + used, capacity - used, "%s%.9e", i ? ", " : "", values[i]);
  if (used < capacity) used += (size_t)snprintf(out + used, capacity - used, ");\n");
  return used;
}

/* The header: the #version line, the layout's constants and the SH recurrence's constants for
 * the asset's order (sh_eval.c's formulas, evaluated in double and rounded once). */
static prt_result compile_program(prt_context* context, prt_gl_pose_shader* s) {
  const prt_pose_info* info = &s->view->info;
  const uint32_t n = info->order;
  double diag[PRT_BLOB_PSTR_MAX_ORDER], sub[PRT_BLOB_PSTR_MAX_ORDER];
  double a[PRT_BLOB_PSTR_MAX_ORDER * (PRT_BLOB_PSTR_MAX_ORDER + 1u) / 2u];
  double b[PRT_BLOB_PSTR_MAX_ORDER * (PRT_BLOB_PSTR_MAX_ORDER + 1u) / 2u];
  char header[4096];
  const prt_GLchar* sources[3];
  size_t used;
  uint32_t l, m;
  diag[0] = 1.0 / sqrt(4.0 * 3.14159265358979323846);
  for (m = 0; m < n; ++m) {
    if (m > 0) diag[m] = sqrt((2.0 * m + 1.0) / (2.0 * m)) * diag[m - 1];
    sub[m] = sqrt(2.0 * m + 3.0);
  }
  for (l = 0; l < n; ++l)
    for (m = 0; m <= l; ++m) {
      const double dl = l, dm = m;
      const uint32_t k = l * (l + 1u) / 2u + m;
      a[k] = b[k] = 0.0;
      if (l < m + 2u) continue;
      a[k] = sqrt((4.0 * dl * dl - 1.0) / (dl * dl - dm * dm));
      b[k] = sqrt(((dl - 1.0) * (dl - 1.0) - dm * dm) / (4.0 * (dl - 1.0) * (dl - 1.0) - 1.0));
    }
  used = (size_t)snprintf(header, sizeof header,
                          "#version 430 core\n#define LOCAL_SIZE %u\n#define ORDER %u\n"
                          "#define MODEL %u\n#define BITS %u\n#define BASIS_DIMS %u\n"
                          "#define JOINTS %u\n"
                          "#define SKIN_WORDS %u\n#define SQRT2 1.41421356\n",
                          LOCAL_SIZE, n, (unsigned)info->model, info->bits, info->basis_dims,
                          info->joint_count, SKIN_WORDS);
  used = append_table(header, used, sizeof header, "SH_DIAG", diag, n);
  used = append_table(header, used, sizeof header, "SH_SUB", sub, n);
  used = append_table(header, used, sizeof header, "SH_A", a, n * (n + 1u) / 2u);
  used = append_table(header, used, sizeof header, "SH_B", b, n * (n + 1u) / 2u);
  if (used >= sizeof header) /* cannot happen for order <= 8; guards the format strings */
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "prt_gl_pose_create: shader header too long");
  sources[0] = header;
  sources[1] = kShaderDeclarations;
  sources[2] = kShaderMain;
  return prt_gl_compile_compute(context, &s->gl, "prt_gl_pose_create", sources, 3, &s->program);
}

/* ---- buffers --------------------------------------------------------------------------- */

/* Storage of `bytes` for buffers[index], filled with `data` (little-endian words) when given. */
static prt_result make_buffer(prt_context* context, prt_gl_pose_shader* s, int index,
                              prt_GLenum usage, const uint8_t* data, uint64_t bytes) {
  const prt_gl_functions* gl = &s->gl;
  prt_result r = PRT_OK;
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[index]);
  if (data)
    r = prt_gl_upload_le_words(context, &s->allocator, gl, "prt_gl_pose_create",
                               PRT_GL_SHADER_STORAGE_BUFFER, 0, 0, data, (size_t)bytes);
  else
    gl->BufferData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLsizeiptr)bytes, NULL, usage);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
  return r;
}

/* Whole uint words of the basis values (the PSTR layout pads them to 4 bytes, so the last word
 * is inside the section), the skin records, the radiance, the joints' matrices and the
 * caller's normals; buffers model 0 never reads get 16 bytes. Empty assets still get valid
 * buffers. */
typedef struct buffer_sizes {
  uint64_t values, skin, radiance, joints, normals;
} buffer_sizes;

static buffer_sizes sizes_of(const prt_pose_view* view) {
  const prt_pose_info* info = &view->info;
  const int model1 = info->model == PRT_POSE_MODEL_RESIDUAL;
  buffer_sizes b;
  b.values =
      ((uint64_t)info->vertex_count * info->basis_dims * (info->bits / 8u) + 3u) & ~(uint64_t)3u;
  b.skin = model1 ? (uint64_t)PRT_BLOB_PSTR_SKIN_SIZE * info->vertex_count : 0u;
  b.radiance = 12u * (uint64_t)info->vertex_count;
  b.joints = model1 ? 48u * (uint64_t)info->joint_count : 0u;
  b.normals = model1 ? 12u * (uint64_t)info->vertex_count : 0u;
  if (b.values == 0) b.values = 4;
  if (b.skin == 0) b.skin = 16;
  if (b.radiance == 0) b.radiance = 12;
  if (b.joints == 0) b.joints = 16;
  if (b.normals == 0) b.normals = 16;
  return b;
}

static prt_result create_buffers(prt_context* context, prt_gl_pose_shader* s,
                                 const buffer_sizes* b) {
  const prt_pose_view* view = s->view;
  const int has_vertices = view->info.vertex_count > 0;
  prt_result r;
  prt_gl_drain_errors(&s->gl);
  s->gl.GenBuffers(BUFFER_COUNT, s->buffers);
  r = make_buffer(context, s, BUFFER_VALUES, 0,
                  has_vertices ? view->data + view->layout.basis_values : NULL, b->values);
  if (r == PRT_OK)
    r = make_buffer(context, s, BUFFER_SKIN, PRT_GL_STATIC_DRAW,
                    residual(s) && has_vertices ? view->data + view->layout.skin : NULL, b->skin);
  if (r == PRT_OK)
    r = make_buffer(context, s, BUFFER_RADIANCE, PRT_GL_DYNAMIC_COPY, NULL, b->radiance);
  if (r == PRT_OK) r = make_buffer(context, s, BUFFER_JOINTS, PRT_GL_DYNAMIC_DRAW, NULL, b->joints);
  if (r == PRT_OK)
    r = make_buffer(context, s, BUFFER_NORMALS, PRT_GL_DYNAMIC_DRAW, NULL, b->normals);
  if (r == PRT_OK)
    r = make_buffer(context, s, BUFFER_LIGHT, PRT_GL_DYNAMIC_DRAW, NULL, 4u * s->light_floats);
  if (r != PRT_OK) return r;
  return prt_gl_check_upload(
      context, &s->gl, "prt_gl_pose_create",
      b->values + b->skin + b->radiance + b->joints + b->normals + 4u * s->light_floats);
}

/* ---- create / destroy ------------------------------------------------------------------ */

prt_result prt_gl_pose_create(prt_context* context, const prt_asset* asset, prt_gl_loader_fn loader,
                              void* loader_user, prt_gl_pose_shader** out_shader) {
  prt_gl_functions gl;
  prt_gl_pose_shader* s;
  const prt_pose_view* view;
  buffer_sizes sizes;
  prt_result r;
  if (out_shader) *out_shader = NULL;
  r = prt_gl_check_create(context, "prt_gl_pose_create", asset, (const void*)loader, out_shader,
                          PRT_TECHNIQUE_POSE, "PSTR", (const void**)&view);
  if (r != PRT_OK) return r;
  memset(&gl, 0, sizeof gl);
  r = prt_gl_open(context, "prt_gl_pose_create", loader, loader_user, &gl);
  sizes = sizes_of(view);
  if (r == PRT_OK) {
    const uint64_t bytes[5] = {sizes.values, sizes.skin, sizes.radiance, sizes.joints,
                               sizes.normals};
    const char* const names[5] = {"basis values", "skin", "radiance", "joints", "normals"};
    r = prt_gl_check_block_sizes(context, &gl, "prt_gl_pose_create", bytes, names, 5);
  }
  if (r != PRT_OK) return r;

  s = (prt_gl_pose_shader*)prt_internal_alloc(&asset->allocator, sizeof *s, 16);
  if (!s)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "prt_gl_pose_create: out of memory");
  memset(s, 0, sizeof *s);
  s->allocator = asset->allocator;
  s->gl = gl;
  s->view = view;
  s->light_floats =
      12u + 4u * view->info.basis_dims + (residual(s) ? 4u * view->layout.coefficients : 0u);
  r = compile_program(context, s);
  if (r == PRT_OK) r = create_buffers(context, s, &sizes);
  if (r != PRT_OK) {
    prt_gl_pose_destroy(s);
    return r;
  }
  *out_shader = s;
  return PRT_OK;
}

void prt_gl_pose_destroy(prt_gl_pose_shader* shader) {
  prt_allocator allocator;
  if (!shader) return;
  if (shader->buffers[0]) shader->gl.DeleteBuffers(BUFFER_COUNT, shader->buffers);
  if (shader->program) shader->gl.DeleteProgram(shader->program);
  allocator = shader->allocator;
  prt_internal_free(&allocator, shader, sizeof *shader);
}

/* ---- per frame ------------------------------------------------------------------------- */

/* The light block from the folded frame: vec4 (bias r, g, b, t_00 base), (L_00 rgb, 0),
 * (t_00 lo, hi, 0, 0), weight[k] = (scale_k w_k[ch], t_00 weight), then exact[c] = (rgb, 0) for
 * model 1; and the joints' K_j as three rows of vec4 each (model 1). */
static void fill_uploads(prt_gl_pose_shader* s) {
  const prt_pose_view* view = s->view;
  const uint32_t q = view->info.basis_dims;
  const uint64_t params = view->layout.basis_params;
  const prt_pose_folded* f = &s->folded;
  float* light = s->light;
  uint32_t k, ch, c, j;
  int r, i;
  for (ch = 0; ch < 3; ++ch) {
    double bias = 0.0;
    for (k = 0; k < q; ++k) {
      bias += prt_pose_f32(view, params + 8u * k) * f->weight[k][ch];
      light[12u + 4u * k + ch] =
          prt_pose_to_float(prt_pose_f32(view, params + 8u * k + 4u) * f->weight[k][ch]);
    }
    light[ch] = prt_pose_to_float(bias);
    light[4u + ch] = prt_pose_to_float(f->light_dc[ch]);
  }
  /* The learned t_00 rides in the fourth lane (SPEC §7.3's clamp): bias.w, weight[k].w. */
  light[3] = prt_pose_to_float(f->dc.base);
  light[7] = 0.0f;
  light[8] = prt_pose_to_float(f->dc.lo);
  light[9] = prt_pose_to_float(f->dc.hi);
  light[10] = light[11] = 0.0f;
  for (k = 0; k < q; ++k) light[12u + 4u * k + 3u] = prt_pose_to_float(f->dc.weight[k]);
  if (!residual(s)) return;
  for (c = 0; c < view->layout.coefficients; ++c) {
    float* e = light + 12u + 4u * q + 4u * c;
    for (ch = 0; ch < 3; ++ch) e[ch] = prt_pose_to_float(f->exact[c][ch]);
    e[3] = 0.0f;
  }
  for (j = 0; j < view->info.joint_count; ++j)
    for (r = 0; r < 3; ++r)
      for (i = 0; i < 4; ++i)
        s->joints[12u * j + 4u * r + i] = prt_pose_to_float(f->skeleton.skin[j].m[r][i]);
}

/* Per-frame calls write no context (prt_gl.h): a bad argument is reported by the result alone. */
static int range_inside(const prt_gl_pose_shader* s, uint32_t first, uint32_t count) {
  return first <= s->view->info.vertex_count && count <= s->view->info.vertex_count - first;
}

static void bind_all(const prt_gl_pose_shader* s, int bind) {
  const prt_gl_functions* gl = &s->gl;
  int i;
  for (i = 0; i < BUFFER_LIGHT; ++i)
    if (i == BUFFER_VALUES || i == BUFFER_RADIANCE || residual(s))
      gl->BindBufferBase(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLuint)i, bind ? s->buffers[i] : 0u);
  gl->BindBufferBase(PRT_GL_UNIFORM_BUFFER, 0, bind ? s->buffers[BUFFER_LIGHT] : 0u);
}

static void sub_data(const prt_gl_pose_shader* s, int index, size_t offset, size_t bytes,
                     const void* data) {
  const prt_gl_functions* gl = &s->gl;
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, s->buffers[index]);
  gl->BufferSubData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLintptr)offset, (prt_GLsizeiptr)bytes,
                    data);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
}

prt_result prt_gl_pose_shade(prt_gl_pose_shader* shader, const prt_pose_input* pose,
                             const prt_pose_light* light, uint32_t first_vertex,
                             uint32_t vertex_count) {
  const prt_gl_functions* gl;
  int given;
  uint32_t done;
  prt_result r;
  if (!shader || !light || !prt_internal_struct_size_ok(light, PRT_POSE_LIGHT_SIZE_1_0) ||
      !light->light_rgb || !range_inside(shader, first_vertex, vertex_count))
    return PRT_ERROR_INVALID_ARGUMENT;
  r = prt_pose_check_input(shader->view, pose);
  if (r != PRT_OK) return r;
  /* Folded before the empty range returns, as prt_pose_shade does: a bad world rotation fails
   * whatever the range. */
  r = prt_pose_fold_shading(shader->view, pose, light, &shader->folded);
  if (r != PRT_OK || vertex_count == 0) return r;
  gl = &shader->gl;
  fill_uploads(shader);
  sub_data(shader, BUFFER_LIGHT, 0, 4u * shader->light_floats, shader->light);
  given = residual(shader) && light->normals != NULL;
  if (residual(shader))
    sub_data(shader, BUFFER_JOINTS, 0, 48u * shader->view->info.joint_count, shader->joints);
  if (given)
    sub_data(shader, BUFFER_NORMALS, 12u * (size_t)first_vertex, 12u * (size_t)vertex_count,
             light->normals);
  bind_all(shader, 1);
  gl->UseProgram(shader->program);
  gl->ProgramUniform1ui(shader->program, UNIFORM_GIVEN_NORMALS, given ? 1u : 0u);
  for (done = 0; done < vertex_count;) {
    uint32_t chunk = vertex_count - done;
    if (chunk > MAX_GROUPS_PER_DISPATCH * LOCAL_SIZE) chunk = MAX_GROUPS_PER_DISPATCH * LOCAL_SIZE;
    gl->ProgramUniform1ui(shader->program, UNIFORM_FIRST_VERTEX, first_vertex + done);
    gl->ProgramUniform1ui(shader->program, UNIFORM_VERTEX_COUNT, chunk);
    gl->DispatchCompute((chunk + LOCAL_SIZE - 1u) / LOCAL_SIZE, 1, 1);
    done += chunk;
  }
  gl->UseProgram(0);
  bind_all(shader, 0);
  /* Make the writes visible to whatever reads the output next: vertex fetch, shaders, copies. */
  gl->MemoryBarrier(PRT_GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | PRT_GL_SHADER_STORAGE_BARRIER_BIT |
                    PRT_GL_BUFFER_UPDATE_BARRIER_BIT);
  return PRT_OK;
}

uint32_t prt_gl_pose_output_buffer(const prt_gl_pose_shader* shader) {
  return shader ? shader->buffers[BUFFER_RADIANCE] : 0u;
}

prt_result prt_gl_pose_read(prt_gl_pose_shader* shader, uint32_t first_vertex,
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
