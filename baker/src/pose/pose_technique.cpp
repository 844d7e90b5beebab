// SPDX-License-Identifier: MIT
// Technique `pose` for prt-bake: `bake pose CHARACTER.glb -o OUT.prtk` samples the character's
// clips, bakes each frame's SH transfer (prt/baker/pose/pose_training.hpp), fits the learned
// model (prt/baker/pose/pose_model.hpp), writes the blob and checks it through the runtime.
// `bake pose --shard i/N` bakes the transfer of a range of the frames; merge_shards joins them
// and fits the model (pose_shards.cpp).
#include <prt/format/pose_layout.h>

#include <memory>
#include <string>
#include <vector>

#include "prt/baker/pose/pose_blob.hpp"
#include "prt/baker/pose/pose_model.hpp"
#include "prt/baker/pose/pose_subdivide.hpp"
#include "prt/baker/pose/pose_training.hpp"
#include "prt/baker/text.hpp"

#include "../common/technique_blob.hpp"
#include "pose_ground_truth.hpp"
#include "pose_technique.hpp"

namespace prt::bake {
namespace {

PoseModelKind parse_model_kind(const std::string& name) {
  return name == "direct" ? PoseModelKind::Direct : PoseModelKind::Residual;
}

PoseCrossValidation parse_cv(const std::string& name) {
  if (name == "frame") return PoseCrossValidation::Frame;
  if (name == "block") return PoseCrossValidation::Block;
  return PoseCrossValidation::Clip;
}

class PoseBake final : public TechniqueBake {
 public:
  PoseBake() {
    training_settings_.transfer.order = 6;
    training_settings_.transfer.kind = ShTransferKind::Shadowed;
    training_settings_.transfer.rays = 512;
    training_settings_.transfer.bounces = 1;
  }

  OptionList options() override {
    PoseTrainingSettings& t = training_settings_;
    PoseModelSettings& m = model_settings_;
    OptionList list;
    list.add("--clips", &t.clips,
             "Clips to train on (comma-separated names); default: every clip that moves the "
             "skin's joints");
    list.add("--rate", &t.rate, "Training frames per second of clip time").range(0.01, 1000.0);
    list.add("--order", &t.transfer.order, "SH order n (n*n coefficients)")
        .range(1, PRT_BLOB_PSTR_MAX_ORDER);
    list.add("--transfer", &kind_, "shadowed|interreflected")
        .choices({"shadowed", "interreflected"});
    list.add("--rays", &t.transfer.rays, "Directions per vertex and frame").range(1, 1u << 24);
    list.add("--bounces", &t.transfer.bounces, "Bounce passes of the interreflected transfer")
        .range(0, 64);
    list.add("--model", &model_kind_,
             "residual (exact unshadowed part + learned occlusion) | direct "
             "(the paper's)")
        .choices({"residual", "direct"});
    list.add("--pose-dims", &m.pose_dims, "Pose PCA dimensions p; 0: by --pose-variance")
        .range(0, 768);
    list.add("--pose-variance", &m.pose_variance, "Pose variance p keeps when --pose-dims is 0")
        .range(0.0, 1.0);
    list.add("--basis-dims", &m.basis_dims, "Vertex basis dimensions q; 0: by --basis-energy")
        .range(0, 256);
    list.add("--basis-energy", &m.basis_energy, "Energy q keeps when --basis-dims is 0")
        .range(0.0, 1.0);
    list.add("--alpha", &m.alpha, "Ridge alpha; negative: chosen by cross-validation");
    list.add("--cv", &cv_, "Cross-validation of alpha: clip (leave one clip out), block, frame")
        .choices({"clip", "block", "frame"});
    list.add("--no-clamp", &no_clamp_, "Do not clamp pose coordinates to the training range");
    list.add("--bits", &m.bits, "Bits per basis value: 8 or 16").choices({8, 16});
    list.add("--subdivide-to", &subdivide_to_,
             "Midpoint-subdivide the character until it has at least N vertices; 0: as imported")
        .range(0, 1u << 24);
    list.add("--ground-truth", &ground_truth_,
             "Also write the baked training frames: PREFIX.transfer.npy [frames][V][n*n], "
             "PREFIX.rotations.npy [frames][J][4], PREFIX.times.npy [frames][2] (clip, s)");
    return list;
  }

  void bake(const Scene& imported, const BakeInput& input, const Context& ctx) override {
    const Scene& scene = prepare_scene(imported);
    training_ = bake_pose_training(scene, resolve(scene, input).training, ctx);
    fit_model(ctx);
  }

  // A shard bakes the transfer of a range of the training frames (pose_shards.cpp).
  const char* shard_unit() const override { return "frames"; }
  std::size_t shard_units(const Scene& imported) const override {
    return sample_pose_training(imported, chosen_training(imported)).frames.size();
  }
  std::vector<std::uint8_t> bake_shard(const Scene& imported, const BakeInput& input,
                                       std::size_t first, std::size_t count,
                                       const Context& ctx) override {
    const Scene& scene = prepare_scene(imported);
    return bake_pose_shard(scene, resolve(scene, input), first, count, ctx);
  }
  void merge_shards(const Scene& imported, const BakeInput& input,
                    const std::vector<std::vector<std::uint8_t>>& parts,
                    const Context& ctx) override {
    const Scene& scene = prepare_scene(imported);
    training_ = merge_pose_shards(scene, resolve(scene, input), parts, ctx);
    fit_model(ctx);
  }

