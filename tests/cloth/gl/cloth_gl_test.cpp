// SPDX-License-Identifier: MIT
// The GL backend of `cloth` (prt_cloth_asset.h) on a headless EGL context: a G-buffer of random
// valid samples (cloth_gl_util.hpp) shaded into a float framebuffer against prt_cloth_shade on
// the scalar reference, for every preset fabric and one of vertical fibres over synthetic
// tables, 8- and 16-bit, live parameters, every setting, up to the largest light; pixels that
// are not cloth and texels outside the viewport untouched; the GL state a call changes and the
// state it leaves alone; every refusal of create and shade.
//
// The bound. The shader follows the reference step by step in float, so a pixel's error has two
// parts. (1) Its directions and angles: the frame, each fibre's angles and the canonical
// directions are dot products and atan2 of unit vectors, each within about 4 u (u = 2^-24) of
// their values in double; what that moves is the reference's own sensitivity to its inputs,
// measured here as D, the largest change of the reference over four random perturbations of the
// normals, warps, views and lobe axes by 4 u, and taken twice (random perturbations need not hit
// the worst direction). D also covers the pixels near one of the method's switches (a lobe
// culled or not, a window split or not, wide or sharp phi nodes), where float may go the other
// way. (2) The evaluation at given angles: a theta node's value is a product of about 30 rounded
// factors (sin, cos, atan2 and acos within about an ulp, exp within 2 ulp and its argument's
// rounding, the Fresnel term, the phi weights), and the panels, parts, lobes and tangents add
// terms that are positive but for the quadrature's small undershoots (in one draw or, for many
// lobes, in several added by blending), which keeps their sum's relative error to that of its
// terms: 32 u S, S the pixel's largest channel. So
//   |gl - reference| <= 2 D + 32 u S        per pixel and channel.
// Each case prints its worst ratio of error to bound and its worst error in units of u S.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "cloth/gl/cloth_gl_util.hpp"
#include "support/counting_allocator.hpp"
#include "support/gl_create_checks.hpp"
#include "support/gl_test_util.hpp"

