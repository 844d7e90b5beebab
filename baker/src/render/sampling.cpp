// SPDX-License-Identifier: MIT
#include "prt/baker/sampling.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include "../common/numbers.hpp"

namespace prt::bake {
namespace {

std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Burley 2020, listing 3: a Laine-Karras style hash that only lets higher bits depend on lower
// ones, applied to bit-reversed values, is a nested uniform (Owen) scramble.
std::uint32_t laine_karras_permutation(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

std::uint32_t nested_uniform_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

// Sobol dimension 0 is the bit-reversed index (van der Corput); dimension 1 uses the direction
// numbers of the primitive polynomial x + 1: v_0 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1). The
// XOR of the v_k of an index's set bits is looked up one byte of the index at a time.
struct SobolDimension1Table {
  std::uint32_t byte_xor[4][256];
  constexpr SobolDimension1Table() : byte_xor{} {
    std::uint32_t v[32] = {};
    v[0] = 0x80000000u;
    for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    for (int b = 0; b < 4; ++b) {
      for (int byte = 0; byte < 256; ++byte) {
        std::uint32_t x = 0;
        for (int j = 0; j < 8; ++j) {
          if (byte & (1 << j)) x ^= v[8 * b + j];
        }
        byte_xor[b][byte] = x;
      }
    }
  }
};
constexpr SobolDimension1Table kSobolDimension1;

std::uint32_t sobol_dimension1(std::uint32_t index) {
  return kSobolDimension1.byte_xor[0][index & 0xffu] ^
         kSobolDimension1.byte_xor[1][(index >> 8) & 0xffu] ^
         kSobolDimension1.byte_xor[2][(index >> 16) & 0xffu] ^
         kSobolDimension1.byte_xor[3][index >> 24];
}

float to_unit_float(std::uint32_t x) {
  return static_cast<float>(x >> 8) * (1.0f / 16777216.0f);
}

float luminance(const glm::vec3& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

// Guide entries per row (see build_guide): a quarter of the columns, so a sample's search within
// a row touches a cache line or two of its CDF rather than a binary search across dozens.
int column_guide_size(int columns) {
  return std::max(64, columns / 4);
}

// guide[g] (g = 0..size) is the bin that holds u = g/size in the normalised CDF (n+1 entries,
// cdf[0] = 0, cdf[n] = 1): the largest i < n with cdf[i] <= u. The bin of any u in
// [g/size, (g+1)/size) then lies in [guide[g], guide[g+1]], so sampling searches only there.
void build_guide(const double* cdf, int n, int size, int* guide) {
  int bin = 0;
  for (int g = 0; g <= size; ++g) {
    const double u = static_cast<double>(g) / size;
    while (bin < n - 1 && cdf[bin + 1] <= u) ++bin;
    guide[g] = bin;
  }
}

// Returns the bin of u (cdf[bin] <= u < cdf[bin+1]) and the position of u inside it, remapped to
// [0,1) so the stratification of u carries over.
int sample_cdf(const double* cdf, const int* guide, int guide_size, double u, double* remapped) {
  const int g = std::min(static_cast<int>(u * guide_size), guide_size - 1);
  const int lo = guide[g], hi = guide[g + 1];
  const int bin = static_cast<int>(std::upper_bound(cdf + lo + 1, cdf + hi + 1, u) - cdf) - 1;
  const double width = cdf[bin + 1] - cdf[bin];
  *remapped = width > 0.0 ? std::clamp((u - cdf[bin]) / width, 0.0, 1.0 - 1e-12) : 0.5;
  return bin;
}

// Density in solid angle of cell (r, c): the probability the CDFs give it over its solid angle.
float cell_density(const double* row_cdf, const double* column_cdf, int r, int c,
                   double solid_angle) {
  return static_cast<float>((row_cdf[r + 1] - row_cdf[r]) * (column_cdf[c + 1] - column_cdf[c]) /
                            solid_angle);
}

}  // namespace

SampleStream::SampleStream(std::uint32_t seed) : seed_(seed) {
  for (std::uint32_t pair = 0; pair < kCachedPairs; ++pair) cached_[pair] = keys(pair);
}

SampleStream::PairKeys SampleStream::keys(std::uint32_t pair) const {
  const std::uint32_t pair_seed = hash_key(seed_, pair);
  return {pair_seed, hash_key(pair_seed, 1), hash_key(pair_seed, 2)};
}

glm::vec2 SampleStream::get_2d(std::uint32_t index, std::uint32_t pair) const {
  const PairKeys k = pair < kCachedPairs ? cached_[pair] : keys(pair);
  const std::uint32_t shuffled = nested_uniform_scramble(index, k.index);
  const std::uint32_t x = nested_uniform_scramble(reverse_bits(shuffled), k.x);
  const std::uint32_t y = nested_uniform_scramble(sobol_dimension1(shuffled), k.y);
  return {to_unit_float(x), to_unit_float(y)};
}

Frame::Frame(const glm::vec3& normal) : n(normal) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b_ = n.x * n.y * a;
  t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b_, -sign * n.x);
  b = glm::vec3(b_, sign + n.y * n.y * a, -n.y);
}

glm::vec3 cosine_hemisphere(const glm::vec2& u) {
  // Shirley-Chiu concentric map of [0,1)^2 onto the unit disc, lifted to the hemisphere.
  const float sx = 2.0f * u.x - 1.0f, sy = 2.0f * u.y - 1.0f;
  float r = 0.0f, phi = 0.0f;
  if (sx != 0.0f || sy != 0.0f) {
    if (std::abs(sx) > std::abs(sy)) {
      r = sx;
      phi = static_cast<float>(kPi / 4) * (sy / sx);
    } else {
      r = sy;
      phi = static_cast<float>(kPi / 2) - static_cast<float>(kPi / 4) * (sx / sy);
    }
  }
  const float x = r * std::cos(phi), y = r * std::sin(phi);
  const float z = std::sqrt(std::max(0.0f, 1.0f - x * x - y * y));
  return {x, y, z};
}

// Grid frame: theta from +Y (row 0 at the top), phi = atan2(z, x) in [0, 2 pi).
namespace {

// Single precision on purpose: this runs for every sample, and a direction that rounding moves
// across a cell edge only changes a multiple-importance weight, never the estimate's mean.
void grid_cell(const glm::vec3& dir, int rows, int columns, int* row, int* column) {
  constexpr float kInvPi = static_cast<float>(1.0 / kPi), kInvTwoPi = static_cast<float>(0.5 / kPi);
  const float len = glm::length(dir);
  const float y = len > 0.0f ? dir.y / len : 1.0f;
  const float theta = std::acos(std::clamp(y, -1.0f, 1.0f));
  float phi = io::atan2_float(dir.z, dir.x);
  if (phi < 0.0f) phi += static_cast<float>(2.0 * kPi);
  *row = std::clamp(static_cast<int>(theta * kInvPi * rows), 0, rows - 1);
  *column = std::clamp(static_cast<int>(phi * kInvTwoPi * columns), 0, columns - 1);
}

}  // namespace

EnvDistribution::EnvDistribution(const io::EnvMap& env) {
  std::size_t valid_texels = 0;
  for (int y = 0; y < env.height(); ++y) {
    for (int x = 0; x < env.width(); ++x) valid_texels += env.texel(x, y, nullptr, nullptr);
  }
  // Twice the map's resolution along each axis: within a cell the bilinear radiance then varies
  // little, which is what keeps the variance of a small bright sun low.
  rows_ = std::clamp(2 * static_cast<int>(std::ceil(std::sqrt(valid_texels / 2.0))), 8, 1024);
  columns_ = 2 * rows_;
  const double dphi = 2.0 * kPi / columns_;
  row_cos_.resize(rows_ + 1);
  for (int r = 0; r <= rows_; ++r) row_cos_[r] = std::cos(kPi * r / rows_);
  cell_solid_angle_.resize(rows_);
  for (int r = 0; r < rows_; ++r) cell_solid_angle_[r] = dphi * (row_cos_[r] - row_cos_[r + 1]);
  const std::vector<double>& cell_solid_angle = cell_solid_angle_;

  // The interpolated map's power, gathered at 2x2 points per cell. Rows run in parallel (on
  // the caller's TBB arena) and each writes only its own cells.
  std::vector<double> weight(static_cast<std::size_t>(rows_) * columns_);
  std::vector<double> sub_cos(2 * columns_), sub_sin(2 * columns_);
  for (int k = 0; k < 2 * columns_; ++k) {
    sub_cos[k] = std::cos(dphi * (0.5 * k + 0.25));
    sub_sin[k] = std::sin(dphi * (0.5 * k + 0.25));
  }
  tbb::parallel_for(0, rows_, [&](int r) {
    double row_cos[2], row_sin[2];
    for (int k = 0; k < 2; ++k) {
      const double theta = kPi * (r + 0.25 + 0.5 * k) / rows_;
      row_cos[k] = std::cos(theta);
      row_sin[k] = std::sin(theta);
    }
    for (int c = 0; c < columns_; ++c) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) {
        const int i = k >> 1, j = 2 * c + (k & 1);
        const glm::dvec3 dir(row_sin[i] * sub_cos[j], row_cos[i], row_sin[i] * sub_sin[j]);
        sum += luminance(env.radiance(glm::vec3(dir)));
      }
      weight[static_cast<std::size_t>(r) * columns_ + c] = 0.25 * sum * cell_solid_angle[r];
    }
  });
  total_ = 0.0;
  for (const double w : weight) total_ += w;
  if (!(total_ > 0.0)) return;

  row_cdf_.assign(rows_ + 1, 0.0);
  column_cdf_.assign(static_cast<std::size_t>(rows_) * (columns_ + 1), 0.0);
  density_.assign(weight.size(), 0.0f);
  for (int r = 0; r < rows_; ++r) {
    double* cdf = &column_cdf_[static_cast<std::size_t>(r) * (columns_ + 1)];
    double row_sum = 0.0;
    for (int c = 0; c < columns_; ++c) {
      const double w = weight[static_cast<std::size_t>(r) * columns_ + c];
      row_sum += w;
      cdf[c + 1] = row_sum;
    }
    for (int c = 1; c <= columns_; ++c) cdf[c] = row_sum > 0.0 ? cdf[c] / row_sum : 0.0;
    cdf[columns_] = 1.0;
    row_cdf_[r + 1] = row_cdf_[r] + row_sum;
  }
  for (int r = 1; r <= rows_; ++r) row_cdf_[r] /= total_;
  row_cdf_[rows_] = 1.0;
  // The density is what the CDFs sample, computed as sample() computes it (from the CDF entries
  // it has just read, which saves it a cache miss on density_): the two agree to the bit.
  for (int r = 0; r < rows_; ++r) {
    const double* cdf = &column_cdf_[static_cast<std::size_t>(r) * (columns_ + 1)];
    for (int c = 0; c < columns_; ++c) {
      density_[static_cast<std::size_t>(r) * columns_ + c] =
          cell_density(row_cdf_.data(), cdf, r, c, cell_solid_angle_[r]);
    }
  }

  row_guide_.resize(rows_ + 1);
  build_guide(row_cdf_.data(), rows_, rows_, row_guide_.data());
  column_guide_size_ = column_guide_size(columns_);
  column_guide_.resize(static_cast<std::size_t>(rows_) * (column_guide_size_ + 1));
  for (int r = 0; r < rows_; ++r) {
    build_guide(&column_cdf_[static_cast<std::size_t>(r) * (columns_ + 1)], columns_,
                column_guide_size_,
                &column_guide_[static_cast<std::size_t>(r) * (column_guide_size_ + 1)]);
  }
}

