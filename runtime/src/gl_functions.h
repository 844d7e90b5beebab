/* SPDX-License-Identifier: MIT */
/* Private to the runtime: the few OpenGL 4.3 core types, constants and entry points the GL
 * backends use (compute for sh, wavelet and pose; a full-screen draw for cloth), declared here so
 * that the runtime includes no GL header and links no GL library. Values are those of the Khronos
 * registry (GL/glcorearb.h). Every entry point is loaded through the application's prt_gl_loader_fn
 * (gl_common.c). */
#ifndef PRT_RUNTIME_GL_FUNCTIONS_H
#define PRT_RUNTIME_GL_FUNCTIONS_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32) && !defined(__CYGWIN__)
#define PRT_GL_APIENTRY __stdcall
#else
#define PRT_GL_APIENTRY
#endif

typedef unsigned int prt_GLenum;
typedef unsigned int prt_GLuint;
typedef unsigned int prt_GLbitfield;
typedef int prt_GLint;
typedef int prt_GLsizei;
typedef char prt_GLchar;
typedef unsigned char prt_GLubyte;
typedef unsigned char prt_GLboolean;
typedef ptrdiff_t prt_GLsizeiptr; /* khronos_ssize_t: pointer-sized and signed */
typedef ptrdiff_t prt_GLintptr;   /* khronos_intptr_t */
typedef int64_t prt_GLint64;

#define PRT_GL_NO_ERROR 0u
#define PRT_GL_INVALID_ENUM 0x0500u
#define PRT_GL_OUT_OF_MEMORY 0x0505u
#define PRT_GL_MAJOR_VERSION 0x821Bu
#define PRT_GL_MINOR_VERSION 0x821Cu
#define PRT_GL_COMPUTE_SHADER 0x91B9u
#define PRT_GL_COMPILE_STATUS 0x8B81u
#define PRT_GL_LINK_STATUS 0x8B82u
#define PRT_GL_INFO_LOG_LENGTH 0x8B84u
#define PRT_GL_SHADER_STORAGE_BUFFER 0x90D2u
#define PRT_GL_UNIFORM_BUFFER 0x8A11u
#define PRT_GL_STATIC_DRAW 0x88E4u
#define PRT_GL_DYNAMIC_DRAW 0x88E8u
#define PRT_GL_DYNAMIC_COPY 0x88EAu
#define PRT_GL_MAX_SHADER_STORAGE_BLOCK_SIZE 0x90DEu
#define PRT_GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT 0x00000001u
#define PRT_GL_BUFFER_UPDATE_BARRIER_BIT 0x00000200u
#define PRT_GL_SHADER_STORAGE_BARRIER_BIT 0x00002000u
#define PRT_GL_VERTEX_SHADER 0x8B31u
#define PRT_GL_FRAGMENT_SHADER 0x8B30u
#define PRT_GL_TRIANGLES 0x0004u
#define PRT_GL_TEXTURE_2D 0x0DE1u
#define PRT_GL_TEXTURE0 0x84C0u
#define PRT_GL_DEPTH_TEST 0x0B71u
#define PRT_GL_BLEND 0x0BE2u
#define PRT_GL_CULL_FACE 0x0B44u
#define PRT_GL_VIEWPORT 0x0BA2u
#define PRT_GL_MAX_TEXTURE_SIZE 0x0D33u
#define PRT_GL_R32UI 0x8236u
#define PRT_GL_RED_INTEGER 0x8D94u
#define PRT_GL_UNSIGNED_INT 0x1405u
#define PRT_GL_TEXTURE_MIN_FILTER 0x2801u
#define PRT_GL_TEXTURE_MAG_FILTER 0x2800u
#define PRT_GL_NEAREST 0x2600u
#define PRT_GL_PIXEL_UNPACK_BUFFER 0x88ECu
#define PRT_GL_PIXEL_UNPACK_BUFFER_BINDING 0x88EFu
#define PRT_GL_UNPACK_SWAP_BYTES 0x0CF0u
#define PRT_GL_UNPACK_ROW_LENGTH 0x0CF2u
#define PRT_GL_UNPACK_SKIP_ROWS 0x0CF3u
#define PRT_GL_UNPACK_SKIP_PIXELS 0x0CF4u
#define PRT_GL_UNPACK_ALIGNMENT 0x0CF5u
#define PRT_GL_ONE 1u
#define PRT_GL_FUNC_ADD 0x8006u
#define PRT_GL_BLEND_SRC_RGB 0x80C9u
#define PRT_GL_BLEND_DST_RGB 0x80C8u
#define PRT_GL_BLEND_SRC_ALPHA 0x80CBu
#define PRT_GL_BLEND_DST_ALPHA 0x80CAu
#define PRT_GL_BLEND_EQUATION_RGB 0x8009u
#define PRT_GL_BLEND_EQUATION_ALPHA 0x883Du