namespace {

using namespace prt_test;

const float kClear[4] = {-1.0f, -2.0f, -3.0f, -4.0f};

struct Outcome {
  double worst_ratio = 0;  // largest |error| / tolerance
  double worst_units = 0;  // largest |error| / (u S)
};

// The framebuffer after a shade: every cloth pixel within the reference's bound with alpha 1,
// every other texel (not cloth, or outside the viewport) still the clear colour.
Outcome expect_matches(const Reference& r, const GBufferSamples& g, const GlTarget& target,
                       const std::vector<float>& rgba, const std::string& what) {
  SCOPED_TRACE(what);
  Outcome o;
  int failures = 0;
  std::vector<unsigned char> shaded(size_t(target.full_width) * target.full_height, 0);
  for (uint32_t i = 0; i < g.count(); ++i) {
    const size_t t = target.texel_of(i);
    const float* px = &rgba[4 * t];
    shaded[t] = g.cloth[i];
    if (!g.cloth[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double err = std::fabs(double(px[c]) - r.value[3 * i + c]);
      const double tol = r.tolerance[3 * i + c];
      o.worst_ratio = std::max(o.worst_ratio, tol > 0 ? err / tol : (err > 0 ? 1e30 : 0.0));
      if (r.scale[i] > 0) o.worst_units = std::max(o.worst_units, err / (kU * r.scale[i]));
      if (!(err <= tol) && failures++ < 8)
        ADD_FAILURE() << "sample " << i << " channel " << c << ": gl " << px[c] << ", reference "
                      << r.value[3 * i + c] << ", tolerance " << tol;
    }
    if (px[3] != 1.0f && failures++ < 8) ADD_FAILURE() << "sample " << i << " alpha " << px[3];
  }
  for (size_t t = 0; t < shaded.size(); ++t) {
    if (shaded[t]) continue;
    for (int c = 0; c < 4; ++c)
      if (rgba[4 * t + c] != kClear[c] && failures++ < 8)
        ADD_FAILURE() << "texel " << t << " (not cloth or outside the viewport) was written";
  }
  std::printf("%s: max err/tol %.3g, max err %.3g u S\n", what.c_str(), o.worst_ratio,
              o.worst_units);
  return o;
}

// ---- a shader over an asset ------------------------------------------------------------------

GlClothShaderPtr create_shader(const ClothAsset& a, headless_gl* gl) {
  prt_gl_cloth_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_cloth_create(a.context.get(), a.asset(), headless_gl_get_proc, gl, &shader),
            PRT_OK)
      << a.message();
  return GlClothShaderPtr(shader);
}

// Shades fabric `fabric` on GL and compares it with the reference.
Outcome shade_and_compare(prt_gl_cloth_shader* shader, const ClothAsset& a, uint32_t fabric,
                          const prt_cloth_params* params, const std::vector<prt_cloth_lobe>& lobes,
                          const prt_cloth_settings* settings, const GBufferSamples& g,
                          GlTarget& target, const std::string& what) {
  target.gl.ClearColor(kClear[0], kClear[1], kClear[2], kClear[3]);
  target.gl.Clear(GL_COLOR_BUFFER_BIT);
  const prt_gl_cloth_gbuffer gbuffer = target.gbuffer();
  const prt_cloth_light light = light_of(lobes);
  EXPECT_EQ(prt_gl_cloth_shade(shader, fabric, params, &light, settings, &gbuffer), PRT_OK);
  return expect_matches(reference(a.asset(), fabric, params, lobes, settings, g), g, target,
                        target.read(), what);
}

std::vector<FabricSpec> all_fabrics() {
  std::vector<FabricSpec> f = presets(prt::bake::cloth_fabric_names());
  f.push_back(vertical_fabric());
  return f;
}

// ---- shading -------------------------------------------------------------------------------

TEST(GlCloth, EveryFabricShadesLikeTheScalarReference) {
  PRT_REQUIRE_GL(gl);
  GlCalls calls;
  const std::vector<FabricSpec> fabrics = all_fabrics();
  const GBufferSamples g = random_gbuffer(37, 29, 3);
  GlTarget target(calls, g, 7, 4, kClear);  // the viewport at (3, 2) of a larger framebuffer
  const std::vector<prt_cloth_lobe> lobes = random_lobes(10, 5);
  Outcome worst;
  for (int bits : {16, 8}) {
    // Ranks from 1 to 9, the largest setting the shader's arrays.
    const ClothAsset a(cloth_section(fabrics, small_grid(), {3, 5, 1, 9, 2}, uint32_t(bits)), bits);
    GlClothShaderPtr shader = create_shader(a, gl.gl);
    ASSERT_TRUE(shader);
    for (uint32_t f = 0; f < fabrics.size(); ++f) {
      const Outcome o = shade_and_compare(shader.get(), a, f, nullptr, lobes, nullptr, g, target,
                                          fabrics[f].name + ", " + std::to_string(bits) + "-bit");
      worst.worst_ratio = std::max(worst.worst_ratio, o.worst_ratio);
      worst.worst_units = std::max(worst.worst_units, o.worst_units);
    }
  }
  std::printf("all fabrics: max err/tol %.3g, max err %.3g u S\n", worst.worst_ratio,
              worst.worst_units);
}

// Live parameters other than the fabric's own (edited without a re-bake), extremes included: no
// interface (eta 1), all or no isotropic volume, wide and narrow lobes, a thread left out.
TEST(GlCloth, LiveParametersShadeLikeTheScalarReference) {
  PRT_REQUIRE_GL(gl);
  GlCalls calls;
  const std::vector<FabricSpec> fabrics = presets({"linen_plain", "polyester_satin_charmeuse"});
  const ClothAsset a(cloth_section(fabrics, small_grid(), {4, 3}, 21), 16);
  GlClothShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const GBufferSamples g = random_gbuffer(23, 19, 22);
  GlTarget target(calls, g, 0, 0, kClear);
  const std::vector<prt_cloth_lobe> lobes = random_lobes(8, 23);
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    prt_cloth_params p = fabrics[trial % 2].params;
    for (prt_cloth_thread& t : p.threads) {
      t.eta = float(1.0 + 1.5 * unit(rng));
      for (float& c : t.albedo) c = float(unit(rng));
      t.kd = float(unit(rng));
      t.gamma_s = float((1.0 + 40.0 * unit(rng)) * kClothPi / 180.0);
      t.gamma_v = float((2.0 + 60.0 * unit(rng)) * kClothPi / 180.0);
      t.coverage = float(0.5 * unit(rng));
    }
    if (trial == 1) p.threads[0].eta = 1.0f, p.threads[1].kd = 0.0f, p.threads[0].kd = 1.0f;
    if (trial == 2) p.threads[1].coverage = 0.0f;
    ASSERT_EQ(prt_cloth_params_validate(&p), PRT_OK);
    shade_and_compare(shader.get(), a, uint32_t(trial % 2), &p, lobes, nullptr, g, target,
                      "live parameters " + std::to_string(trial));
  }
}

