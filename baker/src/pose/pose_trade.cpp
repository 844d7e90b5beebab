// SPDX-License-Identifier: MIT
// prt-bake trade pose CHARACTER --env MAP ... --out-dir DIR: the measured trade of technique
// `pose` (docs/pose/trade.md). The character's clips are baked frame by frame once; the frames
// are split into training and test frames (held-out clips, the clip's halves, or even and odd
// frames); the mean-pose baseline, a visibility oracle, the paper's model (frame cross-validation,
// no clamping) and the residual model (clip or block cross-validation, clamped) are fitted on the
// training frames at each (p, q) swept and measured on the test frames against their baked
// transfer: transfer error Σ|Δt|²/Σ|t|², and shaded relative RMSE under each map and under a narrow
// directional light (both fixed in the model frame). Each model is written to a blob, loaded
// through the runtime and timed shading every vertex. Writes DIR/trade.csv, trade.md and alpha.csv.
#include <prt/format/pose_layout.h>
#include <prt/prt.h>
#include <prt/prt_sh.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "prt/baker/pose/pose_blob.hpp"
#include "prt/baker/pose/pose_model.hpp"
#include "prt/baker/pose/pose_subdivide.hpp"
#include "prt/baker/pose/pose_training.hpp"

#include "../common/technique_blob.hpp"
#include "../common/trade_common.hpp"
#include "pose_technique.hpp"

