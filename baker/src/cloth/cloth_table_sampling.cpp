// SPDX-License-Identifier: MIT
// Sampling technique `cloth`'s tables (formats/SPEC.md §7.4): for each view, W of every offset of
// a multiset on a hemi-octahedral map (and on polar patches where the fibre runs end-on into D's
// edge), then T of each lobe by a quadrature adapted to the lobe and clipped to D exactly, reading
// the maps, summed for every view at once; T_c from W sampled along the cone's arc in D.
//
// Everything is in the table's canonical frame: x = (1, 0, 0), y = (0, 1, 0), n = (0, 0, 1),
// which is thread 0's frame for normal n and warp x, so W is prt_cloth_thread_weights of thread 0
// of a weave whose thread 0 is the table's multiset.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "../common/numbers.hpp"
#include "../render/parallel_tasks.hpp"
#include "prt/baker/cloth/cloth_tables.hpp"

namespace prt::bake {
namespace {

constexpr double kHalfPi = kPi / 2.0;
// Views and light directions in the cloth's plane are evaluated this far above it: their limit
// from above, which a direction in the plane (below the surface for W) would not give.
constexpr double kHorizonZ = 1e-6;
// Nodes of T_c further than this many lobe widths from the lobe's peak, or decay lengths from
// the arc's end nearest a lobe outside it, weigh below exp(-18).
constexpr double kConeWindowWidths = 6.0;
constexpr double kConeWindowDecays = 18.0;
// The coarsest level of the W map.
constexpr std::uint32_t kMinMapSize = 4;
// A lobe's weight below exp(-kMaxExponent) of its peak in D is left out.
constexpr double kMaxExponent = 40.0;
// |xi . b| below this ties D's two corners b and -b as xi's nearest points.
constexpr double kTie = 1e-12;
// The azimuths of a lobe outside D crowd towards D over this many widths of its mass there.
constexpr double kAzimuthSpread = 4.0;
// Lobe rows per task of the T sums.
constexpr std::size_t kRowsPerTask = 64;

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Vec3 axpy(double a, const Vec3& x, const Vec3& y) {
  return {a * x[0] + y[0], a * x[1] + y[1], a * x[2] + y[2]};
}

Vec3 scaled(double a, const Vec3& x) {
  return {a * x[0], a * x[1], a * x[2]};
}

// a's part orthogonal to unit d, normalised; false when it vanishes.
bool orthogonal_unit(const Vec3& a, const Vec3& d, Vec3& out) {
  out = axpy(-dot(a, d), d, a);
  const double length = std::sqrt(dot(out, out));
  if (!(length > 1e-12)) return false;
  for (double& c : out) c /= length;
  return true;
}

// ---- Grids and frames -------------------------------------------------------------------------

// The fibre of offset tau in the canonical frame (docs/cloth/model.md): t, n' and b = y.
struct Fibre {
  Vec3 t, normal, b;
};

Fibre fibre_of(float tau) {
  const double c = std::cos(double(tau)), s = std::sin(double(tau));
  return {{c, 0.0, s}, {-s, 0.0, c}, {0.0, 1.0, 0.0}};
}

const Vec3 kNormal = {0.0, 0.0, 1.0};

// Lobe node (i, j) of the octahedral map (SPEC §7.4).
Vec3 lobe_axis(std::uint32_t n, std::uint32_t i, std::uint32_t j) {
  const double px = 2.0 * i / (n - 1) - 1.0, py = 2.0 * j / (n - 1) - 1.0;
  const double z = 1.0 - std::fabs(px) - std::fabs(py);
  Vec3 a = {px, py, z};
  if (z < 0.0)
    a = {(1.0 - std::fabs(py)) * std::copysign(1.0, px),
         (1.0 - std::fabs(px)) * std::copysign(1.0, py), z};
  const double length = std::sqrt(dot(a, a));
  return {a[0] / length, a[1] / length, a[2] / length};
}

double lobe_sharpness(const ClothGrid& g, std::uint32_t level) {
  if (g.lambda_levels == 1) return g.lambda_min;
  const double ratio = double(g.lambda_max) / double(g.lambda_min);
  return double(g.lambda_min) * std::pow(ratio, double(level) / (g.lambda_levels - 1));
}

Vec3 view_direction(const ClothGrid& g, std::uint32_t a, std::uint32_t b) {
  const double theta = kHalfPi * a / (g.view_theta - 1), phi = kPi * b / (g.view_phi - 1);
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
          std::max(std::cos(theta), kHorizonZ)};
}

// ---- W ----------------------------------------------------------------------------------------

// W of every distinct offset of a multiset, as thread 0 of a weave (thread 1 is a placeholder).
class Weights {
 public:
  explicit Weights(const ClothTableKey& key) {
    weave_.struct_size = sizeof(prt_cloth_weave);
    weave_.tangent_count[0] = std::uint32_t(key.offsets.size());
    for (std::size_t k = 0; k < key.offsets.size(); ++k) {
      weave_.offsets[0][k] = key.offsets[k];
      weave_.multiplicity[0][k] = key.multiplicities[k];
    }
    weave_.tangent_count[1] = 1;
    weave_.multiplicity[1][0] = 1;
  }

  void operator()(const Vec3& light, const float view[3], float* out) const {
    static const float normal[3] = {0.0f, 0.0f, 1.0f}, warp[3] = {1.0f, 0.0f, 0.0f};
    const float dir[3] = {float(light[0]), float(light[1]), float(light[2])};
    if (prt_cloth_thread_weights(&weave_, 0, normal, warp, dir, view, out) != PRT_OK)
      throw Error("cloth tables: prt_cloth_thread_weights rejected a direction");
  }