// Every flag and the extremes of theta_segments, phi_nodes and weak_lobe shade as the reference
// does under the same settings, and each changes the image (so that the shader does read it).
TEST(GlCloth, EverySettingShadesLikeTheScalarReference) {
  PRT_REQUIRE_GL(gl);
  GlCalls calls;
  const std::vector<FabricSpec> fabrics = presets({"polyester_satin_charmeuse"});
  const ClothAsset a(cloth_section(fabrics, small_grid(), {4, 3}, 31), 16);
  GlClothShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const GBufferSamples g = random_gbuffer(23, 17, 32);
  GlTarget target(calls, g, 2, 2, kClear);
  const std::vector<prt_cloth_lobe> lobes = random_lobes(10, 33);
  const prt_cloth_settings cases[] = {
      settings_of(0),
      settings_of(PRT_CLOTH_KEEP_HIDDEN_LOBES),
      settings_of(PRT_CLOTH_KEEP_WEAK_LOBES),
      settings_of(PRT_CLOTH_NO_CONE_TABLE),
      settings_of(PRT_CLOTH_KEEP_HIDDEN_LOBES | PRT_CLOTH_KEEP_WEAK_LOBES |
                  PRT_CLOTH_NO_CONE_TABLE),
      settings_of(0, 1, 1),
      settings_of(0, 16, 8),
      settings_of(0, 3, 5),
      settings_of(0, 0, 0, 0.2f),
  };
  const prt_gl_cloth_gbuffer gbuffer = target.gbuffer();
  const prt_cloth_light light = light_of(lobes);
  ASSERT_EQ(prt_gl_cloth_shade(shader.get(), 0, nullptr, &light, nullptr, &gbuffer), PRT_OK);
  const std::vector<float> defaults = target.read();
  for (const prt_cloth_settings& s : cases) {
    const std::string what = "flags " + std::to_string(s.flags) + ", segments " +
                             std::to_string(s.theta_segments) + ", nodes " +
                             std::to_string(s.phi_nodes) + ", weak " + std::to_string(s.weak_lobe);
    shade_and_compare(shader.get(), a, 0, nullptr, lobes, &s, g, target, what);
    const bool is_default = s.flags == 0 && s.theta_segments == 0 && s.weak_lobe == 0.0f;
    EXPECT_EQ(target.read() == defaults, is_default) << what;
  }
  // The SIMD backend's own switches (how it shares work, the same result either way) are accepted
  // and change nothing here.
  const prt_cloth_settings simd_only =
      settings_of(PRT_CLOTH_NO_FRAME_CACHE | PRT_CLOTH_TANGENT_COPIES | PRT_CLOTH_NO_LOBE_SHARING);
  ASSERT_EQ(prt_gl_cloth_shade(shader.get(), 0, nullptr, &light, &simd_only, &gbuffer), PRT_OK);
  EXPECT_EQ(target.read(), defaults);
}

