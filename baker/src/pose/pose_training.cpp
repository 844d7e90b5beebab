// SPDX-License-Identifier: MIT
// The training data of technique `pose` (James and Fatahalian 2003): every sampled frame of a
// character's clips posed, moved into that frame's model frame (formats/SPEC.md §7.3) and given
// its grey SH transfer.
#include <chrono>
#include <string>

#include "prt/baker/animation.hpp"
#include "prt/baker/pose/pose_training.hpp"

namespace prt::bake {
namespace {

// A clip's name as the settings select it: its own, or "animation <index>" when it has none.
std::string clip_name(const Scene& scene, std::size_t index) {
  const std::string& name = scene.animations[index].name;
  return name.empty() ? "animation " + std::to_string(index) : name;
}

// The clips to sample, in file order: all of them, or those the settings name.
std::vector<std::size_t> chosen_clips(const Scene& scene, const std::vector<std::string>& names) {
  const std::string file = scene.source.empty() ? std::string("scene") : scene.source;
  if (scene.animations.empty())
    throw Error(file + ": pose training needs an animation clip; it has none");
  std::vector<std::size_t> out;
  if (names.empty()) {
    for (std::size_t i = 0; i < scene.animations.size(); ++i) out.push_back(i);
    return out;
  }
  std::vector<unsigned char> chosen(scene.animations.size(), 0);
  for (const std::string& name : names) {
    bool found = false;
    for (std::size_t i = 0; i < scene.animations.size(); ++i) {
      if (clip_name(scene, i) == name) {
        chosen[i] = 1;
        found = true;
      }
    }
    if (!found) {
      std::string available;
      for (std::size_t i = 0; i < scene.animations.size(); ++i)
        available += (i ? ", '" : "'") + clip_name(scene, i) + "'";
      throw Error(file + ": no animation clip named '" + name + "' (the file has " + available +
                  ")");
    }
  }
  for (std::size_t i = 0; i < chosen.size(); ++i)
    if (chosen[i]) out.push_back(i);
  return out;
}

// SPEC §7.3's transform G_j of every joint at the pose's local transforms.
std::vector<glm::mat4> joint_globals(const PoseSkeleton& skeleton, const std::vector<int>& nodes,
                                     const ScenePose& pose) {
  std::vector<glm::mat4> g(skeleton.joints.size(), glm::mat4(1.0f));
  for (std::uint32_t j : skeleton.eval_order) {
    const PoseSkeleton::Joint& joint = skeleton.joints[j];
    const glm::mat4 local = pose.local(static_cast<std::size_t>(nodes[j])).matrix();
    g[j] = joint.parent >= 0 ? g[static_cast<std::size_t>(joint.parent)] * joint.pre * local
                             : joint.pre * local;
  }
  return g;
}

// The model frame M = [R | o] of G_m: o its translation, R its 3x3 part made orthonormal by
// Gram-Schmidt.
struct ModelFrame {
  glm::dmat3 rotation{1.0};
  glm::dvec3 origin{0.0};
};

ModelFrame model_frame(const glm::mat4& g) {
  ModelFrame m;
  const glm::dvec3 x = glm::normalize(glm::dvec3(g[0]));
  const glm::dvec3 y = glm::normalize(glm::dvec3(g[1]) - glm::dot(glm::dvec3(g[1]), x) * x);
  m.rotation = glm::dmat3(x, y, glm::cross(x, y));
  m.origin = glm::dvec3(g[3]);
  return m;
}

// Moves every mesh of a posed scene into the model frame: x = R^T (x_world - o), n = R^T n.
void into_model_frame(const ModelFrame& m, Scene& posed) {
  const glm::dmat3 to_model = glm::transpose(m.rotation);
  for (Mesh& mesh : posed.meshes) {
    for (glm::vec3& p : mesh.positions) p = glm::vec3(to_model * (glm::dvec3(p) - m.origin));
    for (glm::vec3& n : mesh.normals) n = glm::vec3(to_model * glm::dvec3(n));
    for (glm::vec4& t : mesh.tangents)
      t = glm::vec4(glm::vec3(to_model * glm::dvec3(glm::vec3(t))), t.w);
  }
}

// What posing needs of `scene`, without the images and clips every posed copy would otherwise
// carry.
Scene pose_posing_shape(const Scene& scene) {
  Scene shape;
  shape.source = scene.source;
  shape.meshes = scene.meshes;
  shape.materials = scene.materials;
  shape.nodes = scene.nodes;
  shape.skins = scene.skins;
  return shape;
}

// The transfer of every frame: grey, one albedo for every vertex (the first component of the
// settings' albedo), computed for one channel's worth and read from channel 0.
ShTransferSettings pose_grey_transfer_settings(const PoseTrainingSettings& settings) {
  ShTransferSettings transfer = settings.transfer;
  transfer.override_albedo = true;
  transfer.albedo = glm::vec3(settings.transfer.albedo.r);
  return transfer;
}

}  // namespace

PoseTrainingSet sample_pose_training(const Scene& scene, const PoseTrainingSettings& settings) {
  PoseTrainingSet out;
  out.skeleton = pose_skeleton(scene);
  const std::vector<std::size_t> clips = chosen_clips(scene, settings.clips);
  const ShTransferSettings transfer = pose_grey_transfer_settings(settings);
  out.order = transfer.order;
  out.albedo = transfer.albedo.r;
  out.kind = transfer.kind;
  out.bounces = transfer.kind == ShTransferKind::Interreflected ? transfer.bounces : 0;
  out.vertex_count = scene.vertex_count();

  const Scene shape = pose_posing_shape(scene);
  const std::vector<int>& joint_nodes = scene.skins[0].joints;
  for (std::size_t c = 0; c < clips.size(); ++c) {
    out.clip_names.push_back(clip_name(scene, clips[c]));
    for (float t : clip_times(scene.animations[clips[c]], settings.rate)) {
      ScenePose pose(shape);
      pose.apply(scene.animations[clips[c]], t);
      PoseFrame frame;
      frame.clip = static_cast<std::uint32_t>(c);
      frame.time = t;
      for (int node : joint_nodes)
        frame.rotations.push_back(pose.local(static_cast<std::size_t>(node)).rotation);
      frame.features = pose_features(out.skeleton, frame.rotations);
      const std::vector<float> normals = skinned_model_normals(out.skeleton, frame.rotations);
      out.normals.insert(out.normals.end(), normals.begin(), normals.end());
      out.frames.push_back(std::move(frame));
    }
  }
  return out;
}

PoseFramesTransfer bake_pose_frames(const Scene& scene, const PoseTrainingSettings& settings,
                                    const PoseTrainingSet& sampled, std::size_t first,
                                    std::size_t count, const Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  if (first > sampled.frames.size() || count > sampled.frames.size() - first) {
    throw Error("pose training: frames [" + std::to_string(first) + ", " +
                std::to_string(first + count) + ") are beyond the " +
                std::to_string(sampled.frames.size()) + " frames of the clips");
  }
  const std::vector<std::size_t> clips = chosen_clips(scene, settings.clips);
  const ShTransferSettings transfer = pose_grey_transfer_settings(settings);
  const Scene shape = pose_posing_shape(scene);
  const std::vector<int>& joint_nodes = scene.skins[0].joints;
  const std::size_t coefficients = sampled.coefficient_count();

  PoseFramesTransfer out;
  out.transfer.reserve(count * sampled.vertex_count * coefficients);
  const double total = static_cast<double>(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (ctx.progress && !ctx.progress(static_cast<double>(i) / total, "pose training")) {
      throw Error("cancelled");
    }
    const PoseFrame& frame = sampled.frames[first + i];
    ScenePose pose(shape);
    pose.apply(scene.animations[clips[frame.clip]], frame.time);
    Scene posed = posed_scene(shape, pose);
    const std::vector<glm::mat4> g = joint_globals(sampled.skeleton, joint_nodes, pose);
    into_model_frame(model_frame(g[sampled.skeleton.model_joint]), posed);

    // The frame's own progress is a share of the whole; a cancel inside it ends the bake.
    Context frame_ctx = ctx;
    if (ctx.progress) {
      frame_ctx.progress = [&ctx, i, total](double fraction, const std::string&) {
        return ctx.progress((static_cast<double>(i) + fraction) / total, "pose training");
      };
    }
    // Every frame traces the same directions per vertex (from the seed and the vertex): a
    // frame's transfer is a function of its pose alone, whichever frames are baked with it.
    const ShTransfer t = compute_sh_transfer(posed, nullptr, transfer, frame_ctx);
    out.rays_traced += t.rays_traced;
    for (std::size_t v = 0; v < t.vertex_count; ++v) {
      const float* grey = t.vertex_channel(v, 0);
      out.transfer.insert(out.transfer.end(), grey, grey + coefficients);
    }
  }
  if (ctx.progress && !ctx.progress(1.0, "pose training")) throw Error("cancelled");
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

PoseTrainingSet bake_pose_training(const Scene& scene, const PoseTrainingSettings& settings,
                                   const Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  PoseTrainingSet out = sample_pose_training(scene, settings);
  PoseFramesTransfer frames = bake_pose_frames(scene, settings, out, 0, out.frames.size(), ctx);
  out.transfer = std::move(frames.transfer);
  out.rays_traced = frames.rays_traced;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace prt::bake
