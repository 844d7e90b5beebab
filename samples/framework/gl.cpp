// SPDX-License-Identifier: MIT
#include "gl.hpp"

#include <stdexcept>
#include <vector>

namespace prt::sample {

void delete_buffer(GLuint name) {
  glDeleteBuffers(1, &name);
}
void delete_vertex_array(GLuint name) {
  glDeleteVertexArrays(1, &name);
}
void delete_texture(GLuint name) {
  glDeleteTextures(1, &name);
}
void delete_framebuffer(GLuint name) {
  glDeleteFramebuffers(1, &name);
}
void delete_program(GLuint name) {
  glDeleteProgram(name);
}

GlBuffer make_buffer() {
  GLuint name = 0;
  glGenBuffers(1, &name);
  return GlBuffer(name);
}
GlVertexArray make_vertex_array() {
  GLuint name = 0;
  glGenVertexArrays(1, &name);
  return GlVertexArray(name);
}
GlTexture make_texture() {
  GLuint name = 0;
  glGenTextures(1, &name);
  return GlTexture(name);
}
GlFramebuffer make_framebuffer() {
  GLuint name = 0;
  glGenFramebuffers(1, &name);
  return GlFramebuffer(name);
}

namespace {

GLuint compile(const char* what, GLenum stage, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<std::size_t>(length) + 1, '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw std::runtime_error(std::string(what) + ": shader does not compile: " + log.data());
  }
  return shader;
}

}  // namespace

GlProgram link_program(const char* what, const std::string& vertex, const std::string& fragment) {
  const GLuint vs = compile(what, GL_VERTEX_SHADER, vertex);
  const GLuint fs = compile(what, GL_FRAGMENT_SHADER, fragment);
  GlProgram program(glCreateProgram());
  glAttachShader(program.get(), vs);
  glAttachShader(program.get(), fs);
  glLinkProgram(program.get());
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<std::size_t>(length) + 1, '\0');
    glGetProgramInfoLog(program.get(), length, nullptr, log.data());
    throw std::runtime_error(std::string(what) + ": program does not link: " + log.data());
  }
  return program;
}

}  // namespace prt::sample