namespace prt::bake {
namespace {

using namespace trade;

struct PoseTradeSettings {
  std::string split = "auto";  // clips | halves | even-odd | auto (clips when there are several)
  std::vector<std::string> test_clips;  // for clips; default: the last clip
  double rate = 30.0;
  std::uint32_t rays = 256, order = 6;
  std::vector<std::uint32_t> pose_dims{0}, basis_dims{0, 8, 16, 32};
  int bits = 16;
  std::uint32_t subdivide_to = 0;
};

struct Light {
  std::string name;
  std::vector<float> rgb;  // model frame, coefficient-major
};

struct PoseTradeRow {
  std::string model;
  std::uint32_t p = 0, q = 0;
  double alpha = 0.0;
  std::size_t model_bytes = 0;
  double transfer_error = 0.0;
  std::vector<double> shaded_error;  // per light
  double cpu_ms = -1.0, simd_ms = -1.0;
};

// A narrow directional light: the SH projection of a unit-power delta from `dir`.
Light directional_light(std::uint32_t order) {
  const float dir[3] = {0.3f, 0.9f, 0.3f};
  std::vector<float> y(order * order);
  check_runtime(prt_sh_eval(order, dir, y.data()), "prt_sh_eval");
  Light light{"directional", {}};
  for (float v : y) light.rgb.insert(light.rgb.end(), {v, v, v});
  return light;
}

// Test and training frame indices for the split.
void split_frames(const PoseTrainingSet& set, const PoseTradeSettings& o,
                  std::vector<std::size_t>& train, std::vector<std::size_t>& test) {
  std::string split = o.split;
  if (split == "auto") split = set.clip_names.size() > 1 ? "clips" : "halves";
  std::vector<std::uint32_t> test_clips;
  for (std::uint32_t c = 0; c < set.clip_names.size(); ++c) {
    const bool named = std::find(o.test_clips.begin(), o.test_clips.end(), set.clip_names[c]) !=
                       o.test_clips.end();
    if (named || (o.test_clips.empty() && c + 1 == set.clip_names.size())) test_clips.push_back(c);
  }
  std::vector<std::size_t> clip_index(set.frames.size()), clip_count(set.clip_names.size());
  for (std::size_t f = 0; f < set.frames.size(); ++f)
    clip_index[f] = clip_count[set.frames[f].clip]++;
  for (std::size_t f = 0; f < set.frames.size(); ++f) {
    const PoseFrame& frame = set.frames[f];
    bool held_out = false;
    if (split == "clips") {
      held_out = std::find(test_clips.begin(), test_clips.end(), frame.clip) != test_clips.end();
    } else if (split == "halves") {
      held_out = 2 * clip_index[f] >= clip_count[frame.clip];
    } else {
      held_out = clip_index[f] % 2 == 1;
    }
    (held_out ? test : train).push_back(f);
  }
  if (train.empty() || test.empty()) {
    throw Error("trade pose: split '" + split + "' leaves no " +
                (train.empty() ? "training" : "test") + " frames");
  }
}

// Accumulates one frame's errors into sums: transfer error and per-light shaded error.
struct ErrorSums {
  double dt2 = 0.0, t2 = 0.0;
  std::vector<double> ds2, s2;
};

void add_frame(const float* truth, const float* model, std::size_t vertices, std::uint32_t n2,
               const std::vector<Light>& lights, ErrorSums& sums) {
  sums.ds2.resize(lights.size());
  sums.s2.resize(lights.size());
  for (std::size_t v = 0; v < vertices; ++v) {
    const float* t = truth + v * n2;
    const float* m = model + v * n2;
    for (std::uint32_t c = 0; c < n2; ++c) {
      sums.dt2 += double(m[c] - t[c]) * double(m[c] - t[c]);
      sums.t2 += double(t[c]) * double(t[c]);
    }
    for (std::size_t l = 0; l < lights.size(); ++l) {
      for (int ch = 0; ch < 3; ++ch) {
        double st = 0.0, sm = 0.0;
        for (std::uint32_t c = 0; c < n2; ++c) {
          st += double(t[c]) * lights[l].rgb[c * 3 + ch];
          sm += double(m[c]) * lights[l].rgb[c * 3 + ch];
        }
        sums.ds2[l] += (sm - st) * (sm - st);
        sums.s2[l] += st * st;
      }
    }
  }
}

void measure(const PoseTrainingSet& set, const std::vector<std::size_t>& test,
             const std::vector<Light>& lights,
             const std::function<std::vector<float>(std::size_t)>& predict, PoseTradeRow& row) {
  ErrorSums sums;
  for (std::size_t f : test) {
    const std::vector<float> model = predict(f);
    add_frame(set.frame_transfer(f), model.data(), set.vertex_count,
              static_cast<std::uint32_t>(set.coefficient_count()), lights, sums);
  }
  row.transfer_error = sums.t2 > 0.0 ? sums.dt2 / sums.t2 : 0.0;
  for (std::size_t l = 0; l < lights.size(); ++l) {
    row.shaded_error.push_back(sums.s2[l] > 0.0 ? std::sqrt(sums.ds2[l] / sums.s2[l]) : 0.0);
  }
}

// The mean-pose baseline: the mean of the training frames' transfer, whatever the pose.
PoseTradeRow baseline_row(const PoseTrainingSet& set, const std::vector<std::size_t>& train,
                          const std::vector<std::size_t>& test, const std::vector<Light>& lights) {
  std::vector<double> sum(set.vertex_count * set.coefficient_count(), 0.0);
  for (std::size_t f : train) {
    const float* t = set.frame_transfer(f);
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += t[i];
  }
  std::vector<float> mean(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) mean[i] = float(sum[i] / double(train.size()));
  PoseTradeRow row;
  row.model = "mean pose";
  row.model_bytes = mean.size() * sizeof(float);
  measure(
      set, test, lights, [&](std::size_t) { return mean; }, row);
  return row;
}

// The residual model's run-time part alone: the exact unshadowed transfer of each skinned normal.
std::vector<float> unshadowed_frame(const PoseTrainingSet& set, std::size_t f) {
  const std::size_t C = set.coefficient_count();
  std::vector<float> out(set.vertex_count * C);
  for (std::size_t v = 0; v < set.vertex_count; ++v)
    unshadowed_transfer(set.order, set.albedo, set.frame_normals(f) + 3 * v, out.data() + v * C);
  return out;
}

PoseTradeRow unshadowed_row(const PoseTrainingSet& set, const std::vector<std::size_t>& test,
                            const std::vector<Light>& lights) {
  PoseTradeRow row;
  row.model = "unshadowed only";
  measure(
      set, test, lights, [&](std::size_t f) { return unshadowed_frame(set, f); }, row);
  return row;
}

// Each vertex's visibility scalar k = <t, u> / <u, u> of transfer t on its exact part u.
double visibility_scalar(const float* t, const float* u, std::size_t C) {
  double tu = 0.0, uu = 0.0;
  for (std::size_t c = 0; c < C; ++c) {
    tu += double(t[c]) * u[c];
    uu += double(u[c]) * u[c];
  }
  return uu > 0.0 ? tu / uu : 0.0;
}

// What bounds every model that predicts how much of the exact part a vertex sees: each test
// frame's own visibility scalars (fitted to its bake: an oracle no model has), plus the training
// frames' mean of what the scalars leave.
PoseTradeRow visibility_oracle_row(const PoseTrainingSet& set,
                                   const std::vector<std::size_t>& train,
                                   const std::vector<std::size_t>& test,
                                   const std::vector<Light>& lights) {
  const std::size_t V = set.vertex_count, C = set.coefficient_count();
  std::vector<double> rest(V * C, 0.0);
  for (std::size_t f : train) {
    const std::vector<float> u = unshadowed_frame(set, f);
    const float* t = set.frame_transfer(f);
    for (std::size_t v = 0; v < V; ++v) {
      const double k = visibility_scalar(t + v * C, u.data() + v * C, C);
      for (std::size_t c = 0; c < C; ++c) rest[v * C + c] += t[v * C + c] - k * u[v * C + c];
    }
  }
  for (double& r : rest) r /= double(train.size());
  PoseTradeRow row;
  row.model = "visibility oracle";
  measure(
      set, test, lights,
      [&](std::size_t f) {
        std::vector<float> out = unshadowed_frame(set, f);
        const float* t = set.frame_transfer(f);
        for (std::size_t v = 0; v < V; ++v) {
          const double k = visibility_scalar(t + v * C, out.data() + v * C, C);
          for (std::size_t c = 0; c < C; ++c)
            out[v * C + c] = float(k * out[v * C + c] + rest[v * C + c]);
        }
        return out;
      },
      row);
  return row;
}

void time_runtime(const Scene& scene, const PoseTrainingSet& set, const PoseModel& model,
                  std::size_t frame, const Light& light, int frames, PoseTradeRow& row) {
  prt::format::BlobWriter writer = start_technique_blob(scene, "");
  const std::vector<std::uint8_t> pstr =
      encode_pstr_section(set.skeleton, model, set.kind, set.bounces);
  writer.add_section(PRT_BLOB_TAG_PSTR, pstr.data(), pstr.size(), scene.vertex_count(),
                     required_section());
  const RuntimeAsset runtime = load_runtime_asset(writer.finish());
  std::vector<float> rotations;
  for (const glm::quat& q : set.frames[frame].rotations)
    rotations.insert(rotations.end(), {q.x, q.y, q.z, q.w});
  prt_pose_input pose = prt::sized<prt_pose_input>();
  pose.joint_rotations = rotations.data();
  prt_pose_light pose_light = prt::sized<prt_pose_light>();
  pose_light.light_rgb = light.rgb.data();
  std::vector<float> out(set.vertex_count * 3);
  const auto vertices = static_cast<std::uint32_t>(set.vertex_count);
  auto timed = [&](prt_backend backend) {
    return median_frame_ms(frames, "prt_pose_shade", [&] {
      return prt_pose_shade(runtime.asset.get(), backend, &pose, &pose_light, 0, vertices,
                            out.data());
    });
  };
  row.cpu_ms = timed(PRT_BACKEND_CPU);
  row.simd_ms = timed(PRT_BACKEND_SIMD);
}

class PoseTrade final : public TechniqueTrade {
 public:
  TradeInput defaults() const override {
    TradeInput input;
    input.frames = 20;
    return input;
  }

