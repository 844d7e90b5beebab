// SPDX-License-Identifier: MIT
// Sampling the cloth tables (sample_cloth_tables, ClothTableProbe) against what T and T_c must
// be: values in [0, 1]; a lobe far wider than D gives W's mean over D, one far sharper gives W at
// its axis (prt_cloth_thread_weights there); the same along the specular cone; a single offset's
// T is the lobe-weighted mean of M, computed here by brute force on a lat-long grid from
// docs/cloth/model.md's formulas; table entries of mirrored nodes agree; and the tables do not
// depend on the thread count; divided by the lobe's integral over the sphere (paper 003), T is
// scaled by the lobe's share in D.
#include <gtest/gtest.h>
#include <prt/prt_cloth.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "prt/baker/cloth/cloth_tables.hpp"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

float degrees(double d) {
  return float(d * kPi / 180.0);
}

ClothTableKey key_of(std::vector<double> offsets_deg, std::vector<std::uint32_t> counts,
                     std::uint32_t tangent) {
  ClothTableKey key;
  for (const double d : offsets_deg) key.offsets.push_back(degrees(d));
  key.multiplicities = counts;
  key.tangent = tangent;
  return key;
}

const ClothTableKey kSatin18 = key_of({-32, -18, 0, 18, 32}, {2, 1, 2, 1, 2}, 3);
const ClothTableKey kSatin0 = key_of({-32, -18, 0, 18, 32}, {2, 1, 2, 1, 2}, 2);
const ClothTableKey kLinen25 = key_of({-25, 25}, {1, 1}, 1);

// N_xi 8, lambda 0.25, 50, 1e4, views 4 x 4: small enough for a test.
ClothGrid small_grid() {
  ClothGrid g = default_cloth_grid();
  g.xi_size = 8;
  g.lambda_levels = 3;
  g.lambda_min = 0.25f;
  g.lambda_max = 1e4f;
  g.view_theta = 4;
  g.view_phi = 4;
  return g;
}

ClothSampling small_sampling() {
  ClothSampling s;
  s.map_size = 64;
  return s;
}

Vec3 lobe_axis(std::uint32_t n, std::uint32_t i, std::uint32_t j) {  // SPEC §7.4
  const double px = 2.0 * i / (n - 1) - 1.0, py = 2.0 * j / (n - 1) - 1.0;
  const double z = 1.0 - std::fabs(px) - std::fabs(py);
  Vec3 a = z >= 0.0 ? Vec3{px, py, z}
                    : Vec3{(1.0 - std::fabs(py)) * (px < 0.0 ? -1.0 : 1.0),
                           (1.0 - std::fabs(px)) * (py < 0.0 ? -1.0 : 1.0), z};
  const double length = std::sqrt(dot(a, a));
  for (double& c : a) c /= length;
  return a;
}

Vec3 view_of(const ClothGrid& g, std::uint32_t a, std::uint32_t b) {  // SPEC §7.4
  const double theta = 0.5 * kPi * a / (g.view_theta - 1), phi = kPi * b / (g.view_phi - 1);
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// The fibre of offset tau in the canonical frame: t, n', b (docs/cloth/model.md).
struct Fibre {
  Vec3 t, n, b;
};

Fibre fibre_of(float tau) {
  const double c = std::cos(double(tau)), s = std::sin(double(tau));
  return {{c, 0.0, s}, {-s, 0.0, c}, {0.0, 1.0, 0.0}};
}

// W of the key's offset at light w for view v, from the runtime.
double weight(const ClothTableKey& key, const Vec3& w, const Vec3& v) {
  prt_cloth_weave weave{};
  weave.struct_size = sizeof(prt_cloth_weave);
  weave.tangent_count[0] = std::uint32_t(key.offsets.size());
  for (std::size_t k = 0; k < key.offsets.size(); ++k) {
    weave.offsets[0][k] = key.offsets[k];
    weave.multiplicity[0][k] = key.multiplicities[k];
  }
  weave.tangent_count[1] = 1;
  weave.multiplicity[1][0] = 1;
  const float normal[3] = {0.0f, 0.0f, 1.0f}, warp[3] = {1.0f, 0.0f, 0.0f};
  const float light[3] = {float(w[0]), float(w[1]), float(w[2])};
  const float view[3] = {float(v[0]), float(v[1]), float(v[2])};
  float out[PRT_CLOTH_MAX_THREAD_TANGENTS];
  EXPECT_EQ(prt_cloth_thread_weights(&weave, 0, normal, warp, light, view, out), PRT_OK);
  return out[key.tangent];
}

// sum over a lat-long midpoint grid of the upper hemisphere of lobe(w) f(w) dw / lobe(w) dw,
// over the directions in front of the fibre (w . n' > 0).
template <typename F, typename G>
double brute_force_mean(const Fibre& fibre, G lobe, F f, int rows) {
  double num = 0.0, den = 0.0;
  for (int r = 0; r < rows; ++r) {
    const double theta = 0.5 * kPi * (r + 0.5) / rows;
    for (int c = 0; c < 4 * rows; ++c) {
      const double phi = 2.0 * kPi * (c + 0.5) / (4 * rows);
      const Vec3 w = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                      std::cos(theta)};
      if (!(dot(w, fibre.n) > 0.0)) continue;
      const double g = lobe(w) * std::sin(theta);
      num += g * f(w);
      den += g;
    }
  }
  return num / den;
}

