// SPDX-License-Identifier: MIT
// The shadowfield bake's self-check and what the trade shares with it: the object shaded alone
// by the runtime, and the same radiance evaluated from the float object with its quantisation
// bound.
#include <prt/prt_shadowfield.h>
#include <prt/prt_shadowfield_asset.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "prt/baker/sampling.hpp"
#include "prt/baker/text.hpp"

#include "../common/technique_blob.hpp"
#include "shadowfield_technique.hpp"

namespace prt::bake {
namespace {

// Float rounding of the runtime's sums (light rotation, dot products, the g table read), relative
// to the sum of the magnitudes it adds up.
constexpr double kFloatSlack = 1e-5;

void check_call(prt_result result, const char* what) {
  if (result != PRT_OK) throw Error(std::string(what) + " failed: " + prt_result_string(result));
}

// How far a reader's offset + scale q of the transfer's row can be from the float value: half a
// step, and the float rounding of a value as large as the row's largest.
double dequantised_error(const QuantizedShadowfield& quantized, std::size_t row) {
  const double offset = quantized.transfer.offsets[row], scale = quantized.transfer.scales[row];
  const double largest =
      std::max(std::abs(offset), std::abs(offset + scale * double((1u << quantized.bits) - 1u)));
  return 0.5 * scale + 2.0 * std::numeric_limits<float>::epsilon() * largest;
}

// The outgoing direction towards `eye` from `position` in the tangent frame of `normal`, unit;
// the normal itself when the eye is at the vertex (as the runtime takes it).
glm::dvec3 outgoing_direction(const glm::vec3& position, const glm::vec3& normal,
                              const glm::vec3& eye) {
  const Frame frame(normal);
  const glm::vec3 to_eye = eye - position;
  // In double from the float operands, as the runtime does, so both see the same side.
  const auto dot = [&to_eye](const glm::vec3& axis) {
    return double(axis.x) * to_eye.x + double(axis.y) * to_eye.y + double(axis.z) * to_eye.z;
  };
  glm::dvec3 wo(dot(frame.t), dot(frame.b), dot(normal));
  if (wo == glm::dvec3(0.0)) wo.z = 1.0;
  return glm::normalize(wo);
}

// A few lights at the object's order: a constant sky, then lights with every coefficient set,
// decreasing by band, different per channel (not physical: they exercise every coefficient).
std::vector<std::vector<float>> check_lights(std::uint32_t order) {
  std::vector<std::vector<float>> lights;
  const std::size_t n2 = std::size_t(order) * order;
  for (int which = 0; which < 3; ++which) {
    std::vector<float> light(3 * n2, 0.0f);
    for (std::size_t i = 0; i < n2; ++i) {
      const double band = std::floor(std::sqrt(double(i)));
      for (int c = 0; c < 3; ++c) {
        const double varying = std::sin(1.7 * double(i) + 0.9 * c + 2.3 * which) / (1.0 + band);
        light[3 * i + c] = static_cast<float>(i == 0 ? 3.5449077 : which == 0 ? 0.0 : varying);
      }
    }
    lights.push_back(std::move(light));
  }
  return lights;
}

// Eyes around the object's bounding sphere, so glossy terms are read at several directions.
std::vector<glm::vec3> check_eyes(const prt_sf_shells& shells) {
  const glm::vec3 c(shells.centre[0], shells.centre[1], shells.centre[2]);
  const float d = 3.0f * shells.radius;
  return {c + glm::vec3(0.0f, 0.3f * d, d), c + glm::vec3(d, 0.5f * d, -0.2f * d),
          c + glm::vec3(-0.4f * d, -d, 0.1f * d)};
}

std::string header_mismatch(const prt_shadowfield_info& info, const ShadowfieldObject& object,
                            const QuantizedShadowfield& quantized) {
  if (info.order != object.order) return "order";
  if (info.terms != object.material.terms()) return "terms";
  if (info.glossy != (object.material.glossy ? 1u : 0u)) return "glossy";
  if (info.vertex_count != object.positions.size()) return "vertex count";
  if (info.basis_size != object.basis_size) return "basis size";
  if (info.bits != quantized.bits) return "bits";
  if (info.oof_shells.shells != object.oof_shells.shells ||
      info.oof_shells.face_size != object.oof_shells.face_size)
    return "occlusion field shells";
  if (info.srf_shells.shells != object.srf_shells.shells ||
      info.srf_shells.face_size != object.srf_shells.face_size)
    return "source radiance field shells";
  return {};
}

}  // namespace

prt_shadowfield_transform shadowfield_transform(const glm::mat3& rotation,
                                                const glm::vec3& translation) {
  prt_shadowfield_transform t{};
  t.struct_size = sizeof t;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) t.rotation[3 * row + col] = rotation[col][row];
    t.translation[row] = translation[row];
  }
  t.scale = 1.0f;
  return t;
}

LoneShadowfieldScene::LoneShadowfieldScene(const prt_asset* asset,
                                           const prt_shadowfield_transform& transform)
    : scene_(nullptr, prt_shadowfield_scene_destroy) {
  auto [context, made] = prt::create_context();
  check_call(made, "prt_context_create");
  context_ = std::move(context);
  prt_shadowfield_scene* raw = nullptr;
  check_call(prt_shadowfield_scene_create(context_.get(), 1, &raw), "prt_shadowfield_scene_create");
  scene_.reset(raw);
  std::uint32_t object = 0, instance = 0;
  check_call(prt_shadowfield_scene_add_object(raw, asset, &object),
             "prt_shadowfield_scene_add_object");
  check_call(prt_shadowfield_scene_add_instance(raw, object, &transform, &instance),
             "prt_shadowfield_scene_add_instance");
  vertices_ = prt_shadowfield_instance_vertex_count(raw, instance);
}

