// SPDX-License-Identifier: MIT
// Technique `pose` in `prt-bake scene` (prt/baker/scene_bake.hpp): it suits a skinned node that a
// clip animates; its ladder climbs the SH order and the model's basis size and bits; its blobs are
// measured on frames of the clips between the training frames: the character posed at each, the
// path tracer's radiance of the posed mesh against the runtime's shading at that frame's joints.
#include <prt/prt_pose_asset.h>
#include <prt/prt.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "prt/baker/animation.hpp"
#include "prt/baker/reference.hpp"
#include "prt/baker/scene_bake.hpp"
#include "prt/baker/sh/env_sh.hpp"

#include "../common/trade_common.hpp"
#include "pose_technique.hpp"

namespace prt::bake {
namespace {

// Training frames per second of clip time: every rung samples the clips the same way, so the
// measured frames can fall midway between training frames.
constexpr double kPoseSceneRate = 15.0;
// Directions per vertex and frame: the bake's default, so the training transfer's own noise is
// small next to what the model's size leaves.
constexpr const char* kPoseSceneRays = "512";
// Measured frames: a few, spread over the clips (at least one per clip, up to the cap).
constexpr std::size_t kPoseMeasuredFrames = 4;
constexpr std::size_t kPoseMeasuredFramesMax = 8;
// SPEC §7.3 stores joint indices as u8.
constexpr std::size_t kPoseMaxJoints = 256;

std::string pose_scene_clip_name(const Scene& scene, std::size_t clip) {
  const std::string& name = scene.animations[clip].name;
  return name.empty() ? "animation " + std::to_string(clip) : name;
}

bool pose_node_is_under(const Scene& scene, int node, int ancestor) {
  for (int n = node; n >= 0; n = scene.nodes[std::size_t(n)].parent) {
    if (n == ancestor) return true;
  }
  return false;
}

// Whether a channel of `clip` (other than morph weights) moves a joint of `skin`: it targets a
// joint or a node above one.
bool pose_clip_moves_skin(const Scene& scene, const Animation& clip, const Skin& skin) {
  for (const AnimationChannel& channel : clip.channels) {
    if (channel.path == AnimationChannel::Path::Weights || channel.node < 0) continue;
    for (int joint : skin.joints) {
      if (pose_node_is_under(scene, joint, channel.node)) return true;
    }
  }
  return false;
}

// The clips that move the node's skin, in file order.
std::vector<std::size_t> pose_moving_clips(const Scene& scene, int node) {
  std::vector<std::size_t> clips;
  const int skin = scene.nodes.at(std::size_t(node)).skin;
  if (skin < 0 || std::size_t(skin) >= scene.skins.size()) return clips;
  for (std::size_t c = 0; c < scene.animations.size(); ++c) {
    if (pose_clip_moves_skin(scene, scene.animations[c], scene.skins[std::size_t(skin)]))
      clips.push_back(c);
  }
  return clips;
}

// The instant midway between the two training frames around `fraction` of the clip (training
// frames at 0, 1/rate, ... and the duration itself; clip_times).
float pose_held_out_time(float duration, double fraction) {
  const double k = std::floor(fraction * duration * kPoseSceneRate);
  const double lo = k / kPoseSceneRate;
  const double hi = std::min(double(duration), (k + 1.0) / kPoseSceneRate);
  return float(0.5 * (lo + std::max(lo, hi)));
}

// One measured frame: the instant and the joints as the runtime takes them (skin joint order).
struct PoseSceneFrame {
  std::size_t clip = 0;
  float time = 0.0f;
  std::vector<float> rotations, translations, scales;  // J x 4 (x y z w), J x 3, J x 3
};

std::vector<PoseSceneFrame> pose_measured_frames(const Scene& object, int node) {
  const std::vector<std::size_t> clips = pose_moving_clips(object, node);
  if (clips.empty()) throw Error("pose: no clip moves the object's skin");
  const Skin& skin = object.skins[std::size_t(object.nodes[std::size_t(node)].skin)];
  const std::size_t total =
      std::min(std::max(kPoseMeasuredFrames, clips.size()), kPoseMeasuredFramesMax);
  // Frame i goes to clip i * clips / total: every clip when there are at most `total`, else an
  // even spread of them.
  std::vector<std::size_t> clip_of(total), per_clip(clips.size(), 0);
  for (std::size_t i = 0; i < total; ++i) {
    clip_of[i] = i * clips.size() / total;
    ++per_clip[clip_of[i]];
  }
  std::vector<PoseSceneFrame> frames;
  std::vector<std::size_t> taken(clips.size(), 0);
  for (std::size_t i = 0; i < total; ++i) {
    const std::size_t c = clip_of[i];
    const Animation& clip = object.animations[clips[c]];
    PoseSceneFrame frame;
    frame.clip = clips[c];
    frame.time =
        pose_held_out_time(clip.duration, (double(taken[c]++) + 0.5) / double(per_clip[c]));
    ScenePose pose(object);
    pose.apply(clip, frame.time);
    for (int joint : skin.joints) {
      const NodeTRS& trs = pose.local(std::size_t(joint));
      frame.rotations.insert(frame.rotations.end(),
                             {trs.rotation.x, trs.rotation.y, trs.rotation.z, trs.rotation.w});
      frame.translations.insert(frame.translations.end(),
                                {trs.translation.x, trs.translation.y, trs.translation.z});
      frame.scales.insert(frame.scales.end(), {trs.scale.x, trs.scale.y, trs.scale.z});
    }
    frames.push_back(std::move(frame));
  }
  return frames;
}

// What one light's measurement adds up over the frames.
struct PoseErrorSums {
  double difference_sq = 0.0, reference_sq = 0.0, noise_sq = 0.0;

