// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s scene evaluated on the CPU (docs/shadowfield/design.md, "At run
// time") on synthetic objects: the direct light of one instance against albedo x T . L computed
// here, blockers of known visibility (constant 1, 0, a tilted lobe against a dense quadrature of
// the rotated product), pair culling, a uniform source's first bounce against its weights
// computed here, invariance under a rotation of the whole scene and its light, linearity, and
// the staged entry points against the one call.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "shadowfield/runtime/shadowfield_test_scene.hpp"

namespace prt::test {
namespace {

const float kAxis[3] = {0.26726124f, 0.53452248f, 0.80178373f};  // (1, 2, 3) / |(1, 2, 3)|
const float kFarEye[3] = {0.3f, 40.0f, 0.2f};

// sum_i A_l y_i(d) L_i,c / pi: a white Lambertian surface's radiance at normal d under L.
float lambert(uint32_t order, const std::vector<float>& light, const float d[3], int c) {
  std::vector<float> y(order * order);
  prt_sh_eval(order, d, y.data());
  double sum = 0.0;
  for (uint32_t i = 0; i < order * order; ++i) {
    const uint32_t l = uint32_t(std::sqrt(float(i)) + 1e-4f);
    sum += prt_sh_cosine_band_factor(l) * y[i] * light[3 * i + c];
  }
  return float(sum / kSfPi);
}

TEST(ShadowfieldScene, OneInstanceIsAlbedoTimesTransferDotLight) {
  for (const uint32_t order : {2u, 3u, 4u, 6u}) {
    SyntheticObject patch = make_patch(order, 3);
    TestScene s(1);
    float rotation[9];
    axis_rotation(kAxis, 0.7f, rotation);
    s.add_instance(s.add_object(patch), make_transform(rotation, 1.0f, -2.0f, 0.5f, 2.0f));
    const std::vector<float> light = test_light(order);
    const std::vector<float> out = s.shade(light, kFarEye, 3)[0];
    // The world normal is R n: the transfer is the cosine lobe about it.
    const float normal[3] = {rotation[1], rotation[4], rotation[7]};
    double worst = 0.0;
    for (uint32_t v = 0; v < patch.vertex_count; ++v)
      for (int c = 0; c < 3; ++c)
        worst = std::max(
            worst, double(std::fabs(out[3 * v + c] -
                                    patch.albedo[3 * v + c] * lambert(order, light, normal, c))));
    std::printf("order %u: max |radiance - albedo E(R n) / pi| %.2e (radiance about %.2f)\n", order,
                worst, max_abs(out));
    EXPECT_LT(worst, 3e-7) << "order " << order;  // measured up to 1.2e-7: float rounding
  }
}

TEST(ShadowfieldScene, GlossyTermsReadAtTheViewDirection) {
  // One vertex seen along its normal: wo is the centre of the concentric map, so each g_k is the
  // mean of the four centre cells of a 4 x 4 grid.
  SyntheticObject patch = make_patch(4, 1);
  patch.glossy = 1;
  patch.terms = 2;
  patch.brdf_grid = 4;
  for (uint32_t k = 0; k < 2; ++k)
    for (uint32_t cell = 0; cell < 16; ++cell) patch.g_table.push_back(1.0f + 0.1f * cell + k);
  const std::vector<float> cosine = patch.transfer;
  patch.transfer.clear();
  for (uint32_t k = 0; k < 2; ++k)
    for (const float t : cosine) patch.transfer.push_back((1.0f + 0.5f * k) * t);
  TestScene s(1);
  s.add_instance(s.add_object(patch), make_transform(identity_rotation(), 0, 0, 0));
  const std::vector<float> light = test_light(4);
  const float eye[3] = {0.0f, 5.0f, 0.0f};
  const std::vector<float> out = s.shade(light, eye, 0)[0];
  const float up[3] = {0.0f, 1.0f, 0.0f};
  for (int c = 0; c < 3; ++c) {
    double expected = 0.0;
    for (uint32_t k = 0; k < 2; ++k) {
      const double g = (patch.g_table[16 * k + 5] + patch.g_table[16 * k + 6] +
                        patch.g_table[16 * k + 9] + patch.g_table[16 * k + 10]) /
                       4.0;
      expected += g * (1.0 + 0.5 * k) * lambert(4, light, up, c);
    }
    std::printf("channel %d: radiance %.6f, error %.2e\n", c, out[c],
                std::fabs(out[c] - patch.albedo[c] * expected));
    // Measured up to 2.1e-7 of the radiance: float rounding.
    EXPECT_NEAR(out[c], patch.albedo[c] * expected, 5e-7 * patch.albedo[c] * expected)
        << "channel " << c;
  }
}

// Receiver and blocker patches; the blocker's OOF is `oof` at every point.
struct Pair {
  SyntheticObject receiver = make_patch(4, 3), blocker = make_patch(4, 3);
  TestScene scene{2};
  Pair(const std::vector<float>& oof, const float blocker_at[3], const float* blocker_rotation) {
    blocker.set_constant_oof(oof);
    scene.add_instance(scene.add_object(receiver), make_transform(identity_rotation(), 0, 0, 0));
    scene.add_instance(scene.add_object(blocker), make_transform(blocker_rotation, blocker_at[0],
                                                                 blocker_at[1], blocker_at[2]));
  }
};

std::vector<float> alone(SyntheticObject& receiver, const std::vector<float>& light) {
  TestScene s(1);
  s.add_instance(s.add_object(receiver), make_transform(identity_rotation(), 0, 0, 0));
  return s.shade(light, kFarEye, 0)[0];
}

TEST(ShadowfieldScene, AnOpenBlockerChangesNothing) {
  std::vector<float> open(16, 0.0f);
  open[0] = float(std::sqrt(4.0 * kSfPi));
  const float at[3] = {0.0f, 1.0f, 0.0f};
  Pair pair(open, at, identity_rotation());
  const std::vector<float> light = test_light(4);
  const std::vector<float> out = pair.scene.shade(light, kFarEye, 0)[0];
  const double difference = max_difference(out, alone(pair.receiver, light));
  std::printf("open blocker: max difference %.2e of %.2f\n", difference, max_abs(out));
  EXPECT_LT(difference, 5e-7);  // measured 1.8e-7: the triple product's float rounding
}

TEST(ShadowfieldScene, AClosedBlockerBlackensTheDirectLight) {
  const float at[3] = {0.0f, 1.0f, 0.0f};
  Pair pair(std::vector<float>(16, 0.0f), at, identity_rotation());
  const std::vector<float> out = pair.scene.shade(test_light(4), kFarEye, 0)[0];
  EXPECT_EQ(max_abs(out), 0.0);
}

TEST(ShadowfieldScene, ABlockerBeyondItsOuterShellIsCulled) {
  // Outer shell 8 x 0.75 = 6 plus the receiver's 0.75: no pair beyond 6.75, one within.
  const std::vector<float> light = test_light(4);
  const float far[3] = {0.0f, 6.8f, 0.0f}, near[3] = {0.0f, 6.7f, 0.0f};
  Pair culled(std::vector<float>(16, 0.0f), far, identity_rotation());
  const std::vector<float> out = culled.scene.shade(light, kFarEye, 0)[0];
  EXPECT_EQ(max_difference(out, alone(culled.receiver, light)), 0.0);
  EXPECT_EQ(culled.scene.scene->pair_count, 0u);
  Pair kept(std::vector<float>(16, 0.0f), near, identity_rotation());
  kept.scene.shade(light, kFarEye, 0);
  EXPECT_EQ(kept.scene.scene->pair_count, 2u);
}

TEST(ShadowfieldScene, AMovedBlockerShadowsWhereItIsNow) {
  // Frame by frame: a closed blocker near, then moved beyond its reach, then back.
  const std::vector<float> light = test_light(4);
  const float near[3] = {0.0f, 1.0f, 0.0f};
  Pair pair(std::vector<float>(16, 0.0f), near, identity_rotation());
  const std::vector<float> open = alone(pair.receiver, light);
  EXPECT_EQ(max_abs(pair.scene.shade(light, kFarEye, 2)[0]), 0.0);
  const prt_shadowfield_transform far = make_transform(identity_rotation(), 0.0f, 20.0f, 0.0f);
  ASSERT_EQ(prt_shadowfield_scene_set_transform(pair.scene.scene, 1, &far), PRT_OK);
  EXPECT_EQ(max_difference(pair.scene.shade(light, kFarEye, 2)[0], open), 0.0);
  const prt_shadowfield_transform back = make_transform(identity_rotation(), 0.0f, 1.0f, 0.0f);
  ASSERT_EQ(prt_shadowfield_scene_set_transform(pair.scene.scene, 1, &back), PRT_OK);
  EXPECT_EQ(max_abs(pair.scene.shade(light, kFarEye, 2)[0]), 0.0);
}

TEST(ShadowfieldScene, ARotatedBlockerShadowsInItsOwnFrame) {
  // OOF f(w_j) = 0.6 + 0.4 w_j.z (SH frame of the blocker) at every point: the receiver (also
  // rotated) sees L(R_i w) f(R_j^T R_i w) in its frame, projected here by a dense quadrature.
  std::vector<float> oof(16, 0.0f);
  oof[0] = float(0.6 * std::sqrt(4.0 * kSfPi));
  oof[2] = float(0.4 * std::sqrt(4.0 * kSfPi / 3.0));  // Y_10 = sqrt(3 / 4 pi) z
  SyntheticObject receiver = make_patch(4, 2), blocker = make_patch(4, 2);
  blocker.set_constant_oof(oof);
  float ri[9], rj[9];
  axis_rotation(kAxis, 0.9f, ri);
  const float other_axis[3] = {0.0f, 0.6f, 0.8f};
  axis_rotation(other_axis, -1.2f, rj);
  TestScene s(2);
  s.add_instance(s.add_object(receiver), make_transform(ri, 0.5f, 0.0f, 0.0f));
  s.add_instance(s.add_object(blocker), make_transform(rj, 0.5f, 1.5f, 0.0f));
  const std::vector<float> light = test_light(4);
  const std::vector<float> out = s.shade(light, kFarEye, 0)[0];

  auto apply = [](const float* m, const float* v, float* o, bool transpose) {
    for (int r = 0; r < 3; ++r)
      o[r] = transpose ? m[r] * v[0] + m[3 + r] * v[1] + m[6 + r] * v[2]
                       : m[3 * r] * v[0] + m[3 * r + 1] * v[1] + m[3 * r + 2] * v[2];
  };
  double worst = 0.0, scale = 0.0;
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> shadowed = project_dense(4, [&](const float* w) {
      float world[3], in_blocker[3];
      apply(ri, w, world, false);
      apply(rj, world, in_blocker, true);
      std::vector<float> channel(16);
      for (int i = 0; i < 16; ++i) channel[i] = light[3 * i + c];
      return sh_value(4, channel.data(), world) * sh_value(4, oof.data(), in_blocker);
    });
    for (uint32_t v = 0; v < receiver.vertex_count; ++v) {
      double expected = 0.0;
      for (int i = 0; i < 16; ++i) expected += receiver.transfer[16 * v + i] * shadowed[i];
      expected *= receiver.albedo[3 * v + c];
      worst = std::max(worst, std::fabs(out[3 * v + c] - expected));
      scale = std::max(scale, std::fabs(expected));
    }
  }
  std::printf("rotated blocker: max error %.2e of %.2f\n", worst, scale);
  EXPECT_LT(worst, 5e-5 * scale);  // measured 2.0e-5: the dense quadrature's error
}

// p = R_j^T (s_i R_i x + t_i - t_j) / s_j in double.
std::vector<double> point_in_other(const prt_shadowfield_transform& i,
                                   const prt_shadowfield_transform& j, const float* x) {
  double world[3], p[3];
  for (int r = 0; r < 3; ++r) {
    world[r] = i.translation[r] - j.translation[r];
    for (int c = 0; c < 3; ++c) world[r] += double(i.scale) * i.rotation[3 * r + c] * x[c];
  }
  for (int r = 0; r < 3; ++r) {
    p[r] = 0.0;
    for (int c = 0; c < 3; ++c) p[r] += double(j.rotation[3 * c + r]) * world[c];
    p[r] /= j.scale;
  }
  return {p[0], p[1], p[2]};
}

// A field's value at p by the formats layer's prt_sf_locate over values given per grid point.
double read_at(const prt_sf_shells& grid, const std::vector<double>& p,
               const std::function<double(uint64_t)>& value) {
  const float at[3] = {float(p[0]), float(p[1]), float(p[2])};
  prt_sf_lookup lookup;
  prt_sf_locate(&grid, at, &lookup);
  double sum = 0.0;
  for (uint32_t e = 0; e < lookup.count; ++e) sum += lookup.weight[e] * value(lookup.index[e]);
  return sum;
}

TEST(ShadowfieldScene, FieldsAreReadWhereTheVertexIsInTheOthersFrame) {
  // Band-0 fields that differ from point to point: the blocker's visibility v(point) and the
  // source's uniform radiance u(point) (one constant basis function). A rotated, scaled receiver
  // then sees, at each vertex, its direct light times v(p) / sqrt(4 pi) and a first bounce
  // T_0 w u(p), with p the vertex in the other's frame.
  auto visibility = [](uint64_t point) { return 0.5 + 0.4 * std::sin(0.7 * double(point)); };
  auto radiance = [](uint64_t point) { return 0.3 + 0.2 * std::cos(0.3 * double(point)); };
  SyntheticObject receiver = make_patch(4, 3), other = make_patch(4, 2);
  const uint64_t points = prt_sf_point_count(&other.oof_shells);
  other.oof.assign(points * 16, 0.0f);
  for (uint64_t p = 0; p < points; ++p) other.oof[p * 16] = float(visibility(p));
  other.set_basis(1, [&](uint32_t, uint32_t, uint64_t p, uint32_t c) {
    return c == 0 ? float(radiance(p)) : 0.0f;
  });
  float ri[9], rj[9];
  axis_rotation(kAxis, 0.5f, ri);
  const float other_axis[3] = {0.8f, 0.0f, 0.6f};
  axis_rotation(other_axis, 1.9f, rj);
  const prt_shadowfield_transform ti = make_transform(ri, 0.1f, 0.2f, -0.3f, 1.7f);
  const prt_shadowfield_transform tj = make_transform(rj, 0.6f, 1.4f, 0.2f, 0.8f);
  TestScene s(2);
  s.add_instance(s.add_object(receiver), ti);
  s.add_instance(s.add_object(other), tj);
  const std::vector<float> light = test_light(4);
  s.shade(light, kFarEye, 1);
  const std::vector<float> direct = s.pass_output(0, 0), both = s.pass_output(0, 1);

  const float receiver_normal[3] = {ri[1], ri[4], ri[7]}, other_normal[3] = {rj[1], rj[4], rj[7]};
  double worst = 0.0, scale = 0.0;
  for (int c = 0; c < 3; ++c) {
    double weight = 0.0;
    for (uint32_t v = 0; v < other.vertex_count; ++v)
      weight += other.albedo[3 * v + c] * lambert(4, light, other_normal, c);
    weight /= other.vertex_count;
    for (uint32_t v = 0; v < receiver.vertex_count; ++v) {
      const std::vector<double> p = point_in_other(ti, tj, &receiver.positions[3 * v]);
      const double albedo = receiver.albedo[3 * v + c];
      const double expected_direct = albedo * lambert(4, light, receiver_normal, c) *
                                     read_at(other.oof_shells, p, visibility) /
                                     std::sqrt(4.0 * kSfPi);
      const double expected_bounce =
          albedo * receiver.transfer[16 * v] * weight * read_at(other.srf_shells, p, radiance);
      worst = std::max({worst, std::fabs(direct[3 * v + c] - expected_direct),
                        std::fabs(both[3 * v + c] - direct[3 * v + c] - expected_bounce)});
      scale = std::max({scale, expected_direct, expected_bounce});
    }
  }
  std::printf("fields read at p: max error %.2e of %.3f\n", worst, scale);
  EXPECT_LT(worst, 5e-7 * scale);  // measured 2.1e-7 of the scale: float rounding
}

// Three instances with fields that vary over their shell points, glossy terms and a basis.
struct BusyScene {
  SyntheticObject floor = make_patch(4, 4), box = make_patch(4, 3);
  TestScene scene{3};

