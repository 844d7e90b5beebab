/* SPDX-License-Identifier: MIT */
/* Shared by the GL compute backends (gl_common.h). */
#include "internal.h"

#if !defined(PRT_HAS_GL)
typedef int prt_gl_common_unused; /* ISO C forbids an empty translation unit */
#else

#include <stdio.h>
#include <string.h>

#include "gl_common.h"
#include "techniques.h"

#define LOG_EXCERPT 300

typedef struct gl_function_slot {
  const char* name;
  size_t offset; /* of the pointer in prt_gl_functions */
} gl_function_slot;

#define SLOT(fn) \
  { "gl" #fn, offsetof(prt_gl_functions, fn) }
static const gl_function_slot kGlFunctions[] = {
    SLOT(GetError),         SLOT(GetIntegerv),        SLOT(GetInteger64v),
    SLOT(CreateShader),     SLOT(ShaderSource),       SLOT(CompileShader),
    SLOT(GetShaderiv),      SLOT(GetShaderInfoLog),   SLOT(DeleteShader),
    SLOT(CreateProgram),    SLOT(AttachShader),       SLOT(DetachShader),
    SLOT(LinkProgram),      SLOT(GetProgramiv),       SLOT(GetProgramInfoLog),
    SLOT(DeleteProgram),    SLOT(UseProgram),         SLOT(ProgramUniform1ui),
    SLOT(GenBuffers),       SLOT(DeleteBuffers),      SLOT(BindBuffer),
    SLOT(BindBufferBase),   SLOT(BufferData),         SLOT(BufferSubData),
    SLOT(GetBufferSubData), SLOT(DispatchCompute),    SLOT(MemoryBarrier),
    SLOT(DeleteTextures),   SLOT(DeleteVertexArrays), SLOT(BlendFuncSeparate),
    SLOT(PixelStorei),      SLOT(GenTextures),        SLOT(ActiveTexture),
    SLOT(DrawArrays),       SLOT(TexParameteri),      SLOT(GenVertexArrays),
    SLOT(Enable),           SLOT(TexStorage2D),       SLOT(TexSubImage2D),
    SLOT(Disable),          SLOT(BindTexture),        SLOT(BlendEquationSeparate),
    SLOT(BindSampler),      SLOT(BindVertexArray)};
#undef SLOT

const char* prt_gl_load_functions(prt_gl_loader_fn loader, void* user, prt_gl_functions* gl) {
  size_t i;
  for (i = 0; i < sizeof kGlFunctions / sizeof kGlFunctions[0]; ++i) {
    void* address = loader(user, kGlFunctions[i].name);
    if (!address) return kGlFunctions[i].name;
    /* Object-to-function pointer conversion through memcpy: POSIX guarantees equal sizes. */
    memcpy((char*)gl + kGlFunctions[i].offset, &address, sizeof address);
  }
  return NULL;
}

prt_result prt_gl_open(prt_context* context, const char* function, prt_gl_loader_fn loader,
                       void* user, prt_gl_functions* gl) {
  prt_GLint major = 0, minor = 0;
  const char* missing = prt_gl_load_functions(loader, user, gl);
  if (missing)
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND, "%s: the GL loader has no %s",
                             function, missing);
  gl->GetIntegerv(PRT_GL_MAJOR_VERSION, &major);
  gl->GetIntegerv(PRT_GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 3))
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "%s: needs OpenGL 4.3 (compute shaders, SSBOs); the current context "
                             "is %d.%d",
                             function, (int)major, (int)minor);
  return PRT_OK;
}

int prt_gl_allowed(const prt_context* context) {
  return context->backend_limit == PRT_BACKEND_AUTO || context->backend_limit >= PRT_BACKEND_GL;
}

prt_result prt_gl_check_create(prt_context* context, const char* function, const prt_asset* asset,
                               const void* loader, const void* out_shader, prt_technique technique,
                               const char* tag, const void** out_view) {
  if (!context) return PRT_ERROR_INVALID_ARGUMENT;
  if (!asset || !loader || !out_shader)
    return prt_internal_fail(context, PRT_ERROR_INVALID_ARGUMENT,
                             "%s: asset, loader and out_shader must not be NULL", function);
  if (!prt_gl_allowed(context))
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "%s: the context's backend limit (%s) excludes gl", function,
                             prt_backend_name(context->backend_limit));
  *out_view = prt_internal_view(asset, technique);
  if (!*out_view)
    return prt_internal_fail(context, PRT_ERROR_NOT_FOUND, "%s: the asset has no %s section",
                             function, tag);
  return PRT_OK;
}

