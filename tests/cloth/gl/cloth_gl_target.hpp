// SPDX-License-Identifier: MIT
// What the `cloth` GL tests and the conformance cases share without the baker: lights of random
// lobes, G-buffers of random valid samples, the GL calls that upload a G-buffer, draw into a float
// framebuffer and read it back (entry points from the headless context's loader), and the scalar
// reference with its float bound (tests/cloth/gl/cloth_gl_test.cpp explains the bound).
#pragma once

#include <gtest/gtest.h>

#include <GL/glcorearb.h>

#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "headless_gl.h"

namespace prt_test {

constexpr double kClothPi = 3.14159265358979323846;

// ---- lights -------------------------------------------------------------------------------

inline void random_unit(std::mt19937& rng, float out[3]) {
  std::normal_distribution<double> gauss;
  double v[3], len;
  do {
    for (double& x : v) x = gauss(rng);
    len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  } while (len < 1e-3);
  for (int i = 0; i < 3; ++i) out[i] = float(v[i] / len);
}

// `count` lobes, sharpness log-uniform over the whole range, amplitudes in [0.2, 2] and one lobe
// of 1e-6 of that (the weak-lobe cut drops it).
inline std::vector<prt_cloth_lobe> random_lobes(uint32_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<prt_cloth_lobe> lobes(count);
  for (uint32_t k = 0; k < count; ++k) {
    prt_cloth_lobe& l = lobes[k];
    random_unit(rng, l.axis);
    l.sharpness = float(PRT_CLOTH_MIN_SHARPNESS *
                        std::pow(PRT_CLOTH_MAX_SHARPNESS / PRT_CLOTH_MIN_SHARPNESS, unit(rng)));
    for (float& c : l.rgb) c = float((0.2 + 1.8 * unit(rng)) * (k == 1 ? 1e-6 : 1.0));
  }
  return lobes;
}

inline prt_cloth_light light_of(const std::vector<prt_cloth_lobe>& lobes) {
  prt_cloth_light light{};
  light.struct_size = sizeof light;
  light.lobe_count = uint32_t(lobes.size());
  light.lobes = lobes.data();
  return light;
}

// ---- G-buffers ----------------------------------------------------------------------------

// Samples as the CPU backend takes them (count x 3 each) and as texels (count x 4, w = 0).
struct GBufferSamples {
  uint32_t width = 0, height = 0;
  std::vector<float> normals, warps, views;
  std::vector<unsigned char> cloth;  // 0 where the normal is (0, 0, 0): not cloth
  uint32_t count() const { return width * height; }
  prt_cloth_pixels pixels() const {
    prt_cloth_pixels p{};
    p.struct_size = sizeof p;
    p.normals = normals.data();
    p.warps = warps.data();
    p.views = views.data();
    return p;
  }
  static std::vector<float> texels(const std::vector<float>& xyz) {
    std::vector<float> out(xyz.size() / 3 * 4, 0.0f);
    for (size_t i = 0; i < xyz.size() / 3; ++i) std::memcpy(&out[4 * i], &xyz[3 * i], 12);
    return out;
  }
};

inline double dot3(const float a[3], const float b[3]) {
  return double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
}

// Random valid samples: unit normals, unit warps at least 15 degrees from the normal, unit views
// above the horizon by at least `min_cos`; and, at random, a share of pixels that are not cloth
// (normal 0), views below the surface and warps along the normal (both shade to 0).
inline GBufferSamples random_gbuffer(uint32_t width, uint32_t height, uint32_t seed,
                                     double min_cos = 0.02) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  GBufferSamples g;
  g.width = width, g.height = height;
  const size_t n = size_t(width) * height;
  g.normals.assign(3 * n, 0.0f), g.warps.assign(3 * n, 0.0f), g.views.assign(3 * n, 0.0f);
  g.cloth.assign(n, 1);
  for (size_t i = 0; i < n; ++i) {
    float* nn = &g.normals[3 * i];
    float* w = &g.warps[3 * i];
    float* v = &g.views[3 * i];
    const double pick = unit(rng);
    random_unit(rng, nn);
    do random_unit(rng, w);
    while (std::fabs(dot3(w, nn)) > std::cos(15.0 * kClothPi / 180.0));
    do random_unit(rng, v);
    while (dot3(v, nn) < min_cos);
    if (pick < 0.1) {
      nn[0] = nn[1] = nn[2] = 0.0f, g.cloth[i] = 0;
    } else if (pick < 0.13) {
      for (int c = 0; c < 3; ++c) v[c] = -v[c];  // below the surface
    } else if (pick < 0.15) {
      std::memcpy(w, nn, 12);  // warp along the normal
    }
  }
  return g;
}

