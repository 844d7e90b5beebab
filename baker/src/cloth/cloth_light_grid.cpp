// SPDX-License-Identifier: MIT
// The SG light's measures: the map on a lat-long grid, spherical Gaussians smoothed by a vMF
// kernel (exact), the smoothed map (each grid cell, or block of cells, taken as the vMF lobe
// with its power, mean direction and spread, so that its second moments survive), and the
// plain, smoothed and power errors.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "cloth_light_detail.hpp"

namespace prt::bake::sg_light {

namespace {

// Where a lobe's mean over a cell needs no samples: below exp(-kCutoff) of its peak.
constexpr double kCutoff = 30.0;
// Where a smoothed lobe adds nothing: below exp(-kSmoothedCutoff) of its peak.
constexpr double kSmoothedCutoff = 20.0;
constexpr std::uint32_t kMaxCellSamples = 16;

std::uint32_t row_of(std::uint32_t rows, double y) {
  const double theta = std::acos(std::clamp(y, -1.0, 1.0));
  return std::min(rows - 1, static_cast<std::uint32_t>(theta / kPi * rows));
}

std::uint32_t col_of(std::uint32_t cols, double x, double z) {
  const double u = (std::atan2(x, -z) + kPi) / (2.0 * kPi);
  return std::min(cols - 1, static_cast<std::uint32_t>(std::max(0.0, u) * cols));
}

// The mean of exp(l (a . w - 1)) over a lat-long cell centred at polar angle t and azimuth p,
// of extents dt and dp: f + (dt^2 / 12) cot t f_t + (dt^2 / 24) f_tt + (dp^2 / 24) f_pp (the
// first-order term from the sin t weight of the solid angle), as the runtime's report takes it.
double corrected_mean(const Lobe& lobe, double t, double p, double dt, double dp) {
  const glm::dvec3& a = lobe.axis;
  const double l = lobe.sharpness, st = std::sin(t), ct = std::cos(t);
  const double across = a.x * std::sin(p) - a.z * std::cos(p);
  const double dot = st * across + ct * a.y;
  const double polar = ct * across - st * a.y;                     // a . e_t
  const double azimuthal = a.x * std::cos(p) + a.z * std::sin(p);  // a . e_p
  const double correction =
      1.0 + dt * dt / 12.0 * (ct / st) * l * polar +
      dt * dt / 24.0 * (l * l * polar * polar - l * dot) +
      dp * dp / 24.0 * (l * l * st * st * azimuthal * azimuthal - l * st * across);
  return correction > 0.0 ? std::exp(l * (dot - 1.0)) * correction : 0.0;
}

// The mean of a unit-amplitude lobe over cell (row, col) of a grid of `rows`: the solid-angle
// weighted mean of its corrected means over n x n sub-cells; 0 where the lobe is below
// exp(-kCutoff) of its peak.
double lobe_cell_mean(const Lobe& lobe, std::uint32_t rows, std::uint32_t row, std::uint32_t col,
                      std::uint32_t n) {
  const double dtheta = kPi / rows, dphi = kPi / rows;  // cols = 2 rows
  const double t0 = row * dtheta, t1 = t0 + dtheta, p0 = col * dphi - kPi;
  const double widest =
      (t0 < 0.5 * kPi && t1 > 0.5 * kPi) ? 1.0 : std::max(std::sin(t0), std::sin(t1));
  const double radius = 0.5 * dtheta + 0.5 * widest * dphi;
  const double d = glm::dot(lobe.axis, cell_centre(rows, row, col));
  const double nearest = d >= std::cos(radius) ? 1.0 : std::cos(std::acos(d) - radius);
  if (lobe.sharpness * (1.0 - nearest) > kCutoff) return 0.0;
  double sum = 0.0;
  for (std::uint32_t j = 0; j < n; ++j) {
    const double ta = t0 + dtheta * j / n, tb = t0 + dtheta * (j + 1) / n;
    double row_sum = 0.0;
    for (std::uint32_t i = 0; i < n; ++i)
      row_sum +=
          corrected_mean(lobe, 0.5 * (ta + tb), p0 + dphi * (i + 0.5) / n, dtheta / n, dphi / n);
    sum += (std::cos(ta) - std::cos(tb)) * row_sum;
  }
  return sum / n / (std::cos(t0) - std::cos(t1));
}

// The map smoothed by one kernel, from blocks of b x b cells of a grid, each the vMF lobe with
// its power, mean direction and spread (a blob). Blocks are at most half the kernel's width, so
// a blob is several times sharper than the kernel and reaches as far as the kernel does, about:
// a point adds only the blobs of the blocks within `reach` of it.
class SmoothedMap {
 public:
  SmoothedMap(const MapGrid& grid, std::uint32_t b, double kappa)
      : rows_(grid.rows / b), cols_(grid.cols / b), kappa_(kappa), blobs_(rows_ * cols_) {
    double softest = 1e300;
    for (std::uint32_t row = 0; row < rows_; ++row)
      for (std::uint32_t col = 0; col < cols_; ++col) {
        Lobe& blob = blobs_[std::size_t(row) * cols_ + col];
        blob.sharpness = 0.0;  // no power
        glm::dvec3 power{0.0}, resultant{0.0};
        double weight = 0.0;
        for (std::uint32_t r = row * b; r < (row + 1) * b; ++r)
          for (std::uint32_t c = col * b; c < (col + 1) * b; ++c) {
            const std::size_t k = std::size_t(r) * grid.cols + c;
            power += grid.power[k];
            resultant += grid.resultant[k];
            weight += grid.weight[k];
          }
        const double length = glm::length(resultant);
        if (!(weight > 0.0) || !(length > 0.0)) continue;
        blob.axis = resultant / length;
        blob.sharpness = sharpness_of_resultant(std::min(1.0, length / weight), 1e-3, 1e9);
        blob.rgb = power / lobe_integral(blob.sharpness);
        softest = std::min(softest, blob.sharpness);
      }
    // A blob of sharpness l smoothed falls off as exp(-l kappa / (l + kappa) (1 - cos)); a
    // blob's direction may lie a block's diagonal outside its block.
    const double falloff = softest * kappa / (softest + kappa);
    reach_ = std::acos(std::max(-1.0, 1.0 - kSmoothedCutoff / falloff)) + 2.0 * kPi / cols_ +
             kPi / rows_;
  }

