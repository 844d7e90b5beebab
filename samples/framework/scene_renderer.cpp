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

// The G-buffer of a per-pixel view: world normal (turned towards the eye on back faces), the
// tangent made orthogonal to it, the direction to the eye; (0, 0, 0) is left where nothing is
// drawn, and a vertex normal of length 0 draws nothing.
const char* const kGBufferVertex = R"(#version 430 core
layout(location = 0) in vec3 position;
layout(location = 2) in vec3 normal;
layout(location = 3) in vec3 tangent;
uniform mat4 view_projection;
out vec3 v_position, v_normal, v_tangent;
void main() {
  v_position = position;
  v_normal = normal;
  v_tangent = tangent;
  gl_Position = view_projection * vec4(position, 1.0);
}
)";

const char* const kGBufferFragment = R"(#version 430 core
in vec3 v_position, v_normal, v_tangent;
uniform vec3 eye;
layout(location = 0) out vec4 g_normal;
layout(location = 1) out vec4 g_tangent;
layout(location = 2) out vec4 g_view;
void main() {
  float length_n = length(v_normal);
  if (!(length_n > 0.0)) discard;
  vec3 n = v_normal / length_n;
  if (!gl_FrontFacing) n = -n;
  vec3 t = v_tangent - dot(v_tangent, n) * n;
  float length_t = length(t);
  t = length_t > 1e-6 * length(v_tangent) ? t / length_t : vec3(0.0);
  g_normal = vec4(n, 0.0);
  g_tangent = vec4(t, 0.0);
  g_view = vec4(normalize(eye - v_position), 0.0);
}
)";

// A per-pixel view's radiance (or only its depth, with colour writes off) put into the HDR
// target where its G-buffer has a normal and the radiance is a number: texel for pixel, the
// depth the G-buffer pass found.
const char* const kCompositeFragment = R"(#version 430 core
uniform sampler2D normals;
uniform sampler2D radiance;
uniform sampler2D depth;
uniform float tag;
out vec4 frag;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 c = texelFetch(radiance, p, 0).rgb;
  if (texelFetch(normals, p, 0).xyz == vec3(0.0) || isnan(c.r)) discard;
  gl_FragDepth = texelFetch(depth, p, 0).r;
  frag = vec4(c, tag);
}
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