// The views of g's cloth samples above the surface tilted to grazing: cos(theta_o) uniform in
// [0.001, 0.05] (87 to 89.94 degrees from the normal), each in its own azimuth.
inline void make_views_grazing(GBufferSamples& g, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> cosine(0.001, 0.05);
  for (uint32_t i = 0; i < g.count(); ++i) {
    float* n = &g.normals[3 * i];
    float* v = &g.views[3 * i];
    const double d = dot3(v, n);
    if (!g.cloth[i] || !(d > 0.0)) continue;
    double t[3], length = 0.0;
    for (int c = 0; c < 3; ++c) t[c] = v[c] - d * n[c], length += t[c] * t[c];
    length = std::sqrt(length);
    if (!(length > 1e-6)) continue;
    const double c = cosine(rng), s = std::sqrt(1.0 - c * c);
    for (int k = 0; k < 3; ++k) v[k] = float(s * t[k] / length + c * n[k]);
  }
}

// ---- GL -----------------------------------------------------------------------------------

// The GL calls the tests make, from the headless context's loader.
struct GlCalls {
// clang-format off
#define PRT_CLOTH_GL_CALLS(X) \
  X(PFNGLGENTEXTURESPROC, GenTextures) \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures) \
  X(PFNGLBINDTEXTUREPROC, BindTexture) \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D) \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri) \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers) \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers) \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer) \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D) \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus) \
  X(PFNGLVIEWPORTPROC, Viewport) \
  X(PFNGLCLEARCOLORPROC, ClearColor) \
  X(PFNGLCLEARPROC, Clear) \
  X(PFNGLREADPIXELSPROC, ReadPixels) \
  X(PFNGLFINISHPROC, Finish) \
  X(PFNGLPIXELSTOREIPROC, PixelStorei) \
  X(PFNGLGETINTEGERVPROC, GetIntegerv) \
  X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v) \
  X(PFNGLISENABLEDPROC, IsEnabled) \
  X(PFNGLENABLEPROC, Enable) \
  X(PFNGLDISABLEPROC, Disable) \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture) \
  X(PFNGLGETERRORPROC, GetError) \
  X(PFNGLGENSAMPLERSPROC, GenSamplers) \
  X(PFNGLDELETESAMPLERSPROC, DeleteSamplers) \
  X(PFNGLBINDSAMPLERPROC, BindSampler) \
  X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri) \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays) \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays) \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray) \
  X(PFNGLDEPTHFUNCPROC, DepthFunc) \
  X(PFNGLBLENDFUNCPROC, BlendFunc) \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate) \
  X(PFNGLBLENDEQUATIONSEPARATEPROC, BlendEquationSeparate) \
  X(PFNGLCULLFACEPROC, CullFace) \
  X(PFNGLSCISSORPROC, Scissor) \
  X(PFNGLGENBUFFERSPROC, GenBuffers) \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers) \
  X(PFNGLBINDBUFFERPROC, BindBuffer) \
  X(PFNGLBUFFERDATAPROC, BufferData)