// The light's extremes: no lobe (cloth shades to 0), every lobe weak but kept, and the most
// lobes a light may have (the uniform block's capacity).
TEST(GlCloth, LightsFromNoLobeToTheMostShadeLikeTheScalarReference) {
  PRT_REQUIRE_GL(gl);
  GlCalls calls;
  const std::vector<FabricSpec> fabrics = presets({"silk_shot"});
  const ClothAsset a(cloth_section(fabrics, small_grid(), {2, 3}, 41), 8);
  GlClothShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const GBufferSamples g = random_gbuffer(9, 7, 42);
  GlTarget target(calls, g, 0, 0, kClear);
  shade_and_compare(shader.get(), a, 0, nullptr, {}, nullptr, g, target, "no lobe");
  const std::vector<float> none = target.read();
  for (uint32_t i = 0; i < g.count(); ++i) {
    if (!g.cloth[i]) continue;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(none[4 * target.texel_of(i) + c], 0.0f) << i;
  }
  // So many lobes take several passes (cloth_gl.c: PASS_ITERATIONS) added by blending, with the
  // caller's blend functions put back and blending left off.
  calls.Enable(GL_BLEND);
  calls.BlendFuncSeparate(GL_SRC_ALPHA, GL_ZERO, GL_DST_ALPHA, GL_ONE_MINUS_SRC_COLOR);
  calls.BlendEquationSeparate(GL_FUNC_SUBTRACT, GL_MAX);
  const std::vector<prt_cloth_lobe> most = random_lobes(PRT_CLOTH_MAX_LOBES, 43);
  shade_and_compare(shader.get(), a, 0, nullptr, most, nullptr, g, target, "256 lobes");
  EXPECT_FALSE(calls.IsEnabled(GL_BLEND));
  const std::pair<GLenum, GLint> blend[] = {
      {GL_BLEND_SRC_RGB, GL_SRC_ALPHA},          {GL_BLEND_DST_RGB, GL_ZERO},
      {GL_BLEND_SRC_ALPHA, GL_DST_ALPHA},        {GL_BLEND_DST_ALPHA, GL_ONE_MINUS_SRC_COLOR},
      {GL_BLEND_EQUATION_RGB, GL_FUNC_SUBTRACT}, {GL_BLEND_EQUATION_ALPHA, GL_MAX}};
  for (const auto& [name, expected] : blend) {
    GLint value = -1;
    calls.GetIntegerv(name, &value);
    EXPECT_EQ(value, expected) << name;
  }
  calls.BlendFuncSeparate(GL_ONE, GL_ZERO, GL_ONE, GL_ZERO);
  calls.BlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
  const prt_cloth_settings keep = settings_of(PRT_CLOTH_KEEP_WEAK_LOBES);
  shade_and_compare(shader.get(), a, 0, nullptr, most, &keep, g, target, "256 lobes, all kept");
  const prt_cloth_settings finest = settings_of(PRT_CLOTH_KEEP_WEAK_LOBES, 16, 8);
  shade_and_compare(shader.get(), a, 0, nullptr, most, &finest, g, target,
                    "256 lobes, all kept, 16 segments, 8 phi nodes");
}

// Grazing views (87 to 89.94 degrees from the normal), where the fibres' fronts and the theta
// windows are cut hardest, for every preset fabric, under a light with lobes at and below the
// horizon as well as above.
TEST(GlCloth, GrazingViewsShadeLikeTheScalarReference) {
  PRT_REQUIRE_GL(gl);
  GlCalls calls;
  const std::vector<FabricSpec> fabrics = all_fabrics();
  const ClothAsset a(cloth_section(fabrics, small_grid(), {4, 6, 2}, 81), 16);
  GlClothShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  GBufferSamples g = random_gbuffer(19, 13, 82);
  make_views_grazing(g, 83);
  GlTarget target(calls, g, 1, 3, kClear);
  const std::vector<prt_cloth_lobe> lobes = random_lobes(12, 84);
  for (uint32_t f = 0; f < fabrics.size(); ++f)
    shade_and_compare(shader.get(), a, f, nullptr, lobes, nullptr, g, target,
                      fabrics[f].name + ", grazing views");
}

// ---- GL state ------------------------------------------------------------------------------

