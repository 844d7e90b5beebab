// SPDX-License-Identifier: MIT
// Technique `pose`: the stored model measured on its training frames, the self-check through
// the runtime, and the bake report.
#include <prt/prt.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "prt/baker/text.hpp"

#include "../common/technique_blob.hpp"
#include "pose_technique.hpp"

namespace prt::bake {
namespace {

// The frames the self-check evaluates: all of them up to this many, else evenly spaced.
constexpr std::size_t kCheckedFrames = 16;

// The runtime's scalar transfer differs from predict_pose_transfer's by its float features,
// coordinates and skinned normals (u16 weights) against the baker's; allowed: this share of the
// frame's largest |t| (a small multiple of what the bakes measure).
constexpr double kCheckRelativeBudget = 2e-3;

std::vector<float> rotations_xyzw(const PoseFrame& frame) {
  std::vector<float> out;
  out.reserve(frame.rotations.size() * 4);
  for (const glm::quat& q : frame.rotations) out.insert(out.end(), {q.x, q.y, q.z, q.w});
  return out;
}

std::vector<std::size_t> checked_frames(std::size_t count) {
  std::vector<std::size_t> frames;
  const std::size_t n = std::min(count, kCheckedFrames);
  for (std::size_t i = 0; i < n; ++i) frames.push_back(n > 1 ? i * (count - 1) / (n - 1) : 0);
  return frames;
}

bool header_matches(const prt_pose_info& info, const PoseTrainingSet& training,
                    const PoseModel& model) {
  return info.order == model.order && info.vertex_count == model.vertex_count &&
         info.joint_count == training.joint_count() && info.pose_dims == model.pose_dims &&
         info.basis_dims == model.basis_dims &&
         info.model == (model.kind == PoseModelKind::Direct ? PRT_POSE_MODEL_DIRECT
                                                            : PRT_POSE_MODEL_RESIDUAL) &&
         info.bits == static_cast<std::uint32_t>(model.bits) &&
         info.model_joint == training.skeleton.model_joint && info.model_bytes == model.model_bytes;
}

// Compares one frame; returns false with check.message set on a runtime failure.
bool check_frame(const prt_asset* asset, const prt_context* context,
                 const PoseTrainingSet& training, const PoseModel& model, std::size_t f,
                 PoseBlobCheck& check) {
  const PoseFrame& frame = training.frames[f];
  const std::vector<float> rotations = rotations_xyzw(frame);
  prt_pose_input pose = prt::sized<prt_pose_input>();
  pose.joint_rotations = rotations.data();
  std::vector<float> runtime(model.vertex_count * model.order * model.order);
  const auto vertices = static_cast<std::uint32_t>(model.vertex_count);
  const prt_result result =
      prt_pose_transfer(asset, PRT_BACKEND_CPU, &pose, nullptr, 0, vertices, runtime.data());
  if (result != PRT_OK) {
    check.message = runtime_failure("prt_pose_transfer", result, context);
    return false;
  }
  const std::vector<float> baker =
      predict_pose_transfer(model, frame.features, training.frame_normals(f));
  double largest = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < baker.size(); ++i) {
    largest = std::max(largest, std::fabs(double(baker[i])));
    worst = std::max(worst, std::fabs(double(runtime[i]) - double(baker[i])));
  }
  const double allowed = kCheckRelativeBudget * std::max(largest, 1e-30);
  check.max_abs_error = std::max(check.max_abs_error, worst);
  check.max_budget_ratio = std::max(check.max_budget_ratio, worst / allowed);
  ++check.frames_checked;
  return true;
}

}  // namespace