 private:
  prt_cloth_weave weave_{};
};

// ---- The W maps ------------------------------------------------------------------------------

// w moved onto the cloth's plane, just above it, when it is below that height: W there is its
// limit from above (W is 0 below the surface).
Vec3 above_plane(Vec3 w) {
  if (w[2] >= kHorizonZ) return w;
  const double across = std::sqrt(w[0] * w[0] + w[1] * w[1]);
  const double scale = std::sqrt(1.0 - kHorizonZ * kHorizonZ) / across;
  return {w[0] * scale, w[1] * scale, kHorizonZ};
}

// The upper hemisphere on a square of (size + 1)^2 vertices: vertex (i, j) is at (u, v) = (2 i /
// size - 1, 2 j / size - 1), direction normalise(p_x, p_y, 1 - |p_x| - |p_y|) with p = ((u + v)
// / 2, (u - v) / 2); the square's edge is the cloth's plane. x -> -x and y -> -y permute the
// vertices, so the map is exact under both mirrors. Level l has size >> l intervals per side, each
// vertex the [1 2 1] / 4 tent (per axis, clamped at the edge) of level l - 1 around the same point.
// Levels are stored one after another, vertex j (s + 1) + i of a level at offset(l) + j (s + 1) +
// i.
class HemiMap {
 public:
  explicit HemiMap(std::uint32_t size) {
    std::uint64_t at = 0;
    for (std::uint32_t s = size; s >= kMinMapSize; s /= 2) {
      sizes_.push_back(s);
      offsets_.push_back(at);
      at += std::uint64_t(s + 1) * (s + 1);
    }
    vertices_ = at;
  }

  std::uint32_t levels() const { return std::uint32_t(sizes_.size()); }
  std::uint32_t size(std::uint32_t level) const { return sizes_[level]; }
  std::uint64_t offset(std::uint32_t level) const { return offsets_[level]; }
  std::uint64_t vertices() const { return vertices_; }
  std::uint32_t side() const { return sizes_[0] + 1; }

  Vec3 direction(std::uint32_t i, std::uint32_t j) const {
    const double s = sizes_[0];
    const double u = 2.0 * i / s - 1.0, v = 2.0 * j / s - 1.0;
    const double px = 0.5 * (u + v), py = 0.5 * (u - v);
    Vec3 w = {px, py, std::max(0.0, 1.0 - std::fabs(px) - std::fabs(py))};
    const double length = std::sqrt(dot(w, w));
    for (double& c : w) c /= length;
    return above_plane(w);
  }

  // The coarsest level whose spacing (near the equator, where it is largest) is at most `width` /
  // per_width and max_spacing, or level 0.
  std::uint32_t level_for(double width, double per_width, double max_spacing) const {
    double spacing = kHalfPi / sizes_[0];
    std::uint32_t level = 0;
    while (level + 1 < levels() && 2.0 * spacing * per_width <= width &&
           2.0 * spacing <= max_spacing) {
      spacing *= 2.0;
      ++level;
    }
    return level;
  }

  // Bilinear weights of w (z >= 0) between the vertices of a level (indices over all levels).
  void bilinear(const Vec3& w, std::uint32_t level, std::uint64_t index[4],
                double weight[4]) const {
    const std::uint32_t s = sizes_[level];
    const double d = std::fabs(w[0]) + std::fabs(w[1]) + std::max(w[2], 0.0);
    const double px = w[0] / d, py = w[1] / d;
    const double x = std::clamp(0.5 * (px + py + 1.0) * s, 0.0, double(s));
    const double y = std::clamp(0.5 * (px - py + 1.0) * s, 0.0, double(s));
    const std::uint32_t i = std::min(std::uint32_t(x), s - 1),
                        j = std::min(std::uint32_t(y), s - 1);
    const double fx = x - i, fy = y - j;
    index[0] = offsets_[level] + std::uint64_t(j) * (s + 1) + i;
    index[1] = index[0] + 1;
    index[2] = index[0] + s + 1;
    index[3] = index[2] + 1;
    weight[0] = (1.0 - fx) * (1.0 - fy);
    weight[1] = fx * (1.0 - fy);
    weight[2] = (1.0 - fx) * fy;
    weight[3] = fx * fy;
  }

  // Fills levels 1.. of `values` (vertex-major, `count` floats per vertex) from level 0.
  void reduce(float* values, std::size_t count) const {
    for (std::uint32_t l = 1; l < levels(); ++l) {
      const std::uint32_t s = sizes_[l], fine = sizes_[l - 1];
      for (std::uint32_t j = 0; j <= s; ++j)
        for (std::uint32_t i = 0; i <= s; ++i) {
          float* out = values + (offsets_[l] + std::uint64_t(j) * (s + 1) + i) * count;
          std::fill(out, out + count, 0.0f);
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const std::int64_t fi = std::clamp<std::int64_t>(2 * std::int64_t(i) + di, 0, fine);
              const std::int64_t fj = std::clamp<std::int64_t>(2 * std::int64_t(j) + dj, 0, fine);
              const float weight = float((2 - std::abs(di)) * (2 - std::abs(dj))) / 16.0f;
              const float* in =
                  values + (offsets_[l - 1] + std::uint64_t(fj) * (fine + 1) + fi) * count;
              for (std::size_t k = 0; k < count; ++k) out[k] += weight * in[k];
            }
        }
    }
  }

 private:
  std::vector<std::uint32_t> sizes_;
  std::vector<std::uint64_t> offsets_;
  std::uint64_t vertices_ = 0;
};

// W around a point c where the fibre runs end-on into D's boundary (c = +-t, c . n' = 0): on a
// polar grid, w = cos(r) c + sin(r) (cos(a) b + sin(a) n') with r log-spaced in [r_min, r_max]
// (rings) and a in [0, pi] (angles: the half towards D), read bilinearly in (log r, a).
struct PolarPatch {
  Vec3 centre, along, inward;  // c, b, n'
  std::uint64_t offset = 0;    // of vertex (ring 0, angle 0) in the table's values
};

class PolarGrid {
 public:
  explicit PolarGrid(const ClothSampling& s)
      : rings_(s.polar_rings),
        angles_(s.polar_angles),
        cos_max_(std::cos(s.polar_radius)),
        log_min_(std::log(s.polar_radius_min)),
        log_max_(std::log(s.polar_radius)) {}

  std::uint64_t vertices() const { return std::uint64_t(rings_) * angles_; }

  Vec3 direction(const PolarPatch& p, std::uint32_t ring, std::uint32_t angle) const {
    const double r = std::exp(log_min_ + (log_max_ - log_min_) * ring / (rings_ - 1));
    const double a = kPi * angle / (angles_ - 1);
    const Vec3 side = axpy(std::cos(a), p.along, scaled(std::sin(a), p.inward));
    return above_plane(axpy(std::cos(r), p.centre, scaled(std::sin(r), side)));
  }