// State a game may leave set that would spoil the draw (depth test, blending, culling, a sampler
// that makes the G-buffer incomplete) is disabled or unbound, and left so as documented; the
// scissor box (a mask the caller may set on purpose), other texture units, the viewport and the
// framebuffer are the caller's and left alone.
TEST(GlCloth, StateIsSetForTheDrawAndLeftAsDocumented) {
  PRT_REQUIRE_GL(gl);
  GlCalls calls;
  const std::vector<FabricSpec> fabrics = presets({"linen_plain"});
  const ClothAsset a(cloth_section(fabrics, small_grid(), {3, 2}, 51), 16);
  GlClothShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const GBufferSamples g = random_gbuffer(16, 12, 52);
  GlTarget target(calls, g, 4, 4, kClear);
  const std::vector<prt_cloth_lobe> lobes = random_lobes(5, 53);
  const prt_cloth_light light = light_of(lobes);
  const prt_gl_cloth_gbuffer gbuffer = target.gbuffer();

  calls.Enable(GL_DEPTH_TEST);
  calls.DepthFunc(GL_NEVER);
  calls.Enable(GL_BLEND);
  calls.BlendFunc(GL_ONE, GL_ONE);
  calls.Enable(GL_CULL_FACE);
  calls.CullFace(GL_FRONT_AND_BACK);
  GLuint sampler = 0, other = float_texture(calls, 2, 2, nullptr), vertex_array = 0;
  calls.GenSamplers(1, &sampler);
  calls.SamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  for (GLuint unit = 0; unit < 4; ++unit) calls.BindSampler(unit, sampler);
  calls.ActiveTexture(GL_TEXTURE5);
  calls.BindTexture(GL_TEXTURE_2D, other);
  calls.GenVertexArrays(1, &vertex_array);
  calls.BindVertexArray(vertex_array);
  // The scissor box keeps the lower half of the viewport.
  calls.Enable(GL_SCISSOR_TEST);
  calls.Scissor(target.x0, target.y0, GLsizei(target.width), GLsizei(target.height / 2));

  ASSERT_EQ(prt_gl_cloth_shade(shader.get(), 0, nullptr, &light, nullptr, &gbuffer), PRT_OK);
  expect_gl_state_restored("prt_gl_cloth_shade");
  EXPECT_FALSE(calls.IsEnabled(GL_DEPTH_TEST));
  EXPECT_FALSE(calls.IsEnabled(GL_BLEND));
  EXPECT_FALSE(calls.IsEnabled(GL_CULL_FACE));
  EXPECT_TRUE(calls.IsEnabled(GL_SCISSOR_TEST));
  GLint value = -1;
  calls.GetIntegerv(GL_ACTIVE_TEXTURE, &value);
  EXPECT_EQ(value, GL_TEXTURE0);
  calls.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &value);
  EXPECT_EQ(value, 0);
  for (GLuint unit = 0; unit < 4; ++unit) {  // the G-buffer's and the tables'
    calls.ActiveTexture(GL_TEXTURE0 + unit);
    calls.GetIntegerv(GL_TEXTURE_BINDING_2D, &value);
    EXPECT_EQ(value, 0) << "unit " << unit;
    calls.GetIntegerv(GL_SAMPLER_BINDING, &value);
    EXPECT_EQ(value, 0) << "unit " << unit;
  }
  calls.ActiveTexture(GL_TEXTURE5);
  calls.GetIntegerv(GL_TEXTURE_BINDING_2D, &value);
  EXPECT_EQ(value, GLint(other)) << "unit 5 is not the shader's";
  calls.ActiveTexture(GL_TEXTURE0);
  GLint viewport[4];
  calls.GetIntegerv(GL_VIEWPORT, viewport);
  EXPECT_EQ(viewport[0], target.x0);
  EXPECT_EQ(viewport[1], target.y0);
  calls.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &value);
  EXPECT_EQ(value, GLint(target.framebuffer));

  // The lower half is shaded as without the state above, the upper half is left.
  const std::vector<float> rgba = target.read();
  const Reference r = reference(a.asset(), 0, nullptr, lobes, nullptr, g);
  for (uint32_t i = 0; i < g.count(); ++i) {
    const float* px = &rgba[4 * target.texel_of(i)];
    const bool inside = i / g.width < g.height / 2 && g.cloth[i];
    for (int c = 0; c < 3; ++c) {
      if (inside)
        EXPECT_LE(std::fabs(double(px[c]) - r.value[3 * i + c]), r.tolerance[3 * i + c]) << i;
      else
        EXPECT_EQ(px[c], kClear[c]) << i;
    }
  }
  calls.Disable(GL_SCISSOR_TEST);
  calls.DeleteSamplers(1, &sampler);
  calls.DeleteTextures(1, &other);
  calls.DeleteVertexArrays(1, &vertex_array);
  EXPECT_EQ(take_gl_error(), 0u);
}