  glm::dvec3 at(const glm::dvec3& v) const {
    const double theta = std::acos(std::clamp(v.y, -1.0, 1.0));
    const double phi = std::atan2(v.x, -v.z);
    const double row_height = kPi / rows_, col_width = 2.0 * kPi / cols_;
    const auto first_row = static_cast<std::int64_t>(std::floor((theta - reach_) / row_height));
    const auto last_row = static_cast<std::int64_t>(std::floor((theta + reach_) / row_height));
    glm::dvec3 sum{0.0};
    for (std::int64_t row = std::max<std::int64_t>(0, first_row);
         row <= std::min<std::int64_t>(rows_ - 1, last_row); ++row) {
      // The azimuths within reach on this row: all of them when a pole is within reach.
      std::int64_t first_col = 0, count = cols_;
      const double t0 = std::max(row * row_height, theta - reach_);
      const double t1 = std::min((row + 1) * row_height, theta + reach_);
      const double narrowest = std::min(std::sin(t0), std::sin(t1));
      if (theta - reach_ > 0.0 && theta + reach_ < kPi && std::sin(reach_) < narrowest) {
        const double half = std::asin(std::sin(reach_) / narrowest);
        first_col = static_cast<std::int64_t>(std::floor((phi - half + kPi) / col_width));
        count = std::min<std::int64_t>(
            cols_,
            static_cast<std::int64_t>(std::floor((phi + half + kPi) / col_width)) - first_col + 1);
      }
      for (std::int64_t k = 0; k < count; ++k) {
        const std::int64_t col = ((first_col + k) % cols_ + cols_) % cols_;
        add(blobs_[std::size_t(row) * cols_ + std::size_t(col)], v, &sum);
      }
    }
    return sum;
  }

