// SPDX-License-Identifier: MIT
// Where a sample's frames go: a GLFW window (GL 4.3 core through GLX, or EGL) or the headless
// EGL context of samples/common/headless_gl with an offscreen framebuffer. Both draw the same
// frames; a presenter only owns the context, the events and the last step (swap or nothing).
#pragma once

#include <prt/prt.h>

#include <memory>
#include <string>

#include "gl.hpp"
#include "input.hpp"

namespace prt::sample {

class Presenter {
 public:
  virtual ~Presenter() = default;
  // The frame's size in pixels.
  virtual void framebuffer_size(int* width, int* height) const = 0;
  // Resizes the window (as its user would) or the headless frame to width x height pixels.
  virtual void resize(int width, int height) = 0;
  // Framebuffer pixels per window coordinate (1 unless the display scales).
  virtual double pixel_ratio() const = 0;
  virtual bool should_close() const = 0;
  virtual void request_close() = 0;
  // Handles the window system's events (calling the InputSink the presenter was made with).
  virtual void poll() = 0;
  // ImGui's platform side of a new frame (display size, time step, window input).
  virtual void imgui_new_frame(double seconds) = 0;
  virtual void imgui_shutdown() = 0;
  // The framebuffer the frame is composed in (0: the window's back buffer).
  virtual GLuint output_framebuffer() const = 0;
  virtual void present() = 0;
  virtual prt_gl_loader_fn loader() const = 0;
  virtual void* loader_user() const = 0;
  // "GLX window", "EGL window" or "headless EGL".
  virtual std::string kind() const = 0;
};

struct WindowRequest {
  int width = 1280, height = 720;
  std::string title;
  bool egl = false;   // the context through EGL instead of GLX
  bool vsync = true;  // swap interval 1
  bool visible = true;
};

// Throws std::runtime_error with GLFW's reason when no window can be made (no display, say).
std::unique_ptr<Presenter> make_window_presenter(const WindowRequest& request, InputSink& sink);
// Throws std::runtime_error with the EGL attempts' reasons.
std::unique_ptr<Presenter> make_headless_presenter(int width, int height);

}  // namespace prt::sample
