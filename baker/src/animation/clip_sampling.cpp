// SPDX-License-Identifier: MIT
// Keyframe interpolation (glTF 2.0 Appendix C), a scene's node transforms at one instant, and the
// instants a clip is sampled at.
#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "prt/baker/animation.hpp"

namespace prt::bake {
namespace {

using Channel = AnimationChannel;

// Key `key`'s value (part 1 of 3 for cubic splines; 0 = in-tangent, 2 = out-tangent).
glm::vec4 key_value(const Channel& c, std::size_t key, int part) {
  const std::size_t parts = c.interpolation == Channel::Interpolation::CubicSpline ? 3 : 1;
  const std::size_t slot = parts == 3 ? key * 3 + static_cast<std::size_t>(part) : key;
  const float* v = c.values.data() + slot * static_cast<std::size_t>(c.components);
  glm::vec4 out(0.0f);
  for (int i = 0; i < std::min(c.components, 4); ++i) out[i] = v[i];
  return out;
}

glm::vec4 normalized_quat(const glm::vec4& q) {
  const float len = glm::length(q);
  return len > 0.0f && std::isfinite(len) ? q / len : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

// Spherical interpolation along the shorter arc; nearly equal keys are blended linearly, where
// the sine ratio would lose its precision.
glm::vec4 slerp(const glm::vec4& a, glm::vec4 b, float s) {
  float cosine = glm::dot(a, b);
  if (cosine < 0.0f) {
    b = -b;
    cosine = -cosine;
  }
  if (cosine > 0.9995f) return normalized_quat(a + s * (b - a));
  const float angle = std::acos(cosine), sine = std::sin(angle);
  return (std::sin((1.0f - s) * angle) / sine) * a + (std::sin(s * angle) / sine) * b;
}

// Hermite segment between keys k and k+1 at s in [0,1] over an interval of dt seconds.
glm::vec4 cubic(const Channel& c, std::size_t k, float s, float dt) {
  const float s2 = s * s, s3 = s2 * s;
  return (2.0f * s3 - 3.0f * s2 + 1.0f) * key_value(c, k, 1) +
         dt * (s3 - 2.0f * s2 + s) * key_value(c, k, 2) +
         (-2.0f * s3 + 3.0f * s2) * key_value(c, k + 1, 1) +
         dt * (s3 - s2) * key_value(c, k + 1, 0);
}

glm::vec4 interpolate(const Channel& c, float time) {
  const std::vector<float>& t = c.times;
  if (!(time > t.front())) return key_value(c, 0, 1);  // before the first key, or NaN
  if (time >= t.back()) return key_value(c, t.size() - 1, 1);
  // t[k] <= time < t[k+1], so the interval is never empty.
  const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time) - t.begin()) - 1;
  const float dt = t[k + 1] - t[k], s = (time - t[k]) / dt;
  const bool rotation = c.path == Channel::Path::Rotation;
  switch (c.interpolation) {
    case Channel::Interpolation::Step:
      return key_value(c, k, 1);
    case Channel::Interpolation::CubicSpline:
      return cubic(c, k, s, dt);
    case Channel::Interpolation::Linear:
      break;
  }
  const glm::vec4 a = key_value(c, k, 1), b = key_value(c, k + 1, 1);
  return rotation ? slerp(normalized_quat(a), normalized_quat(b), s) : a + s * (b - a);
}

}  // namespace

glm::mat4 NodeTRS::matrix() const {
  // The importer's expression for a node's local matrix, so that an untouched node gives the
  // same bits either way.
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
         glm::scale(glm::mat4(1.0f), scale);
}

glm::vec4 sample_channel(const AnimationChannel& channel, float time) {
  if (channel.times.empty()) throw Error("animation channel without keyframes");
  const glm::vec4 value = interpolate(channel, time);
  return channel.path == Channel::Path::Rotation ? normalized_quat(value) : value;
}

ScenePose::ScenePose(const Scene& scene)
    : scene_(&scene), local_(scene.nodes.size()), from_file_(scene.nodes.size(), 1) {
  for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
    local_[n] = {scene.nodes[n].translation, scene.nodes[n].rotation, scene.nodes[n].scale};
    if (scene.nodes[n].parent < 0) parents_first_.push_back(static_cast<int>(n));
  }
  for (std::size_t i = 0; i < parents_first_.size(); ++i)  // grows as children are appended
    for (int child : scene.nodes[static_cast<std::size_t>(parents_first_[i])].children)
      parents_first_.push_back(child);
}

void ScenePose::set_local(std::size_t node, const NodeTRS& trs) {
  local_.at(node) = trs;
  from_file_[node] = 0;
}

void ScenePose::apply(const Animation& clip, float time) {
  for (const AnimationChannel& channel : clip.channels) {
    if (channel.path == Channel::Path::Weights) continue;
    if (channel.node < 0 || static_cast<std::size_t>(channel.node) >= local_.size()) {
      throw Error("animation '" + clip.name + "' targets node " + std::to_string(channel.node) +
                  ", which the scene does not have");
    }
    const std::size_t n = static_cast<std::size_t>(channel.node);
    const glm::vec4 v = sample_channel(channel, time);
    switch (channel.path) {
      case Channel::Path::Translation:
        local_[n].translation = glm::vec3(v);
        break;
      case Channel::Path::Rotation:
        local_[n].rotation = glm::quat(v.w, v.x, v.y, v.z);
        break;
      case Channel::Path::Scale:
        local_[n].scale = glm::vec3(v);
        break;
      case Channel::Path::Weights:
        break;
    }
    from_file_[n] = 0;
  }
}

std::vector<glm::mat4> ScenePose::world_matrices() const {
  std::vector<glm::mat4> world(local_.size(), glm::mat4(1.0f));
  for (int node : parents_first_) {
    const std::size_t n = static_cast<std::size_t>(node);
    const Node& source = scene_->nodes[n];
    const glm::mat4 local = from_file_[n] ? source.local : local_[n].matrix();
    world[n] = source.parent >= 0 ? world[static_cast<std::size_t>(source.parent)] * local : local;
  }
  return world;
}

std::vector<float> clip_times(const Animation& clip, double rate) {
  if (!(rate > 0.0) || !std::isfinite(rate)) {
    throw Error("clip sampling rate must be a positive number of frames per second");
  }
  const double duration = std::max(0.0, static_cast<double>(clip.duration));
  // The small allowance keeps a frame that lands on the duration up to rounding.
  const double last = std::floor(duration * rate * (1.0 + 1e-9));
  std::vector<float> times;
  for (double k = 0.0; k <= last; k += 1.0) times.push_back(static_cast<float>(k / rate));
  if (duration - last / rate > 1e-6) times.push_back(static_cast<float>(duration));
  return times;
}

}  // namespace prt::bake
