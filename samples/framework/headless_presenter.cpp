// SPDX-License-Identifier: MIT
// --headless: the EGL context of samples/common/headless_gl (no window, no display) and an 8-bit
// framebuffer of --size that the frame is composed in, overlay included.
#include <imgui.h>

#include <stdexcept>

#include "headless_gl.h"
#include "presenter.hpp"

namespace prt::sample {
namespace {

class HeadlessPresenter : public Presenter {
 public:
  HeadlessPresenter(int width, int height) {
    char error[1024] = {0};
    gl_ = headless_gl_create(error, sizeof error);
    if (!gl_) throw std::runtime_error(std::string("no headless GL context: ") + error);
    framebuffer_ = make_framebuffer();
    resize(width, height);
  }
  ~HeadlessPresenter() override {
    framebuffer_.reset();
    colour_.reset();
    headless_gl_destroy(gl_);
  }

  void framebuffer_size(int* width, int* height) const override {
    *width = width_, *height = height_;
  }
  // A new colour texture (its storage is immutable) attached to the same framebuffer.
  void resize(int width, int height) override {
    width_ = width, height_ = height;
    colour_ = make_texture();
    glBindTexture(GL_TEXTURE_2D, colour_.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, width, height);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_.get(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  double pixel_ratio() const override { return 1.0; }
  bool should_close() const override { return close_; }
  void request_close() override { close_ = true; }
  void poll() override {}
  void imgui_new_frame(double seconds) override {
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(width_), float(height_));
    io.DeltaTime = float(seconds > 0.0 ? seconds : 1.0 / 60.0);
  }
  void imgui_shutdown() override {}
  GLuint output_framebuffer() const override { return framebuffer_.get(); }
  void present() override {}
  prt_gl_loader_fn loader() const override { return headless_gl_get_proc; }
  void* loader_user() const override { return gl_; }
  std::string kind() const override { return "headless EGL"; }

 private:
  headless_gl* gl_ = nullptr;
  int width_ = 0, height_ = 0;
  bool close_ = false;
  GlTexture colour_;
  GlFramebuffer framebuffer_;
};

}  // namespace

std::unique_ptr<Presenter> make_headless_presenter(int width, int height) {
  return std::make_unique<HeadlessPresenter>(width, height);
}

}  // namespace prt::sample