// ---- creation ------------------------------------------------------------------------------

// Pixel-unpack state an application left set (a bound unpack buffer, row length, skips, byte
// swapping, alignment) would garble the tables' upload: create uploads as if it were not set,
// shades as the reference does, and puts every value back.
TEST(GlCloth, UnpackStateTheApplicationLeftSetDoesNotSpoilTheTables) {
  PRT_REQUIRE_GL(gl);
  GlCalls calls;
  const std::vector<FabricSpec> fabrics = presets({"linen_plain"});
  const ClothAsset a(cloth_section(fabrics, small_grid(), {3, 2}, 55), 16);
  GLuint unpack = 0;
  calls.GenBuffers(1, &unpack);
  calls.BindBuffer(GL_PIXEL_UNPACK_BUFFER, unpack);
  const std::vector<unsigned char> junk(1 << 16, 0x5a);
  calls.BufferData(GL_PIXEL_UNPACK_BUFFER, GLsizeiptr(junk.size()), junk.data(), GL_STATIC_DRAW);
  const GLenum names[] = {GL_UNPACK_SWAP_BYTES, GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_ROWS,
                          GL_UNPACK_SKIP_PIXELS, GL_UNPACK_ALIGNMENT};
  const GLint values[] = {1, 3, 1, 2, 8};
  for (int i = 0; i < 5; ++i) calls.PixelStorei(names[i], values[i]);
  GlClothShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  GLint value = -1;
  calls.GetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &value);
  EXPECT_EQ(value, GLint(unpack));
  for (int i = 0; i < 5; ++i) {
    calls.GetIntegerv(names[i], &value);
    EXPECT_EQ(value, values[i]) << names[i];
  }
  calls.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  calls.DeleteBuffers(1, &unpack);
  const GLint defaults[] = {0, 0, 0, 0, 4};
  for (int i = 0; i < 5; ++i) calls.PixelStorei(names[i], defaults[i]);
  const GBufferSamples g = random_gbuffer(11, 9, 56);
  GlTarget target(calls, g, 0, 0, kClear);
  shade_and_compare(shader.get(), a, 0, nullptr, random_lobes(5, 57), nullptr, g, target,
                    "unpack state set at create");
  EXPECT_EQ(take_gl_error(), 0u);
}

ClothAsset small_asset(prt_backend limit = PRT_BACKEND_AUTO,
                       const prt_allocator* allocator = nullptr) {
  return ClothAsset(cloth_section(presets({"linen_plain"}), small_grid(), {2}, 61), 8, limit,
                    allocator);
}

TryCreateShader try_create(const ClothAsset& a) {
  return [&a](prt_context* context, prt_gl_loader_fn loader, void* user, bool* shader_null) {
    prt_gl_cloth_shader* shader = nullptr;
    const prt_result r = prt_gl_cloth_create(context, a.asset(), loader, user, &shader);
    *shader_null = shader == nullptr;
    prt_gl_cloth_destroy(shader);
    return r;
  };
}

TEST(GlCloth, MissingEntryPointIsUnsupportedAndNamed) {
  PRT_REQUIRE_GL(gl);
  const ClothAsset a = small_asset();
  expect_refused_without_entry_points(try_create(a), a.context.get(), gl.gl,
                                      {"glDrawArrays", "glBindVertexArray", "glBindSampler",
                                       "glActiveTexture", "glDisable", "glGetError"});
}

TEST(GlCloth, ContextOlderThan43IsUnsupported) {
  PRT_REQUIRE_GL(gl);
  const ClothAsset a = small_asset();
  expect_refused_below_gl_43(try_create(a), a.context.get());
}