TEST(ClothTableSampling, ValuesLieInTheUnitInterval) {
  const ClothGrid grid = small_grid();
  Context ctx;
  const auto tables =
      sample_cloth_tables({kSatin0, kSatin18, kLinen25}, grid, small_sampling(), ctx);
  ASSERT_EQ(tables.size(), 3u);
  for (const ClothTableSamples& t : tables) {
    ASSERT_EQ(t.full.size(), grid.rows() * grid.columns());
    ASSERT_EQ(t.cone.size(), grid.rows() * grid.columns());
    for (const std::vector<float>* values : {&t.full, &t.cone}) {
      const auto [low, high] = std::minmax_element(values->begin(), values->end());
      EXPECT_GE(*low, 0.0f);
      EXPECT_LE(*high, 1.0f);
      EXPECT_GT(*high, 0.3f);  // not a table of zeros
    }
  }
}

TEST(ClothTableSampling, AVeryWideLobeGivesTheMeanOfWOverD) {
  const Fibre fibre = fibre_of(kSatin18.offset());
  for (const Vec3& view : {Vec3{0.0, 0.0, 1.0}, Vec3{0.6, 0.48, 0.64}}) {
    const ClothTableProbe probe(kSatin18, view.data(), ClothSampling{});
    const double mean = brute_force_mean(
        fibre, [](const Vec3&) { return 1.0; },
        [&](const Vec3& w) { return weight(kSatin18, w, view); }, 128);
    for (const Vec3& xi : {Vec3{0.0, 0.0, 1.0}, Vec3{0.0, 0.6, -0.8}, Vec3{-1.0, 0.0, 0.0}}) {
      // lambda = 1e-3: the lobe varies by 0.2 % over the sphere (measured within 1.3e-4).
      EXPECT_NEAR(probe.full(xi.data(), 1e-3), mean, 3e-4) << xi[0] << " " << xi[1];
    }
  }
}

TEST(ClothTableSampling, TheSharpestLobeGivesWAtItsAxis) {
  const ClothGrid grid = small_grid();
  Context ctx;
  for (const ClothTableKey& key : {kSatin18, kLinen25}) {
    const ClothTableSamples t = sample_cloth_tables({key}, grid, ClothSampling{}, ctx)[0];
    const Fibre fibre = fibre_of(key.offset());
    const std::uint32_t n = grid.xi_size, level = grid.lambda_levels - 1;
    double largest = 0.0;
    int compared = 0;
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i) {
        const Vec3 xi = lobe_axis(n, i, j);
        // Inside D, away from its edges and from t (where W depends on the way in).
        if (xi[2] < 0.1 || dot(xi, fibre.n) < 0.1 || dot(xi, fibre.t) > 0.95) continue;
        // Views off the grazing row, where W has steps along w . n'(tau') = 0.
        for (std::uint32_t a = 0; a + 1 < grid.view_theta; ++a)
          for (std::uint32_t b = 0; b < grid.view_phi; ++b) {
            const std::uint64_t row = (std::uint64_t(level) * n + j) * n + i;
            const double value = t.full[row * grid.columns() + a * grid.view_phi + b];
            largest = std::max(largest, std::fabs(value - weight(key, xi, view_of(grid, a, b))));
            ++compared;
          }
      }
    EXPECT_GT(compared, 30);
    EXPECT_LE(largest, 1e-3);  // measured 7e-4: the map's interpolation, and the lobe's width
  }
}