 private:
  void add(const Lobe& blob, const glm::dvec3& v, glm::dvec3* sum) const {
    const double t = glm::dot(blob.axis, v), l = blob.sharpness;
    if (l == 0.0) return;
    const double rho = std::sqrt(std::max(0.0, l * l + kappa_ * kappa_ + 2.0 * l * kappa_ * t));
    if (2.0 * l * kappa_ * (t - 1.0) / (rho + l + kappa_) < -kSmoothedCutoff) return;
    *sum += blob.rgb * smoothed_lobe(l, kappa_, t);
  }

  std::int64_t rows_, cols_;
  double kappa_, reach_ = kPi;
  std::vector<Lobe> blobs_;
};

// The smoothed sum of lobes at v (sources that cannot reach it skipped).
glm::dvec3 smoothed_sum(const std::vector<Lobe>& lobes, double kappa, const glm::dvec3& v) {
  glm::dvec3 sum{0.0};
  for (const Lobe& lobe : lobes) {
    const double t = glm::dot(lobe.axis, v), l = lobe.sharpness;
    const double rho = std::sqrt(std::max(0.0, l * l + kappa * kappa + 2.0 * l * kappa * t));
    if (2.0 * l * kappa * (t - 1.0) / (rho + l + kappa) < -kSmoothedCutoff) continue;
    sum += lobe.rgb * smoothed_lobe(l, kappa, t);
  }
  return sum;
}

}  // namespace

std::vector<Lobe> to_lobes(const std::vector<prt_cloth_lobe>& lobes) {
  std::vector<Lobe> out;
  for (const prt_cloth_lobe& l : lobes) {
    Lobe lobe;
    lobe.axis = glm::normalize(glm::dvec3(l.axis[0], l.axis[1], l.axis[2]));
    lobe.sharpness = l.sharpness;
    lobe.rgb = glm::dvec3(l.rgb[0], l.rgb[1], l.rgb[2]);
    out.push_back(lobe);
  }
  return out;
}

std::vector<prt_cloth_lobe> to_cloth_lobes(const std::vector<Lobe>& lobes) {
  std::vector<prt_cloth_lobe> out;
  for (const Lobe& lobe : lobes) {
    const glm::dvec3 axis = glm::normalize(lobe.axis);
    prt_cloth_lobe l{};
    for (int c = 0; c < 3; ++c) {
      l.axis[c] = static_cast<float>(axis[c]);
      l.rgb[c] = static_cast<float>(std::min<double>(lobe.rgb[c], 3.4e38));
    }
    l.sharpness = static_cast<float>(
        std::clamp<double>(lobe.sharpness, PRT_CLOTH_MIN_SHARPNESS, PRT_CLOTH_MAX_SHARPNESS));
    out.push_back(l);
  }
  return out;
}

glm::dvec3 cell_centre(std::uint32_t rows, std::uint32_t row, std::uint32_t col) {
  const double t = kPi * (row + 0.5) / rows, p = kPi * (col + 0.5) / rows - kPi;
  return {std::sin(t) * std::sin(p), std::cos(t), -std::sin(t) * std::cos(p)};
}

double cell_solid_angle(std::uint32_t rows, std::uint32_t row) {
  return kPi / rows * (std::cos(kPi * row / rows) - std::cos(kPi * (row + 1) / rows));
}

MapGrid grid_of(const io::EnvMap& map, std::uint32_t rows) {
  MapGrid grid;
  grid.rows = rows;
  grid.cols = 2 * rows;
  const std::size_t cells = std::size_t(grid.rows) * grid.cols;
  grid.power.assign(cells, glm::dvec3(0.0));
  grid.weight.assign(cells, 0.0);
  grid.resultant.assign(cells, glm::dvec3(0.0));
  grid.solid_angle.assign(cells, 0.0);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      glm::vec3 dir;
      float solid_angle = 0.0f;
      if (!map.texel(x, y, &dir, &solid_angle)) continue;
      const glm::dvec3 d = glm::normalize(glm::dvec3(dir));
      const std::size_t k =
          std::size_t(row_of(grid.rows, d.y)) * grid.cols + col_of(grid.cols, d.x, d.z);
      const glm::dvec3 power = glm::dvec3(map.texel_value(x, y)) * double(solid_angle);
      const double weight = power.x + power.y + power.z;
      grid.solid_angle[k] += solid_angle;
      grid.power[k] += power;
      grid.weight[k] += weight;
      grid.resultant[k] += weight * d;
      grid.total_power += power;
    }
  }
  return grid;
}