// A loader whose GL answers a GL_MAX_TEXTURE_SIZE of 8.
void narrow_textures_get_integerv(GLenum name, GLint* data) {
  reinterpret_cast<PFNGLGETINTEGERVPROC>(headless_gl_get_proc(nullptr, "glGetIntegerv"))(name,
                                                                                         data);
  if (name == GL_MAX_TEXTURE_SIZE) *data = 8;
}
void* narrow_textures_loader(void*, const char* name) {
  if (std::string(name) == "glGetIntegerv")
    return reinterpret_cast<void*>(&narrow_textures_get_integerv);
  return headless_gl_get_proc(nullptr, name);
}

// The tables' words fill a square texture of a power-of-two side: 936 bytes (234 words) need 16
// texels a side, more than the 8 this GL claims.
TEST(GlCloth, TablesWiderThanTheLargestTextureAreUnsupported) {
  PRT_REQUIRE_GL(gl);
  const ClothAsset a = small_asset();
  prt_cloth_info info{};
  info.struct_size = sizeof info;
  ASSERT_EQ(prt_cloth_get_info(a.asset(), &info), PRT_OK);
  ASSERT_GT(info.table_bytes, 4u * 8u * 8u);
  expect_refused(try_create(a), a.context.get(), narrow_textures_loader, nullptr,
                 "need a texture 16 texels wide; this GL allows 8");
}

TEST(GlCloth, BackendLimitBelowGlIsUnsupported) {
  PRT_REQUIRE_GL(gl);
  for (prt_backend limit : {PRT_BACKEND_CPU, PRT_BACKEND_SIMD}) {
    const ClothAsset a = small_asset(limit);
    prt_gl_cloth_shader* shader = reinterpret_cast<prt_gl_cloth_shader*>(&gl);
    EXPECT_EQ(prt_gl_cloth_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
              PRT_ERROR_UNSUPPORTED_BACKEND);
    EXPECT_EQ(shader, nullptr);
    EXPECT_NE(a.message().find("backend limit"), std::string::npos) << a.message();
  }
  const ClothAsset a = small_asset(PRT_BACKEND_GL);
  EXPECT_TRUE(create_shader(a, gl.gl));
}