  OptionList options() override {
    OptionList list;
    list.add("--split", &o_.split,
             "Test frames: clips (held-out clips), halves (each clip's "
             "second half), even-odd (odd frames), auto")
        .choices({"auto", "clips", "halves", "even-odd"});
    list.add("--test-clips", &o_.test_clips, "Held-out clips of --split clips; default: the last");
    list.add("--rate", &o_.rate, "Frames per second of clip time").range(0.01, 1000.0);
    list.add("--rays", &o_.rays, "Rays per vertex and frame").range(1, 1u << 24);
    list.add("--order", &o_.order, "SH order").range(1, 8);
    list.add("--pose-dims", &o_.pose_dims, "Pose PCA dimensions swept (0: 90 % of the variance)");
    list.add("--basis-dims", &o_.basis_dims, "Vertex basis dimensions swept (0: by energy)");
    list.add("--bits", &o_.bits, "Bits per basis value").choices({8, 16});
    list.add("--subdivide-to", &o_.subdivide_to,
             "Midpoint-subdivide the character until it has at least N vertices; 0: as imported")
        .range(0, 1u << 24);
    return list;
  }

  void check(const TradeInput& input) const override {
    if (input.envs.empty()) throw Error("trade pose: --env needs at least one map");
    for (std::uint32_t q : o_.basis_dims) {
      if (q > 256) throw Error("trade pose: --basis-dims above 256");
    }
  }

