// SPDX-License-Identifier: MIT
// Shards of technique `pose` (docs/farm.md): `bake pose --shard i/N` bakes the SH transfer of a
// range of the training frames (every sampled frame of the clips); the merge joins every frame's
// transfer to the training set and leaves the model fit to PoseBake, as bake() does. The frames'
// ray tracing is the bake's cost and is what the shards spread; the merge still samples the
// frames' poses and skinned normals (no rays: cheaper to redo than to ship) and fits the model,
// which needs every frame at once (pose PCA, vertex basis, ridge regression with
// cross-validation over frames and clips).
#include <string>
#include <vector>

#include "prt/baker/pose/pose_training.hpp"

#include "../common/shard_payload.hpp"
#include "pose_technique.hpp"

namespace prt::bake {
namespace {

// A shard's payload: the magic and version, this header, the chosen clips' names (clips_chars
// chars, comma-separated), then the range's transfer (count x vertices x order^2 floats, frame
// by frame as PoseTrainingSet::transfer). Native byte order.
constexpr std::uint32_t kPoseShardMagic = 0x44535350;  // "PSSD"
constexpr std::uint32_t kPoseShardVersion = 1;
struct PoseShardHeader {
  std::uint32_t order = 0, kind = 0, rays = 0, seed = 0;
  std::int32_t bounces = 0;  // the transfer's bounces (0 unless interreflected)
  std::uint32_t model_kind = 0, cv = 0, clamp = 0;
  std::uint32_t bits = 0, pose_dims = 0, basis_dims = 0, subdivide_to = 0;
  glm::vec3 albedo{0.0f};
  std::uint32_t clips_chars = 0;
  double rate = 0.0, pose_variance = 0.0, basis_energy = 0.0, alpha = 0.0;
  std::uint64_t scene = 0;  // shard_scene_fingerprint of the baked (subdivided) scene
  std::uint64_t poses = 0;  // pose_shard_poses_fingerprint
  std::uint64_t vertices = 0, frames = 0, first = 0, count = 0;
  std::uint64_t rays_traced = 0;
  double seconds = 0.0;
};
static_assert(sizeof(PoseShardHeader) == 160, "PoseShardHeader has padding");

// FNV-1a over what poses the character besides its geometry (shard_scene_fingerprint's part):
// the skeleton and skin, and every sampled frame's clip, time and joint rotations. A part baked
// from a file with another rig or other clips is refused even when it has as many frames.
std::uint64_t pose_shard_poses_fingerprint(const PoseTrainingSet& sampled) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  const auto add = [&h](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    for (std::size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 0x100000001b3ull;
  };
  const auto add_vector = [&add](const auto& values) {
    add(values.data(), values.size() * sizeof(values[0]));
  };
  const PoseSkeleton& skeleton = sampled.skeleton;
  for (const PoseSkeleton::Joint& joint : skeleton.joints) {
    add(&joint.parent, sizeof joint.parent);
    add(&joint.bind_rotation, sizeof joint.bind_rotation);
    add(&joint.rest_translation, sizeof joint.rest_translation);
    add(&joint.rest_scale, sizeof joint.rest_scale);
    add(&joint.pre, sizeof joint.pre);
    add(&joint.inverse_bind, sizeof joint.inverse_bind);
  }
  add_vector(skeleton.skin_joints);
  add_vector(skeleton.skin_weights);
  for (const PoseFrame& frame : sampled.frames) {
    add(&frame.clip, sizeof frame.clip);
    add(&frame.time, sizeof frame.time);
    add_vector(frame.rotations);
  }
  return h;
}

std::string pose_shard_clips_text(const std::vector<std::string>& clips) {
  std::string text;
  for (const std::string& clip : clips) text += (text.empty() ? "" : ",") + clip;
  return text;
}

// What a shard of this bake states about it, the range and its figures left 0.
PoseShardHeader pose_shard_header(const Scene& scene, const PoseBakeSettings& settings,
                                  const PoseTrainingSet& sampled) {
  const ShTransferSettings& t = settings.training.transfer;
  const PoseModelSettings& m = settings.model;
  PoseShardHeader h;
  h.order = t.order;
  h.kind = static_cast<std::uint32_t>(t.kind);
  h.rays = t.rays;
  h.seed = t.seed;
  h.bounces = t.kind == ShTransferKind::Interreflected ? t.bounces : 0;
  h.model_kind = static_cast<std::uint32_t>(m.kind);
  h.cv = static_cast<std::uint32_t>(m.cv);
  h.clamp = m.clamp ? 1 : 0;
  h.bits = static_cast<std::uint32_t>(m.bits);
  h.pose_dims = m.pose_dims;
  h.basis_dims = m.basis_dims;
  h.subdivide_to = settings.subdivide_to;
  h.albedo = t.albedo;
  h.clips_chars = static_cast<std::uint32_t>(pose_shard_clips_text(sampled.clip_names).size());
  h.rate = settings.training.rate;
  h.pose_variance = m.pose_variance;
  h.basis_energy = m.basis_energy;
  h.alpha = m.alpha;
  h.scene = shard_scene_fingerprint(scene);
  h.poses = pose_shard_poses_fingerprint(sampled);
  h.vertices = scene.vertex_count();
  h.frames = sampled.frames.size();
  return h;
}

const char* pose_shard_kind_text(std::uint32_t kind) {
  return kind <= 2 ? sh_transfer_kind_name(static_cast<ShTransferKind>(kind)) : "unknown";
}
const char* pose_shard_model_text(std::uint32_t kind) {
  return kind == static_cast<std::uint32_t>(PoseModelKind::Direct) ? "direct" : "residual";
}
const char* pose_shard_cv_text(std::uint32_t cv) {
  if (cv == static_cast<std::uint32_t>(PoseCrossValidation::Frame)) return "frame";
  return cv == static_cast<std::uint32_t>(PoseCrossValidation::Block) ? "block" : "clip";
}

// Error naming every setting of a part that differs from this merge's, as the options spell them
// (the clips by the names they resolve to).
void pose_shard_check_settings(const ShardPayloadReader& in, const PoseShardHeader& h,
                               const std::string& clips, const PoseShardHeader& expected,
                               const std::string& expected_clips) {
  ShardSettingsDiff diff;
  diff.compare("--clips", clips, expected_clips);
  diff.compare("--rate", h.rate, expected.rate);
  diff.compare("--order", h.order, expected.order);
  diff.compare<std::string>("--transfer", pose_shard_kind_text(h.kind),
                            pose_shard_kind_text(expected.kind));
  diff.compare("--rays", h.rays, expected.rays);
  diff.compare("--bounces", h.bounces, expected.bounces);
  diff.compare("--seed", h.seed, expected.seed);
  diff.compare("--albedo", h.albedo, expected.albedo);
  diff.compare<std::string>("--model", pose_shard_model_text(h.model_kind),
                            pose_shard_model_text(expected.model_kind));
  diff.compare("--pose-dims", h.pose_dims, expected.pose_dims);
  diff.compare("--pose-variance", h.pose_variance, expected.pose_variance);
  diff.compare("--basis-dims", h.basis_dims, expected.basis_dims);
  diff.compare("--basis-energy", h.basis_energy, expected.basis_energy);
  diff.compare("--alpha", h.alpha, expected.alpha);
  diff.compare<std::string>("--cv", pose_shard_cv_text(h.cv), pose_shard_cv_text(expected.cv));
  diff.compare<std::string>("--no-clamp", h.clamp ? "not given" : "given",
                            expected.clamp ? "not given" : "given");
  diff.compare("--bits", h.bits, expected.bits);
  diff.compare("--subdivide-to", h.subdivide_to, expected.subdivide_to);
  diff.check(in.who());
}

// Reads a part's magic, version, header and clips; Error naming what differs from `expected`
// (this merge's bake).
PoseShardHeader pose_shard_read_header(ShardPayloadReader& in, const PoseShardHeader& expected,
                                       const std::string& expected_clips) {
  if (in.get<std::uint32_t>() != kPoseShardMagic)
    throw Error(in.who() + " is not a shard of technique pose");
  if (const auto version = in.get<std::uint32_t>(); version != kPoseShardVersion) {
    throw Error(in.who() + " has pose shard version " + std::to_string(version) +
                ", this baker reads " + std::to_string(kPoseShardVersion));
  }
  const PoseShardHeader h = in.get<PoseShardHeader>();
  const std::vector<char> clips = in.get_vector<char>(h.clips_chars);
  pose_shard_check_settings(in, h, std::string(clips.begin(), clips.end()), expected,
                            expected_clips);
  if (h.scene != expected.scene || h.vertices != expected.vertices)
    throw Error(in.who() + " was baked from another scene (its geometry or materials differ)");
  if (h.poses != expected.poses || h.frames != expected.frames) {
    throw Error(in.who() + " was baked from another scene (its skeleton, skin or clips differ)");
  }
  return h;
}

}  // namespace

std::vector<std::uint8_t> bake_pose_shard(const Scene& scene, const PoseBakeSettings& settings,
                                          std::size_t first, std::size_t count,
                                          const Context& ctx) {
  const PoseTrainingSet sampled = sample_pose_training(scene, settings.training);
  const PoseFramesTransfer part =
      bake_pose_frames(scene, settings.training, sampled, first, count, ctx);
  PoseShardHeader h = pose_shard_header(scene, settings, sampled);
  h.first = first;
  h.count = count;
  h.rays_traced = part.rays_traced;
  h.seconds = part.seconds;
  const std::string clips = pose_shard_clips_text(sampled.clip_names);
  ShardPayloadWriter out;
  out.put(kPoseShardMagic);
  out.put(kPoseShardVersion);
  out.put(h);
  out.put_array(clips.data(), clips.size());
  out.put_vector(part.transfer);
  return std::move(out).bytes();
}

PoseTrainingSet merge_pose_shards(const Scene& scene, const PoseBakeSettings& settings,
                                  const std::vector<std::vector<std::uint8_t>>& parts,
                                  const Context& ctx) {
  PoseTrainingSet training = sample_pose_training(scene, settings.training);
  const PoseShardHeader expected = pose_shard_header(scene, settings, training);
  const std::string expected_clips = pose_shard_clips_text(training.clip_names);
  // Every header first: the ranges are checked before a count sizes a read.
  std::vector<ShardPayloadReader> readers;
  readers.reserve(parts.size());
  std::vector<PoseShardHeader> headers;
  std::vector<ShardPartRange> spans;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    readers.emplace_back(parts[i], "pose merge: shard " + std::to_string(i));
    headers.push_back(pose_shard_read_header(readers.back(), expected, expected_clips));
    spans.push_back({headers.back().first, headers.back().count, headers.back().frames});
  }
  check_shard_ranges("pose", "frames", spans, training.frames.size());

  const std::size_t frame_floats = training.vertex_count * training.coefficient_count();
  training.transfer.reserve(training.frames.size() * frame_floats);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::vector<float> transfer =
        readers[i].get_vector<float>(headers[i].count * frame_floats);
    readers[i].finish();
    training.transfer.insert(training.transfer.end(), transfer.begin(), transfer.end());
    training.rays_traced += headers[i].rays_traced;
    training.seconds += headers[i].seconds;  // the frames' tracing, summed over the farm
  }
  if (ctx.progress && !ctx.progress(1.0, "pose training")) throw Error("cancelled");
  return training;
}

}  // namespace prt::bake