  // The bilinear weights of w when it is within the patch's radius.
  bool bilinear(const PolarPatch& p, const Vec3& w, std::uint64_t index[4],
                double weight[4]) const {
    const double c = dot(w, p.centre);
    if (!(c > cos_max_)) return false;
    const double x = dot(w, p.along), y = std::max(dot(w, p.inward), 0.0);
    const double r = std::atan2(std::sqrt(x * x + y * y), c);
    const double u = std::clamp(
        (std::log(std::max(r, 1e-300)) - log_min_) / (log_max_ - log_min_) * (rings_ - 1), 0.0,
        double(rings_ - 1));
    const double v = std::atan2(y, x) / kPi * (angles_ - 1);
    const std::uint32_t i = std::min(std::uint32_t(u), rings_ - 2);
    const std::uint32_t j = std::min(std::uint32_t(std::max(v, 0.0)), angles_ - 2);
    const double fx = u - i, fy = std::clamp(v - j, 0.0, 1.0);
    index[0] = p.offset + std::uint64_t(i) * angles_ + j;
    index[1] = index[0] + angles_;
    index[2] = index[0] + 1;
    index[3] = index[1] + 1;
    weight[0] = (1.0 - fx) * (1.0 - fy);
    weight[1] = fx * (1.0 - fy);
    weight[2] = (1.0 - fx) * fy;
    weight[3] = fx * fy;
    return true;
  }

 private:
  std::uint32_t rings_, angles_;
  double cos_max_, log_min_, log_max_;
};

// Where a table's W values are: the hemi map's levels, then one polar patch per end-on point of
// its fibre in D's closure (t when sin(tau) >= 0, -t when sin(tau) <= 0: both for tau = 0).
struct TableMaps {
  TableMaps(const HemiMap& hemi, const PolarGrid& polar, const Fibre& f)
      : hemi(hemi), polar(polar) {
    std::uint64_t at = hemi.vertices();
    for (const double sign : {1.0, -1.0}) {
      if (sign * f.t[2] < 0.0) continue;
      patches.push_back({scaled(sign, f.t), f.b, f.normal, at});
      at += polar.vertices();
    }
    values = at;
  }

  // The four values and weights of w, on the hemi map's level or a patch.
  void bilinear(const Vec3& w, std::uint32_t level, std::uint64_t index[4],
                double weight[4]) const {
    for (const PolarPatch& p : patches)
      if (polar.bilinear(p, w, index, weight)) return;
    hemi.bilinear(w, level, index, weight);
  }

  const HemiMap& hemi;
  const PolarGrid& polar;
  std::vector<PolarPatch> patches;
  std::uint64_t values = 0;
};

// ---- The lobe quadrature of T -----------------------------------------------------------------

// The part of a great half-circle w = cos(alpha) xi + sin(alpha) e, alpha in [0, pi], where w . h
// > 0, as [s_lo, s_hi] in s = 1 - cos(alpha), from a = xi . h and b = e . h (a cos(alpha) +
// b sin(alpha) peaks at atan2(b, a) and is positive within pi/2 of it); false when empty. 1 -
// |b| / r is written a^2 / (r (r + |b|)) to keep it accurate near 0.
bool positive_part(double a, double b, double& s_lo, double& s_hi) {
  const double r = std::sqrt(a * a + b * b);
  if (!(r > 0.0)) return false;
  const double near_one = a * a / (r * (r + std::fabs(b)));
  if (a >= 0.0) {
    s_lo = 0.0;
    s_hi = b >= 0.0 ? 1.0 + b / r : near_one;
  } else {
    s_lo = b >= 0.0 ? near_one : 1.0 - b / r;
    s_hi = 2.0;
  }
  return s_lo < s_hi;
}

// The point of the closure of D = {z > 0, w . n' > 0} nearest to xi (xi itself when inside):
// one of xi's projections onto the two boundary circles, or one of their crossings +-b.
Vec3 nearest_in_front(const Vec3& xi, const Fibre& f, bool& inside) {
  inside = dot(xi, kNormal) >= 0.0 && dot(xi, f.normal) >= 0.0;
  if (inside) return xi;
  const Vec3* planes[2] = {&kNormal, &f.normal};
  Vec3 best = f.b;
  double best_dot = -2.0;
  for (int k = 0; k < 2; ++k) {
    Vec3 q;
    if (orthogonal_unit(xi, *planes[k], q) && dot(q, *planes[1 - k]) >= 0.0 &&
        dot(q, xi) > best_dot) {
      best = q;
      best_dot = dot(q, xi);
    }
  }
  for (const double sign : {1.0, -1.0}) {
    const Vec3 corner = {sign * f.b[0], sign * f.b[1], sign * f.b[2]};
    if (dot(corner, xi) > best_dot) {
      best = corner;
      best_dot = dot(corner, xi);
    }
  }
  return best;
}

// [s0, s1] of D on the great half-circle from xi towards dir (false: it misses D).
bool clip_half_circle(const Fibre& f, const Vec3& xi, const Vec3& dir, double& s0, double& s1) {
  double lo1, hi1, lo2, hi2;
  if (!positive_part(xi[2], dir[2], lo1, hi1) ||
      !positive_part(dot(xi, f.normal), dot(dir, f.normal), lo2, hi2))
    return false;
  s0 = std::max(lo1, lo2);
  s1 = std::min(hi1, hi2);
  return s0 < s1;
}

// The azimuths' frame at xi: e1 towards the nearest point of D when xi is outside (so that the
// azimuths crowd around it; around b and -b both when they tie), else towards the normal; both
// commute with the mirrors x -> -x (of a symmetric multiset) and y -> -y. `spread` is the width
// in azimuth, times kAzimuthSpread, of the lobe's mass in D: 1 inside D; outside, where the lobe
// has fallen by 1/e from its value at the nearest point along D's edge (found by doubling: the
// edge may be smooth there or a corner). `width` is the lobe's extent in D: 1/sqrt(lambda), or,
// outside, the decay length 1 / (lambda sin(d)) of its mass into D (d the distance to D) when
// that is shorter.
struct AzimuthFrame {
  Vec3 e1, e2;
  double spread = 1.0;
  double width = 1.0;
  bool both_ways = false;  // D's nearest points are b and -b, at phi = 0 and pi
};

double azimuth_spread(const Fibre& f, const Vec3& xi, const AzimuthFrame& frame, double lambda) {
  double s_near, s1;
  if (!clip_half_circle(f, xi, frame.e1, s_near, s1)) return 1.0;
  for (double phi = 1e-6; phi < kPi; phi *= 2.0) {
    bool fallen = true;
    for (const double sign : {1.0, -1.0}) {
      const Vec3 dir = axpy(std::cos(phi), frame.e1, scaled(sign * std::sin(phi), frame.e2));
      double s0;
      if (clip_half_circle(f, xi, dir, s0, s1) && lambda * (s0 - s_near) < 1.0) fallen = false;
    }
    if (fallen) return std::min(1.0, kAzimuthSpread * phi);
  }
  return 1.0;
}