glm::vec3 EnvDistribution::sample(const glm::vec2& u, float* pdf) const {
  double v_row = 0.0, u_column = 0.0;
  const int r = sample_cdf(row_cdf_.data(), row_guide_.data(), rows_, u.y, &v_row);
  const double* column_cdf = &column_cdf_[static_cast<std::size_t>(r) * (columns_ + 1)];
  const int c =
      sample_cdf(column_cdf, &column_guide_[static_cast<std::size_t>(r) * (column_guide_size_ + 1)],
                 column_guide_size_, u.x, &u_column);
  const double cos_theta = row_cos_[r] - v_row * (row_cos_[r] - row_cos_[r + 1]);
  const float sin_theta = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta)));
  const float phi = static_cast<float>(2.0 * kPi * (c + u_column) / columns_);
  *pdf = cell_density(row_cdf_.data(), column_cdf, r, c, cell_solid_angle_[r]);
  return {sin_theta * std::cos(phi), static_cast<float>(cos_theta), sin_theta * std::sin(phi)};
}

float EnvDistribution::pdf(const glm::vec3& dir) const {
  if (!valid()) return 0.0f;
  return density_[cell(dir)];
}

std::size_t EnvDistribution::cell(const glm::vec3& dir) const {
  int r = 0, c = 0;
  grid_cell(dir, rows_, columns_, &r, &c);
  return static_cast<std::size_t>(r) * columns_ + c;
}

void EnvDistribution::prefetch_cell(std::size_t cell) const {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(density_.data() + cell);
#else
  (void)cell;
#endif
}

}  // namespace prt::bake
