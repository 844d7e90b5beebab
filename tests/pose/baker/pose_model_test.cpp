// SPDX-License-Identifier: MIT
// The `pose` model fit (prt/baker/pose/pose_model.hpp) on synthetic training sets whose answer is
// known: a transfer exactly linear in the features through a rank-2 vertex basis, the mean
// under a huge alpha, clamping outside the training range, a joint that never moves, a single
// frame; and the exact unshadowed part against quadrature of the clamped cosine.
#include <gtest/gtest.h>
#include <prt/prt_sh.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "prt/baker/pose/pose_model.hpp"

namespace prt::bake {
namespace {

constexpr std::uint32_t kOrder = 2, kC = 4, kJoints = 3;
constexpr std::size_t kVertices = 50;

double uniform(std::uint64_t& state) {  // [-1, 1), splitmix64
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return double((z ^ (z >> 31)) >> 11) * 0x1.0p-52 - 1.0;
}

// T(a) = U (W0 + sum_i a_i W_i): U is V x 2, each W is 2 x C; joint 0 is the model joint.
struct LinearTruth {
  std::vector<double> u, w;  // V x 2, (F + 1) x 2 x C
  std::vector<float> at(const std::vector<float>& a) const {
    std::vector<float> t(kVertices * kC);
    for (std::size_t v = 0; v < kVertices; ++v)
      for (std::size_t c = 0; c < kC; ++c) {
        double sum = 0.0;
        for (std::size_t k = 0; k < 2; ++k) {
          double coefficient = w[k * kC + c];
          for (std::size_t i = 0; i < a.size(); ++i)
            coefficient += double(a[i]) * w[((i + 1) * 2 + k) * kC + c];
          sum += u[v * 2 + k] * coefficient;
        }
        t[v * kC + c] = float(sum);
      }
    return t;
  }
};

LinearTruth linear_truth(std::uint64_t seed) {
  LinearTruth truth;
  for (std::size_t i = 0; i < kVertices * 2; ++i) truth.u.push_back(uniform(seed));
  for (std::size_t i = 0; i < (3 * kJoints + 1) * 2 * kC; ++i) truth.w.push_back(uniform(seed));
  // t_00 = 0 everywhere: the predictions clamp t_00 to a physical range (SPEC §7.3), which a
  // random t_00 would leave; 0 lies in it, so the clamp leaves every exact recovery alone.
  for (std::size_t i = 0; i < truth.w.size(); i += kC) truth.w[i] = 0.0;
  return truth;
}

std::vector<float> random_features(std::uint64_t& seed, double extent, bool still_joint_2) {
  std::vector<float> a(3 * kJoints, 0.0f);
  for (std::size_t f = 3; f < a.size(); ++f) a[f] = float(extent * uniform(seed));
  if (still_joint_2) a[6] = a[7] = a[8] = 0.25f;
  return a;
}

// `frames` frames over two clips, the transfer given by `truth`; normals are not used by the
// direct model and are zero.
PoseTrainingSet training_set(const LinearTruth& truth, std::size_t frames, bool still_joint_2) {
  PoseTrainingSet set;
  set.order = kOrder;
  set.vertex_count = kVertices;
  set.skeleton.joints.resize(kJoints);
  set.clip_names = {"a", "b"};
  std::uint64_t seed = 42;
  for (std::size_t f = 0; f < frames; ++f) {
    PoseFrame frame;
    frame.clip = f < frames / 2 ? 0 : 1;
    frame.features = random_features(seed, 1.0, still_joint_2);
    const std::vector<float> t = truth.at(frame.features);
    set.transfer.insert(set.transfer.end(), t.begin(), t.end());
    set.frames.push_back(frame);
  }
  set.normals.assign(frames * kVertices * 3, 0.0f);
  return set;
}

PoseModelSettings direct(double alpha) {
  PoseModelSettings s;
  s.kind = PoseModelKind::Direct;
  s.alpha = alpha;
  s.pose_dims = 6;
  s.basis_dims = 2;
  s.clamp = false;
  return s;
}

double relative_error(const std::vector<float>& a, const std::vector<float>& b) {
  double d = 0.0, n = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    n += double(b[i]) * b[i];
  }
  return std::sqrt(d / n);
}

// At alpha 0 with p and q covering the data, a new pose inside the range is predicted to the
// 16-bit quantisation of the basis (measured 1.3e-5 relative).
TEST(PoseModelFit, RecoversATransferLinearInThePose) {
  const LinearTruth truth = linear_truth(7);
  const PoseTrainingSet set = training_set(truth, 40, false);
  const PoseModel model = fit_pose_model(set, direct(0.0), Context{});
  EXPECT_EQ(model.pose_dims, 6u);
  EXPECT_EQ(model.basis_dims, 2u);
  std::uint64_t seed = 99;
  for (int trial = 0; trial < 5; ++trial) {
    const std::vector<float> a = random_features(seed, 0.8, false);
    EXPECT_LT(relative_error(predict_pose_transfer(model, a, nullptr), truth.at(a)), 5e-5);
  }
}

// The basis energy rule finds the data's rank: two dimensions keep all of it.
TEST(PoseModelFit, BasisEnergyFindsTheRank) {
  const LinearTruth truth = linear_truth(8);
  const PoseTrainingSet set = training_set(truth, 30, false);
  PoseModelSettings s = direct(0.0);
  s.basis_dims = 0;
  s.basis_energy = 0.999999;
  EXPECT_EQ(fit_pose_model(set, s, Context{}).basis_dims, 2u);
}

// A huge alpha leaves only the bias: every pose predicts the training frames' mean.
TEST(PoseModelFit, HugeAlphaPredictsTheMean) {
  const LinearTruth truth = linear_truth(9);
  const PoseTrainingSet set = training_set(truth, 40, false);
  const PoseModel model = fit_pose_model(set, direct(1e9), Context{});
  std::vector<float> mean(kVertices * kC, 0.0f);
  std::vector<double> sum(mean.size(), 0.0);
  for (std::size_t f = 0; f < set.frames.size(); ++f)
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += set.frame_transfer(f)[i];
  for (std::size_t i = 0; i < sum.size(); ++i) mean[i] = float(sum[i] / set.frames.size());
  std::uint64_t seed = 3;
  EXPECT_LT(relative_error(predict_pose_transfer(model, random_features(seed, 3.0, false), nullptr),
                           mean),
            5e-5);
}

// Clamped, poses 2x and 3x past the range's end along the first pose axis predict the same
// (that coordinate is held at its maximum, the others stay 0); the unclamped model extrapolates.
TEST(PoseModelFit, ClampingHoldsPosesOutsideTheRange) {
  const LinearTruth truth = linear_truth(10);
  const PoseTrainingSet set = training_set(truth, 40, false);
  PoseModelSettings s = direct(0.0);
  s.clamp = true;
  const PoseModel clamped = fit_pose_model(set, s, Context{});
  const PoseModel free = fit_pose_model(set, direct(0.0), Context{});
  auto along_first_axis = [&](double times) {
    std::vector<float> a(3 * kJoints);
    for (std::size_t f = 0; f < a.size(); ++f)
      a[f] = float(clamped.pose_mean[f] +
                   times * clamped.pose_max[0] * clamped.pose_basis[f * clamped.pose_dims]);
    return a;
  };
  const std::vector<float> t2 = predict_pose_transfer(clamped, along_first_axis(2.0), nullptr);
  const std::vector<float> t3 = predict_pose_transfer(clamped, along_first_axis(3.0), nullptr);
  EXPECT_LT(relative_error(t3, t2), 1e-6);
  for (float v : t2) EXPECT_TRUE(std::isfinite(v));
  EXPECT_GT(relative_error(predict_pose_transfer(free, along_first_axis(3.0), nullptr), t2), 0.05);
}

// A joint that never moves gives constant feature columns: the pose PCA drops them, the fit
// stays finite at alpha 0 and still recovers the data.
TEST(PoseModelFit, AJointThatNeverMovesIsHarmless) {
  const LinearTruth truth = linear_truth(11);
  const PoseTrainingSet set = training_set(truth, 40, true);
  PoseModelSettings s = direct(0.0);
  s.pose_dims = 0;
  s.pose_variance = 1.0;
  const PoseModel model = fit_pose_model(set, s, Context{});
  EXPECT_EQ(model.pose_dims, 3u);
  std::uint64_t seed = 5;
  const std::vector<float> a = random_features(seed, 0.8, true);
  EXPECT_LT(relative_error(predict_pose_transfer(model, a, nullptr), truth.at(a)), 5e-5);
}

// One training frame: no pose dimension, no cross-validation, and the model is that frame.
TEST(PoseModelFit, OneFrameIsAConstantModel) {
  const LinearTruth truth = linear_truth(12);
  const PoseTrainingSet set = training_set(truth, 1, false);
  PoseModelSettings s = direct(-1.0);
  s.pose_dims = 0;
  const PoseModel model = fit_pose_model(set, s, Context{});
  EXPECT_EQ(model.pose_dims, 0u);
  EXPECT_TRUE(model.alpha_curve_alpha.empty());
  std::vector<float> frame(set.frame_transfer(0), set.frame_transfer(0) + kVertices * kC);
  std::uint64_t seed = 6;
  EXPECT_LT(relative_error(predict_pose_transfer(model, random_features(seed, 2.0, false), nullptr),
                           frame),
            5e-5);
}

// rho (A_l / pi) y_lm(n) is the projection of rho max(0, n.w) / pi: checked by midpoint
// quadrature over the sphere (its own error on this grid is below 2e-5).
TEST(PoseModelFit, UnshadowedTransferIsTheClampedCosine) {
  const std::uint32_t order = 6, count = order * order;
  const float n[3] = {0.48f, 0.6f, 0.64f};
  std::vector<float> exact(count);
  unshadowed_transfer(order, 0.7f, n, exact.data());
  std::vector<double> sum(count, 0.0);
  const int rows = 600, cols = 1200;
  const double pi = 3.14159265358979323846;
  std::vector<float> y(count);
  for (int i = 0; i < rows; ++i) {
    const double theta = pi * (i + 0.5) / rows;
    for (int j = 0; j < cols; ++j) {
      const double phi = 2 * pi * (j + 0.5) / cols;
      const float w[3] = {float(std::sin(theta) * std::cos(phi)),
                          float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))};
      const double cosine = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
      if (cosine <= 0.0) continue;
      ASSERT_EQ(prt_sh_eval(order, w, y.data()), PRT_OK);
      const double weight = 0.7 * cosine / pi * std::sin(theta) * (pi / rows) * (2 * pi / cols);
      for (std::uint32_t c = 0; c < count; ++c) sum[c] += weight * y[c];
    }
  }
  for (std::uint32_t c = 0; c < count; ++c) EXPECT_NEAR(exact[c], sum[c], 2e-5) << c;
  const float zero[3] = {0.0f, 0.0f, 0.0f};
  unshadowed_transfer(order, 0.7f, zero, exact.data());
  for (float v : exact) EXPECT_EQ(v, 0.0f);
}

}  // namespace
}  // namespace prt::bake
