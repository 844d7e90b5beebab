// SPDX-License-Identifier: MIT
// Scripted, looping paths of shadowfield instances (shadowfield_scenes.hpp).
#include <cmath>
#include <string>

#include "prt/baker/context.hpp"
#include "prt/baker/shadowfield/shadowfield_scenes.hpp"

namespace prt::bake {
namespace {

bool finite(const ShadowfieldPlacement& p) {
  const glm::quat& q = p.rotation;
  return std::isfinite(p.translation.x) && std::isfinite(p.translation.y) &&
         std::isfinite(p.translation.z) && std::isfinite(q.w) && std::isfinite(q.x) &&
         std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(p.scale);
}

ShadowfieldPlacement interpolate(const ShadowfieldPlacement& a, const ShadowfieldPlacement& b,
                                 float t) {
  ShadowfieldPlacement p;
  p.translation = glm::mix(a.translation, b.translation, t);
  p.scale = a.scale + (b.scale - a.scale) * t;
  // glm::slerp takes the shorter arc; renormalised so that long loops cannot drift.
  p.rotation = glm::normalize(glm::slerp(a.rotation, b.rotation, t));
  return p;
}

}  // namespace

void ShadowfieldPath::check() const {
  if (keyframes.empty()) throw Error("shadowfield path: no keyframe");
  const bool loops = keyframes.size() > 1;
  if (loops && !(std::isfinite(duration) && duration > 0.0f))
    throw Error("shadowfield path: duration must be finite and > 0");
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const ShadowfieldKeyframe& k = keyframes[i];
    const std::string which = "shadowfield path: keyframe " + std::to_string(i);
    if (!finite(k.placement) || !std::isfinite(k.time)) throw Error(which + " is not finite");
    if (!(k.placement.scale > 0.0f)) throw Error(which + ": scale must be > 0");
    if (glm::length(k.placement.rotation) < 1e-6f) throw Error(which + ": zero rotation");
    if (loops && (k.time < 0.0f || k.time >= duration))
      throw Error(which + ": time outside [0, duration)");
    if (i > 0 && !(k.time > keyframes[i - 1].time)) throw Error(which + ": times not ascending");
  }
}

ShadowfieldPlacement ShadowfieldPath::at(float time) const {
  check();
  if (keyframes.size() == 1) {
    ShadowfieldPlacement p = keyframes[0].placement;
    p.rotation = glm::normalize(p.rotation);
    return p;
  }
  if (!std::isfinite(time)) throw Error("shadowfield path: time is not finite");
  float tau = std::fmod(time, duration);
  if (tau < 0.0f) tau += duration;
  // The wrap-around segment runs from the last keyframe to the first one, a period later.
  const ShadowfieldKeyframe& first = keyframes.front();
  const ShadowfieldKeyframe& last = keyframes.back();
  if (tau < first.time || tau >= last.time) {
    const float start = last.time, end = first.time + duration;
    const float local = tau < first.time ? tau + duration : tau;
    return interpolate(last.placement, first.placement, (local - start) / (end - start));
  }
  std::size_t i = 1;
  while (keyframes[i].time <= tau) ++i;
  const ShadowfieldKeyframe& a = keyframes[i - 1];
  const ShadowfieldKeyframe& b = keyframes[i];
  return interpolate(a.placement, b.placement, (tau - a.time) / (b.time - a.time));
}

}  // namespace prt::bake
