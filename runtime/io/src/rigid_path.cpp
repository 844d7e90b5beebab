// SPDX-License-Identifier: MIT
#include "prt/io/rigid_path.hpp"

#include <cmath>
#include <string>

#include "prt/io/error.hpp"

namespace prt::io {
namespace {

bool finite(const RigidPlacement& p) {
  const glm::quat& q = p.rotation;
  return std::isfinite(p.translation.x) && std::isfinite(p.translation.y) &&
         std::isfinite(p.translation.z) && std::isfinite(q.w) && std::isfinite(q.x) &&
         std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(p.scale);
}

RigidPlacement interpolate(const RigidPlacement& a, const RigidPlacement& b, float t) {
  RigidPlacement p;
  p.translation = glm::mix(a.translation, b.translation, t);
  p.scale = a.scale + (b.scale - a.scale) * t;
  // glm::slerp takes the shorter arc; renormalised so that long loops cannot drift.
  p.rotation = glm::normalize(glm::slerp(a.rotation, b.rotation, t));
  return p;
}

}  // namespace

void RigidPlacement::to_rows(float rows[9]) const {
  const glm::mat3 m = glm::mat3_cast(rotation);  // column-major: m[column][row]
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) rows[3 * r + c] = m[c][r];
}

void RigidPath::check() const {
  if (keyframes.empty()) throw Error("path: no keyframe");
  if (moves() && !(std::isfinite(duration) && duration > 0.0f))
    throw Error("path: duration must be finite and > 0");
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const RigidKeyframe& k = keyframes[i];
    const std::string which = "path: keyframe " + std::to_string(i);
    if (!finite(k.placement) || !std::isfinite(k.time)) throw Error(which + " is not finite");
    if (!(k.placement.scale > 0.0f)) throw Error(which + ": scale must be > 0");
    if (glm::length(k.placement.rotation) < 1e-6f) throw Error(which + ": zero rotation");
    if (moves() && (k.time < 0.0f || k.time >= duration))
      throw Error(which + ": time outside [0, duration)");
    if (i > 0 && !(k.time > keyframes[i - 1].time)) throw Error(which + ": times not ascending");
  }
}

RigidPlacement RigidPath::at(float time) const {
  check();
  if (!moves()) {
    RigidPlacement p = keyframes[0].placement;
    p.rotation = glm::normalize(p.rotation);
    return p;
  }
  if (!std::isfinite(time)) throw Error("path: time is not finite");
  float tau = std::fmod(time, duration);
  if (tau < 0.0f) tau += duration;
  // The wrap-around segment runs from the last keyframe to the first one, a period later.
  const RigidKeyframe& first = keyframes.front();
  const RigidKeyframe& last = keyframes.back();
  if (tau < first.time || tau >= last.time) {
    const float start = last.time, end = first.time + duration;
    const float local = tau < first.time ? tau + duration : tau;
    return interpolate(last.placement, first.placement, (local - start) / (end - start));
  }
  std::size_t i = 1;
  while (keyframes[i].time <= tau) ++i;
  const RigidKeyframe& a = keyframes[i - 1];
  const RigidKeyframe& b = keyframes[i];
  return interpolate(a.placement, b.placement, (tau - a.time) / (b.time - a.time));
}

}  // namespace prt::io
