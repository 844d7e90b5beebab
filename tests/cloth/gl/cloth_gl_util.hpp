// SPDX-License-Identifier: MIT
// Shared by the `cloth` GL tests and benchmark: assets of the preset fabrics over synthetic tables
// (smooth random factors on small grids, written by the baker's encoder), lights of random lobes,
// G-buffers of random valid samples, and the GL calls that upload a G-buffer, draw into a float
// framebuffer and read it back (entry points from the headless context's loader).
#pragma once

#include <gtest/gtest.h>

#include <GL/glcorearb.h>

#include <prt/baker/cloth/cloth_blob.hpp>
#include <prt/baker/cloth/fabrics.hpp>
#include <prt/prt.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "headless_gl.h"
#include "support/limited_context.hpp"
#include "support/mesh_blob.hpp"

namespace prt_test {

constexpr double kClothPi = 3.14159265358979323846;

// ---- assets -------------------------------------------------------------------------------

// A smooth random function on [0, 1]^3: a constant and a few low-frequency cosines.
struct SmoothField {
  double constant = 0;
  struct Wave {
    double amplitude, k[3], phase;
  };
  std::vector<Wave> waves;
  double operator()(double x, double y, double z) const {
    double v = constant;
    for (const Wave& w : waves)
      v += w.amplitude * std::cos(w.k[0] * x + w.k[1] * y + w.k[2] * z + w.phase);
    return v;
  }
};

inline SmoothField smooth_field(std::mt19937& rng, double constant, double amplitude) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  SmoothField f;
  f.constant = constant;
  for (int i = 0; i < 3; ++i)
    f.waves.push_back({amplitude * unit(rng),
                       {6.0 * unit(rng) - 3.0, 6.0 * unit(rng) - 3.0, 6.0 * unit(rng) - 3.0},
                       2.0 * kClothPi * unit(rng)});
  return f;
}

// A factorisation of rank `rank` whose product is mostly in (0, 1) (a weight), sometimes a little
// outside it (the lookup clamps): component 0 carries the mean, the others small smooth ripples.
inline prt::bake::ClothFactor smooth_factor(const prt::bake::ClothGrid& g, uint32_t rank,
                                            std::mt19937& rng) {
  prt::bake::ClothFactor f;
  f.rank = rank;
  f.u.resize(g.rows() * rank);
  f.v.resize(g.columns() * rank);
  for (uint32_t r = 0; r < rank; ++r) {
    const SmoothField u = smooth_field(rng, r == 0 ? 0.75 : 0.0, r == 0 ? 0.25 : 0.35);
    const SmoothField v = smooth_field(rng, r == 0 ? 0.75 : 0.0, r == 0 ? 0.2 : 0.35);
    for (uint32_t l = 0; l < g.lambda_levels; ++l)
      for (uint32_t j = 0; j < g.xi_size; ++j)
        for (uint32_t i = 0; i < g.xi_size; ++i) {
          const size_t row = (size_t(l) * g.xi_size + j) * g.xi_size + i;
          f.u[row * rank + r] =
              float(u(double(i) / (g.xi_size - 1), double(j) / (g.xi_size - 1),
                      g.lambda_levels > 1 ? double(l) / (g.lambda_levels - 1) : 0));
        }
    for (uint32_t a = 0; a < g.view_theta; ++a)
      for (uint32_t b = 0; b < g.view_phi; ++b) {
        const size_t column = size_t(a) * g.view_phi + b;
        f.v[column * rank + r] =
            float(v(double(a) / (g.view_theta - 1), double(b) / (g.view_phi - 1), 0.5));
      }
  }
  return f;
}

// A fabric to put in a section: its name, default live parameters and weave.
struct FabricSpec {
  std::string name;
  prt_cloth_params params{};
  prt_cloth_weave weave{};
};

inline FabricSpec preset(const std::string& name) {
  const prt::bake::ClothPreset& p = prt::bake::cloth_fabric(name);
  return {p.name, p.params, p.weave};
}