// clang-format on
#define PRT_CLOTH_GL_MEMBER(type, name) type name = nullptr;
  PRT_CLOTH_GL_CALLS(PRT_CLOTH_GL_MEMBER)
#undef PRT_CLOTH_GL_MEMBER
  GlCalls() {
#define PRT_CLOTH_GL_LOAD(type, name) load(name, "gl" #name);
    PRT_CLOTH_GL_CALLS(PRT_CLOTH_GL_LOAD)
#undef PRT_CLOTH_GL_LOAD
  }

 private:
  template <typename Fn>
  static void load(Fn& fn, const char* name) {
    void* address = headless_gl_get_proc(nullptr, name);
    std::memcpy(&fn, &address, sizeof fn);
    EXPECT_NE(address, nullptr) << name;
  }
};
#undef PRT_CLOTH_GL_CALLS

// A float texture of width x height texels (RGBA32F), with `rgba` (or nothing) as its texels.
inline GLuint float_texture(const GlCalls& gl, uint32_t width, uint32_t height, const float* rgba) {
  GLuint texture = 0;
  gl.GenTextures(1, &texture);
  gl.BindTexture(GL_TEXTURE_2D, texture);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, GLsizei(width), GLsizei(height), 0, GL_RGBA, GL_FLOAT,
                rgba);
  gl.BindTexture(GL_TEXTURE_2D, 0);
  return texture;
}

// The G-buffer's three textures and a framebuffer with one RGBA32F colour attachment of
// (width + margin_x) x (height + margin_y) texels, bound for drawing and reading, cleared to
// `clear`, with the viewport at (margin_x / 2, margin_y / 2) of the G-buffer's size.
struct GlTarget {
  const GlCalls& gl;
  uint32_t width, height, full_width, full_height;
  int x0, y0;
  GLuint textures[3] = {0, 0, 0}, colour = 0, framebuffer = 0;
  GlTarget(const GlCalls& calls, const GBufferSamples& g, uint32_t margin_x, uint32_t margin_y,
           const float clear[4])
      : gl(calls),
        width(g.width),
        height(g.height),
        full_width(g.width + margin_x),
        full_height(g.height + margin_y),
        x0(int(margin_x / 2)),
        y0(int(margin_y / 2)) {
    const std::vector<float>* sources[3] = {&g.normals, &g.warps, &g.views};
    for (int i = 0; i < 3; ++i)
      textures[i] = float_texture(gl, width, height, GBufferSamples::texels(*sources[i]).data());
    colour = float_texture(gl, full_width, full_height, nullptr);
    gl.GenFramebuffers(1, &framebuffer);
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour, 0);
    EXPECT_EQ(gl.CheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    gl.ClearColor(clear[0], clear[1], clear[2], clear[3]);
    gl.Clear(GL_COLOR_BUFFER_BIT);
    gl.Viewport(x0, y0, GLsizei(width), GLsizei(height));
  }
  ~GlTarget() {
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.DeleteFramebuffers(1, &framebuffer);
    gl.DeleteTextures(3, textures);
    gl.DeleteTextures(1, &colour);
  }
  GlTarget(const GlTarget&) = delete;
  GlTarget& operator=(const GlTarget&) = delete;
  prt_gl_cloth_gbuffer gbuffer() const {
    prt_gl_cloth_gbuffer b{};
    b.struct_size = sizeof b;
    b.normal_texture = textures[0];
    b.warp_texture = textures[1];
    b.view_texture = textures[2];
    return b;
  }
  // The whole attachment, RGBA per texel, rows bottom-up.
  std::vector<float> read() const {
    std::vector<float> rgba(4 * size_t(full_width) * full_height, 0.0f);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, GLsizei(full_width), GLsizei(full_height), GL_RGBA, GL_FLOAT, rgba.data());
    return rgba;
  }
  // The attachment's texel of G-buffer sample i (row-major from the bottom row).
  size_t texel_of(size_t i) const {
    return (size_t(y0) + i / width) * full_width + size_t(x0) + i % width;
  }
};