AzimuthFrame azimuth_frame(const Vec3& xi, const Fibre& f, double lambda) {
  bool inside = false;
  const Vec3 near = nearest_in_front(xi, f, inside);
  AzimuthFrame frame;
  frame.width = 1.0 / std::sqrt(lambda);
  Vec3& e = frame.e1;
  const bool outside = !inside && orthogonal_unit(near, xi, e);
  if (!outside && !orthogonal_unit(kNormal, xi, e) && !orthogonal_unit(f.b, xi, e))
    orthogonal_unit(Vec3{1.0, 0.0, 0.0}, xi, e);
  frame.e2 = cross(xi, e);
  if (outside) {
    const double c = std::clamp(dot(near, xi), -1.0, 1.0), s = std::sqrt(1.0 - c * c);
    if (s > 0.0) frame.width = std::min(frame.width, 1.0 / (lambda * s));
    frame.both_ways = std::fabs(dot(xi, f.b)) <= kTie && std::fabs(dot(near, f.b)) >= 1.0 - kTie;
    frame.spread = azimuth_spread(f, xi, frame, lambda);
  }
  return frame;
}

// The weights of one lobe's quadrature on a table's values, merged per value; T is the sum of
// weight x W over them divided by `total`.
struct LobeStencil {
  std::vector<std::uint64_t> values;
  std::vector<double> weights;
  double total = 0.0;
  // Scratch: one per value of the table, zero between calls.
  std::vector<double> dense;
};

// The great half-circles from xi: their directions, the measure dphi each stands for, and [s0,
// s1], the part in D of each in s = 1 - w . xi; s_near is the least s0 (the nearest point of D).
// Azimuth phi = 2 atan(r tan(t / 2)) at the midpoints t of `count` equal steps over (-pi, pi):
// uniform for r = 1, crowded near 0 (towards D) with spacing r dt there for r = the frame's
// spread; when D's nearest points tie, phi = atan2(r sin(t), cos(t)), crowded near 0 and pi. No
// azimuth runs exactly through the nearest point of D: where the fibre runs end-on into D's
// boundary, W along that azimuth is unlike W on either side.
struct Azimuths {
  std::vector<double> half_tangents;  // tan(t / 2) of each azimuth
  std::vector<Vec3> dirs;
  std::vector<double> measure, s0, s1;
  double s_near = std::numeric_limits<double>::infinity();
  double width = 1.0;  // the frame's
};

void clip_azimuths(const Fibre& f, const Vec3& xi, double lambda, std::uint32_t count,
                   Azimuths& out) {
  if (out.half_tangents.size() != count) {
    out.half_tangents.resize(count);
    for (std::uint32_t m = 0; m < count; ++m)
      out.half_tangents[m] = std::tan(kPi * (m + 0.5) / count - 0.5 * kPi);
  }
  const AzimuthFrame frame = azimuth_frame(xi, f, lambda);
  const double r = frame.spread;
  out.width = frame.width;
  out.dirs.resize(count);
  out.measure.resize(count);
  out.s0.assign(count, 0.0);
  out.s1.assign(count, 0.0);
  out.s_near = std::numeric_limits<double>::infinity();
  for (std::uint32_t m = 0; m < count; ++m) {
    // cos(phi), sin(phi) and dphi/dt from T = tan(t / 2), without trigonometry.
    const double tt = out.half_tangents[m] * out.half_tangents[m];
    double cos_phi, sin_phi;
    if (frame.both_ways) {  // phi = atan2(r sin(t), cos(t))
      const double c = (1.0 - tt) / (1.0 + tt), s = 2.0 * out.half_tangents[m] / (1.0 + tt);
      const double rho = std::sqrt(c * c + r * r * s * s);
      cos_phi = c / rho;
      sin_phi = r * s / rho;
      out.measure[m] = 2.0 * kPi / count * r / (rho * rho);
    } else {  // phi = 2 atan(q), q = r tan(t / 2)
      const double q = r * out.half_tangents[m];
      cos_phi = (1.0 - q * q) / (1.0 + q * q);
      sin_phi = 2.0 * q / (1.0 + q * q);
      out.measure[m] = 2.0 * kPi / count * r * (1.0 + tt) / (1.0 + r * r * tt);
    }
    out.dirs[m] = axpy(cos_phi, frame.e1, scaled(sin_phi, frame.e2));
    double lo, hi;
    if (!clip_half_circle(f, xi, out.dirs[m], lo, hi)) continue;
    out.s0[m] = lo;
    out.s1[m] = hi;
    out.s_near = std::min(out.s_near, lo);
  }
}

// Adds the nodes of one great half-circle, [s0, s1] of it in D: in x = lambda (s - s0) the lobe
// is exp(-x) dx, cut into pieces at x = 1, 3, 7, 15, ... (so that its tail is sampled as well as
// its peak), at most lambda radial_step long (so that W's own features are), ending at
// kMaxExponent; each piece has radial_nodes points at the midpoints of equal shares of its mass.
void add_half_circle(const TableMaps& maps, const ClothSampling& sampling, const Vec3& xi,
                     const Vec3& dir, double s0, double s1, double lambda, double scale,
                     std::uint32_t level, LobeStencil& out) {
  const std::uint32_t k_count = sampling.radial_nodes;
  const double x_end = std::min(lambda * (s1 - s0), kMaxExponent);
  double a = 0.0, next = 1.0;
  while (a < x_end) {
    while (next <= a) next = 2.0 * next + 1.0;
    const double b = std::min({next, a + lambda * sampling.radial_step, x_end});
    const double share = -std::expm1(-(b - a));
    const double node_weight = scale * std::exp(-a) * share / k_count;
    out.total += node_weight * k_count;
    for (std::uint32_t k = 0; k < k_count; ++k) {
      const double u = (k + 0.5) / k_count;
      const double s = std::min(s0 + (a - std::log1p(-u * share)) / lambda, 2.0);
      const Vec3 w = axpy(1.0 - s, xi, scaled(std::sqrt(std::max(0.0, s * (2.0 - s))), dir));
      std::uint64_t index[4];
      double weight[4];
      maps.bilinear(w, level, index, weight);
      for (int c = 0; c < 4; ++c) {
        if (weight[c] == 0.0) continue;
        if (out.dense[index[c]] == 0.0) out.values.push_back(index[c]);
        out.dense[index[c]] += node_weight * weight[c];
      }
    }
    a = b;
  }
}