  void prepare(const Scene&, const TradeInput& input, const Context& ctx) override {
    for (const std::string& path : input.envs) {
      lights_.push_back({stem(path), load_sh_light(path, o_.order, ctx).rgb});
    }
    lights_.push_back(directional_light(o_.order));
  }

  void sweep(const Scene& imported, const EmbreeScene&, const TradeInput& input,
             const Context& ctx) override {
    const Scene subdivided =
        o_.subdivide_to > 0 ? subdivide_scene(imported, o_.subdivide_to) : Scene{};
    const Scene& scene = o_.subdivide_to > 0 ? subdivided : imported;
    PoseTrainingSettings training;
    training.rate = o_.rate;
    training.transfer.order = o_.order;
    training.transfer.rays = o_.rays;
    training.transfer.seed = input.seed;
    training.transfer.override_albedo = true;
    training.transfer.albedo = glm::vec3(1.0f);
    const PoseTrainingSet set = bake_pose_training(scene, training, ctx);
    std::vector<std::size_t> train, test;
    split_frames(set, o_, train, test);
    rows_.push_back(baseline_row(set, train, test, lights_));
    rows_.push_back(unshadowed_row(set, test, lights_));
    rows_.push_back(visibility_oracle_row(set, train, test, lights_));
    for (std::uint32_t p : o_.pose_dims) {
      for (std::uint32_t q : o_.basis_dims) {
        fit_and_measure(scene, set, train, test, p, q, input, ctx, PoseModelKind::Direct);
        fit_and_measure(scene, set, train, test, p, q, input, ctx, PoseModelKind::Residual);
      }
    }
    write_tables(scene, set, train, test, input);
  }

 private:
  void fit_and_measure(const Scene& scene, const PoseTrainingSet& set,
                       const std::vector<std::size_t>& train, const std::vector<std::size_t>& test,
                       std::uint32_t p, std::uint32_t q, const TradeInput& input,
                       const Context& ctx, PoseModelKind kind) {
    PoseModelSettings s;
    s.kind = kind;
    s.pose_dims = p;
    s.basis_dims = q;
    s.bits = o_.bits;
    s.cv = kind == PoseModelKind::Direct ? PoseCrossValidation::Frame : PoseCrossValidation::Clip;
    s.clamp = kind == PoseModelKind::Residual;
    const PoseModel model = fit_pose_model(set, train, s, ctx);
    PoseTradeRow row;
    row.model = kind == PoseModelKind::Direct ? "paper (direct)" : "residual";
    row.p = model.pose_dims;
    row.q = model.basis_dims;
    row.alpha = model.alpha;
    row.model_bytes = model.model_bytes;
    measure(
        set, test, lights_,
        [&](std::size_t f) {
          return predict_pose_transfer(model, set.frames[f].features, set.frame_normals(f));
        },
        row);
    time_runtime(scene, set, model, test.front(), lights_.front(), input.frames, row);
    rows_.push_back(row);
    // The basis does not depend on p: one bound per q.
    if (kind == PoseModelKind::Residual && p == o_.pose_dims.front())
      basis_projection_row(set, test, model);
    for (std::size_t i = 0; i < model.alpha_curve_alpha.size(); ++i) {
      alpha_rows_.push_back({row.model, std::to_string(row.p), std::to_string(row.q),
                             format("%.6g", model.alpha_curve_alpha[i]),
                             format("%.6g", model.alpha_curve_error[i])});
    }
  }

  // What bounds the residual model: each test frame's residual projected on the model's own
  // basis by least squares, the best any regression from the pose onto that basis could do.
  void basis_projection_row(const PoseTrainingSet& set, const std::vector<std::size_t>& test,
                            const PoseModel& model) {
    const std::size_t V = set.vertex_count, C = set.coefficient_count(), q = model.basis_dims;
    Eigen::MatrixXd u(static_cast<Eigen::Index>(V), static_cast<Eigen::Index>(q));
    for (std::size_t v = 0; v < V; ++v)
      for (std::size_t k = 0; k < q; ++k)
        u(Eigen::Index(v), Eigen::Index(k)) = model.basis[v * q + k];
    const Eigen::LDLT<Eigen::MatrixXd> gram(u.transpose() * u);
    PoseTradeRow row;
    row.model = "basis projection";
    row.q = std::uint32_t(q);
    measure(
        set, test, lights_,
        [&](std::size_t f) {
          std::vector<float> out = unshadowed_frame(set, f);
          Eigen::MatrixXd r(static_cast<Eigen::Index>(V), static_cast<Eigen::Index>(C));
          for (std::size_t i = 0; i < V * C; ++i)
            r(Eigen::Index(i / C), Eigen::Index(i % C)) = set.frame_transfer(f)[i] - out[i];
          const Eigen::MatrixXd fit = u * gram.solve(u.transpose() * r);
          for (std::size_t i = 0; i < V * C; ++i)
            out[i] += float(fit(Eigen::Index(i / C), Eigen::Index(i % C)));
          return out;
        },
        row);
    rows_.push_back(row);
  }

