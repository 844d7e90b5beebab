// SPDX-License-Identifier: MIT
#include "glossy_lobe.hpp"

#include <algorithm>
#include <cmath>

#include "../common/numbers.hpp"
#include "prt/baker/sampling.hpp"

namespace prt::bake::render {
namespace {

// Cosine sampling keeps this share at least, so every direction of the hemisphere has density
// whatever the lobe's shape.
constexpr double kLargestLobeShare = 0.9;

// A unit vector's orthonormal completion (Duff et al.), in double.
void complete_basis(const glm::dvec3& n, glm::dvec3* t, glm::dvec3* b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  *t = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  *b = glm::dvec3(c, sign + n.y * n.y * a, -n.y);
}

double lobe_share_of(const SurfaceBrdf& brdf) {
  if (brdf.model == SurfaceBrdf::Model::Ggx) return kLargestLobeShare;
  const double total = brdf.phong.specular + brdf.phong.diffuse;
  return total > 0.0 ? kLargestLobeShare * brdf.phong.specular / total : 0.0;
}

}  // namespace

GlossyLobe::GlossyLobe(const SurfaceBrdf& brdf, const glm::vec3& normal, const glm::vec3& outgoing)
    : brdf_(brdf), lobe_share_(lobe_share_of(brdf)) {
  n_ = glm::normalize(glm::dvec3(normal));
  complete_basis(n_, &t_, &b_);
  outgoing_ = to_local(outgoing);
  mirror_ = glm::dvec3(-outgoing_.x, -outgoing_.y, outgoing_.z);
}

glm::dvec3 GlossyLobe::to_local(const glm::vec3& w) const {
  const glm::dvec3 d(w);
  return glm::dvec3(glm::dot(d, t_), glm::dot(d, b_), glm::dot(d, n_));
}

glm::vec3 GlossyLobe::to_world(const glm::dvec3& local) const {
  return glm::vec3(glm::normalize(t_ * local.x + b_ * local.y + n_ * local.z));
}

double GlossyLobe::f(const glm::vec3& w) const {
  const glm::dvec3 local = to_local(w);
  return brdf_.model == SurfaceBrdf::Model::Phong ? evaluate_brdf(brdf_.phong, local, outgoing_)
                                                  : evaluate_brdf(brdf_.ggx, local, outgoing_);
}

glm::dvec3 GlossyLobe::sample_lobe(const glm::dvec2& u) const {
  const double phi = 2.0 * kPi * u.y;
  if (brdf_.model == SurfaceBrdf::Model::Phong) {
    // cos^n about the mirror direction: cos(a) = u^(1 / (n + 1)).
    const double cos_a = std::pow(u.x, 1.0 / (brdf_.phong.exponent + 1.0));
    const double sin_a = std::sqrt(std::max(0.0, 1.0 - cos_a * cos_a));
    glm::dvec3 t, b;
    complete_basis(mirror_, &t, &b);
    return t * (sin_a * std::cos(phi)) + b * (sin_a * std::sin(phi)) + mirror_ * cos_a;
  }
  // GGX: the half vector from D(h) cos(h), tan^2(theta_h) = alpha^2 u / (1 - u); w its mirror.
  const double alpha = brdf_.ggx.alpha;
  const double cos_h = 1.0 / std::sqrt(1.0 + alpha * alpha * u.x / (1.0 - u.x));
  const double sin_h = std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h));
  const glm::dvec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
  return 2.0 * glm::dot(outgoing_, h) * h - outgoing_;
}

double GlossyLobe::lobe_pdf(const glm::dvec3& w) const {
  if (brdf_.model == SurfaceBrdf::Model::Phong) {
    const double c = glm::dot(w, mirror_);
    const double n = brdf_.phong.exponent;
    return c > 0.0 ? (n + 1.0) / (2.0 * kPi) * std::pow(c, n) : 0.0;
  }
  const glm::dvec3 sum = w + outgoing_;
  const double length = glm::length(sum);
  if (!(length > 0.0)) return 0.0;
  const glm::dvec3 h = sum / length;
  const double cos_oh = glm::dot(outgoing_, h);
  if (!(h.z > 0.0) || !(cos_oh > 0.0)) return 0.0;
  return ggx_distribution(brdf_.ggx.alpha, h.z) * h.z / (4.0 * cos_oh);
}

GlossyLobe::Sample GlossyLobe::sample(const glm::vec2& u) const {
  const double q = lobe_share_;
  if (u.x < q) {
    const double ux = std::min(u.x / q, 1.0 - 1e-12);
    return {to_world(sample_lobe(glm::dvec2(ux, u.y))), true};
  }
  const double ux = (u.x - q) / (1.0 - q);
  const glm::vec3 local = cosine_hemisphere(glm::vec2(static_cast<float>(ux), u.y));
  return {to_world(glm::dvec3(local)), false};
}

GlossyLobe::Densities GlossyLobe::densities(const glm::vec3& w) const {
  const glm::dvec3 local = to_local(w);
  Densities d;
  d.cosine = local.z > 0.0 ? (1.0 - lobe_share_) * local.z / kPi : 0.0;
  d.lobe = lobe_share_ > 0.0 ? lobe_share_ * lobe_pdf(local) : 0.0;
  return d;
}

}  // namespace prt::bake::render
