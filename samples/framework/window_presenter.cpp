// SPDX-License-Identifier: MIT
// The GLFW window: a GL 4.3 core, forward-compatible, resizable context; ImGui's GLFW backend on
// it, and the window's events passed to the sample's InputSink unless ImGui takes them.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>

#include <cstring>
#include <stdexcept>

#include "presenter.hpp"

// Under AddressSanitizer, glfwTerminate closes the X display, which unloads the Mesa driver, and
// LeakSanitizer then reports the driver's allocations from an unknown module, which no
// suppression can match (as eglTerminate does, samples/common/headless_gl.c); so sanitizer builds
// leave GLFW initialised (the process ends soon after anyway).
#if defined(__SANITIZE_ADDRESS__)
#define PRT_SAMPLE_KEEP_GLFW 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PRT_SAMPLE_KEEP_GLFW 1
#endif
#endif
#ifndef PRT_SAMPLE_KEEP_GLFW
#define PRT_SAMPLE_KEEP_GLFW 0
#endif

namespace prt::sample {
namespace {

std::string& glfw_error() {
  static std::string text;  // GLFW reports through a global callback only
  return text;
}

void record_glfw_error(int code, const char* description) {
  glfw_error() =
      std::string(description ? description : "?") + " (GLFW error " + std::to_string(code) + ")";
}

void* glfw_loader(void*, const char* name) {
  const GLFWglproc proc = glfwGetProcAddress(name);
  void* address = nullptr;
  std::memcpy(&address, &proc, sizeof address);
  return address;
}

std::string key_name(int key) {
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return std::string(1, char('A' + key - GLFW_KEY_A));
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return std::string(1, char('0' + key - GLFW_KEY_0));
  if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F12) return "F" + std::to_string(key - GLFW_KEY_F1 + 1);
  if (key == GLFW_KEY_ESCAPE) return "ESCAPE";
  if (key == GLFW_KEY_SPACE) return "SPACE";
  return "";
}

class WindowPresenter : public Presenter {
 public:
  WindowPresenter(const WindowRequest& request, InputSink& sink) : sink_(sink) {
    glfwSetErrorCallback(record_glfw_error);
    if (!glfwInit())
      throw std::runtime_error("no window: glfwInit failed: " + glfw_error() +
                               " (without a display, use --headless or run under xvfb-run)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, request.visible ? GLFW_TRUE : GLFW_FALSE);
    if (request.egl) glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
    window_ =
        glfwCreateWindow(request.width, request.height, request.title.c_str(), nullptr, nullptr);
    if (!window_) {
      const std::string why = glfw_error();
      glfwTerminate();
      throw std::runtime_error("no GL 4.3 core window: " + why);
    }
    kind_ = request.egl ? "EGL window" : "GLX window";
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(request.vsync ? 1 : 0);
    glfwSetWindowUserPointer(window_, this);
    glfwSetCursorPosCallback(window_, on_cursor);
    glfwSetMouseButtonCallback(window_, on_button);
    glfwSetScrollCallback(window_, on_scroll);
    glfwSetKeyCallback(window_, on_key);
    glfwSetDropCallback(window_, on_drop);
    // ImGui's callbacks call the ones above first (it chains to those installed before it).
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
  }

  ~WindowPresenter() override {
    glfwDestroyWindow(window_);
    if (!PRT_SAMPLE_KEEP_GLFW) glfwTerminate();
  }

  void framebuffer_size(int* width, int* height) const override {
    glfwGetFramebufferSize(window_, width, height);
  }
  void resize(int width, int height) override {
    const double ratio = pixel_ratio();
    glfwSetWindowSize(window_, int(width / ratio), int(height / ratio));
  }
  double pixel_ratio() const override {
    int fw = 0, fh = 0, ww = 0, wh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    glfwGetWindowSize(window_, &ww, &wh);
    return ww > 0 ? double(fw) / ww : 1.0;
  }
  bool should_close() const override { return glfwWindowShouldClose(window_); }
  void request_close() override { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
  void poll() override { glfwPollEvents(); }
  void imgui_new_frame(double) override { ImGui_ImplGlfw_NewFrame(); }
  void imgui_shutdown() override { ImGui_ImplGlfw_Shutdown(); }
  GLuint output_framebuffer() const override { return 0; }
  void present() override { glfwSwapBuffers(window_); }
  prt_gl_loader_fn loader() const override { return glfw_loader; }
  void* loader_user() const override { return nullptr; }
  std::string kind() const override { return kind_; }

 private:
  GLFWwindow* window_ = nullptr;
  InputSink& sink_;
  std::string kind_;

  static WindowPresenter& self(GLFWwindow* window) {
    return *static_cast<WindowPresenter*>(glfwGetWindowUserPointer(window));
  }
  static bool ui_has_mouse() {
    return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse;
  }

  static void on_cursor(GLFWwindow* window, double x, double y) { self(window).sink_.cursor(x, y); }
  static void on_button(GLFWwindow* window, int button, int action, int) {
    if (button != GLFW_MOUSE_BUTTON_LEFT && button != GLFW_MOUSE_BUTTON_RIGHT) return;
    // Releases always pass, so a drag that ends over the panel still ends.
    if (action == GLFW_PRESS && ui_has_mouse()) return;
    self(window).sink_.button(
        button == GLFW_MOUSE_BUTTON_LEFT ? MouseButton::Left : MouseButton::Right,
        action == GLFW_PRESS);
  }
  static void on_scroll(GLFWwindow* window, double, double y) {
    if (!ui_has_mouse()) self(window).sink_.scroll(y);
  }
  static void on_key(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
    const std::string name = key_name(key);
    if (!name.empty()) self(window).sink_.key(name);
  }
  static void on_drop(GLFWwindow* window, int count, const char** paths) {
    self(window).sink_.drop(std::vector<std::string>(paths, paths + count));
  }
};

}  // namespace

std::unique_ptr<Presenter> make_window_presenter(const WindowRequest& request, InputSink& sink) {
  return std::make_unique<WindowPresenter>(request, sink);
}

}  // namespace prt::sample