// The quadrature of lobe (xi, lambda) over D: on each great half-circle from xi, clipped to D,
// the lobe is exp(-lambda s) ds dphi, weighed relative to the nearest part of D (so that no lobe
// underflows) and sampled by add_half_circle.
void lobe_stencil(const TableMaps& maps, const Fibre& f, const ClothSampling& sampling,
                  const Vec3& xi, double lambda, Azimuths& azimuths, LobeStencil& out) {
  out.values.clear();
  out.weights.clear();
  out.total = 0.0;
  if (out.dense.size() != maps.values) out.dense.assign(maps.values, 0.0);
  clip_azimuths(f, xi, lambda, sampling.azimuth_nodes, azimuths);
  const std::uint32_t level =
      maps.hemi.level_for(azimuths.width, sampling.map_texels_per_width, sampling.max_spacing);
  for (std::uint32_t m = 0; m < sampling.azimuth_nodes; ++m) {
    const double s0 = azimuths.s0[m], s1 = azimuths.s1[m];
    const double scale = std::exp(-lambda * (s0 - azimuths.s_near)) * azimuths.measure[m];
    if (!(s1 > s0) || !(scale > 0.0)) continue;
    add_half_circle(maps, sampling, xi, azimuths.dirs[m], s0, s1, lambda, scale, level, out);
  }
  for (const std::uint64_t v : out.values) {
    out.weights.push_back(out.dense[v]);
    out.dense[v] = 0.0;
  }
}

// The lobe's integral over D as a share of its integral over the sphere, from the stencil's total
// (lambda times the integral over D of exp(-lambda (s - s_near))): what T over D becomes divided
// by the whole sphere's integral instead (ClothSampling::full_sphere_denominator).
double share_in_domain(const LobeStencil& stencil, const Azimuths& azimuths, double lambda) {
  return stencil.total * std::exp(-lambda * azimuths.s_near) /
         (2.0 * kPi * -std::expm1(-2.0 * lambda));
}

// ---- The cone of T_c --------------------------------------------------------------------------

// The fibre's specular cone of a view: w = -s_o t + c_o (cos(phi) n' + sin(phi) b), and its arc
// in D, |phi| < phi_max (w . n' > 0 needs |phi| < pi/2, z > 0 needs c_o cos(tau) cos(phi) > s_o
// sin(tau)).
struct ConeArc {
  double s_o = 0.0, c_o = 0.0, phi_max = 0.0;
  bool empty = true;
};

ConeArc cone_arc(const Fibre& f, const Vec3& view) {
  ConeArc arc;
  arc.s_o = std::clamp(dot(view, f.t), -1.0, 1.0);
  arc.c_o = std::sqrt(std::max(0.0, 1.0 - arc.s_o * arc.s_o));
  const double q = arc.s_o * f.t[2];                      // s_o sin(tau)
  const double r = arc.c_o * std::max(f.normal[2], 0.0);  // c_o cos(tau)
  if (q < 0.0) {
    arc.phi_max = kHalfPi;
  } else if (r > q) {
    arc.phi_max = std::acos(q / r);
  }
  arc.empty = !(arc.phi_max > 0.0);
  return arc;
}

// W along a cone's arc at `nodes` midpoints of equal dphi, then means of pairs: level l holds
// nodes >> l values at offset 2 nodes - 2 (nodes >> (l - 1)).
class ConeSamples {
 public:
  void sample(const Weights& weights, std::uint32_t tangent, const Fibre& f, const ConeArc& arc,
              const float view[3], std::uint32_t nodes) {
    nodes_ = nodes;
    arc_ = arc;
    values_.assign(2 * std::size_t(nodes) - 1, 0.0);
    if (arc.empty) return;
    float w[PRT_CLOTH_MAX_THREAD_TANGENTS];
    const double h = 2.0 * arc.phi_max / nodes;
    for (std::uint32_t n = 0; n < nodes; ++n) {
      const double phi = -arc.phi_max + (n + 0.5) * h;
      const double c = arc.c_o * std::cos(phi), s = arc.c_o * std::sin(phi);
      const Vec3 dir =
          axpy(-arc.s_o, f.t, axpy(c, f.normal, Vec3{s * f.b[0], s * f.b[1], s * f.b[2]}));
      weights(dir, view, w);
      values_[n] = w[tangent];
    }
    std::size_t from = 0, to = nodes;
    for (std::uint32_t count = nodes / 2; count >= 1; count /= 2) {
      for (std::uint32_t n = 0; n < count; ++n)
        values_[to + n] = 0.5 * (values_[from + 2 * n] + values_[from + 2 * n + 1]);
      from = to;
      to += count;
    }
  }