  void add(const std::vector<glm::vec3>& estimate, const VertexRadiance& reference) {
    double frame_sq = 0.0;
    for (std::size_t i = 0; i < estimate.size(); ++i) {
      const glm::dvec3 r(reference.radiance[i]);
      const glm::dvec3 d = glm::dvec3(estimate[i]) - r;
      difference_sq += glm::dot(d, d);
      frame_sq += glm::dot(r, r);
    }
    reference_sq += frame_sq;
    noise_sq += reference.relative_rmse * reference.relative_rmse * frame_sq;
  }
};

// The measurement of a pose blob. The error is pooled over the frames (the relative RMSE of all
// frames' probe radiance together, which is the RMS over frames weighted by their energy) rather
// than the worst frame: a handful of frames is a sample of the animation, and the worst of them
// would make the figure depend on how many are sampled and on the noise of each frame's few probe
// vertices; the budget is an RMSE over the animation as it plays. Lights are not pooled: the
// worst light is the figure, as for every technique.
class PoseSceneMeasure final : public ObjectMeasure {
 public:
  explicit PoseSceneMeasure(const ObjectMeasureInput& input)
      : input_(input),
        probes_(spread_vertices(input.object->vertex_count(), input.probe_vertices)),
        frames_(pose_measured_frames(*input.object, input.node)) {
    for (const std::size_t v : probes_) albedo_.push_back(vertex_albedo(v));
  }

  Measurement measure(const Technique&, const std::vector<std::uint8_t>& blob,
                      const Context& ctx) override {
    const trade::RuntimeAsset loaded = trade::load_runtime_asset(blob);
    prt_pose_info info = prt::sized<prt_pose_info>();
    trade::check_runtime(prt_pose_get_info(loaded.asset.get(), &info), "prt_pose_get_info");
    check_fits(info);
    const std::vector<std::vector<float>>& lights = sh_lights(info.order);
    render_references(ctx);
    std::vector<PoseErrorSums> sums(lights.size());
    std::vector<float> shaded(std::size_t(info.vertex_count) * 3);
    for (std::size_t f = 0; f < frames_.size(); ++f) {
      prt_pose_input pose = prt::sized<prt_pose_input>();
      pose.joint_rotations = frames_[f].rotations.data();
      pose.joint_translations = frames_[f].translations.data();
      pose.joint_scales = frames_[f].scales.data();
      for (std::size_t l = 0; l < lights.size(); ++l) {
        // The lights are in the world frame, as the reference sees them; the runtime turns them
        // into the frame's model frame (the identity places the character in the world).
        prt_pose_light light = prt::sized<prt_pose_light>();
        light.light_rgb = lights[l].data();
        trade::check_runtime(prt_pose_shade(loaded.asset.get(), PRT_BACKEND_CPU, &pose, &light, 0,
                                            info.vertex_count, shaded.data()),
                             "prt_pose_shade");
        sums[l].add(at_probes(shaded, info.albedo), references_[l][f]);
      }
    }
    Measurement worst;
    for (std::size_t l = 0; l < sums.size(); ++l) {
      if (!(sums[l].reference_sq > 0.0))
        throw Error("pose: the reference is zero at every probe vertex");
      const double noise = std::sqrt(sums[l].noise_sq / sums[l].reference_sq);
      double error =
          trade::noise_removed(std::sqrt(sums[l].difference_sq / sums[l].reference_sq), noise);
      if (!std::isfinite(error)) error = HUGE_VAL;
      if (l == 0 || error > worst.error) worst = {error, noise};
    }
    return worst;
  }

 private:
  glm::vec3 vertex_albedo(std::size_t vertex) const {
    for (const Mesh& mesh : input_.object->meshes) {
      if (vertex < mesh.vertex_count()) return input_.object->vertex_albedo(mesh, vertex);
      vertex -= mesh.vertex_count();
    }
    return glm::vec3(0.0f);
  }

  void check_fits(const prt_pose_info& info) const {
    if (info.vertex_count != input_.object->vertex_count())
      throw Error("the blob shades " + std::to_string(info.vertex_count) + " vertices, not " +
                  std::to_string(input_.object->vertex_count()));
    if (std::size_t(info.joint_count) * 4 != frames_.front().rotations.size())
      throw Error("the blob has " + std::to_string(info.joint_count) + " joints, not " +
                  std::to_string(frames_.front().rotations.size() / 4));
    if (!(info.albedo > 0.0f)) throw Error("the blob's albedo is not positive");
  }