TEST(GlCloth, NoClthSectionIsNotFound) {
  PRT_REQUIRE_GL(gl);
  const prt::ContextPtr ctx = limited_context();
  LoadedAsset loaded(ctx.get(), mesh_only_blob());
  ASSERT_EQ(loaded.result, PRT_OK);
  prt_gl_cloth_shader* shader = reinterpret_cast<prt_gl_cloth_shader*>(&loaded);
  EXPECT_EQ(prt_gl_cloth_create(ctx.get(), loaded.asset, headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(shader, nullptr);
  EXPECT_NE(std::string(prt_context_last_message(ctx.get())).find("CLTH"), std::string::npos);
}

TEST(GlCloth, NullArgumentsAreInvalid) {
  PRT_REQUIRE_GL(gl);
  const ClothAsset a = small_asset();
  prt_gl_cloth_shader* shader = nullptr;
  EXPECT_EQ(prt_gl_cloth_create(nullptr, a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_cloth_create(a.context.get(), nullptr, headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_cloth_create(a.context.get(), a.asset(), nullptr, gl.gl, &shader),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_cloth_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(shader, nullptr);
  prt_gl_cloth_destroy(nullptr);  // ignored
}

TEST(GlCloth, ShaderComesFromTheAssetsAllocator) {
  PRT_REQUIRE_GL(gl);
  CountingAllocator counter;
  const prt_allocator allocator = counter.api();
  const ClothAsset a = small_asset(PRT_BACKEND_AUTO, &allocator);
  const int before = counter.live;
  prt_gl_cloth_shader* shader = nullptr;
  ASSERT_EQ(prt_gl_cloth_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_OK);
  EXPECT_GT(counter.live, before);
  prt_gl_cloth_destroy(shader);
  EXPECT_EQ(counter.live, before);
  counter.fail = true;
  EXPECT_EQ(prt_gl_cloth_create(a.context.get(), a.asset(), headless_gl_get_proc, gl.gl, &shader),
            PRT_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(shader, nullptr);
  counter.fail = false;
  EXPECT_EQ(counter.live, before);
  EXPECT_FALSE(counter.size_mismatch);
}

TEST(GlCloth, ErrorsTheApplicationLeftPendingDoNotFailCreation) {
  PRT_REQUIRE_GL(gl);
  leave_gl_error_pending();
  const ClothAsset a = small_asset();
  EXPECT_TRUE(create_shader(a, gl.gl));
  EXPECT_EQ(take_gl_error(), 0u) << "create cleared the pending error and raised none";
}

// ---- shade's refusals ----------------------------------------------------------------------

// Bad arguments, and the paper's study switches, are refused before anything is drawn, and write
// no context.
TEST(GlCloth, BadShadeArgumentsAreRefusedAndDrawNothing) {
  PRT_REQUIRE_GL(gl);
  GlCalls calls;
  const ClothAsset a = small_asset();
  GlClothShaderPtr shader = create_shader(a, gl.gl);
  ASSERT_TRUE(shader);
  const GBufferSamples g = random_gbuffer(6, 5, 71);
  GlTarget target(calls, g, 0, 0, kClear);
  const std::vector<prt_cloth_lobe> lobes = random_lobes(3, 72);
  const prt_cloth_light light = light_of(lobes);
  const prt_gl_cloth_gbuffer gbuffer = target.gbuffer();
  const std::vector<float> cleared = target.read();
  const std::string message_before = a.message();

  prt_gl_cloth_gbuffer small_gbuffer = gbuffer;
  small_gbuffer.struct_size = 8;
  prt_cloth_light bad_light = light;
  std::vector<prt_cloth_lobe> bad_lobes = lobes;
  bad_lobes[1].sharpness = 0.0f;
  bad_light.lobes = bad_lobes.data();
  prt_cloth_params bad_params{};
  bad_params.struct_size = sizeof bad_params;
  ASSERT_EQ(prt_cloth_get_fabric(a.asset(), 0, nullptr, &bad_params, nullptr, nullptr), PRT_OK);
  bad_params.threads[0].coverage = 0.9f;  // a_1 + a_2 > 1
  prt_cloth_settings bad[4] = {settings_of(1u << 31), settings_of(0, 17), settings_of(0, 0, 9),
                               settings_of(0)};
  bad[3].struct_size = 4;  // below 1.0's

  prt_gl_cloth_shader* s = shader.get();
  EXPECT_EQ(prt_gl_cloth_shade(nullptr, 0, nullptr, &light, nullptr, &gbuffer),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_cloth_shade(s, 0, nullptr, nullptr, nullptr, &gbuffer),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_cloth_shade(s, 0, nullptr, &light, nullptr, nullptr),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_cloth_shade(s, 0, nullptr, &light, nullptr, &small_gbuffer),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_cloth_shade(s, 1, nullptr, &light, nullptr, &gbuffer), PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_gl_cloth_shade(s, UINT32_MAX, nullptr, &light, nullptr, &gbuffer),
            PRT_ERROR_NOT_FOUND);
  EXPECT_EQ(prt_gl_cloth_shade(s, 0, nullptr, &bad_light, nullptr, &gbuffer),
            PRT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(prt_gl_cloth_shade(s, 0, &bad_params, &light, nullptr, &gbuffer),
            PRT_ERROR_INVALID_ARGUMENT);
  for (const prt_cloth_settings& settings : bad)
    EXPECT_EQ(prt_gl_cloth_shade(s, 0, nullptr, &light, &settings, &gbuffer),
              PRT_ERROR_INVALID_ARGUMENT);
  // the paper's study switches are the scalar reference's alone (prt_cloth_asset.h)
  for (const uint32_t flags : {PRT_CLOTH_PAPER_PHI_DOMAIN, PRT_CLOTH_PAPER_THETA_SEGMENTS,
                               PRT_CLOTH_PAPER_FRESNEL, PRT_CLOTH_PAPER_NARROW_GU}) {
    const prt_cloth_settings paper = settings_of(flags);
    EXPECT_EQ(prt_gl_cloth_shade(s, 0, nullptr, &light, &paper, &gbuffer),
              PRT_ERROR_UNSUPPORTED_BACKEND)
        << flags;
  }
  EXPECT_EQ(target.read(), cleared) << "a refused call drew";
  EXPECT_EQ(a.message(), message_before) << "a shade call wrote the context";
  EXPECT_EQ(take_gl_error(), 0u);
}

}  // namespace