  // T_c of a lobe whose axis has the part `across` (its length in the plane of n' and b) at
  // azimuth phi_xi about t: on the cone the lobe is exp(lambda (A - 1)) exp(-2 kappa sin^2((phi -
  // phi_xi) / 2)) with kappa = lambda c_o across; the first factor cancels in the ratio.
  double value(double across, double phi_xi, double lambda, double per_width,
               double max_spacing) const {
    if (arc_.empty) return 0.0;
    const double kappa = lambda * arc_.c_o * across;
    // The lobe's extent along the arc: its width, or, when it peaks outside the arc, the decay
    // length 1 / (kappa sin(d)) of its weight into the arc from the end at distance d if shorter.
    double width = kappa > 0.0 ? 1.0 / std::sqrt(kappa) : std::numeric_limits<double>::infinity();
    double reach = kConeWindowWidths * width;
    const double beyond = std::fabs(phi_xi) - arc_.phi_max;
    if (beyond > 0.0 && kappa > 0.0) {
      const double decay = 1.0 / (kappa * std::sin(std::min(beyond, kHalfPi)));
      width = std::min(width, decay);
      reach = std::max(reach, kConeWindowDecays * decay);
    }
    std::uint32_t count = nodes_;
    std::size_t at = 0;
    while (count > 1 && 2.0 * (2.0 * arc_.phi_max / count) * per_width <= width &&
           2.0 * (2.0 * arc_.phi_max / count) <= max_spacing) {
      at += count;
      count /= 2;
    }
    const double h = 2.0 * arc_.phi_max / count;
    const std::int64_t half = std::isfinite(reach) && reach < 2.0 * arc_.phi_max
                                  ? std::int64_t(std::ceil(reach / h)) + 1
                                  : std::int64_t(count);
    const double clamped = std::clamp(phi_xi, -arc_.phi_max, arc_.phi_max);
    const std::int64_t last = std::int64_t(count) - 1;
    const std::int64_t centre =
        std::clamp(std::int64_t((clamped + arc_.phi_max) / h), std::int64_t(0), last);
    // A lobe outside the arc peaks at an end; one behind the fibre may peak at either.
    std::int64_t ranges[2][2] = {
        {std::max<std::int64_t>(0, centre - half), std::min(last, centre + half)}, {1, 0}};
    if (std::fabs(phi_xi) > arc_.phi_max) {
      const std::int64_t other = centre == 0 ? last : 0;
      ranges[1][0] = std::max<std::int64_t>(0, other - half);
      ranges[1][1] = std::min(last, other + half);
      if (ranges[1][0] <= ranges[0][1] && ranges[0][0] <= ranges[1][1]) {
        ranges[0][0] = std::min(ranges[0][0], ranges[1][0]);
        ranges[0][1] = std::max(ranges[0][1], ranges[1][1]);
        ranges[1][0] = 1;
        ranges[1][1] = 0;
      }
    }
    // Level l holds means of 2^l samples, about W + (h^2 / 24)(1 - 4^-l) W'' over a spacing h;
    // the kernel's weights are corrected by the same amount of its second derivative so that the
    // sum keeps the integral's accuracy (the smoothing would otherwise bias sharp lobes).
    const double smoothing =
        h * h / 24.0 * (1.0 - double(count) * count / (double(nodes_) * nodes_));
    // Exponent and curvature of each node, cos and sin of its distance d from phi_xi stepped by
    // rotation through h.
    const double cos_h = std::cos(h), sin_h = std::sin(h);
    scratch_.clear();
    double peak = -std::numeric_limits<double>::infinity();
    for (const auto& r : ranges) {
      const double d0 = -arc_.phi_max + (r[0] + 0.5) * h - phi_xi;
      double c = std::cos(d0), s = std::sin(d0);
      for (std::int64_t n = r[0]; n <= r[1]; ++n) {
        const double e = -kappa * (1.0 - c);
        peak = std::max(peak, e);
        scratch_.push_back({e, kappa * kappa * s * s - kappa * c});
        const double next = c * cos_h - s * sin_h;
        s = s * cos_h + c * sin_h;
        c = next;
      }
    }
    double sum_w = 0.0, sum = 0.0;
    std::size_t k = 0;
    for (const auto& r : ranges)
      for (std::int64_t n = r[0]; n <= r[1]; ++n, ++k) {
        const double g = std::exp(scratch_[k][0] - peak) * (1.0 - smoothing * scratch_[k][1]);
        sum_w += g * values_[at + n];
        sum += g;
      }
    return std::clamp(sum_w / sum, 0.0, 1.0);
  }

 private:
  std::uint32_t nodes_ = 0;
  ConeArc arc_;
  std::vector<double> values_;
  mutable std::vector<std::array<double, 2>> scratch_;
};

// A lobe axis's coordinates about a fibre: its length across t and its azimuth from n'.
void cone_coordinates(const Vec3& xi, const Fibre& f, double& across, double& phi_xi) {
  const double a = dot(xi, f.normal), b = dot(xi, f.b);
  across = std::sqrt(a * a + b * b);
  phi_xi = std::atan2(b, a);
}

// ---- Checks -----------------------------------------------------------------------------------

bool power_of_two(std::uint32_t v) {
  return v != 0 && (v & (v - 1)) == 0;
}

void check_grid(const ClothGrid& g) {
  const bool ok = g.xi_size >= 2 && g.xi_size <= 256 && g.lambda_levels >= 1 &&
                  g.lambda_levels <= 64 && std::isfinite(g.lambda_min) && g.lambda_min > 0.0f &&
                  std::isfinite(g.lambda_max) && g.lambda_max >= g.lambda_min &&
                  (g.lambda_levels > 1 || g.lambda_max == g.lambda_min) && g.view_theta >= 2 &&
                  g.view_theta <= 256 && g.view_phi >= 2 && g.view_phi <= 256;
  if (!ok) throw Error("cloth tables: invalid grid (formats/SPEC.md §7.4's ranges)");
}

void check_sampling(const ClothSampling& s) {
  const bool ok = power_of_two(s.map_size) && s.map_size >= 8 && s.map_size <= 1024 &&
                  std::isfinite(s.map_texels_per_width) && s.map_texels_per_width > 0.0 &&
                  s.radial_nodes >= 1 && s.radial_nodes <= 1024 && std::isfinite(s.radial_step) &&
                  s.radial_step > 0.0 && s.azimuth_nodes >= 2 && s.azimuth_nodes <= 1024 &&
                  s.azimuth_nodes % 2 == 0 && power_of_two(s.cone_nodes) && s.cone_nodes >= 8 &&
                  s.cone_nodes <= 65536 && std::isfinite(s.cone_nodes_per_width) &&
                  s.cone_nodes_per_width > 0.0 && std::isfinite(s.max_spacing) &&
                  s.max_spacing > 0.0 && std::isfinite(s.polar_radius) && s.polar_radius > 0.0 &&
                  s.polar_radius < 1.0 && std::isfinite(s.polar_radius_min) &&
                  s.polar_radius_min > 0.0 && s.polar_radius_min < s.polar_radius &&
                  s.polar_rings >= 2 && s.polar_rings <= 1024 && s.polar_angles >= 2 &&
                  s.polar_angles <= 1024;
  if (!ok) throw Error("cloth tables: invalid sampling settings");
}

void check_key(const ClothTableKey& key) {
  const std::size_t count = key.offsets.size();
  bool ok = count >= 1 && count <= PRT_CLOTH_MAX_THREAD_TANGENTS &&
            key.multiplicities.size() == count && key.tangent < count;
  for (std::size_t k = 0; ok && k < count; ++k)
    ok = std::isfinite(key.offsets[k]) && std::fabs(key.offsets[k]) <= float(kHalfPi) &&
         (k == 0 || key.offsets[k - 1] < key.offsets[k]) && key.multiplicities[k] >= 1 &&
         key.multiplicities[k] <= PRT_CLOTH_MAX_MULTIPLICITY;
  if (!ok) throw Error("cloth tables: invalid table key (a thread's multiset and one offset)");
}

