// SPDX-License-Identifier: MIT
#include "scene_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace prt::sample {
namespace {

// The HDR target's alpha says what a pixel holds: 0 the environment, 1 a surface's radiance,
// 2 display colours (a heat map and its backdrop), which the tone-map pass passes through.
constexpr float kTagSurface = 1.0f, kTagDisplay = 2.0f;

const char* const kMeshVertex = R"(#version 430 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 colour;
uniform mat4 view_projection;
out vec3 v_colour;
void main() {
  v_colour = colour;
  gl_Position = view_projection * vec4(position, 1.0);
}
)";

const char* const kMeshFragment = R"(#version 430 core
in vec3 v_colour;
uniform float tag;
out vec4 frag;
void main() { frag = vec4(v_colour, tag); }
)";

// A triangle that covers the viewport.
const char* const kFullscreenVertex = R"(#version 430 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
)";

// The ray through each pixel (prt_io's Camera::direction), turned into the map's own frame
// (R^T d) and looked up on the lat-long grid of formats/SPEC.md.
const char* const kBackgroundFragment = R"(#version 430 core
uniform sampler2D environment;
uniform mat3 rotation;
uniform vec3 forward, right, up;
uniform float tan_half, aspect;
uniform vec4 viewport;  // x, y, width, height in pixels
uniform int backdrop;   // 1: flat display grey instead of the map
out vec4 frag;
const float kPi = 3.14159265358979;
void main() {
  if (backdrop == 1) { frag = vec4(vec3(0.25), 2.0); return; }
  vec2 s = (gl_FragCoord.xy - viewport.xy) / viewport.zw;
  vec3 d = normalize(forward + (2.0 * s.x - 1.0) * tan_half * aspect * right +
                     (2.0 * s.y - 1.0) * tan_half * up);
  vec3 m = transpose(rotation) * d;
  float u = atan(m.x, -m.z) / (2.0 * kPi) + 0.5;
  float v = acos(clamp(m.y, -1.0, 1.0)) / kPi;
  frag = vec4(textureLod(environment, vec2(u, v), 0.0).rgb, 0.0);
}
)";

// prt_io's tone_map_srgb8: radiance x 2^EV, the ACES fit of Narkowicz (2015) (or a clamp),
// sRGB encoding; the supersamples of a pixel averaged first, in linear light.
const char* const kToneFragment = R"(#version 430 core
uniform sampler2D hdr;
uniform int supersample;
uniform float exposure_scale;
uniform int filmic;
out vec4 frag;
float aces(float x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
float srgb(float v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}
void main() {
  ivec2 base = ivec2(gl_FragCoord.xy) * supersample;
  vec3 sum = vec3(0.0);
  bool display = false;
  for (int j = 0; j < supersample; ++j)
    for (int i = 0; i < supersample; ++i) {
      vec4 t = texelFetch(hdr, base + ivec2(i, j), 0);
      sum += t.rgb;
      display = display || t.a > 1.5;
    }
  vec3 c = sum / float(supersample * supersample);
  if (display) { frag = vec4(clamp(c, 0.0, 1.0), 1.0); return; }
  vec3 outc;
  for (int k = 0; k < 3; ++k) {
    float v = c[k] * exposure_scale;
    if (isnan(v) || isinf(v)) v = 0.0;
    v = max(v, 0.0);
    outc[k] = clamp(srgb(filmic == 1 ? aces(v) : min(v, 1.0)), 0.0, 1.0);
  }
  frag = vec4(outc, 1.0);
}
)";

// A FrameRect in GL pixels (origin bottom left) of a width x height target.
struct PixelRect {
  GLint x, y;
  GLsizei width, height;
};

PixelRect pixels(const FrameRect& r, int width, int height) {
  const int x0 = static_cast<int>(std::lround(r.x0 * width));
  const int x1 = static_cast<int>(std::lround(r.x1 * width));
  const int y0 = static_cast<int>(std::lround((1.0f - r.y1) * height));
  const int y1 = static_cast<int>(std::lround((1.0f - r.y0) * height));
  return {x0, y0, std::max(x1 - x0, 1), std::max(y1 - y0, 1)};
}