PoseFit measure_pose_fit(const PoseTrainingSet& training, const PoseModel& model) {
  PoseFit fit;
  double error = 0.0, energy = 0.0;
  for (std::size_t f = 0; f < training.frames.size(); ++f) {
    const std::vector<float> predicted =
        predict_pose_transfer(model, training.frames[f].features, training.frame_normals(f));
    const float* truth = training.frame_transfer(f);
    double frame_error = 0.0, frame_energy = 0.0;
    for (std::size_t i = 0; i < predicted.size(); ++i) {
      const double d = double(predicted[i]) - double(truth[i]);
      frame_error += d * d;
      frame_energy += double(truth[i]) * double(truth[i]);
    }
    error += frame_error;
    energy += frame_energy;
    if (frame_energy > 0.0) {
      fit.worst_frame_error = std::max(fit.worst_frame_error, frame_error / frame_energy);
    }
  }
  fit.transfer_error = energy > 0.0 ? error / energy : 0.0;
  return fit;
}

PoseBlobCheck check_pose_blob(const std::vector<std::uint8_t>& blob,
                              const PoseTrainingSet& training, const PoseModel& model) {
  PoseBlobCheck check;
  const SelfCheckAsset loaded = load_for_self_check(blob);
  if (!loaded.asset) {
    check.message = loaded.failure;
    return check;
  }
  prt_context* raw_context = loaded.context.get();
  prt_asset* raw_asset = loaded.asset.get();
  prt_pose_info info = prt::sized<prt_pose_info>();
  const prt_result result = prt_pose_get_info(raw_asset, &info);
  if (result != PRT_OK) {
    check.message = runtime_failure("prt_pose_get_info", result, raw_context);
    return check;
  }
  if (!header_matches(info, training, model)) {
    check.message = "the blob's PSTR header does not match the model";
    return check;
  }
  for (std::size_t f : checked_frames(training.frames.size())) {
    if (!check_frame(raw_asset, raw_context, training, model, f, check)) return check;
  }
  check.passed = check.max_budget_ratio <= 1.0;
  check.message = format(
      "%zu frames through the runtime (features, skin, model): max |dt| %.3g "
      "= %.2f of the budget",
      check.frames_checked, check.max_abs_error, check.max_budget_ratio);
  return check;
}

void write_pose_bake_report(const std::string& path, const BakeInput& input, const BakeFacts& facts,
                            const PoseTrainingSet& training, const PoseModel& model,
                            const PoseFit& fit, const PoseBlobCheck& check) {
  const double rays_per_second =
      training.seconds > 0.0 ? double(training.rays_traced) / training.seconds : 0.0;
  nlohmann::json clips = nlohmann::json::array();
  for (const std::string& name : training.clip_names) clips.push_back(name);
  nlohmann::json json = {
      {"command", "bake"},
      {"technique", "pose"},
      {"scene",
       {{"file", input.scene},
        {"vertices", facts.vertices},
        {"triangles", facts.triangles},
        {"joints", training.joint_count()}}},
      {"training",
       {{"clips", clips},
        {"frames", training.frames.size()},
        {"order", training.order},
        {"transfer", sh_transfer_kind_name(training.kind)},
        {"bounces", training.bounces},
        {"albedo", training.albedo},
        {"seed", input.seed},
        {"seconds", training.seconds},
        {"rays", training.rays_traced},
        {"rays_per_second", rays_per_second},
        {"threads", facts.threads}}},
      {"model",
       {{"kind", model.kind == PoseModelKind::Direct ? "direct" : "residual"},
        {"pose_dims", model.pose_dims},
        {"basis_dims", model.basis_dims},
        {"alpha", model.alpha},
        {"alpha_curve", {{"alpha", model.alpha_curve_alpha}, {"error", model.alpha_curve_error}}},
        {"clamp", model.clamp},
        {"bits", model.bits},
        {"model_bytes", model.model_bytes},
        {"training_transfer_error", fit.transfer_error},
        {"worst_training_frame_error", fit.worst_frame_error}}},
      {"blob", {{"file", input.output}, {"bytes", facts.blob_bytes}}},
      {"self_check",
       {{"passed", check.passed},
        {"message", check.message},
        {"frames", check.frames_checked},
        {"max_abs_error", check.max_abs_error},
        {"max_budget_ratio", check.max_budget_ratio}}},
  };
  std::ofstream file(path);
  if (!file || !(file << json.dump(2) << '\n')) throw Error(path + ": cannot write the report");
}

}  // namespace prt::bake