TEST(ClothTableSampling, AConeLobeOnTheConeGivesWThere) {
  const Fibre fibre = fibre_of(kSatin18.offset());
  for (const Vec3& view : {Vec3{0.0, 0.0, 1.0}, Vec3{0.6, 0.48, 0.64}, Vec3{-0.5, 0.1, 0.86}}) {
    const ClothTableProbe probe(kSatin18, view.data(), ClothSampling{});
    // The cone: theta(w) = -theta(view), w = -s t + c (cos(phi) n' + sin(phi) b).
    const double s = dot(view, fibre.t), c = std::sqrt(1.0 - s * s);
    for (const double phi : {-0.6, 0.0, 0.4, 0.9}) {
      Vec3 xi;
      for (int k = 0; k < 3; ++k)
        xi[k] = -s * fibre.t[k] + c * (std::cos(phi) * fibre.n[k] + std::sin(phi) * fibre.b[k]);
      if (xi[2] < 0.05) continue;
      EXPECT_NEAR(probe.cone(xi.data(), 1e4), weight(kSatin18, xi, view), 1e-4) << phi;
    }
    // A lobe far wider than the cone weighs it evenly in phi: W's mean over the arc in D.
    double sum = 0.0;
    int count = 0;
    for (int k = 0; k < 20000; ++k) {
      const double phi = kPi * ((k + 0.5) / 20000 - 0.5);
      Vec3 w;
      for (int i = 0; i < 3; ++i)
        w[i] = -s * fibre.t[i] + c * (std::cos(phi) * fibre.n[i] + std::sin(phi) * fibre.b[i]);
      if (!(w[2] > 0.0)) continue;
      sum += weight(kSatin18, w, view);
      ++count;
    }
    const Vec3 pole = {0.0, 0.0, 1.0};
    EXPECT_NEAR(probe.cone(pole.data(), 1e-3), sum / count, 3e-5);  // measured 1.5e-5
  }
}

// M of a single fibre (docs/cloth/model.md), by hand.
double shadowing_masking(const Fibre& f, const Vec3& wi, const Vec3& wo) {
  const double beta = 20.0 * kPi / 180.0;
  const double phi_i = std::atan2(dot(wi, f.b), dot(wi, f.n));
  const double phi_o = std::atan2(dot(wo, f.b), dot(wo, f.n));
  double d = phi_i - phi_o;
  if (d > kPi) d -= 2.0 * kPi;
  if (d <= -kPi) d += 2.0 * kPi;
  const double mi = std::max(std::cos(phi_i), 0.0), mo = std::max(std::cos(phi_o), 0.0);
  const double u = std::exp(-d * d / (2.0 * beta * beta));
  return (1.0 - u) * mi * mo + u * std::min(mi, mo);
}

TEST(ClothTableSampling, OneOffsetsTIsTheLobeWeightedMeanOfM) {
  // With one offset W = M P / P = M wherever the view sees the fibre's front.
  const ClothTableKey single = key_of({17.2}, {1}, 0);
  const Fibre fibre = fibre_of(single.offset());
  for (const Vec3& view : {Vec3{0.0, 0.0, 1.0}, Vec3{-0.6, 0.48, 0.64}}) {
    const ClothTableProbe probe(single, view.data(), ClothSampling{});
    for (const Vec3& xi : {Vec3{0.0, 0.0, 1.0}, Vec3{0.48, -0.6, 0.64}}) {
      for (const double lambda : {2.0, 20.0}) {
        const double expected = brute_force_mean(
            fibre, [&](const Vec3& w) { return std::exp(lambda * (dot(w, xi) - 1.0)); },
            [&](const Vec3& w) { return shadowing_masking(fibre, w, view); }, 512);
        // Measured within 4.3e-4 (the brute force is within 2e-5 of its limit).
        EXPECT_NEAR(probe.full(xi.data(), lambda), expected, 6e-4) << lambda;
      }
    }
  }
}

// Entry (level, j, i; a, b) of a table.
float entry(const std::vector<float>& t, const ClothGrid& g, std::uint32_t level, std::uint32_t j,
            std::uint32_t i, std::uint32_t a, std::uint32_t b) {
  const std::uint64_t row = (std::uint64_t(level) * g.xi_size + j) * g.xi_size + i;
  return t[row * g.columns() + a * g.view_phi + b];
}