void prt_gl_read_radiance(const prt_gl_functions* gl, prt_GLuint buffer, uint32_t first,
                          uint32_t count, float* out_rgb) {
  gl->MemoryBarrier(PRT_GL_BUFFER_UPDATE_BARRIER_BIT);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, buffer);
  gl->GetBufferSubData(PRT_GL_SHADER_STORAGE_BUFFER, (prt_GLintptr)(12u * (size_t)first),
                       (prt_GLsizeiptr)(12u * (size_t)count), out_rgb);
  gl->BindBuffer(PRT_GL_SHADER_STORAGE_BUFFER, 0);
}

prt_result prt_gl_check_block_sizes(prt_context* context, const prt_gl_functions* gl,
                                    const char* function, const uint64_t* bytes,
                                    const char* const* names, int count) {
  char needs[256] = "";
  prt_GLint64 max_block = 0;
  int i, fits = 1;
  size_t used = 0;
  gl->GetInteger64v(PRT_GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  for (i = 0; i < count; ++i) {
    if (max_block <= 0 || bytes[i] > (uint64_t)max_block || bytes[i] > UINT32_MAX ||
        bytes[i] > (uint64_t)PTRDIFF_MAX)
      fits = 0;
    if (used < sizeof needs)
      used += (size_t)snprintf(needs + used, sizeof needs - used, "%s%llu (%s)",
                               i == 0 ? "" : (i + 1 == count ? " and " : ", "),
                               (unsigned long long)bytes[i], names[i]);
  }
  if (!fits)
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "%s: the asset needs shader storage blocks of %s bytes; this GL "
                             "allows %lld",
                             function, needs, (long long)max_block);
  return PRT_OK;
}

/* Compiles one stage; 0 with the failure recorded when it does not compile. */
static prt_GLuint compile_stage(prt_context* context, const prt_gl_functions* gl,
                                const char* function, prt_GLenum type, const char* stage,
                                const prt_GLchar* const* sources, int source_count) {
  prt_GLint ok = 0;
  char log[LOG_EXCERPT + 1] = "";
  prt_GLuint shader = gl->CreateShader(type);
  if (!shader) {
    prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND, "%s: glCreateShader(%s) failed",
                      function, stage);
    return 0;
  }
  gl->ShaderSource(shader, source_count, sources, NULL);
  gl->CompileShader(shader);
  gl->GetShaderiv(shader, PRT_GL_COMPILE_STATUS, &ok);
  if (!ok) {
    gl->GetShaderInfoLog(shader, (prt_GLsizei)sizeof log, NULL, log);
    gl->DeleteShader(shader);
    prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                      "%s: the %s shader does not compile: %s", function, stage, log);
    return 0;
  }
  return shader;
}

/* Links the compiled stages into *out_program (set even when linking fails, for the caller to
 * delete); the stages are detached and deleted. */
static prt_result link_program(prt_context* context, const prt_gl_functions* gl,
                               const char* function, const char* what, const prt_GLuint* shaders,
                               int shader_count, prt_GLuint* out_program) {
  prt_GLint ok = 0;
  char log[LOG_EXCERPT + 1] = "";
  int i;
  *out_program = gl->CreateProgram();
  for (i = 0; i < shader_count; ++i) gl->AttachShader(*out_program, shaders[i]);
  gl->LinkProgram(*out_program);
  for (i = 0; i < shader_count; ++i) {
    gl->DetachShader(*out_program, shaders[i]);
    gl->DeleteShader(shaders[i]);
  }
  gl->GetProgramiv(*out_program, PRT_GL_LINK_STATUS, &ok);
  if (!ok) {
    gl->GetProgramInfoLog(*out_program, (prt_GLsizei)sizeof log, NULL, log);
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND, "%s: the %s does not link: %s",
                             function, what, log);
  }
  return PRT_OK;
}