  std::vector<std::string> cells(const PoseTradeRow& row, double frame_bytes,
                                 double training_bytes) const {
    const bool fitted = row.model == "paper (direct)" || row.model == "residual";
    std::vector<std::string> c = {
        row.model,
        fitted ? std::to_string(row.p) : "",
        fitted || row.model == "basis projection" ? std::to_string(row.q) : "",
        fitted ? format("%.3g", row.alpha) : "",
        std::to_string(row.model_bytes),
        format("%.2f", 100.0 * row.model_bytes / training_bytes),
        format("%.1f", 100.0 * row.model_bytes / frame_bytes),
        format("%.4f", row.transfer_error)};
    for (double e : row.shaded_error) c.push_back(format("%.4f", e));
    c.push_back(ms_text(row.cpu_ms));
    c.push_back(ms_text(row.simd_ms));
    return c;
  }

  void write_tables(const Scene& scene, const PoseTrainingSet& set,
                    const std::vector<std::size_t>& train, const std::vector<std::size_t>& test,
                    const TradeInput& input) const {
    const double frame_bytes = double(set.vertex_count * set.coefficient_count() * 4);
    const double training_bytes = frame_bytes * double(train.size());
    std::vector<Column> columns = {{"model", false},
                                   {"p"},
                                   {"q"},
                                   {"alpha"},
                                   {"model bytes"},
                                   {"% of training data"},
                                   {"% of one frame"},
                                   {"transfer error"}};
    for (const Light& light : lights_) columns.push_back({"shaded RMSE " + light.name});
    columns.push_back({"CPU ms"});
    columns.push_back({"SIMD ms"});
    // trade.csv is long (one row per model and light, the map column naming the light) for
    // scripts/trade.d/pose.py; trade.md is the wide table.
    const std::string csv_path = input.out_dir + "/trade.csv";
    std::ofstream csv(csv_path);
    write_csv_row(csv,
                  {"model", "p", "q", "alpha", "model_bytes", "training_share", "frame_share",
                   "transfer_error", "map", "shaded_rel_rmse", "shade_cpu_ms", "shade_simd_ms"});
    for (const PoseTradeRow& row : rows_) {
      const std::vector<std::string> c = cells(row, frame_bytes, training_bytes);
      for (std::size_t l = 0; l < lights_.size(); ++l) {
        write_csv_row(csv, {c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], lights_[l].name,
                            c[8 + l], c[8 + lights_.size()], c[9 + lights_.size()]});
      }
    }
    check_written(csv, csv_path);
    const std::string md_path = input.out_dir + "/trade.md";
    std::ofstream md(md_path);
    md << scene_description(input.scene, scene) << "; " << set.joint_count() << " joints, "
       << train.size() << " training and " << test.size() << " test frames (split " << o_.split
       << "), order " << o_.order << ", " << o_.rays << " rays per vertex.\n"
       << machine_description(1) << ".\n\n";
    write_markdown_header(md, columns);
    for (const PoseTradeRow& row : rows_)
      write_markdown_row(md, cells(row, frame_bytes, training_bytes));
    check_written(md, md_path);
    const std::string alpha_path = input.out_dir + "/alpha.csv";
    std::ofstream alpha(alpha_path);
    write_csv_row(alpha, {"model", "p", "q", "alpha", "cv error"});
    for (const auto& r : alpha_rows_) write_csv_row(alpha, r);
    check_written(alpha, alpha_path);
  }

  PoseTradeSettings o_;
  std::vector<Light> lights_;
  std::vector<PoseTradeRow> rows_;
  std::vector<std::vector<std::string>> alpha_rows_;
};

}  // namespace

std::unique_ptr<TechniqueTrade> make_pose_trade() {
  return std::make_unique<PoseTrade>();
}

}  // namespace prt::bake
