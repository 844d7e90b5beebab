// SPDX-License-Identifier: MIT
#include "progressive_pixels.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

namespace prt::cloth_app {
namespace {

constexpr int kSteps[] = {16, 8, 4, 2, 1};
constexpr int kStepCount = 5;

// The coarsest step whose grid the pixel is on (index into kSteps).
int step_of(std::uint32_t x, std::uint32_t y) {
  for (int k = 0; k < kStepCount; ++k)
    if (x % kSteps[k] == 0 && y % kSteps[k] == 0) return k;
  return kStepCount - 1;
}

template <typename T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Unit vectors that agree to well within what a pixel's step changes them by.
bool nearly_equal(const float* u, const float* v) {
  const float d0 = u[0] - v[0], d1 = u[1] - v[1], d2 = u[2] - v[2];
  return d0 * d0 + d1 * d1 + d2 * d2 < 1e-8f;
}

}  // namespace

bool same_samples(const prt::sample::PixelSamples& a, const prt::sample::PixelSamples& b) {
  return a.width == b.width && a.height == b.height && same(a.pixel, b.pixel) &&
         same(a.normals, b.normals) && same(a.tangents, b.tangents) && same(a.views, b.views);
}

PairedValues paired_values(const ProgressivePixels& a, const ProgressivePixels& b) {
  PairedValues pairs;
  const prt::sample::PixelSamples &sa = a.samples(), &sb = b.samples();
  if (sa.width != sb.width || sa.height != sb.height) return pairs;
  for (std::size_t s = 0; s < sb.size(); ++s) {
    const std::int32_t r = a.sample_at(sb.pixel[s]);
    if (r < 0 || !a.is_computed(std::size_t(r)) || !b.is_computed(s)) continue;
    const std::size_t t = std::size_t(r);
    if (!nearly_equal(&sa.normals[3 * t], &sb.normals[3 * s]) ||
        !nearly_equal(&sa.views[3 * t], &sb.views[3 * s]) ||
        !nearly_equal(&sa.tangents[3 * t], &sb.tangents[3 * s]))
      continue;
    const float *x = a.value(t), *y = b.value(s);
    pairs.a.emplace_back(x[0], x[1], x[2]);
    pairs.b.emplace_back(y[0], y[1], y[2]);
    pairs.b_sample.push_back(s);
  }
  return pairs;
}

bool ProgressivePixels::track(const prt::sample::PixelSamples& samples, std::uint64_t version,
                              bool finish_first) {
  if (tracking_ && same_samples(samples, samples_)) {
    samples_.clip = samples.clip;  // the same pixels, another side of the screen
    if (version == version_ || (finish_first && !complete())) return false;
  }
  start(samples, version);
  return true;
}

void ProgressivePixels::start(const prt::sample::PixelSamples& samples, std::uint64_t version) {
  // The same pixels computed anew (the light turned, say): what they showed stays until each
  // is computed again, rather than blocks.
  std::vector<float> shown;
  if (tracking_ && same_samples(samples, samples_)) fill(shown);
  previous_.swap(shown);
  samples_ = samples;
  version_ = version;
  tracking_ = true;
  done_ = 0;
  const std::size_t n = samples.size();
  const std::uint32_t w = std::uint32_t(std::max(samples.width, 1));
  std::vector<std::vector<std::uint32_t>> by_step(kStepCount);
  for (std::uint32_t s = 0; s < n; ++s)
    by_step[step_of(samples.pixel[s] % w, samples.pixel[s] / w)].push_back(s);
  order_.clear();
  level_end_.clear();
  for (const std::vector<std::uint32_t>& step : by_step) {
    order_.insert(order_.end(), step.begin(), step.end());
    level_end_.push_back(std::uint32_t(order_.size()));
  }
  rank_.assign(n, 0);
  normals_.resize(3 * n), tangents_.resize(3 * n), views_.resize(3 * n);
  values_.assign(3 * n, 0.0f);
  for (std::uint32_t r = 0; r < n; ++r) {
    const std::uint32_t s = order_[r];
    rank_[s] = r;
    std::memcpy(&normals_[3 * r], &samples.normals[3 * s], 12);
    std::memcpy(&tangents_[3 * r], &samples.tangents[3 * s], 12);
    std::memcpy(&views_[3 * r], &samples.views[3 * s], 12);
  }
  at_pixel_.assign(std::size_t(samples.width) * samples.height, -1);
  for (std::uint32_t s = 0; s < n; ++s) at_pixel_[samples.pixel[s]] = std::int32_t(s);
}

void ProgressivePixels::set_all(const prt::sample::PixelSamples& samples, std::uint64_t version,
                                const std::vector<float>& rgb) {
  if (!track(samples, version)) done_ = 0;
  for (std::size_t r = 0; r < order_.size(); ++r)
    std::memcpy(&values_[3 * r], &rgb[3 * order_[r]], 12);
  done_ = order_.size();
}

double ProgressivePixels::advance(double budget_ms, const Compute& compute) {
  const auto start = std::chrono::steady_clock::now();
  double spent = 0.0;
  while (!complete()) {
    const std::size_t left = order_.size() - done_;
    std::size_t batch = left;
    if (budget_ms > 0.0) {
      // What the rest of the budget buys at the last batch's speed (a small first batch).
      const double rest = std::max(budget_ms - spent, 0.0);
      batch = ms_per_sample_ > 0.0 ? std::size_t(rest / ms_per_sample_) : 64;
      batch = std::clamp<std::size_t>(batch, 16, left);
    }
    const auto t0 = std::chrono::steady_clock::now();
    compute(std::uint32_t(done_), std::uint32_t(batch), &values_[3 * done_]);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ms_per_sample_ = ms / double(batch);
    done_ += batch;
    spent =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (budget_ms > 0.0 && spent >= budget_ms) break;
  }
  return spent;
}

// The finest step all of whose pixels (and the coarser steps') are computed, as a step in
// pixels; 0 when not even the coarsest is.
int ProgressivePixels::finest_complete_step() const {
  int finest = 0;
  for (int k = 0; k < kStepCount; ++k)
    if (done_ >= level_end_[k]) finest = kSteps[k];
  return finest;
}

void ProgressivePixels::fill(std::vector<float>& rgb) const {
  const std::size_t n = samples_.size();
  rgb.resize(3 * n);
  const int step = finest_complete_step();
  const std::uint32_t w = std::uint32_t(std::max(samples_.width, 1));
  for (std::size_t s = 0; s < n; ++s) {
    if (is_computed(s)) {
      std::memcpy(&rgb[3 * s], value(s), 12);
      continue;
    }
    if (!previous_.empty() && !std::isnan(previous_[3 * s])) {
      std::memcpy(&rgb[3 * s], &previous_[3 * s], 12);
      continue;
    }
    rgb[3 * s] = rgb[3 * s + 1] = rgb[3 * s + 2] = std::nanf("");
    if (step == 0) continue;
    const std::uint32_t x = samples_.pixel[s] % w, y = samples_.pixel[s] / w;
    const std::int32_t corner = at_pixel_[std::size_t(y - y % step) * w + (x - x % step)];
    if (corner >= 0 && is_computed(std::size_t(corner)))
      std::memcpy(&rgb[3 * s], value(corner), 12);
  }
}

}  // namespace prt::cloth_app