void LoneShadowfieldScene::shade(const std::vector<float>& light_rgb, const glm::vec3& eye,
                                 std::vector<float>* rgb) {
  rgb->resize(std::size_t(3) * vertices_);
  prt_shadowfield_settings settings{};
  settings.struct_size = sizeof settings;
  settings.backend = PRT_BACKEND_CPU;
  float* const out[] = {rgb->data()};
  const float eye_xyz[3] = {eye.x, eye.y, eye.z};
  check_call(prt_shadowfield_shade(scene_.get(), light_rgb.data(), eye_xyz, &settings, out),
             "prt_shadowfield_shade");
}

std::vector<float> shade_lone_shadowfield(const prt_asset* asset,
                                          const prt_shadowfield_transform& transform,
                                          const std::vector<float>& light_rgb,
                                          const glm::vec3& eye) {
  LoneShadowfieldScene scene(asset, transform);
  std::vector<float> rgb;
  scene.shade(light_rgb, eye, &rgb);
  return rgb;
}

std::vector<double> shade_float_shadowfield(const ShadowfieldObject& object,
                                            const std::vector<float>& light_rgb,
                                            const glm::vec3& eye,
                                            const QuantizedShadowfield* quantized,
                                            std::vector<double>* bound) {
  const std::size_t n2 = std::size_t(object.order) * object.order,
                    vertices = object.positions.size();
  const std::uint32_t terms = object.material.terms();
  std::vector<double> rgb(3 * vertices, 0.0);
  if (bound) bound->assign(3 * vertices, 0.0);
  for (std::size_t v = 0; v < vertices; ++v) {
    const glm::dvec3 wo = outgoing_direction(object.positions[v], object.normals[v], eye);
    for (std::uint32_t k = 0; k < terms; ++k) {
      // Seen from behind, a glossy surface reflects nothing towards the eye (as the runtime).
      const double g = !object.material.glossy ? 1.0
                       : wo.z > 0.0            ? object.material.brdf.outgoing_at(k, wo)
                                               : 0.0;
      const float* t = object.transfer.data() + (v * terms + k) * n2;
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0, magnitude = 0.0, step = 0.0;
        for (std::size_t i = 0; i < n2; ++i) {
          const double l = light_rgb[3 * i + c];
          sum += double(t[i]) * l;
          magnitude += std::abs(double(t[i]) * l);
          if (quantized) step += dequantised_error(*quantized, k * n2 + i) * std::abs(l);
        }
        const double a = object.albedo[v][c];
        rgb[3 * v + c] += a * g * sum;
        if (bound) (*bound)[3 * v + c] += a * std::abs(g) * (step + kFloatSlack * magnitude);
      }
    }
  }
  if (bound) {
    for (double& b : *bound) b = b * (1.0 + kFloatSlack) + 1e-7;
  }
  return rgb;
}

ShadowfieldBlobCheck check_shadowfield_blob(const std::vector<std::uint8_t>& blob,
                                            const ShadowfieldObject& object,
                                            const QuantizedShadowfield& quantized) {
  ShadowfieldBlobCheck check;
  const SelfCheckAsset loaded = load_for_self_check(blob);
  if (!loaded.asset) {
    check.message = loaded.failure;
    return check;
  }
  prt_shadowfield_info info = prt::sized<prt_shadowfield_info>();
  const prt_result result = prt_shadowfield_get_info(loaded.asset.get(), &info);
  if (result != PRT_OK) {
    check.message = runtime_failure("prt_shadowfield_get_info", result, loaded.context.get());
    return check;
  }
  const std::string mismatch = header_mismatch(info, object, quantized);
  if (!mismatch.empty()) {
    check.message = "the blob's SFLD header does not match the bake: " + mismatch;
    return check;
  }
  const prt_shadowfield_transform identity =
      shadowfield_transform(glm::mat3(1.0f), glm::vec3(0.0f));
  std::size_t compared = 0;
  try {
    for (const std::vector<float>& light : check_lights(object.order)) {
      for (const glm::vec3& eye : check_eyes(object.oof_shells)) {
        const std::vector<float> runtime =
            shade_lone_shadowfield(loaded.asset.get(), identity, light, eye);
        std::vector<double> bound;
        const std::vector<double> expected =
            shade_float_shadowfield(object, light, eye, &quantized, &bound);
        for (std::size_t i = 0; i < expected.size(); ++i) {
          const double error = std::abs(double(runtime[i]) - expected[i]);
          if (!(error <= bound[i])) {
            check.message = format(
                "vertex %zu channel %zu: runtime %.9g, float object %.9g, "
                "outside the quantisation bound %.3g",
                i / 3, i % 3, double(runtime[i]), expected[i], bound[i]);
            return check;
          }
          check.max_abs_error = std::max(check.max_abs_error, error);
          check.max_budget_ratio = std::max(check.max_budget_ratio, error / bound[i]);
        }
        compared += expected.size();
      }
    }
  } catch (const Error& e) {
    check.message = e.what();
    return check;
  }
  check.passed = true;
  check.message = format("shaded %zu values by the runtime, max error %.3g (%.3f of the bound)",
                         compared, check.max_abs_error, check.max_budget_ratio);
  return check;
}

}  // namespace prt::bake