  static void vary_oof(SyntheticObject& o) {
    const uint64_t points = prt_sf_point_count(&o.oof_shells);
    o.oof.assign(points * 16, 0.0f);
    for (uint64_t p = 0; p < points; ++p) {
      o.oof[p * 16] = float((0.5 + 0.3 * std::sin(0.37 * p)) * std::sqrt(4.0 * kSfPi));
      for (int c = 1; c < 16; ++c) o.oof[p * 16 + c] = 0.15f * std::cos(0.11f * float(p * c));
    }
  }

  static void make_glossy(SyntheticObject& o) {
    o.glossy = 1;
    o.terms = 2;
    o.brdf_grid = 4;
    o.g_table.clear();
    for (uint32_t k = 0; k < 2; ++k)
      for (uint32_t cell = 0; cell < 16; ++cell)
        o.g_table.push_back(1.0f + 0.3f * std::sin(float(cell + 5 * k)));
    const std::vector<float> cosine = o.transfer;
    o.transfer.clear();
    for (uint32_t v = 0; v < o.vertex_count; ++v)
      for (uint32_t k = 0; k < 2; ++k)
        for (uint32_t i = 0; i < 16; ++i)
          o.transfer.push_back((1.0f - 0.4f * k) * cosine[16 * v + i]);
  }