// The largest difference between entries of `a` and the entries of `b` at mirrored nodes: x ->
// -x (i -> N - 1 - i, b -> N_phi - 1 - b) or y -> -y (j -> N - 1 - j, views with y = 0 only).
double largest_mirror_difference(const std::vector<float>& ta, const std::vector<float>& tb,
                                 const ClothGrid& g, bool in_x) {
  const std::uint32_t n = g.xi_size, last_b = g.view_phi - 1;
  double largest = 0.0;
  for (std::uint32_t l = 0; l < g.lambda_levels; ++l)
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t a = 0; a < g.view_theta; ++a)
          for (std::uint32_t b = 0; b <= last_b; ++b) {
            if (!in_x && b != 0 && b != last_b) continue;
            const float mirrored = in_x ? entry(tb, g, l, j, n - 1 - i, a, last_b - b)
                                        : entry(tb, g, l, n - 1 - j, i, a, b);
            largest = std::max(largest, double(std::fabs(entry(ta, g, l, j, i, a, b) - mirrored)));
          }
  return largest;
}

TEST(ClothTableSampling, EntriesOfMirroredNodesAgree) {
  const ClothGrid grid = small_grid();
  Context ctx;
  ClothTableKey satin_minus_18 = kSatin18;
  satin_minus_18.tangent = 1;
  const auto t =
      sample_cloth_tables({kSatin0, kSatin18, satin_minus_18}, grid, small_sampling(), ctx);
  // Offset 0 of a symmetric multiset is its own mirror image; -18 is 18 mirrored. The
  // quadrature commutes with both mirrors: entries agree to float rounding (measured 5e-7).
  EXPECT_LE(largest_mirror_difference(t[0].full, t[0].full, grid, true), 1e-6);
  EXPECT_LE(largest_mirror_difference(t[0].cone, t[0].cone, grid, true), 1e-6);
  EXPECT_LE(largest_mirror_difference(t[2].full, t[1].full, grid, true), 1e-6);
  EXPECT_LE(largest_mirror_difference(t[2].cone, t[1].cone, grid, true), 1e-6);
  // ... and not the identity: 18's own table is no mirror image of itself.
  EXPECT_GT(largest_mirror_difference(t[1].full, t[1].full, grid, true), 0.1);
  for (const ClothTableSamples& table : t) {
    EXPECT_LE(largest_mirror_difference(table.full, table.full, grid, false), 1e-6);
    EXPECT_LE(largest_mirror_difference(table.cone, table.cone, grid, false), 1e-6);
  }
}

TEST(ClothTableSampling, TablesDoNotDependOnTheThreadCount) {
  const ClothGrid grid = small_grid();
  Context one, two;
  one.threads = 1;
  two.threads = 2;
  const std::vector<ClothTableKey> keys = {kSatin18, kLinen25, kSatin0};
  const auto a = sample_cloth_tables(keys, grid, small_sampling(), one);
  const auto b = sample_cloth_tables(keys, grid, small_sampling(), two);
  for (std::size_t k = 0; k < keys.size(); ++k) {
    ASSERT_EQ(a[k].full.size(), b[k].full.size());
    EXPECT_EQ(std::memcmp(a[k].full.data(), b[k].full.data(), a[k].full.size() * 4), 0);
    EXPECT_EQ(std::memcmp(a[k].cone.data(), b[k].cone.data(), a[k].cone.size() * 4), 0);
  }
}