// ---- The batch --------------------------------------------------------------------------------

// What one table needs in the batch: its fibre and maps, its W values for every view (value-major,
// views contiguous) and, per lobe axis, the axis's coordinates about the fibre.
struct TableWork {
  TableWork(std::size_t key, float tau, const HemiMap& hemi, const PolarGrid& polar)
      : key(key), fibre(fibre_of(tau)), maps(hemi, polar, fibre) {}

  std::size_t key;
  Fibre fibre;
  TableMaps maps;
  std::vector<float> values;
  std::vector<double> across, phi_xi;
};

// Every direction a table's polar patches read W at, in the order of their values.
std::vector<Vec3> polar_directions(const TableMaps& maps, const ClothSampling& s) {
  std::vector<Vec3> dirs;
  for (const PolarPatch& p : maps.patches)
    for (std::uint32_t ring = 0; ring < s.polar_rings; ++ring)
      for (std::uint32_t angle = 0; angle < s.polar_angles; ++angle)
        dirs.push_back(maps.polar.direction(p, ring, angle));
  return dirs;
}

// The tables' columns [first_view, first_view + view_count) (all of them in a whole bake): every
// step of a column reads its own view only, so a column is the same whichever others it is
// computed with.
class Batch {
 public:
  Batch(const ClothGrid& grid, const ClothSampling& sampling, std::uint64_t first_view,
        std::uint64_t view_count, const Context& ctx)
      : grid_(grid), sampling_(sampling), ctx_(ctx), hemi_(sampling.map_size), polar_(sampling) {
    const std::uint32_t n = grid.xi_size;
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i) axes_.push_back(lobe_axis(n, i, j));
    for (std::uint32_t l = 0; l < grid.lambda_levels; ++l)
      lambdas_.push_back(lobe_sharpness(grid, l));
    for (std::uint64_t v = first_view; v < first_view + view_count; ++v)
      views_.push_back(
          view_direction(grid, std::uint32_t(v / grid.view_phi), std::uint32_t(v % grid.view_phi)));
    for (std::uint32_t j = 0; j < hemi_.side(); ++j)
      for (std::uint32_t i = 0; i < hemi_.side(); ++i) hemi_dirs_.push_back(hemi_.direction(i, j));
  }

  // The tables of one multiset (keys[k] for k in `group`), into out[k].
  void run(const std::vector<ClothTableKey>& keys, const std::vector<std::size_t>& group,
           std::vector<ClothTableSamples>& out) {
    const std::size_t columns = views_.size();
    std::vector<TableWork> work;
    work.reserve(group.size());
    for (const std::size_t k : group) {
      TableWork& w = work.emplace_back(k, keys[k].offset(), hemi_, polar_);
      w.values.assign(w.maps.values * columns, 0.0f);
      for (const Vec3& xi : axes_) {
        double across, phi;
        cone_coordinates(xi, w.fibre, across, phi);
        w.across.push_back(across);
        w.phi_xi.push_back(phi);
      }
      out[k].full.assign(grid_.rows() * columns, 0.0f);
      out[k].cone.assign(grid_.rows() * columns, 0.0f);
    }
    const Weights weights(keys[group[0]]);
    render::parallel_tasks(columns, ctx_, "cloth tables: W per view",
                           [&](std::size_t v) { sample_view(weights, keys, v, work, out); });
    for (TableWork& w : work) hemi_.reduce(w.values.data(), columns);
    const std::size_t blocks = (grid_.rows() + kRowsPerTask - 1) / kRowsPerTask;
    render::parallel_tasks(blocks * work.size(), ctx_, "cloth tables: lobe sums",
                           [&](std::size_t task) {
                             const TableWork& w = work[task / blocks];
                             sum_rows(w, task % blocks, out[w.key].full);
                           });
  }

 private:
  // W on the maps of every table for view v, and that view's column of every T_c.
  void sample_view(const Weights& weights, const std::vector<ClothTableKey>& keys, std::size_t v,
                   std::vector<TableWork>& work, std::vector<ClothTableSamples>& out) const {
    const std::size_t columns = views_.size();
    const float view[3] = {float(views_[v][0]), float(views_[v][1]), float(views_[v][2])};
    float w[PRT_CLOTH_MAX_THREAD_TANGENTS];
    for (std::size_t i = 0; i < hemi_dirs_.size(); ++i) {
      weights(hemi_dirs_[i], view, w);
      for (TableWork& t : work) t.values[i * columns + v] = w[keys[t.key].tangent];
    }
    ConeSamples cone;
    const std::size_t n2 = axes_.size();
    for (TableWork& t : work) {
      const std::uint32_t tangent = keys[t.key].tangent;
      const std::vector<Vec3> dirs = polar_directions(t.maps, sampling_);
      for (std::size_t i = 0; i < dirs.size(); ++i) {
        weights(dirs[i], view, w);
        t.values[(hemi_.vertices() + i) * columns + v] = w[tangent];
      }
      cone.sample(weights, tangent, t.fibre, cone_arc(t.fibre, views_[v]), view,
                  sampling_.cone_nodes);
      float* column = out[t.key].cone.data() + v;
      for (std::size_t l = 0; l < lambdas_.size(); ++l)
        for (std::size_t x = 0; x < n2; ++x)
          column[(l * n2 + x) * columns] =
              float(cone.value(t.across[x], t.phi_xi[x], lambdas_[l],
                               sampling_.cone_nodes_per_width, sampling_.max_spacing));
    }
  }

  // Rows [block kRowsPerTask, ...) of a table's T: each lobe's stencil against every view's values.
  void sum_rows(const TableWork& w, std::size_t block, std::vector<float>& full) const {
    const std::size_t columns = views_.size(), n2 = axes_.size();
    const std::size_t first = block * kRowsPerTask;
    const std::size_t last = std::min<std::size_t>(first + kRowsPerTask, grid_.rows());
    LobeStencil stencil;
    Azimuths azimuths;
    std::vector<float> sum(columns);
    for (std::size_t row = first; row < last; ++row) {
      lobe_stencil(w.maps, w.fibre, sampling_, axes_[row % n2], lambdas_[row / n2], azimuths,
                   stencil);
      std::fill(sum.begin(), sum.end(), 0.0f);
      for (std::size_t k = 0; k < stencil.values.size(); ++k) {
        const float weight = float(stencil.weights[k] / stencil.total);
        const float* values = w.values.data() + stencil.values[k] * columns;
        for (std::size_t c = 0; c < columns; ++c) sum[c] += weight * values[c];
      }
      if (sampling_.full_sphere_denominator) {
        const float share = float(share_in_domain(stencil, azimuths, lambdas_[row / n2]));
        for (std::size_t c = 0; c < columns; ++c) sum[c] *= share;
      }
      for (std::size_t c = 0; c < columns; ++c)
        full[row * columns + c] = std::clamp(sum[c], 0.0f, 1.0f);
    }
  }

  ClothGrid grid_;
  ClothSampling sampling_;
  const Context& ctx_;
  HemiMap hemi_;
  PolarGrid polar_;
  std::vector<Vec3> axes_, views_, hemi_dirs_;
  std::vector<double> lambdas_;
};

