// SPDX-License-Identifier: MIT
// The GL 4.3 core entry points the framework calls, from GLVND's libOpenGL, which dispatches to
// whichever context is current (GLX through GLFW, or EGL headless). The runtime's GL backend gets
// the host's own loader instead (prt_gl.h).
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>

namespace prt::sample {

// A GL object name that deletes itself (the context must still be current then).
template <void (*Delete)(GLuint)>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint name) : name_(name) {}
  ~GlName() { reset(); }
  GlName(GlName&& other) noexcept : name_(other.release()) {}
  GlName& operator=(GlName&& other) noexcept {
    if (this != &other) {
      reset();
      name_ = other.release();
    }
    return *this;
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;

  GLuint get() const { return name_; }
  GLuint release() {
    const GLuint name = name_;
    name_ = 0;
    return name;
  }
  void reset() {
    if (name_) Delete(name_);
    name_ = 0;
  }

 private:
  GLuint name_ = 0;
};

void delete_buffer(GLuint name);
void delete_vertex_array(GLuint name);
void delete_texture(GLuint name);
void delete_framebuffer(GLuint name);
void delete_program(GLuint name);

using GlBuffer = GlName<delete_buffer>;
using GlVertexArray = GlName<delete_vertex_array>;
using GlTexture = GlName<delete_texture>;
using GlFramebuffer = GlName<delete_framebuffer>;
using GlProgram = GlName<delete_program>;

GlBuffer make_buffer();
GlVertexArray make_vertex_array();
GlTexture make_texture();
GlFramebuffer make_framebuffer();

// Compiles and links a vertex + fragment shader pair; throws std::runtime_error with the GL log
// naming `what` on failure.
GlProgram link_program(const char* what, const std::string& vertex, const std::string& fragment);

}  // namespace prt::sample