inline std::vector<FabricSpec> presets(const std::vector<std::string>& names) {
  std::vector<FabricSpec> out;
  for (const std::string& name : names) out.push_back(preset(name));
  return out;
}

// Velvet's parameters on fibres at or near the vertical, where the front of a fibre is a whole
// half of its azimuths or none (tau = +-90 degrees) or closes over a sliver of elevations.
inline FabricSpec vertical_fabric() {
  FabricSpec f = preset("velvet");
  f.name = "vertical";
  const float degrees[2][2] = {{90.0f, -90.0f}, {89.0f, -75.0f}};
  for (int j = 0; j < 2; ++j) {
    f.weave.tangent_count[j] = 2;
    for (int k = 0; k < 2; ++k) {
      f.weave.offsets[j][k] = float(degrees[j][k] * kClothPi / 180.0);
      f.weave.multiplicity[j][k] = uint32_t(1 + k);
    }
  }
  return f;
}

// A section of the fabrics, each tangent reading a table of its own |offset| (a negative offset
// reads it mirrored), every table of smooth random factors with ranks from `ranks` in turn.
inline prt::bake::ClothSection cloth_section(const std::vector<FabricSpec>& fabrics,
                                             const prt::bake::ClothGrid& grid,
                                             const std::vector<uint32_t>& ranks, uint32_t seed) {
  std::mt19937 rng(seed);
  prt::bake::ClothSection s;
  s.grid = grid;
  std::vector<float> table_offsets;
  for (const FabricSpec& spec : fabrics) {
    prt::bake::ClothFabric fabric;
    fabric.name = spec.name;
    fabric.params = spec.params;
    for (int j = 0; j < 2; ++j)
      for (uint32_t k = 0; k < spec.weave.tangent_count[j]; ++k) {
        const float tau = spec.weave.offsets[j][k];
        uint32_t table = 0;
        while (table < table_offsets.size() && table_offsets[table] != std::fabs(tau)) ++table;
        if (table == table_offsets.size()) table_offsets.push_back(std::fabs(tau));
        fabric.threads[j].push_back({tau, spec.weave.multiplicity[j][k], table, tau < 0.0f});
      }
    s.fabrics.push_back(fabric);
  }
  for (size_t q = 0; q < table_offsets.size(); ++q) {
    prt::bake::ClothTable table;
    table.full = smooth_factor(grid, ranks[(2 * q) % ranks.size()], rng);
    table.cone = smooth_factor(grid, ranks[(2 * q + 1) % ranks.size()], rng);
    s.tables.push_back(table);
  }
  return s;
}

// Small grids over the whole sharpness range.
inline prt::bake::ClothGrid small_grid() {
  prt::bake::ClothGrid g;
  g.xi_size = 7;
  g.lambda_levels = 4;
  g.lambda_min = PRT_CLOTH_MIN_SHARPNESS;
  g.lambda_max = PRT_CLOTH_MAX_SHARPNESS;
  g.view_theta = 5;
  g.view_phi = 6;
  return g;
}

// A cloth asset loaded in its own context.
struct ClothAsset {
  prt::ContextPtr context;
  std::unique_ptr<LoadedAsset> loaded;
  ClothAsset(const prt::bake::ClothSection& section, int bits, prt_backend limit = PRT_BACKEND_AUTO,
             const prt_allocator* allocator = nullptr)
      : context(limited_context(limit, PRT_SIMD_ISA_AUTO, allocator)) {
    loaded = std::make_unique<LoadedAsset>(context.get(),
                                           prt::bake::write_cloth_blob(section, bits, nullptr, ""));
    EXPECT_EQ(loaded->result, PRT_OK) << message();
  }
  const prt_asset* asset() const { return loaded->asset; }
  std::string message() const { return prt_context_last_message(context.get()); }
};

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

}  // namespace prt_test