  explicit BusyScene(const float* q = identity_rotation(), float srf_scale = 1.0f) {
    vary_oof(floor);
    vary_oof(box);
    make_glossy(box);
    auto field = [srf_scale](uint32_t i, uint32_t k, uint64_t p, uint32_t c) {
      return srf_scale *
             (c == 0 ? 0.3f + 0.05f * float(i + k) : 0.04f * std::sin(float(p + 3 * c + i)));
    };
    floor.set_basis(2, field);
    box.set_basis(2, field);
    const uint32_t floor_id = scene.add_object(floor), box_id = scene.add_object(box);
    add(floor_id, identity_rotation(), 0.0f, 0.0f, 0.0f, 3.0f, q);
    float tilt[9];
    axis_rotation(kAxis, 0.5f, tilt);
    add(box_id, tilt, 0.3f, 0.6f, 0.2f, 0.8f, q);
    const float other_axis[3] = {0.0f, 0.0f, 1.0f};
    axis_rotation(other_axis, -0.9f, tilt);  // still facing kNearEye: seen from behind, glossy is 0
    add(box_id, tilt, -0.7f, 0.9f, -0.4f, 1.1f, q);
  }

  // An instance at (Q R, Q t).
  void add(uint32_t object, const float* r, float x, float y, float z, float scale,
           const float* q) {
    float qr[9];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        qr[3 * a + b] = q[3 * a] * r[b] + q[3 * a + 1] * r[3 + b] + q[3 * a + 2] * r[6 + b];
    const float t[3] = {x, y, z};
    float qt[3];
    for (int a = 0; a < 3; ++a) qt[a] = q[3 * a] * t[0] + q[3 * a + 1] * t[1] + q[3 * a + 2] * t[2];
    scene.add_instance(object, make_transform(qr, qt[0], qt[1], qt[2], scale));
  }
};

const float kNearEye[3] = {1.5f, 2.5f, 2.0f};

TEST(ShadowfieldScene, RotatingTheSceneAndItsLightRotatesNothing) {
  BusyScene plain;
  const std::vector<float> light = test_light(4);
  const auto expected = plain.scene.shade(light, kNearEye, 3);

  float q[9];
  const float axis[3] = {0.6f, 0.0f, -0.8f};
  axis_rotation(axis, 2.2f, q);
  BusyScene turned(q);
  std::vector<float> turned_light(light.size());
  ASSERT_EQ(prt_sh_rotate(4, q, light.data(), turned_light.data(), 3), PRT_OK);
  float eye[3];
  for (int a = 0; a < 3; ++a)
    eye[a] = q[3 * a] * kNearEye[0] + q[3 * a + 1] * kNearEye[1] + q[3 * a + 2] * kNearEye[2];
  const auto out = turned.scene.shade(turned_light, eye, 3);
  for (size_t i = 0; i < out.size(); ++i) {
    const double difference = max_difference(out[i], expected[i]);
    std::printf("instance %zu: max difference %.2e of %.2f\n", i, difference, max_abs(expected[i]));
    EXPECT_LT(difference, 1e-6 * max_abs(expected[i]));  // measured up to 3.1e-7
  }
}

TEST(ShadowfieldScene, LinearInTheLight) {
  BusyScene busy;
  const std::vector<float> a = test_light(4, 0.0f), b = test_light(4, 1.7f);
  std::vector<float> mix(a.size());
  for (size_t e = 0; e < a.size(); ++e) mix[e] = 2.0f * a[e] - 0.5f * b[e];
  const auto out_a = busy.scene.shade(a, kNearEye, 3), out_b = busy.scene.shade(b, kNearEye, 3);
  const auto out_mix = busy.scene.shade(mix, kNearEye, 3);
  for (size_t i = 0; i < out_mix.size(); ++i) {
    std::vector<float> expected(out_a[i].size());
    for (size_t e = 0; e < expected.size(); ++e)
      expected[e] = 2.0f * out_a[i][e] - 0.5f * out_b[i][e];
    const double difference = max_difference(out_mix[i], expected);
    std::printf("instance %zu: max difference %.2e of %.2f\n", i, difference, max_abs(expected));
    EXPECT_LT(difference, 1.2e-6 * max_abs(expected));  // measured up to 4e-7
  }
}

TEST(ShadowfieldScene, ASourceOfZeroRadianceAddsNothing) {
  BusyScene dark(identity_rotation(), 0.0f);
  const std::vector<float> light = test_light(4);
  const auto direct = dark.scene.shade(light, kNearEye, 0);
  const auto bounced = dark.scene.shade(light, kNearEye, 3);
  for (size_t i = 0; i < direct.size(); ++i) EXPECT_EQ(max_difference(direct[i], bounced[i]), 0.0);
}

TEST(ShadowfieldScene, BouncesAddLightPassByPass) {
  BusyScene busy;
  const auto out = busy.scene.shade(test_light(4), kNearEye, 3);
  for (uint32_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(max_difference(busy.scene.pass_output(i, 3), out[i]), 0.0);
    // Each pass adds light: the sources glow with positive radiance.
    double previous = 0.0;
    for (uint32_t pass = 0; pass <= 3; ++pass) {
      double total = 0.0;
      for (const float v : busy.scene.pass_output(i, pass)) total += v;
      EXPECT_GT(total, previous) << "instance " << i << " pass " << pass;
      previous = total;
    }
  }
}

TEST(ShadowfieldScene, AUniformSourceLightsByItsMeanRadiance) {
  // The source: one constant basis function (A^-1 = 1 with weights 1/V), its SRF the uniform
  // radiance s sqrt(4 pi) e_0 at every point. Its weight is the mean of albedo x its direct
  // light, and the receiver's first bounce is T_0 . (w s sqrt(4 pi) e_0).
  SyntheticObject receiver = make_patch(4, 2), source = make_patch(4, 3);
  const float s = 0.25f;
  source.set_basis(1, [s](uint32_t, uint32_t, uint64_t, uint32_t c) {
    return c == 0 ? float(s * std::sqrt(4.0 * kSfPi)) : 0.0f;
  });
  TestScene scene(2);
  scene.add_instance(scene.add_object(receiver), make_transform(identity_rotation(), 0, 0, 0));
  float tilt[9];
  axis_rotation(kAxis, 0.4f, tilt);
  scene.add_instance(scene.add_object(source), make_transform(tilt, 0.2f, 1.2f, 0.0f));
  const std::vector<float> light = test_light(4);
  scene.shade(light, kFarEye, 1);
  const std::vector<float> direct = scene.pass_output(0, 0), both = scene.pass_output(0, 1);
  const float source_normal[3] = {tilt[1], tilt[4], tilt[7]};
  double worst = 0.0, scale = 0.0;
  for (int c = 0; c < 3; ++c) {
    double weight = 0.0;
    for (uint32_t v = 0; v < source.vertex_count; ++v)
      weight += source.albedo[3 * v + c] * lambert(4, light, source_normal, c);
    weight /= source.vertex_count;
    for (uint32_t v = 0; v < receiver.vertex_count; ++v) {
      const double expected = receiver.albedo[3 * v + c] * receiver.transfer[16 * v] * weight * s *
                              std::sqrt(4.0 * kSfPi);
      worst = std::max(worst, std::fabs(both[3 * v + c] - direct[3 * v + c] - expected));
      scale = std::max(scale, expected);
    }
  }
  std::printf("first bounce: max error %.2e of %.3f\n", worst, scale);
  EXPECT_LT(worst, 2.5e-7);  // measured 7.9e-8
}

TEST(ShadowfieldScene, TheStagesGiveTheOneCallsResult) {
  BusyScene busy;
  const std::vector<float> light = test_light(4);
  const auto expected = busy.scene.shade(light, kNearEye, 2);
  prt_shadowfield_scene* scene = busy.scene.scene;
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.bounces = 2;
  ASSERT_EQ(prt_shadowfield_prepare(scene, light.data(), kNearEye, &settings), PRT_OK);
  const uint32_t count = prt_shadowfield_scene_instance_count(scene);
  for (uint32_t pass = 0; pass <= 2; ++pass) {
    // Vertex ranges of 3 in reverse order, as a job system might run them.
    for (uint32_t i = count; i-- > 0;) {
      const uint32_t vertices = prt_shadowfield_instance_vertex_count(scene, i);
      for (uint32_t first = 0; first < vertices; first += 3) {
        ASSERT_EQ(prt_shadowfield_gather(scene, pass, i, first, std::min(3u, vertices - first)),
                  PRT_OK);
      }
    }
    if (pass < 2) {
      for (uint32_t i = 0; i < count; ++i) {
        ASSERT_EQ(prt_shadowfield_project(scene, pass, i, 1), PRT_OK);
      }
    }
  }
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t vertices = prt_shadowfield_instance_vertex_count(scene, i);
    std::vector<float> out(size_t(vertices) * 3);
    ASSERT_EQ(prt_shadowfield_output(scene, i, 2, 1, vertices - 1, out.data() + 3), PRT_OK);
    ASSERT_EQ(prt_shadowfield_output(scene, i, 2, 0, 1, out.data()), PRT_OK);
    EXPECT_EQ(max_difference(out, expected[i]), 0.0) << "instance " << i;
  }
}