MapGrid coarser(const MapGrid& fine) {
  MapGrid grid;
  grid.rows = fine.rows / 2;
  grid.cols = fine.cols / 2;
  const std::size_t cells = std::size_t(grid.rows) * grid.cols;
  grid.power.assign(cells, glm::dvec3(0.0));
  grid.weight.assign(cells, 0.0);
  grid.resultant.assign(cells, glm::dvec3(0.0));
  grid.solid_angle.assign(cells, 0.0);
  grid.total_power = fine.total_power;
  for (std::uint32_t r = 0; r < fine.rows; ++r)
    for (std::uint32_t c = 0; c < fine.cols; ++c) {
      const std::size_t from = std::size_t(r) * fine.cols + c;
      const std::size_t to = std::size_t(r / 2) * grid.cols + c / 2;
      grid.power[to] += fine.power[from];
      grid.weight[to] += fine.weight[from];
      grid.resultant[to] += fine.resultant[from];
      grid.solid_angle[to] += fine.solid_angle[from];
    }
  return grid;
}

double sharpness_of_resultant(double r, double lo, double hi) {
  const auto resultant = [](double l) { return 1.0 / std::tanh(l) - 1.0 / l; };
  if (!(r > resultant(lo))) return lo;
  if (r >= resultant(hi)) return hi;
  double l = std::clamp(r * (3.0 - r * r) / (1.0 - r * r), lo, hi);
  for (int i = 0; i < 32; ++i) {
    const double s = std::sinh(l);
    const double slope = 1.0 / (l * l) - (s > 1e150 ? 0.0 : 1.0 / (s * s));
    const double next = std::clamp(l - (resultant(l) - r) / slope, lo, hi);
    if (std::fabs(next - l) <= 1e-12 * l) return next;
    l = next;
  }
  return l;
}

double lobe_integral(double sharpness) {
  return -2.0 * kPi / sharpness * std::expm1(-2.0 * sharpness);
}

// G = kappa / (1 - e^(-2 kappa)) e^(rho - l - kappa) (1 - e^(-2 rho)) / rho, with
// rho = |l a + kappa v| and rho - l - kappa = 2 l kappa (t - 1) / (rho + l + kappa).
void smoothed_lobe_derivatives(double l, double kappa, double t, double* value, double* d_l,
                               double* d_t) {
  const double rho = std::sqrt(std::max(0.0, l * l + kappa * kappa + 2.0 * l * kappa * t));
  const double scale = kappa > 20.0 ? kappa : -kappa / std::expm1(-2.0 * kappa);
  const double e = std::exp(2.0 * l * kappa * (t - 1.0) / (rho + l + kappa));
  // u = (1 - e^(-2 rho)) / rho and u', by their series near rho = 0 and without the
  // exponential where it is below double precision.
  double u, du;
  if (rho < 1e-4) {
    u = 2.0 - 2.0 * rho + 4.0 / 3.0 * rho * rho;
    du = -2.0 + 8.0 / 3.0 * rho;
  } else if (rho > 20.0) {
    u = 1.0 / rho;
    du = -u / rho;
  } else {
    u = -std::expm1(-2.0 * rho) / rho;
    du = 2.0 * std::exp(-2.0 * rho) / rho - u / rho;
  }
  *value = scale * e * u;
  if (d_l) {
    const double drho_dl = rho > 0.0 ? (l + kappa * t) / rho : 1.0;
    *d_l = scale * e * ((u + du) * drho_dl - u);
  }
  if (d_t) *d_t = rho > 0.0 ? scale * e * (u + du) * l * kappa / rho : 0.0;
}

double smoothed_lobe(double l, double kappa, double t) {
  double value;
  smoothed_lobe_derivatives(l, kappa, t, &value, nullptr, nullptr);
  return value;
}