prt_result prt_gl_compile_compute(prt_context* context, const prt_gl_functions* gl,
                                  const char* function, const prt_GLchar* const* sources,
                                  int source_count, prt_GLuint* out_program) {
  prt_GLuint shader;
  *out_program = 0;
  shader =
      compile_stage(context, gl, function, PRT_GL_COMPUTE_SHADER, "compute", sources, source_count);
  if (!shader) return PRT_ERROR_UNSUPPORTED_BACKEND;
  return link_program(context, gl, function, "compute shader", &shader, 1, out_program);
}

prt_result prt_gl_compile_draw(prt_context* context, const prt_gl_functions* gl,
                               const char* function, const prt_GLchar* const* vertex_sources,
                               int vertex_count, const prt_GLchar* const* fragment_sources,
                               int fragment_count, prt_GLuint* out_program) {
  prt_GLuint shaders[2];
  *out_program = 0;
  shaders[0] = compile_stage(context, gl, function, PRT_GL_VERTEX_SHADER, "vertex", vertex_sources,
                             vertex_count);
  if (!shaders[0]) return PRT_ERROR_UNSUPPORTED_BACKEND;
  shaders[1] = compile_stage(context, gl, function, PRT_GL_FRAGMENT_SHADER, "fragment",
                             fragment_sources, fragment_count);
  if (!shaders[1]) {
    gl->DeleteShader(shaders[0]);
    return PRT_ERROR_UNSUPPORTED_BACKEND;
  }
  return link_program(context, gl, function, "program", shaders, 2, out_program);
}

void prt_gl_drain_errors(const prt_gl_functions* gl) {
  int drained;
  for (drained = 0; drained < 16 && gl->GetError() != PRT_GL_NO_ERROR; ++drained) {
  }
}

prt_result prt_gl_check_upload(prt_context* context, const prt_gl_functions* gl,
                               const char* function, uint64_t bytes) {
  const prt_GLenum error = gl->GetError();
  if (error == PRT_GL_OUT_OF_MEMORY)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY,
                             "%s: GL_OUT_OF_MEMORY creating %llu bytes of buffers", function,
                             (unsigned long long)bytes);
  if (error != PRT_GL_NO_ERROR)
    return prt_internal_fail(context, PRT_ERROR_UNSUPPORTED_BACKEND,
                             "%s: GL error 0x%04x creating the buffers", function, (unsigned)error);
  return PRT_OK;
}

static int host_is_little_endian(void) {
  const uint32_t one = 1;
  uint8_t first;
  memcpy(&first, &one, 1);
  return first == 1;
}

static void buffer_bytes(const prt_gl_functions* gl, prt_GLenum target, int sub, size_t offset,
                         const void* data, size_t bytes) {
  if (sub)
    gl->BufferSubData(target, (prt_GLintptr)offset, (prt_GLsizeiptr)bytes, data);
  else
    gl->BufferData(target, (prt_GLsizeiptr)bytes, data, PRT_GL_STATIC_DRAW);
}

prt_result prt_gl_upload_le_words(prt_context* context, const prt_allocator* allocator,
                                  const prt_gl_functions* gl, const char* function,
                                  prt_GLenum target, int sub, size_t offset, const uint8_t* data,
                                  size_t bytes) {
  uint32_t* words;
  size_t i;
  if (!data || host_is_little_endian()) { /* NULL: an empty buffer's storage only */
    if (data || !sub) buffer_bytes(gl, target, sub, offset, data, bytes);
    return PRT_OK;
  }
  words = (uint32_t*)prt_internal_alloc(allocator, bytes, 16);
  if (!words)
    return prt_internal_fail(context, PRT_ERROR_OUT_OF_MEMORY, "%s: out of memory (%zu bytes)",
                             function, bytes);
  for (i = 0; i < bytes / 4u; ++i) words[i] = prt_le_load_u32(data + 4u * i);
  buffer_bytes(gl, target, sub, offset, words, bytes);
  prt_internal_free(allocator, words, bytes);
  return PRT_OK;
}

#endif /* PRT_HAS_GL */
