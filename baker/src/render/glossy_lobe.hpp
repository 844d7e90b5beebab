// SPDX-License-Identifier: MIT
// A glossy BRDF at one path vertex: its exact value, and its two sampling strategies,
// cosine-weighted and lobe sampling, picked at random for each sample (private header).
#pragma once

#include <glm/glm.hpp>

#include "prt/baker/reference.hpp"

namespace prt::bake::render {

class GlossyLobe {
 public:
  // `brdf` is Phong or GGX; normal and outgoing (towards the viewer) are unit, world space.
  GlossyLobe(const SurfaceBrdf& brdf, const glm::vec3& normal, const glm::vec3& outgoing);

  // False when the viewer is on or below the surface's horizon: f is 0 for every w.
  bool visible() const { return outgoing_.z > 0.0; }
  // f(w, wo) of shadowfield_brdf.hpp, w unit in world space (no albedo, no cosine).
  double f(const glm::vec3& w) const;
  // The BRDF's two sampling strategies, as one sample: lobe sampling with probability
  // q = lobe_share(), else cosine-weighted (u.x picks the strategy and is rescaled, so the
  // point's stratification carries over). The direction may lie below the horizon (then f is 0
  // there).
  struct Sample {
    glm::vec3 direction;
    bool from_lobe = false;
  };
  Sample sample(const glm::vec2& u) const;
  // Each strategy's density in solid angle at w times its probability of being picked:
  // (1 - q) p_cos(w) and q p_lobe(w). Their sum is the density of sample()'s direction.
  struct Densities {
    double cosine = 0.0, lobe = 0.0;
    double sum() const { return cosine + lobe; }
  };
  Densities densities(const glm::vec3& w) const;
  double lobe_share() const { return lobe_share_; }

 private:
  glm::dvec3 to_local(const glm::vec3& w) const;
  glm::vec3 to_world(const glm::dvec3& local) const;
  double lobe_pdf(const glm::dvec3& w) const;
  glm::dvec3 sample_lobe(const glm::dvec2& u) const;

  SurfaceBrdf brdf_;
  glm::dvec3 t_, b_, n_;  // the shading frame
  glm::dvec3 outgoing_;   // local
  glm::dvec3 mirror_;     // local mirror of the outgoing direction about the normal
  double lobe_share_ = 0.0;
};

}  // namespace prt::bake::render