GLint uniform(const GlProgram& program, const char* name) {
  return glGetUniformLocation(program.get(), name);
}

}  // namespace

const char* tone_map_name(ToneMap tone_map) {
  return tone_map == ToneMap::Filmic ? "filmic" : "linear";
}

GpuMesh::GpuMesh(const float* positions, std::uint32_t vertex_count, const std::uint32_t* indices,
                 std::uint32_t triangle_count)
    : array_(make_vertex_array()),
      positions_(make_buffer()),
      indices_(make_buffer()),
      colours_(make_buffer()),
      vertex_count_(vertex_count),
      index_count_(3 * triangle_count) {
  lo_ = glm::vec3(INFINITY), hi_ = glm::vec3(-INFINITY);
  for (std::uint32_t i = 0; i < index_count_; ++i) {
    const float* p = positions + 3u * indices[i];
    lo_ = glm::min(lo_, glm::vec3(p[0], p[1], p[2]));
    hi_ = glm::max(hi_, glm::vec3(p[0], p[1], p[2]));
  }
  if (index_count_ == 0) lo_ = hi_ = glm::vec3(0.0f);
  glBindVertexArray(array_.get());
  glBindBuffer(GL_ARRAY_BUFFER, positions_.get());
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertex_count) * 12, positions, GL_STATIC_DRAW);
  glVertexAttribFormat(0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexAttribBinding(0, 0);
  glBindVertexBuffer(0, positions_.get(), 0, 12);
  glEnableVertexAttribArray(0);
  glVertexAttribFormat(1, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexAttribBinding(1, 1);
  glEnableVertexAttribArray(1);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(index_count_) * 4, indices, GL_STATIC_DRAW);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, colours_.get());
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertex_count) * 12, nullptr, GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void GpuMesh::upload_colours(const float* rgb) {
  glBindBuffer(GL_ARRAY_BUFFER, colours_.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(vertex_count_) * 12, rgb);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void GpuMesh::upload_positions(const float* positions) {
  glBindBuffer(GL_ARRAY_BUFFER, positions_.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(vertex_count_) * 12, positions);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void GpuMesh::draw(GLuint colour_buffer) const {
  glBindVertexArray(array_.get());
  glBindVertexBuffer(1, colour_buffer, 0, 12);
  glDrawElements(GL_TRIANGLES, GLsizei(index_count_), GL_UNSIGNED_INT, nullptr);
  glBindVertexBuffer(1, 0, 0, 12);
  glBindVertexArray(0);
}

SceneRenderer::SceneRenderer()
    : mesh_program_(link_program("mesh", kMeshVertex, kMeshFragment)),
      background_program_(link_program("background", kFullscreenVertex, kBackgroundFragment)),
      tone_program_(link_program("tone map", kFullscreenVertex, kToneFragment)),
      empty_array_(make_vertex_array()) {}

void SceneRenderer::resize(int width, int height, int supersample) {
  if (width == width_ && height == height_ && supersample == supersample_ && hdr_fbo_.get()) return;
  width_ = width, height_ = height, supersample_ = supersample;
  const int w = width * supersample, h = height * supersample;
  hdr_colour_ = make_texture();
  glBindTexture(GL_TEXTURE_2D, hdr_colour_.get());
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, w, h);
  hdr_depth_ = make_texture();
  glBindTexture(GL_TEXTURE_2D, hdr_depth_.get());
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, w, h);
  display_colour_ = make_texture();
  glBindTexture(GL_TEXTURE_2D, display_colour_.get());
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, width, height);
  glBindTexture(GL_TEXTURE_2D, 0);
  hdr_fbo_ = make_framebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, hdr_fbo_.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, hdr_colour_.get(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, hdr_depth_.get(), 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("the HDR framebuffer is incomplete");
  display_fbo_ = make_framebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, display_fbo_.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, display_colour_.get(),
                         0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("the display framebuffer is incomplete");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void SceneRenderer::render(int width, int height, int supersample, const std::vector<View>& views,
                           const OrbitCamera& camera, const Background& background) {
  resize(width, height, supersample);
  glBindFramebuffer(GL_FRAMEBUFFER, hdr_fbo_.get());
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glViewport(0, 0, width * supersample, height * supersample);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  for (const View& view : views) draw_view(view, camera, background);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void SceneRenderer::draw_view(const View& view, const OrbitCamera& camera,
                              const Background& background) {
  const int w = width_ * supersample_, h = height_ * supersample_;
  const PixelRect port = pixels(view.viewport, w, h), clip = pixels(view.clip, w, h);
  const float aspect = float(port.width) / float(port.height);
  glViewport(port.x, port.y, port.width, port.height);
  glEnable(GL_SCISSOR_TEST);
  glScissor(clip.x, clip.y, clip.width, clip.height);

  const prt::io::Camera pinhole = camera.camera(aspect);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glUseProgram(background_program_.get());
  glUniform1i(uniform(background_program_, "backdrop"), view.display_colours ? 1 : 0);
  glUniformMatrix3fv(uniform(background_program_, "rotation"), 1, GL_FALSE,
                     &background.rotation[0][0]);
  glUniform3fv(uniform(background_program_, "forward"), 1, &pinhole.forward[0]);
  glUniform3fv(uniform(background_program_, "right"), 1, &pinhole.right[0]);
  glUniform3fv(uniform(background_program_, "up"), 1, &pinhole.up[0]);
  glUniform1f(uniform(background_program_, "tan_half"),
              std::tan(glm::radians(OrbitCamera::kFovDegrees) * 0.5f));
  glUniform1f(uniform(background_program_, "aspect"), aspect);
  glUniform4f(uniform(background_program_, "viewport"), float(port.x), float(port.y),
              float(port.width), float(port.height));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, background.latlong_texture);
  glUniform1i(uniform(background_program_, "environment"), 0);
  glBindVertexArray(empty_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);

  if (!view.mesh) return;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glUseProgram(mesh_program_.get());
  const glm::mat4 view_projection = camera.view_projection(aspect);
  glUniformMatrix4fv(uniform(mesh_program_, "view_projection"), 1, GL_FALSE,
                     &view_projection[0][0]);
  glUniform1f(uniform(mesh_program_, "tag"), view.display_colours ? kTagDisplay : kTagSurface);
  view.mesh->draw(view.colour_buffer);
  glUseProgram(0);
}

void SceneRenderer::tone_map(const RenderSettings& settings) {
  glBindFramebuffer(GL_FRAMEBUFFER, display_fbo_.get());
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glUseProgram(tone_program_.get());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, hdr_colour_.get());
  glUniform1i(uniform(tone_program_, "hdr"), 0);
  glUniform1i(uniform(tone_program_, "supersample"), supersample_);
  glUniform1f(uniform(tone_program_, "exposure_scale"), std::exp2(settings.exposure_ev));
  glUniform1i(uniform(tone_program_, "filmic"), settings.tone_map == ToneMap::Filmic ? 1 : 0);
  glBindVertexArray(empty_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

prt::io::LinearImage SceneRenderer::read_hdr() const {
  const int w = width_ * supersample_, h = height_ * supersample_;
  std::vector<float> rgba(std::size_t(w) * h * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, hdr_fbo_.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  prt::io::LinearImage image;
  image.width = w, image.height = h;
  image.pixels.resize(std::size_t(w) * h);
  image.coverage.resize(image.pixels.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float* p = &rgba[(std::size_t(h - 1 - y) * w + x) * 4];
      const std::size_t i = std::size_t(y) * w + x;
      image.pixels[i] = {p[0], p[1], p[2]};
      image.coverage[i] = p[3] == kTagSurface ? 1.0f : 0.0f;
    }
  return image;
}

std::vector<std::uint8_t> SceneRenderer::read_display(int* width, int* height) const {
  std::vector<std::uint8_t> rgba(std::size_t(width_) * height_ * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, display_fbo_.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  std::vector<std::uint8_t> rgb(std::size_t(width_) * height_ * 3);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      std::memcpy(&rgb[(std::size_t(y) * width_ + x) * 3],
                  &rgba[(std::size_t(height_ - 1 - y) * width_ + x) * 4], 3);
  *width = width_, *height = height_;
  return rgb;
}

}  // namespace prt::sample