GpuMesh::GpuMesh(const float* positions, const float* normals, const float* tangents,
                 std::uint32_t vertex_count, const std::uint32_t* indices,
                 std::uint32_t triangle_count)
    : GpuMesh(positions, vertex_count, indices, triangle_count) {
  normals_ = make_buffer();
  tangents_ = make_buffer();
  glBindVertexArray(array_.get());
  const GlBuffer* buffers[2] = {&normals_, &tangents_};
  const float* data[2] = {normals, tangents};
  for (GLuint k = 0; k < 2; ++k) {
    glBindBuffer(GL_ARRAY_BUFFER, buffers[k]->get());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertex_count) * 12, data[k], GL_STATIC_DRAW);
    glVertexAttribFormat(2 + k, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexAttribBinding(2 + k, 2 + k);
    glBindVertexBuffer(2 + k, buffers[k]->get(), 0, 12);
    glEnableVertexAttribArray(2 + k);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
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

void GpuMesh::draw_frames() const {
  glBindVertexArray(array_.get());
  glDrawElements(GL_TRIANGLES, GLsizei(index_count_), GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

SceneRenderer::SceneRenderer()
    : mesh_program_(link_program("mesh", kMeshVertex, kMeshFragment)),
      background_program_(link_program("background", kFullscreenVertex, kBackgroundFragment)),
      tone_program_(link_program("tone map", kFullscreenVertex, kToneFragment)),
      gbuffer_program_(link_program("G-buffer", kGBufferVertex, kGBufferFragment)),
      composite_program_(link_program("composite", kFullscreenVertex, kCompositeFragment)),
      empty_array_(make_vertex_array()) {}

void SceneRenderer::resize(int width, int height, int supersample) {
  if (width == width_ && height == height_ && supersample == supersample_ && hdr_fbo_.get()) return;
  width_ = width, height_ = height, supersample_ = supersample;
  const int w = width * supersample, h = height * supersample;
  gbuffer_fbo_.reset();  // made again at the new size by the next per-pixel view
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

void SceneRenderer::make_gbuffer() {
  if (gbuffer_fbo_.get()) return;
  const int w = width_ * supersample_, h = height_ * supersample_;
  const GLenum formats[4] = {GL_RGBA32F, GL_RGBA32F, GL_RGBA32F, GL_DEPTH_COMPONENT32F};
  for (int i = 0; i < 4; ++i) {
    gbuffer_[i] = make_texture();
    glBindTexture(GL_TEXTURE_2D, gbuffer_[i].get());
    glTexStorage2D(GL_TEXTURE_2D, 1, formats[i], w, h);
  }
  radiance_ = make_texture();
  glBindTexture(GL_TEXTURE_2D, radiance_.get());
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, w, h);
  glBindTexture(GL_TEXTURE_2D, 0);
  gbuffer_fbo_ = make_framebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer_fbo_.get());
  for (int i = 0; i < 3; ++i)
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D,
                           gbuffer_[i].get(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, gbuffer_[3].get(), 0);
  const GLenum draw[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  glDrawBuffers(3, draw);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("the G-buffer framebuffer is incomplete");
  radiance_fbo_ = make_framebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, radiance_fbo_.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, radiance_.get(), 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("the radiance framebuffer is incomplete");
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
  if (view.pixel_shader) {
    ViewPixels at{{port.x, port.y, port.width, port.height}, {}};
    // The clip within the viewport (the G-buffer holds nothing else for this view).
    const GLint x0 = std::max(clip.x, port.x), y0 = std::max(clip.y, port.y);
    const GLint x1 = std::min(clip.x + clip.width, port.x + port.width);
    const GLint y1 = std::min(clip.y + clip.height, port.y + port.height);
    at.clip[0] = x0, at.clip[1] = y0, at.clip[2] = std::max(x1 - x0, 0);
    at.clip[3] = std::max(y1 - y0, 0);
    draw_pixels(view, camera, at);
    return;
  }
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

// A per-pixel view: its mesh into the G-buffer, then the app's GL pass into the HDR target (and
// the G-buffer's depth after it), or its CPU shading of the samples read back (or its GL pass
// into the radiance target, read back) uploaded and put in with the depth.
void SceneRenderer::draw_pixels(const View& view, const OrbitCamera& camera, const ViewPixels& at) {
  if (!view.mesh->has_frames())
    throw std::runtime_error("a per-pixel view needs a mesh made with normals and tangents");
  make_gbuffer();
  fill_gbuffer(*view.mesh, camera, at);
  PixelShader& shader = *view.pixel_shader;
  const float tag = view.display_colours ? kTagDisplay : kTagSurface;
  const int w = width_ * supersample_, h = height_ * supersample_;
  const GlGBuffer gbuffer{gbuffer_[0].get(), gbuffer_[1].get(), gbuffer_[2].get(), w, h};
  glDisable(GL_DEPTH_TEST);
  glViewport(0, 0, w, h);
  if (shader.uses_gl() && !shader.reads_gl_radiance()) {
    glBindFramebuffer(GL_FRAMEBUFFER, hdr_fbo_.get());
    glScissor(at.clip[0], at.clip[1], at.clip[2], at.clip[3]);
    shader.shade_gl(gbuffer);
    composite(at, tag, false);
    return;
  }
  const PixelSamples samples = read_samples(at);
  std::vector<float> rgb(3 * samples.size(), 0.0f);
  if (shader.uses_gl()) {
    glBindFramebuffer(GL_FRAMEBUFFER, radiance_fbo_.get());
    glScissor(at.port[0], at.port[1], at.port[2], at.port[3]);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    shader.shade_gl(gbuffer);
    rgb = read_radiance(samples, at);
    shader.gl_radiance(samples, rgb);
  } else {
    shader.shade(samples, rgb);
    upload_radiance(samples, rgb, at);
  }
  composite(at, tag, true);
}

void SceneRenderer::fill_gbuffer(const GpuMesh& mesh, const OrbitCamera& camera,
                                 const ViewPixels& at) {
  const float aspect = float(at.port[2]) / float(at.port[3]);
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer_fbo_.get());
  glEnable(GL_SCISSOR_TEST);
  glScissor(at.port[0], at.port[1], at.port[2], at.port[3]);
  glDepthMask(GL_TRUE);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, far = 1.0f;
  for (int i = 0; i < 3; ++i) glClearBufferfv(GL_COLOR, i, zero);
  glClearBufferfv(GL_DEPTH, 0, &far);
  // Inside the clip, what the earlier views drew hides the mesh; outside, it is drawn alone.
  if (at.clip[2] > 0 && at.clip[3] > 0) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, hdr_fbo_.get());
    glScissor(at.clip[0], at.clip[1], at.clip[2], at.clip[3]);
    const GLint x1 = at.clip[0] + at.clip[2], y1 = at.clip[1] + at.clip[3];
    glBlitFramebuffer(at.clip[0], at.clip[1], x1, y1, at.clip[0], at.clip[1], x1, y1,
                      GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, gbuffer_fbo_.get());
    glScissor(at.port[0], at.port[1], at.port[2], at.port[3]);
  }
  glViewport(at.port[0], at.port[1], at.port[2], at.port[3]);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(gbuffer_program_.get());
  const glm::mat4 view_projection = camera.view_projection(aspect);
  const prt::io::Camera pinhole = camera.camera(aspect);
  glUniformMatrix4fv(uniform(gbuffer_program_, "view_projection"), 1, GL_FALSE,
                     &view_projection[0][0]);
  glUniform3fv(uniform(gbuffer_program_, "eye"), 1, &pinhole.eye[0]);
  mesh.draw_frames();
  glUseProgram(0);
}

PixelSamples SceneRenderer::read_samples(const ViewPixels& at) const {
  const int w = at.port[2], h = at.port[3];
  PixelSamples samples;
  samples.width = w, samples.height = h;
  const int top = at.port[1] + h;  // GL rows run up, the samples' rows down
  samples.clip = {at.clip[0] - at.port[0], top - (at.clip[1] + at.clip[3]),
                  at.clip[0] - at.port[0] + at.clip[2], top - at.clip[1]};
  std::vector<float> texels[3];
  glBindFramebuffer(GL_READ_FRAMEBUFFER, gbuffer_fbo_.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  for (int i = 0; i < 3; ++i) {
    texels[i].resize(std::size_t(w) * h * 4);
    glReadBuffer(GL_COLOR_ATTACHMENT0 + i);
    glReadPixels(at.port[0], at.port[1], w, h, GL_RGBA, GL_FLOAT, texels[i].data());
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  std::vector<float>* out[3] = {&samples.normals, &samples.tangents, &samples.views};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t at_gl = (std::size_t(h - 1 - y) * w + x) * 4;
      const float* n = &texels[0][at_gl];
      if (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f) continue;
      samples.pixel.push_back(std::uint32_t(y) * std::uint32_t(w) + std::uint32_t(x));
      for (int i = 0; i < 3; ++i)
        out[i]->insert(out[i]->end(), &texels[i][at_gl], &texels[i][at_gl] + 3);
    }
  return samples;
}

void SceneRenderer::upload_radiance(const PixelSamples& samples, const std::vector<float>& rgb,
                                    const ViewPixels& at) {
  const int w = at.port[2], h = at.port[3];
  std::vector<float> texels(std::size_t(w) * h * 4, 0.0f);
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const std::uint32_t x = samples.pixel[s] % std::uint32_t(w),
                        y = samples.pixel[s] / std::uint32_t(w);
    std::memcpy(&texels[(std::size_t(h - 1 - y) * w + x) * 4], &rgb[3 * s], 3 * sizeof(float));
  }
  glBindTexture(GL_TEXTURE_2D, radiance_.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexSubImage2D(GL_TEXTURE_2D, 0, at.port[0], at.port[1], w, h, GL_RGBA, GL_FLOAT, texels.data());
  glBindTexture(GL_TEXTURE_2D, 0);
}

std::vector<float> SceneRenderer::read_radiance(const PixelSamples& samples,
                                                const ViewPixels& at) const {
  const int w = at.port[2], h = at.port[3];
  std::vector<float> texels(std::size_t(w) * h * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, radiance_fbo_.get());
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(at.port[0], at.port[1], w, h, GL_RGBA, GL_FLOAT, texels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  std::vector<float> rgb(3 * samples.size());
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const std::uint32_t x = samples.pixel[s] % std::uint32_t(w),
                        y = samples.pixel[s] / std::uint32_t(w);
    std::memcpy(&rgb[3 * s], &texels[(std::size_t(h - 1 - y) * w + x) * 4], 3 * sizeof(float));
  }
  return rgb;
}

void SceneRenderer::composite(const ViewPixels& at, float tag, bool colour) {
  const int w = width_ * supersample_, h = height_ * supersample_;
  glBindFramebuffer(GL_FRAMEBUFFER, hdr_fbo_.get());
  glViewport(0, 0, w, h);
  glEnable(GL_SCISSOR_TEST);
  glScissor(at.clip[0], at.clip[1], at.clip[2], at.clip[3]);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glDepthMask(GL_TRUE);
  if (!colour) glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glUseProgram(composite_program_.get());
  const GLuint textures[3] = {gbuffer_[0].get(), radiance_.get(), gbuffer_[3].get()};
  const char* names[3] = {"normals", "radiance", "depth"};
  for (int i = 0; i < 3; ++i) {
    glActiveTexture(GL_TEXTURE0 + i);
    glBindTexture(GL_TEXTURE_2D, textures[i]);
    glUniform1i(uniform(composite_program_, names[i]), i);
  }
  glUniform1f(uniform(composite_program_, "tag"), tag);
  glBindVertexArray(empty_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  for (int i = 2; i >= 0; --i) {
    glActiveTexture(GL_TEXTURE0 + i);
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glUseProgram(0);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_LESS);
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