// The lexicographic order of multisets, for grouping tables by multiset.
bool multiset_less(const ClothTableKey& a, const ClothTableKey& b) {
  if (a.offsets != b.offsets) return a.offsets < b.offsets;
  return a.multiplicities < b.multiplicities;
}

}  // namespace

bool ClothTableKey::operator==(const ClothTableKey& other) const {
  return offsets == other.offsets && multiplicities == other.multiplicities &&
         tangent == other.tangent;
}

ClothGrid default_cloth_grid() {
  ClothGrid g;
  g.xi_size = 32;
  g.lambda_levels = 10;
  g.lambda_min = PRT_CLOTH_MIN_SHARPNESS;
  g.lambda_max = PRT_CLOTH_MAX_SHARPNESS;
  g.view_theta = 16;
  g.view_phi = 16;
  return g;
}

std::vector<ClothTableSamples> sample_cloth_tables(const std::vector<ClothTableKey>& keys,
                                                   const ClothGrid& grid,
                                                   const ClothSampling& sampling,
                                                   const Context& ctx) {
  check_grid(grid);
  return sample_cloth_table_views(keys, grid, sampling, 0, grid.columns(), ctx);
}

std::vector<ClothTableSamples> sample_cloth_table_views(
    const std::vector<ClothTableKey>& keys, const ClothGrid& grid, const ClothSampling& sampling,
    std::uint64_t first_view, std::uint64_t view_count, const Context& ctx) {
  check_grid(grid);
  check_sampling(sampling);
  for (const ClothTableKey& key : keys) check_key(key);
  if (first_view > grid.columns() || view_count > grid.columns() - first_view)
    throw Error("cloth tables: views [" + std::to_string(first_view) + ", " +
                std::to_string(first_view + view_count) + ") are beyond the grid's " +
                std::to_string(grid.columns()));
  // Tables of one multiset share their W calls: group them, groups in order of first key.
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    auto same = [&](const std::vector<std::size_t>& g) {
      return !multiset_less(keys[g[0]], keys[k]) && !multiset_less(keys[k], keys[g[0]]);
    };
    auto it = std::find_if(groups.begin(), groups.end(), same);
    if (it == groups.end())
      groups.push_back({k});
    else
      it->push_back(k);
  }
  std::vector<ClothTableSamples> out(keys.size());
  if (view_count == 0) return out;  // no columns: nothing to sample
  Batch batch(grid, sampling, first_view, view_count, ctx);
  for (const auto& group : groups) batch.run(keys, group, out);
  return out;
}

// ---- The probe --------------------------------------------------------------------------------

struct ClothTableProbe::State {
  State(const ClothTableKey& key, const double v[3], const ClothSampling& s)
      : sampling(s),
        hemi(s.map_size),
        polar(s),
        fibre(fibre_of(key.offset())),
        maps(hemi, polar, fibre),
        weights(key) {
    const float view[3] = {float(v[0]), float(v[1]), float(v[2])};
    values.assign(maps.values, 0.0f);
    float w[PRT_CLOTH_MAX_THREAD_TANGENTS];
    for (std::uint32_t j = 0; j < hemi.side(); ++j)
      for (std::uint32_t i = 0; i < hemi.side(); ++i) {
        weights(hemi.direction(i, j), view, w);
        values[std::size_t(j) * hemi.side() + i] = w[key.tangent];
      }
    hemi.reduce(values.data(), 1);
    const std::vector<Vec3> dirs = polar_directions(maps, s);
    for (std::size_t i = 0; i < dirs.size(); ++i) {
      weights(dirs[i], view, w);
      values[hemi.vertices() + i] = w[key.tangent];
    }
    cone.sample(weights, key.tangent, fibre, cone_arc(fibre, Vec3{v[0], v[1], v[2]}), view,
                s.cone_nodes);
  }

  ClothSampling sampling;
  HemiMap hemi;
  PolarGrid polar;
  Fibre fibre;
  TableMaps maps;
  Weights weights;
  std::vector<float> values;
  ConeSamples cone;
  LobeStencil stencil;
  Azimuths azimuths;
};

ClothTableProbe::ClothTableProbe(const ClothTableKey& key, const double view[3],
                                 const ClothSampling& sampling) {
  check_sampling(sampling);
  check_key(key);
  state_ = new State(key, view, sampling);
}

ClothTableProbe::~ClothTableProbe() {
  delete state_;
}

double ClothTableProbe::full(const double xi[3], double lambda) const {
  State& s = *state_;
  lobe_stencil(s.maps, s.fibre, s.sampling, Vec3{xi[0], xi[1], xi[2]}, lambda, s.azimuths,
               s.stencil);
  double sum = 0.0;
  for (std::size_t k = 0; k < s.stencil.values.size(); ++k)
    sum += s.stencil.weights[k] * s.values[s.stencil.values[k]];
  if (s.sampling.full_sphere_denominator)
    return std::clamp(sum / s.stencil.total * share_in_domain(s.stencil, s.azimuths, lambda), 0.0,
                      1.0);
  return std::clamp(sum / s.stencil.total, 0.0, 1.0);
}

double ClothTableProbe::cone(const double xi[3], double lambda) const {
  double across, phi_xi;
  cone_coordinates(Vec3{xi[0], xi[1], xi[2]}, state_->fibre, across, phi_xi);
  return state_->cone.value(across, phi_xi, lambda, state_->sampling.cone_nodes_per_width,
                            state_->sampling.max_spacing);
}

}  // namespace prt::bake