// The share of lobe (xi, lambda)'s integral over the sphere that lies in D (z > 0, w . n' > 0):
// the lobe sampled at points of equal mass (1 - w . xi through its inverse CDF, the azimuth about
// xi uniform), counted in D.
double brute_force_share_in_d(const Fibre& fibre, const Vec3& xi, double lambda, int n) {
  const Vec3 pick = std::fabs(xi[0]) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  Vec3 e1 = {xi[1] * pick[2] - xi[2] * pick[1], xi[2] * pick[0] - xi[0] * pick[2],
             xi[0] * pick[1] - xi[1] * pick[0]};
  const double l1 = std::sqrt(dot(e1, e1));
  for (double& c : e1) c /= l1;
  const Vec3 e2 = {xi[1] * e1[2] - xi[2] * e1[1], xi[2] * e1[0] - xi[0] * e1[2],
                   xi[0] * e1[1] - xi[1] * e1[0]};
  std::int64_t in = 0, all = 0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n;
    const double s = -std::log1p(-u * -std::expm1(-2.0 * lambda)) / lambda;
    const double ca = 1.0 - s, sa = std::sqrt(std::max(0.0, 1.0 - ca * ca));
    for (int j = 0; j < 4 * n; ++j, ++all) {
      const double b = 2.0 * kPi * (j + 0.5) / (4 * n);
      Vec3 w;
      for (int k = 0; k < 3; ++k)
        w[k] = ca * xi[k] + sa * (std::cos(b) * e1[k] + std::sin(b) * e2[k]);
      if (w[2] > 0.0 && dot(w, fibre.n) > 0.0) ++in;
    }
  }
  return double(in) / double(all);
}

// Paper 003's T divides by the lobe's integral over the whole sphere: every entry of a row is the
// table's over D times the share of the lobe in D, the same for every view.
TEST(ClothTableSampling, FullSphereDenominatorScalesTByTheLobesShareInD) {
  ClothGrid grid = small_grid();
  grid.lambda_levels = 2;
  grid.lambda_max = 20.0f;  // lambda 0.25 and 20
  Context ctx;
  ClothSampling paper = small_sampling();
  paper.full_sphere_denominator = true;
  const auto over_d = sample_cloth_tables({kLinen25}, grid, small_sampling(), ctx)[0].full;
  const auto over_sphere = sample_cloth_tables({kLinen25}, grid, paper, ctx)[0].full;
  const Fibre fibre = fibre_of(kLinen25.offset());
  const std::size_t n2 = std::size_t(grid.xi_size) * grid.xi_size, columns = grid.columns();
  double worst = 0.0;
  int checked = 0;
  for (std::size_t row = 0; row < grid.rows(); row += 3) {
    const double lambda = row < n2 ? 0.25 : 20.0;
    const Vec3 xi = lobe_axis(grid.xi_size, std::uint32_t(row % n2 % grid.xi_size),
                              std::uint32_t(row % n2 / grid.xi_size));
    const double share = brute_force_share_in_d(fibre, xi, lambda, 400);
    for (std::size_t c = 0; c < columns; ++c) {
      const float t = over_d[row * columns + c];
      if (t < 0.05f) continue;
      worst = std::max(worst, std::fabs(over_sphere[row * columns + c] / t - share));
      ++checked;
    }
  }
  // a small multiple of both quadratures' error at D's edge (the bake's azimuths)
  EXPECT_GT(checked, 100);
  EXPECT_LE(worst, 5e-4);
  // and the probe, the same way
  const Vec3 view = {0.6, 0.48, 0.64};
  const ClothTableProbe probe_d(kLinen25, view.data(), small_sampling());
  const ClothTableProbe probe_sphere(kLinen25, view.data(), paper);
  for (const Vec3& xi : {Vec3{0.0, 0.0, 1.0}, Vec3{0.8, 0.0, 0.6}, Vec3{0.0, 0.6, -0.8}})
    for (const double lambda : {0.5, 8.0}) {
      const double t = probe_d.full(xi.data(), lambda);
      ASSERT_GT(t, 0.05);
      EXPECT_NEAR(probe_sphere.full(xi.data(), lambda) / t,
                  brute_force_share_in_d(fibre, xi, lambda, 400), 5e-4)
          << xi[0] << " " << xi[2] << " lambda " << lambda;
    }
}

TEST(ClothTableSampling, RejectsInvalidInput) {
  Context ctx;
  ClothGrid grid = small_grid();
  grid.lambda_max = 0.1f;  // below lambda_min
  EXPECT_THROW(sample_cloth_tables({kSatin18}, grid, small_sampling(), ctx), Error);
  ClothSampling sampling = small_sampling();
  sampling.map_size = 100;  // not a power of two
  EXPECT_THROW(sample_cloth_tables({kSatin18}, small_grid(), sampling, ctx), Error);
  ClothTableKey key = kSatin18;
  key.tangent = 5;
  EXPECT_THROW(sample_cloth_tables({key}, small_grid(), small_sampling(), ctx), Error);
}

}  // namespace
}  // namespace prt::bake