/* The entry points (gl_common.c loads each one named in kGlFunctions). */
typedef struct prt_gl_functions {
  prt_GLenum(PRT_GL_APIENTRY* GetError)(void);
  void(PRT_GL_APIENTRY* GetIntegerv)(prt_GLenum pname, prt_GLint* data);
  void(PRT_GL_APIENTRY* GetInteger64v)(prt_GLenum pname, prt_GLint64* data);
  prt_GLuint(PRT_GL_APIENTRY* CreateShader)(prt_GLenum type);
  void(PRT_GL_APIENTRY* ShaderSource)(prt_GLuint shader, prt_GLsizei count,
                                      const prt_GLchar* const* string, const prt_GLint* length);
  void(PRT_GL_APIENTRY* CompileShader)(prt_GLuint shader);
  void(PRT_GL_APIENTRY* GetShaderiv)(prt_GLuint shader, prt_GLenum pname, prt_GLint* params);
  void(PRT_GL_APIENTRY* GetShaderInfoLog)(prt_GLuint shader, prt_GLsizei size, prt_GLsizei* length,
                                          prt_GLchar* log);
  void(PRT_GL_APIENTRY* DeleteShader)(prt_GLuint shader);
  prt_GLuint(PRT_GL_APIENTRY* CreateProgram)(void);
  void(PRT_GL_APIENTRY* AttachShader)(prt_GLuint program, prt_GLuint shader);
  void(PRT_GL_APIENTRY* DetachShader)(prt_GLuint program, prt_GLuint shader);
  void(PRT_GL_APIENTRY* LinkProgram)(prt_GLuint program);
  void(PRT_GL_APIENTRY* GetProgramiv)(prt_GLuint program, prt_GLenum pname, prt_GLint* params);
  void(PRT_GL_APIENTRY* GetProgramInfoLog)(prt_GLuint program, prt_GLsizei size,
                                           prt_GLsizei* length, prt_GLchar* log);
  void(PRT_GL_APIENTRY* DeleteProgram)(prt_GLuint program);
  void(PRT_GL_APIENTRY* UseProgram)(prt_GLuint program);
  void(PRT_GL_APIENTRY* ProgramUniform1ui)(prt_GLuint program, prt_GLint location, prt_GLuint v0);
  void(PRT_GL_APIENTRY* GenBuffers)(prt_GLsizei n, prt_GLuint* buffers);
  void(PRT_GL_APIENTRY* DeleteBuffers)(prt_GLsizei n, const prt_GLuint* buffers);
  void(PRT_GL_APIENTRY* BindBuffer)(prt_GLenum target, prt_GLuint buffer);
  void(PRT_GL_APIENTRY* BindBufferBase)(prt_GLenum target, prt_GLuint index, prt_GLuint buffer);
  void(PRT_GL_APIENTRY* BufferData)(prt_GLenum target, prt_GLsizeiptr size, const void* data,
                                    prt_GLenum usage);
  void(PRT_GL_APIENTRY* BufferSubData)(prt_GLenum target, prt_GLintptr offset, prt_GLsizeiptr size,
                                       const void* data);
  void(PRT_GL_APIENTRY* GetBufferSubData)(prt_GLenum target, prt_GLintptr offset,
                                          prt_GLsizeiptr size, void* data);
  void(PRT_GL_APIENTRY* DispatchCompute)(prt_GLuint x, prt_GLuint y, prt_GLuint z);
  void(PRT_GL_APIENTRY* MemoryBarrier)(prt_GLbitfield barriers);
  void(PRT_GL_APIENTRY* GenVertexArrays)(prt_GLsizei n, prt_GLuint* arrays);
  void(PRT_GL_APIENTRY* DeleteVertexArrays)(prt_GLsizei n, const prt_GLuint* arrays);
  void(PRT_GL_APIENTRY* BindVertexArray)(prt_GLuint array);
  void(PRT_GL_APIENTRY* ActiveTexture)(prt_GLenum texture);
  void(PRT_GL_APIENTRY* BindTexture)(prt_GLenum target, prt_GLuint texture);
  void(PRT_GL_APIENTRY* BindSampler)(prt_GLuint unit, prt_GLuint sampler);
  void(PRT_GL_APIENTRY* Enable)(prt_GLenum cap);
  void(PRT_GL_APIENTRY* Disable)(prt_GLenum cap);
  void(PRT_GL_APIENTRY* DrawArrays)(prt_GLenum mode, prt_GLint first, prt_GLsizei count);
  void(PRT_GL_APIENTRY* GenTextures)(prt_GLsizei n, prt_GLuint* textures);
  void(PRT_GL_APIENTRY* DeleteTextures)(prt_GLsizei n, const prt_GLuint* textures);
  void(PRT_GL_APIENTRY* TexStorage2D)(prt_GLenum target, prt_GLsizei levels,
                                      prt_GLenum internal_format, prt_GLsizei width,
                                      prt_GLsizei height);
  void(PRT_GL_APIENTRY* TexSubImage2D)(prt_GLenum target, prt_GLint level, prt_GLint x, prt_GLint y,
                                       prt_GLsizei width, prt_GLsizei height, prt_GLenum format,
                                       prt_GLenum type, const void* pixels);
  void(PRT_GL_APIENTRY* TexParameteri)(prt_GLenum target, prt_GLenum name, prt_GLint value);
  void(PRT_GL_APIENTRY* PixelStorei)(prt_GLenum name, prt_GLint value);
  void(PRT_GL_APIENTRY* BlendFuncSeparate)(prt_GLenum src_rgb, prt_GLenum dst_rgb,
                                           prt_GLenum src_alpha, prt_GLenum dst_alpha);
  void(PRT_GL_APIENTRY* BlendEquationSeparate)(prt_GLenum rgb, prt_GLenum alpha);
} prt_gl_functions;

#endif /* PRT_RUNTIME_GL_FUNCTIONS_H */
