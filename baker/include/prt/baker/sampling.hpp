// SPDX-License-Identifier: MIT
// Sampling for the reference renderer: randomised quasi-Monte Carlo points (Owen-scrambled Sobol),
// cosine-weighted hemispheres, and an importance distribution over an environment map.
//
// Points are Burley's "padded" Owen-scrambled Sobol sequence (B. Burley, Practical Hash-based
// Owen Scrambling, JCGT 9(4), 2020): every 2-D pair of dimensions is the first two Sobol
// dimensions, with the sample index and each coordinate scrambled by hash-keyed nested uniform
// scrambling, so any number of pairs stays well stratified and pairs are decorrelated. A stream
// is keyed by one 32-bit seed; two streams with different seeds are independent randomisations.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prt/io/envmap.hpp"

namespace prt::bake {

// The splitmix64 finaliser.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Mixes values into a well-distributed 32-bit key (splitmix64 finaliser). Inline: bakes call it
// once per texel sample.
inline std::uint32_t hash_key(std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0) {
  std::uint64_t h = splitmix64(a);
  h = splitmix64(h ^ b);
  h = splitmix64(h ^ c);
  return static_cast<std::uint32_t>(h >> 32);
}

class SampleStream {
 public:
  explicit SampleStream(std::uint32_t seed);
  // Point `index` of the stream in dimensions (2*pair, 2*pair+1); both in [0,1).
  glm::vec2 get_2d(std::uint32_t index, std::uint32_t pair) const;

 private:
  struct PairKeys {
    std::uint32_t index, x, y;  // scrambling keys of the index and of each coordinate
  };
  static constexpr std::uint32_t kCachedPairs = 8;  // enough for 3 bounces of a pixel's path
  PairKeys keys(std::uint32_t pair) const;

  std::uint32_t seed_;
  PairKeys cached_[kCachedPairs];
};

// An orthonormal frame around unit n (Duff et al., "Building an Orthonormal Basis, Revisited").
struct Frame {
  glm::vec3 t, b, n;
  explicit Frame(const glm::vec3& normal);
  glm::vec3 to_world(const glm::vec3& local) const {
    return t * local.x + b * local.y + n * local.z;
  }
};

// Cosine-weighted direction about +Z from u in [0,1)^2 (concentric disc mapping, which keeps the
// stratification of u). pdf = z / pi.
glm::vec3 cosine_hemisphere(const glm::vec2& u);

// A piecewise-constant distribution over directions proportional to the environment's luminance
// x solid angle, for importance sampling. Its cells are an equal-angle latitude-longitude grid of
// its own, with twice the map's resolution along each axis (about four cells per texel that
// belongs to the mapping; at most 1024 x 2048), so a direction is sampled uniformly in solid
// angle inside a cell and the density is exact whatever the map's mapping. A cell's weight is its
// solid angle x the mean luminance of the map's radiance (EnvMap::radiance, which never reads the
// padding of a cross or the outside of a probe's disc) at 2x2 points inside it: half-texel cells
// sampled at quarter-texel spacing follow the bilinear radiance closely, so a sun of a few texels
// gets its share of samples and little variance. Any cell this misses still gets cosine samples:
// the renderer combines both by multiple importance sampling, so the estimate stays unbiased.
class EnvDistribution {
 public:
  // Builds the distribution; runs in parallel on the calling thread's TBB arena.
  explicit EnvDistribution(const io::EnvMap& env);

  // False when the map is black everywhere: then it cannot be sampled.
  bool valid() const { return total_ > 0.0; }
  // Samples a direction; *pdf receives its density in solid angle (> 0).
  glm::vec3 sample(const glm::vec2& u, float* pdf) const;
  // Density in solid angle of sampling `dir` (unit).
  float pdf(const glm::vec3& dir) const;
  // pdf() in two steps, so a renderer can prefetch before it traces a ray: the grid cell of
  // `dir` (unit), and its density (valid() only). pdf(dir) == cell_pdf(cell(dir)).
  std::size_t cell(const glm::vec3& dir) const;
  float cell_pdf(std::size_t cell) const { return density_[cell]; }
  void prefetch_cell(std::size_t cell) const;

  int columns() const { return columns_; }
  int rows() const { return rows_; }

 private:
  int columns_ = 0, rows_ = 0;
  int column_guide_size_ = 0;             // guide buckets per row (a row stores this + 1 entries)
  std::vector<double> row_cdf_;           // rows_+1 entries, normalised
  std::vector<double> row_cos_;           // rows_+1 entries: cos(theta) at the row boundaries
  std::vector<double> column_cdf_;        // rows_ x (columns_+1), each row normalised
  std::vector<int> row_guide_;            // rows_+1 entries: where to start searching row_cdf_
  std::vector<int> column_guide_;         // per row: where to start searching its column CDF
  std::vector<float> density_;            // rows_ x columns_: pdf in solid angle
  std::vector<double> cell_solid_angle_;  // rows_ entries: of one cell in each row
  double total_ = 0.0;
};

}  // namespace prt::bake