struct GlClothDeleter {
  void operator()(prt_gl_cloth_shader* shader) const noexcept { prt_gl_cloth_destroy(shader); }
};
using GlClothShaderPtr = std::unique_ptr<prt_gl_cloth_shader, GlClothDeleter>;

// ---- the scalar reference and its bound ---------------------------------------------------

constexpr double kU = 0x1p-24;
constexpr double kPerturbation = 4 * kU;  // of the inputs, for D
constexpr double kEvaluation = 32 * kU;   // of S

inline prt_cloth_settings settings_of(uint32_t flags, uint32_t segments = 0, uint32_t nodes = 0,
                                      float weak = 0.0f) {
  prt_cloth_settings s{};
  s.struct_size = sizeof s;
  s.flags = flags;
  s.theta_segments = segments;
  s.phi_nodes = nodes;
  s.weak_lobe = weak;
  return s;
}

// ---- the reference and its bound ------------------------------------------------------------

struct Reference {
  std::vector<float> value;       // 3 per sample
  std::vector<double> tolerance;  // 3 per sample
  std::vector<double> scale;      // S per sample
};

inline std::vector<float> cpu_shade(const prt_asset* a, uint32_t fabric,
                                    const prt_cloth_params* params, const prt_cloth_light& light,
                                    const prt_cloth_settings* settings, const GBufferSamples& g) {
  std::vector<float> rgb(3 * size_t(g.count()));
  const prt_cloth_pixels pixels = g.pixels();
  EXPECT_EQ(prt_cloth_shade(a, PRT_BACKEND_CPU, fabric, params, &light, settings, &pixels, 0,
                            g.count(), rgb.data()),
            PRT_OK);
  return rgb;
}

// Every nonzero component moved by `size` times a standard normal number.
inline void perturb(std::vector<float>& values, double size, std::mt19937& rng) {
  std::normal_distribution<double> gauss;
  for (float& x : values)
    if (x != 0.0f) x = float(x + size * gauss(rng));
}

inline Reference reference(const prt_asset* a, uint32_t fabric, const prt_cloth_params* params,
                           const std::vector<prt_cloth_lobe>& lobes,
                           const prt_cloth_settings* settings, const GBufferSamples& g) {
  Reference r;
  r.value = cpu_shade(a, fabric, params, light_of(lobes), settings, g);
  std::vector<double> moved(3 * size_t(g.count()), 0.0);
  std::mt19937 rng(fabric + 17);
  for (int trial = 0; trial < 4; ++trial) {
    GBufferSamples p = g;
    perturb(p.normals, kPerturbation, rng);
    perturb(p.warps, kPerturbation, rng);
    perturb(p.views, kPerturbation, rng);
    std::vector<prt_cloth_lobe> l = lobes;
    for (prt_cloth_lobe& lobe : l) {
      std::vector<float> axis(lobe.axis, lobe.axis + 3);
      perturb(axis, kPerturbation, rng);
      std::copy(axis.begin(), axis.end(), lobe.axis);
    }
    const std::vector<float> v = cpu_shade(a, fabric, params, light_of(l), settings, p);
    for (size_t i = 0; i < v.size(); ++i)
      moved[i] = std::max(moved[i], std::fabs(double(v[i]) - r.value[i]));
  }
  r.scale.resize(g.count());
  r.tolerance.resize(3 * size_t(g.count()));
  for (uint32_t i = 0; i < g.count(); ++i) {
    double s = 0, d = 0;
    for (int c = 0; c < 3; ++c) {
      s = std::max(s, std::fabs(double(r.value[3 * i + c])));
      d = std::max(d, moved[3 * i + c]);
    }
    r.scale[i] = s;
    for (int c = 0; c < 3; ++c) r.tolerance[3 * i + c] = 2 * d + kEvaluation * s;
  }
  return r;
}

}  // namespace prt_test