  // The fit quantises the vertex basis as the blob stores it; what is left is measuring the
  // stored model on its own training frames.
  void quantize() override { fit_ = measure_pose_fit(training_, model_); }

  std::vector<std::uint8_t> write(const Scene& imported, const BakeInput& input) const override {
    const Scene& scene = scene_of(imported);
    const std::string info = "prtkit pose bake: " + input.scene + ", order " +
                             std::to_string(training_.order) + ", " + model_name() + " model";
    prt::format::BlobWriter writer = start_technique_blob(scene, info);
    const std::vector<std::uint8_t> pstr =
        encode_pstr_section(training_.skeleton, model_, training_.kind, training_.bounces);
    writer.add_section(PRT_BLOB_TAG_PSTR, pstr.data(), pstr.size(), scene.vertex_count(),
                       required_section());
    return writer.finish();
  }

  std::string summary(const Scene& imported, const BakeInput& input,
                      std::size_t blob_bytes) const override {
    const Scene& scene = scene_of(imported);
    return std::to_string(scene.vertex_count()) + " vertices, " +
           std::to_string(training_.frames.size()) + " frames of " +
           std::to_string(training_.clip_names.size()) + " clips, order " +
           std::to_string(training_.order) + ": " + model_name() + " model " +
           format("PCA(%u, %u), alpha %.3g, %zu model bytes, training error %.3g; ",
                  model_.pose_dims, model_.basis_dims, model_.alpha, model_.model_bytes,
                  fit_.transfer_error) +
           "wrote " + input.output + " (" + std::to_string(blob_bytes) + " bytes)";
  }

  SelfCheck self_check(const std::vector<std::uint8_t>& blob) override {
    check_ = check_pose_blob(blob, training_, model_);
    return {check_.passed, check_.message};
  }

  void write_report(const std::string& path, const BakeInput& input,
                    const BakeFacts& facts) const override {
    write_pose_bake_report(path, input, facts, training_, model_, fit_, check_);
  }

 private:
  // The scene every step bakes and writes: the subdivided one when --subdivide-to asks for it.
  const Scene& scene_of(const Scene& imported) const {
    return subdivide_to_ > 0 ? subdivided_ : imported;
  }
  const Scene& prepare_scene(const Scene& imported) {
    if (subdivide_to_ > 0) subdivided_ = subdivide_scene(imported, subdivide_to_);
    return scene_of(imported);
  }
  // The settings as every bake step takes them: from the options and the shared flags.
  PoseBakeSettings resolve(const Scene& scene, const BakeInput& input) {
    ShTransferSettings& s = training_settings_.transfer;
    s.seed = input.seed;
    s.kind = parse_sh_transfer_kind(kind_.c_str());
    s.override_albedo = true;
    s.albedo = glm::vec3(1.0f);
    if (!input.albedo.empty()) s.albedo = parse_albedo(input.albedo);
    model_settings_.kind = parse_model_kind(model_kind_);
    model_settings_.cv = parse_cv(cv_);
    model_settings_.clamp = !no_clamp_;
    return {chosen_training(scene), model_settings_, subdivide_to_};
  }
  // A clip that moves nothing of the character would only add copies of its rest pose (and,
  // in a scene bake, make the blob depend on other objects' animation).
  PoseTrainingSettings chosen_training(const Scene& scene) const {
    PoseTrainingSettings training = training_settings_;
    if (training.clips.empty()) training.clips = pose_clips_moving_skin(scene);
    return training;
  }
  void fit_model(const Context& ctx) {
    if (!ground_truth_.empty()) write_pose_ground_truth(ground_truth_, training_);
    model_ = fit_pose_model(training_, model_settings_, ctx);
  }
  const char* model_name() const {
    return model_.kind == PoseModelKind::Direct ? "direct" : "residual";
  }

  PoseTrainingSettings training_settings_;
  PoseModelSettings model_settings_;
  std::string kind_ = "shadowed", model_kind_ = "residual", cv_ = "clip", ground_truth_;
  bool no_clamp_ = false;
  std::uint32_t subdivide_to_ = 0;
  Scene subdivided_;
  PoseTrainingSet training_;
  PoseModel model_;
  PoseFit fit_;
  PoseBlobCheck check_;
};

class PoseTechnique final : public Technique {
 public:
  const char* name() const override { return "pose"; }
  const char* summary() const override {
    return "Bake a skinned character's SH transfer over its clips and learn it from joint "
           "rotations";
  }
  const char* trade_summary() const override {
    return "Measure technique pose's trade: held-out clips and frames, model sizes, alpha";
  }
  std::unique_ptr<TechniqueBake> make_bake() const override { return std::make_unique<PoseBake>(); }
  std::unique_ptr<TechniqueTrade> make_trade() const override { return make_pose_trade(); }

  ObjectFit fit(const Scene& scene, int node) const override { return pose_scene_fit(scene, node); }
  std::vector<Rung> ladder(int bounces) const override { return pose_scene_ladder(bounces); }
  ObjectMeasureFactory measure() const override { return &make_pose_scene_measure; }
};

}  // namespace

const Technique& pose_technique() {
  static const PoseTechnique technique;
  return technique;
}

}  // namespace prt::bake