TEST(ShadowfieldScene, AWorkerPoolGivesTheOneThreadResult) {
  BusyScene busy;
  const std::vector<float> light = test_light(4);
  const auto expected = busy.scene.shade(light, kNearEye, 3);
  for (const uint32_t threads : {2u, 3u}) {
    prt_workers_desc desc{};
    desc.struct_size = sizeof desc;
    desc.thread_count = threads;
    prt_workers* workers = nullptr;
    ASSERT_EQ(prt_workers_create(busy.scene.context, &desc, &workers), PRT_OK);
    std::vector<std::vector<float>> out(expected.size());
    std::vector<float*> pointers;
    for (size_t i = 0; i < expected.size(); ++i) {
      out[i].assign(expected[i].size(), -1.0f);
      pointers.push_back(i == 1 ? nullptr : out[i].data());  // a skipped output stays as it was
    }
    prt_shadowfield_settings settings{};
    settings.struct_size = sizeof settings;
    settings.bounces = 3;
    EXPECT_EQ(prt_shadowfield_shade_workers(workers, busy.scene.scene, light.data(), kNearEye,
                                            &settings, pointers.data()),
              PRT_OK);
    for (size_t i = 0; i < expected.size(); ++i) {
      if (i == 1)
        EXPECT_EQ(out[i], std::vector<float>(expected[i].size(), -1.0f));
      else
        EXPECT_EQ(out[i], expected[i]) << threads << " threads, instance " << i;
    }
    prt_workers_destroy(workers);
  }
}

