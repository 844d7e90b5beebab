// SPDX-License-Identifier: MIT
// The learned model of technique `pose` (paper 002 and our improvement; formats/SPEC.md §7.3):
// pose PCA, one vertex basis shared by every SH coefficient, ridge regression with a bias, and
// their quantisation as the PSTR section stores them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/baker/pose/pose_training.hpp"

namespace prt::bake {

enum class PoseModelKind { Direct, Residual };          // SPEC §7.3 model 0 and 1
enum class PoseCrossValidation { Frame, Block, Clip };  // leave-one-frame/-block/-clip-out

struct PoseModelSettings {
  PoseModelKind kind = PoseModelKind::Residual;
  std::uint32_t pose_dims = 0;   // p; 0: the fewest that keep `pose_variance`
  double pose_variance = 0.9;    // share of the pose variance p keeps when pose_dims = 0
  std::uint32_t basis_dims = 0;  // q; 0: the fewest that keep `basis_energy`
  // Share of the training transfer's energy (squared norm) the basis keeps: its truncation
  // leaves at most (1 - basis_energy) of it, whichever part is learned.
  double basis_energy = 0.99;
  double alpha = -1.0;  // ridge alpha (X = (A^T A + alpha^2 I)^-1 A^T B); < 0: by CV
  PoseCrossValidation cv = PoseCrossValidation::Clip;  // Clip falls back to Block for one clip
  std::uint32_t cv_blocks = 5;
  bool clamp = true;  // clamp pose coordinates to the training range
  int bits = 16;      // basis values, 8 or 16
};

struct PoseModel {
  PoseModelKind kind = PoseModelKind::Residual;
  std::uint32_t order = 6, pose_dims = 0, basis_dims = 0;
  std::size_t vertex_count = 0, feature_count = 0;
  float albedo = 1.0f;
  bool clamp = true;
  double alpha = 0.0;
  std::vector<double> alpha_curve_alpha, alpha_curve_error;  // the CV curve (for the trade)
  std::vector<float> pose_mean;                              // F
  std::vector<float> pose_basis;                             // F x p, [f * p + i]
  std::vector<float> pose_min, pose_max;                     // p
  std::vector<float> regression;  // (p + 1) x q x C, [(i * q + k) * C + c]
  std::vector<float> basis;       // V x q, [v * q + k], before quantisation
  // Quantised basis (bits per value), as stored: U = offset_k + scale_k * values[v * q + k].
  int bits = 16;
  std::vector<float> basis_offset, basis_scale;
  std::vector<std::uint16_t> basis_values;
  std::size_t model_bytes = 0;  // pose PCA + regression + quantised basis, uncompressed
};

// Fits the model to every frame of `training`; Error for settings that cannot be met.
PoseModel fit_pose_model(const PoseTrainingSet& training, const PoseModelSettings& settings,
                         const Context& ctx);
// Fits to the frames listed (indices into training.frames) only, for held-out measurements.
PoseModel fit_pose_model(const PoseTrainingSet& training, const std::vector<std::size_t>& frames,
                         const PoseModelSettings& settings, const Context& ctx);

// The model's transfer (vertex_count x order^2, grey, model frame) at pose features with skinned
// normals (vertex_count x 3; used by the residual model), from the quantised basis, in double:
// what the runtime's scalar backend computes.
std::vector<float> predict_pose_transfer(const PoseModel& model, const std::vector<float>& features,
                                         const float* normals);

// The exact unshadowed transfer of unit normal n for albedo rho: rho (A_l / pi) y_lm(n), order^2.
void unshadowed_transfer(std::uint32_t order, float rho, const float n[3], float* out);

}  // namespace prt::bake