double relative_error(const MapGrid& grid, const std::vector<Lobe>& lobes) {
  // Sub-cells at most half a lobe's width (1 / sqrt(sharpness)) across.
  std::vector<std::uint32_t> samples;
  for (const Lobe& lobe : lobes)
    samples.push_back(std::clamp<std::uint32_t>(
        static_cast<std::uint32_t>(std::ceil(2.0 * std::sqrt(lobe.sharpness) * kPi / grid.rows)), 1,
        kMaxCellSamples));
  double error = 0.0, norm = 0.0;
  for (std::uint32_t row = 0; row < grid.rows; ++row) {
    for (std::uint32_t col = 0; col < grid.cols; ++col) {
      const std::size_t k = std::size_t(row) * grid.cols + col;
      if (!(grid.solid_angle[k] > 0.0)) continue;
      glm::dvec3 model{0.0};
      for (std::size_t i = 0; i < lobes.size(); ++i)
        model += lobes[i].rgb * lobe_cell_mean(lobes[i], grid.rows, row, col, samples[i]);
      const glm::dvec3 map = grid.power[k] / grid.solid_angle[k];
      error += grid.solid_angle[k] * glm::dot(model - map, model - map);
      norm += grid.solid_angle[k] * glm::dot(map, map);
    }
  }
  return norm > 0.0 ? std::sqrt(error / norm) : 0.0;
}

double power_error(const MapGrid& grid, const std::vector<Lobe>& lobes) {
  const double map = grid.total_power.x + grid.total_power.y + grid.total_power.z;
  double fitted = 0.0;
  for (const Lobe& lobe : lobes)
    fitted += (lobe.rgb.x + lobe.rgb.y + lobe.rgb.z) * lobe_integral(lobe.sharpness);
  return map > 0.0 ? std::fabs(fitted - map) / map : 0.0;
}

std::vector<SmoothedTarget> smoothed_targets(const MapGrid& fine,
                                             const std::vector<double>& degrees,
                                             const Context& ctx) {
  std::vector<SmoothedTarget> targets;
  const double cell = kPi / fine.rows;
  for (double deg : degrees) {
    const double sigma = deg * kPi / 180.0;
    SmoothedTarget target;
    target.kappa = 1.0 / (sigma * sigma);
    // Blocks at most half the kernel's width; points on a grid spaced at most two thirds of
    // it, no finer than the error's grid (half the fine grid's rows).
    std::uint32_t block = 1;
    while (4 * block * cell <= sigma && fine.rows % (2 * block) == 0) block *= 2;
    const SmoothedMap map(fine, block, target.kappa);
    const auto rows =
        std::clamp<std::uint32_t>(static_cast<std::uint32_t>(std::ceil(1.5 * kPi / sigma)),
                                  std::min(8u, fine.rows / 2), fine.rows / 2);
    for (std::uint32_t row = 0; row < rows; ++row) {
      for (std::uint32_t col = 0; col < 2 * rows; ++col) {
        target.points.push_back(cell_centre(rows, row, col));
        target.weights.push_back(cell_solid_angle(rows, row));
      }
    }
    target.target.assign(target.points.size(), glm::dvec3(0.0));
    tbb::task_arena arena(static_cast<int>(ctx.thread_count()));
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, target.points.size()),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i < range.end(); ++i)
                            target.target[i] = map.at(target.points[i]);
                        });
    });
    for (std::size_t i = 0; i < target.points.size(); ++i)
      target.norm += target.weights[i] * glm::dot(target.target[i], target.target[i]);
    targets.push_back(std::move(target));
  }
  return targets;
}

double smoothed_error(const SmoothedTarget& target, const std::vector<Lobe>& lobes) {
  if (!(target.norm > 0.0)) return 0.0;
  double error = 0.0;
  for (std::size_t i = 0; i < target.points.size(); ++i) {
    const glm::dvec3 diff = smoothed_sum(lobes, target.kappa, target.points[i]) - target.target[i];
    error += target.weights[i] * glm::dot(diff, diff);
  }
  return std::sqrt(error / target.norm);
}

}  // namespace prt::bake::sg_light
