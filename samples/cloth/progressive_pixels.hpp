// SPDX-License-Identifier: MIT
// Per-pixel values that take longer than a frame (the brute-force reference always, the CPU
// backends' shading in a window): computed a share at a time for the samples of one G-buffer,
// coarse to fine (every 16th pixel of every 16th row first, then every 8th, ... then the rest),
// and shown meanwhile with each pixel not yet computed taking the value of the pixel at the
// corner of its block at the finest step completed. Starts over when the samples (the view) or
// what they are computed from (a version the caller keeps) change; when only the version does,
// each pixel shows its former value until it is computed again.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "scene_renderer.hpp"

namespace prt::cloth_app {

class ProgressivePixels {
 public:
  // compute(first, count, out): values of samples [first, first + count) of the ordered arrays
  // (ordered_normals() ...), 3 floats each, into out.
  using Compute = std::function<void(std::uint32_t first, std::uint32_t count, float* out)>;

  // Starts over unless these are the samples it holds, with the same version (or another one
  // while the picture is not finished, when finish_first: a light turning faster than the
  // picture is computed then shows whole pictures that lag it, not blocks); true when it did.
  bool track(const prt::sample::PixelSamples& samples, std::uint64_t version,
             bool finish_first = false);
  // Takes every sample's value at once (3 floats each, in the samples' order): computed elsewhere.
  void set_all(const prt::sample::PixelSamples& samples, std::uint64_t version,
               const std::vector<float>& rgb);
  // Computes the next samples: all that are left when budget_ms is 0, else for about budget_ms
  // (at least one batch). Returns the milliseconds spent.
  double advance(double budget_ms, const Compute& compute);

  bool complete() const { return done_ == order_.size(); }
  double progress() const { return order_.empty() ? 1.0 : double(done_) / double(order_.size()); }
  std::size_t computed() const { return done_; }
  std::size_t size() const { return order_.size(); }
  const prt::sample::PixelSamples& samples() const { return samples_; }
  std::uint64_t version() const { return version_; }

  // The samples in the order they are computed in (3 floats each).
  const float* ordered_normals() const { return normals_.data(); }
  const float* ordered_tangents() const { return tangents_.data(); }
  const float* ordered_views() const { return views_.data(); }

  // Whether sample s (in the samples' own order) is computed, and its value (3 floats).
  bool is_computed(std::size_t s) const { return rank_[s] < done_; }
  const float* value(std::size_t s) const { return &values_[3 * std::size_t(rank_[s])]; }
  // The sample at viewport pixel y * width + x, or -1.
  std::int32_t sample_at(std::uint32_t pixel) const {
    return pixel < at_pixel_.size() ? at_pixel_[pixel] : -1;
  }
  // Every sample's value, those not computed yet showing their former value or else filled from
  // their block's corner; NaN where neither is there.
  void fill(std::vector<float>& rgb) const;

 private:
  prt::sample::PixelSamples samples_;
  std::uint64_t version_ = 0;
  bool tracking_ = false;
  std::vector<std::uint32_t> order_;      // sample indices in computing order
  std::vector<std::uint32_t> rank_;       // per sample: its place in order_
  std::vector<std::uint32_t> level_end_;  // order_ index where each step's pixels end (16 .. 1)
  std::vector<std::int32_t> at_pixel_;    // per viewport pixel: its sample, or -1
  std::vector<float> normals_, tangents_, views_, values_;  // in order_
  std::vector<float> previous_;  // per sample: what it showed before the version changed
  std::size_t done_ = 0;
  double ms_per_sample_ = 0.0;

  void start(const prt::sample::PixelSamples& samples, std::uint64_t version);
  int finest_complete_step() const;
};

// Whether two sample sets are the same pixels with the same vectors.
bool same_samples(const prt::sample::PixelSamples& a, const prt::sample::PixelSamples& b);

// The values of two pictures at the samples both have computed: pixels at the same place of
// viewports of one size whose vectors agree (two viewports side by side rasterise the mesh a
// rounding apart; a stale picture of another camera does not pair). Per pair: a's value, b's,
// and b's sample index.
struct PairedValues {
  std::vector<glm::vec3> a, b;
  std::vector<std::size_t> b_sample;
};
PairedValues paired_values(const ProgressivePixels& a, const ProgressivePixels& b);

}  // namespace prt::cloth_app