// A source's field is cast only at the points receivers' cells read: after a frame, every point
// that some cell reads holds bitwise what casting the whole field gives.
TEST(ShadowfieldScene, EveryFieldPointACellReadsIsCast) {
  BusyScene busy;
  const std::vector<float> light = test_light(4);
  busy.scene.shade(light, kNearEye, 2);
  const prt_shadowfield_scene* scene = busy.scene.scene;
  const uint32_t n2 = scene->order * scene->order;
  uint64_t checked = 0;
  for (uint32_t s = 0; s < scene->instance_count; ++s) {
    const prt_sf_instance& source = scene->instances[s];
    if (!source.is_source) continue;
    const prt_sf_object* object = scene->objects[source.object];
    const uint64_t points = prt_sf_point_count(&object->srf_shells);
    std::vector<float> whole(points * n2 * 3);
    scene->kernels->cast_field(object, source.weights, whole.data(), 0, points);
    for (uint32_t r = 0; r < scene->instance_count; ++r) {
      const prt_sf_instance& receiver = scene->instances[r];
      const uint32_t vertices = scene->objects[receiver.object]->vertex_count;
      for (uint32_t q = 0; q < receiver.pair_count; ++q) {
        const prt_sf_pair& pair = scene->pairs[receiver.pair_first + q];
        if (pair.other != s || !pair.lights) continue;
        for (uint32_t v = 0; v < vertices; ++v) {
          ASSERT_EQ(receiver.located[v], scene->frame);
          const prt_sf_cell& cell = scene->cells[receiver.cell_first + v * receiver.pair_count + q];
          checked += expect_cell_points_cast(source, object, whole, cell, n2);
        }
      }
    }
  }
  EXPECT_GT(checked, 0u);
}

}  // namespace
}  // namespace prt::test