  // The runtime's radiance is for the grey albedo the blob was baked with; the reference's is
  // for each vertex's own.
  std::vector<glm::vec3> at_probes(const std::vector<float>& shaded, float baked_albedo) const {
    std::vector<glm::vec3> out;
    out.reserve(probes_.size());
    for (std::size_t i = 0; i < probes_.size(); ++i) {
      const float* rgb = shaded.data() + 3 * probes_[i];
      out.push_back(glm::vec3(rgb[0], rgb[1], rgb[2]) * albedo_[i] / baked_albedo);
    }
    return out;
  }

  const std::vector<std::vector<float>>& sh_lights(std::uint32_t order) {
    std::vector<std::vector<float>>& lights = sh_lights_[order];
    if (lights.empty()) {
      for (const io::EnvMap* map : input_.lights)
        lights.push_back(project_env_sh(*map, order).to_float());
    }
    return lights;
  }

  // Each frame's posed character alone, in the world, under each light.
  void render_references(const Context& ctx) {
    if (!references_.empty()) return;
    std::vector<std::vector<VertexRadiance>> references(input_.lights.size());
    ReferenceSettings rs;
    rs.bounces = input_.bounces;
    rs.spp = input_.ref_spp;
    rs.seed = input_.seed;
    for (const PoseSceneFrame& frame : frames_) {
      ScenePose pose(*input_.object);
      pose.apply(input_.object->animations[frame.clip], frame.time);
      const Scene posed = posed_scene(*input_.object, pose);
      for (std::size_t l = 0; l < input_.lights.size(); ++l) {
        const ReferenceRenderer renderer(posed, *input_.lights[l], rs, ctx);
        references[l].push_back(renderer.render_vertices(probes_, ctx));
      }
    }
    references_ = std::move(references);
  }

  ObjectMeasureInput input_;
  std::vector<std::size_t> probes_;
  std::vector<glm::vec3> albedo_;  // of each probe vertex
  std::vector<PoseSceneFrame> frames_;
  std::map<std::uint32_t, std::vector<std::vector<float>>> sh_lights_;  // by SH order
  std::vector<std::vector<VertexRadiance>> references_;                 // [light][frame]
};

}  // namespace

std::vector<std::string> pose_clips_moving_skin(const Scene& scene) {
  std::vector<std::string> names;
  if (scene.skins.size() != 1) return names;
  for (std::size_t c = 0; c < scene.animations.size(); ++c) {
    if (pose_clip_moves_skin(scene, scene.animations[c], scene.skins.front()))
      names.push_back(pose_scene_clip_name(scene, c));
  }
  return names;
}

ObjectFit pose_scene_fit(const Scene& scene, int node) {
  const NodeKind kind = node_kind(scene, node);
  if (!kind.has_mesh) return {false, "no mesh"};
  if (!kind.skinned) return {false, "not skinned"};
  if (scene.skins.size() != 1) {
    return {false, "the scene has " + std::to_string(scene.skins.size()) +
                       " skins; pose bakes a scene with one"};
  }
  if (scene.skins.front().joints.size() > kPoseMaxJoints)
    return {false, "more than " + std::to_string(kPoseMaxJoints) + " joints"};
  const std::vector<std::size_t> clips = pose_moving_clips(scene, node);
  if (clips.empty()) return {false, "skinned but no clip moves it"};
  std::string names;
  for (const std::size_t c : clips)
    names += (names.empty() ? "'" : ", '") + pose_scene_clip_name(scene, c) + "'";
  return {true, "skinned, animated by " + names};
}

std::vector<Rung> pose_scene_ladder(int bounces) {
  struct Candidate {
    std::uint32_t order, basis_dims;
    int bits;
  };
  // Bytes grow with the basis (q values per vertex at `bits`) and the regression ((p + 1) q n²
  // floats): no rung has a lower order, q or bits than the one before, so the ladder is in byte
  // order whatever the character's size. The orders are odd: the clamped cosine has no odd band
  // above 1, so an even order adds little but the occlusion's share of its last band. The order
  // caps what the light can shade; q how much of the occlusion the model can learn.
  const Candidate candidates[] = {{3, 4, 8},  {5, 8, 8},   {5, 16, 8},
                                  {7, 16, 8}, {7, 32, 16}, {7, 64, 16}};
  std::vector<Rung> ladder;
  for (const Candidate& c : candidates) {
    Rung rung;
    rung.args = {"--order", std::to_string(c.order), "--basis-dims", std::to_string(c.basis_dims),
                 "--bits",  std::to_string(c.bits),  "--rate",       format("%g", kPoseSceneRate),
                 "--rays",  kPoseSceneRays};
    if (bounces > 0) {
      rung.args.insert(rung.args.end(),
                       {"--transfer", "interreflected", "--bounces", std::to_string(bounces)});
    } else {
      rung.args.insert(rung.args.end(), {"--transfer", "shadowed"});
    }
    ladder.push_back(std::move(rung));
  }
  return ladder;
}

std::unique_ptr<ObjectMeasure> make_pose_scene_measure(const ObjectMeasureInput& input) {
  return std::make_unique<PoseSceneMeasure>(input);
}

}  // namespace prt::bake
