// SPDX-License-Identifier: MIT
// Technique `shadowfield`'s glossy BRDFs and their separable approximation by a truncated SVD
// (paper 000, Eq. 2; conventions in prt/baker/shadowfield/shadowfield_brdf.hpp).
#include "prt/baker/shadowfield/shadowfield_brdf.hpp"

#include <Eigen/Dense>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

#include "../common/numbers.hpp"
#include "../common/thin_svd.hpp"

namespace prt::bake {
namespace {

constexpr std::uint32_t kMinGridSize = 4;
constexpr std::uint32_t kMaxGridSize = 64;

// ---- Models ------------------------------------------------------------------------------------

// Smith's Lambda for GGX at a direction with cos(theta) = cos_theta > 0.
double ggx_lambda(double alpha, double cos_theta) {
  const double cos2 = cos_theta * cos_theta;
  const double tan2 = std::max(0.0, 1.0 - cos2) / cos2;
  return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

// ---- The grid's interpolation ------------------------------------------------------------------

// The two cells along one square axis that bracket `coordinate` in [-1, 1], and the weight of
// the second; clamped to the outermost centres at the edge.
struct AxisSpan {
  std::uint32_t first = 0, second = 0;
  double weight = 0.0;
};

AxisSpan axis_span(double coordinate, std::uint32_t size) {
  const double at = std::clamp((coordinate + 1.0) * 0.5 * size - 0.5, 0.0, double(size - 1));
  AxisSpan span;
  span.first = std::min(std::uint32_t(at), size - 1);
  span.second = std::min(span.first + 1, size - 1);
  span.weight = at - span.first;
  return span;
}

// The four cells and weights of a bilinear read at a direction, shared by every term.
struct Stencil {
  std::uint32_t cells[4] = {};
  double weights[4] = {};

  double apply(const std::vector<double>& values, std::size_t term_offset) const {
    double value = 0.0;
    for (int c = 0; c < 4; ++c) value += weights[c] * values[term_offset + cells[c]];
    return value;
  }
};

Stencil stencil_at(const HemisphereGrid& grid, const glm::dvec3& direction) {
  double a = 0.0, b = 0.0;
  square_from_hemisphere(direction, &a, &b);
  const AxisSpan x = axis_span(a, grid.size), y = axis_span(b, grid.size);
  Stencil stencil;
  stencil.cells[0] = y.first * grid.size + x.first;
  stencil.cells[1] = y.first * grid.size + x.second;
  stencil.cells[2] = y.second * grid.size + x.first;
  stencil.cells[3] = y.second * grid.size + x.second;
  stencil.weights[0] = (1.0 - x.weight) * (1.0 - y.weight);
  stencil.weights[1] = x.weight * (1.0 - y.weight);
  stencil.weights[2] = (1.0 - x.weight) * y.weight;
  stencil.weights[3] = x.weight * y.weight;
  return stencil;
}

std::size_t term_offset(const SeparableBrdf& brdf, std::uint32_t term) {
  return std::size_t(term) * brdf.grid.count();
}

// ---- The factorisation -------------------------------------------------------------------------

void check_brdf_options(const SeparableBrdfOptions& options) {
  if (options.grid_size < kMinGridSize || options.grid_size > kMaxGridSize)
    throw Error("shadowfield brdf: grid_size " + std::to_string(options.grid_size) +
                " is outside 4..64");
  const std::uint32_t count = options.grid_size * options.grid_size;
  if (options.terms == 0 || options.terms > count)
    throw Error("shadowfield brdf: terms " + std::to_string(options.terms) + " is outside 1.." +
                std::to_string(count) + " (the grid's directions)");
}

// ---- Radiance errors ---------------------------------------------------------------------------

// A light as a quadrature: directions with weights L(w) cos(w) dw.
struct LightQuadrature {
  std::vector<glm::dvec3> directions;
  std::vector<double> weights;
};

// L = 1 over the hemisphere, on a concentric grid finer than any table's.
LightQuadrature sky_light() {
  const HemisphereGrid grid{96};
  LightQuadrature light;
  for (std::uint32_t q = 0; q < grid.count(); ++q) {
    const glm::dvec3 w = grid.direction(q);
    light.directions.push_back(w);
    light.weights.push_back(w.z * grid.solid_angle());
  }
  return light;
}

// L = 1 within a cone of half-angle 0.2 rad about a direction 30 degrees off the normal: equal
// solid-angle cells, rings uniform in cos(psi) about the axis times angles.
LightQuadrature disc_light() {
  constexpr std::uint32_t kRings = 16, kAngles = 64;
  const double tilt = kPi / 6.0, cos_max = std::cos(0.2);
  const glm::dvec3 axis(std::sin(tilt), 0.0, std::cos(tilt));
  const glm::dvec3 across(std::cos(tilt), 0.0, -std::sin(tilt)), side(0.0, 1.0, 0.0);
  const double cell = 2.0 * kPi * (1.0 - cos_max) / (kRings * kAngles);
  LightQuadrature light;
  for (std::uint32_t r = 0; r < kRings; ++r) {
    const double cos_psi = 1.0 - (r + 0.5) / kRings * (1.0 - cos_max);
    const double sin_psi = std::sqrt(1.0 - cos_psi * cos_psi);
    for (std::uint32_t a = 0; a < kAngles; ++a) {
      const double phi = 2.0 * kPi * (a + 0.5) / kAngles;
      const glm::dvec3 w =
          cos_psi * axis + sin_psi * (std::cos(phi) * across + std::sin(phi) * side);
      light.directions.push_back(w);
      light.weights.push_back(w.z * cell);
    }
  }
  return light;
}

// The view directions: midpoints of a (cos(theta), phi) grid, equal solid angles, independent of
// the table's grid so that both factors are read between their samples.
std::vector<glm::dvec3> view_directions() {
  constexpr std::uint32_t kCos = 16, kPhi = 32;
  std::vector<glm::dvec3> views;
  for (std::uint32_t c = 0; c < kCos; ++c) {
    const double z = (c + 0.5) / kCos, s = std::sqrt(1.0 - z * z);
    for (std::uint32_t p = 0; p < kPhi; ++p) {
      const double phi = 2.0 * kPi * (p + 0.5) / kPhi;
      views.emplace_back(s * std::cos(phi), s * std::sin(phi), z);
    }
  }
  return views;
}

// The exact outgoing radiance of f under one light at every view.
std::vector<double> exact_radiance(const BrdfFunction& f, const LightQuadrature& light,
                                   const std::vector<glm::dvec3>& views) {
  std::vector<double> radiance(views.size(), 0.0);
  for (std::size_t v = 0; v < views.size(); ++v)
    for (std::size_t q = 0; q < light.directions.size(); ++q)
      radiance[v] += f(light.directions[q], views[v]) * light.weights[q];
  return radiance;
}

// The outgoing radiance of sum_k g_k(wo) L_k at every view, L_k = integral h_k L cos (the
// paper's Eq. 3).
std::vector<double> approximate_radiance(const SeparableBrdf& brdf, const LightQuadrature& light,
                                         const std::vector<glm::dvec3>& views) {
  std::vector<double> light_terms(brdf.terms, 0.0);
  for (std::size_t q = 0; q < light.directions.size(); ++q) {
    const Stencil stencil = stencil_at(brdf.grid, light.directions[q]);
    for (std::uint32_t k = 0; k < brdf.terms; ++k)
      light_terms[k] += stencil.apply(brdf.incident, term_offset(brdf, k)) * light.weights[q];
  }
  std::vector<double> radiance(views.size(), 0.0);
  for (std::size_t v = 0; v < views.size(); ++v) {
    const Stencil stencil = stencil_at(brdf.grid, views[v]);
    for (std::uint32_t k = 0; k < brdf.terms; ++k)
      radiance[v] += stencil.apply(brdf.outgoing, term_offset(brdf, k)) * light_terms[k];
  }
  return radiance;
}

// ||approximate - reference|| / ||reference|| over the views (equal solid angles).
double relative_difference(const std::vector<double>& approximate,
                           const std::vector<double>& reference) {
  double error2 = 0.0, norm2 = 0.0;
  for (std::size_t v = 0; v < reference.size(); ++v) {
    error2 += (approximate[v] - reference[v]) * (approximate[v] - reference[v]);
    norm2 += reference[v] * reference[v];
  }
  return norm2 > 0.0 ? std::sqrt(error2 / norm2) : std::sqrt(error2);
}

// The lights, views and reference radiances of one f and its full-rank approximation, computed
// once for every truncation.
struct RadianceReference {
  LightQuadrature sky = sky_light(), disc = disc_light();
  std::vector<glm::dvec3> views = view_directions();
  std::vector<double> sky_exact, disc_exact, sky_table, disc_table;

  RadianceReference(const BrdfFunction& f, const SeparableBrdf& full_rank)
      : sky_exact(exact_radiance(f, sky, views)),
        disc_exact(exact_radiance(f, disc, views)),
        sky_table(approximate_radiance(full_rank, sky, views)),
        disc_table(approximate_radiance(full_rank, disc, views)) {}

  SeparableBrdfErrors measure(const SeparableBrdf& brdf) const {
    const std::vector<double> sky_radiance = approximate_radiance(brdf, sky, views);
    const std::vector<double> disc_radiance = approximate_radiance(brdf, disc, views);
    SeparableBrdfErrors errors;
    errors.grid = brdf.relative_error();
    errors.sky = relative_difference(sky_radiance, sky_exact);
    errors.disc = relative_difference(disc_radiance, disc_exact);
    errors.sky_truncation = relative_difference(sky_radiance, sky_table);
    errors.disc_truncation = relative_difference(disc_radiance, disc_table);
    return errors;
  }
};

void append_rows(const std::string& model, double parameter, const BrdfFunction& f,
                 std::uint32_t grid_size, std::vector<SeparableBrdfErrorRow>* rows) {
  static constexpr std::uint32_t kTerms[] = {1, 2, 4, 8, 16};
  const SeparableBrdf full = separate_brdf(f, {grid_size, grid_size * grid_size});
  const RadianceReference reference(f, full);
  for (const std::uint32_t terms : kTerms) {
    SeparableBrdfErrorRow row;
    row.model = model;
    row.parameter = parameter;
    row.requested_terms = terms;
    row.terms = whole_pair_terms(full.singular_values, terms, SeparableBrdfOptions{}.max_terms);
    row.errors = reference.measure(truncate_separable_brdf(full, row.terms));
    rows->push_back(row);
  }
}

}  // namespace

// ---- Models ------------------------------------------------------------------------------------

void check_brdf(const PhongBrdf& brdf) {
  if (!(brdf.exponent >= 0.0) || !std::isfinite(brdf.exponent))
    throw Error("shadowfield brdf: Phong exponent " + std::to_string(brdf.exponent) +
                " is not a finite number >= 0");
  if (!(brdf.specular >= 0.0) || !(brdf.diffuse >= 0.0))
    throw Error("shadowfield brdf: Phong specular and diffuse weights must be >= 0");
}

void check_brdf(const GgxBrdf& brdf) {
  if (!(brdf.alpha > 0.0) || !std::isfinite(brdf.alpha))
    throw Error("shadowfield brdf: GGX alpha " + std::to_string(brdf.alpha) +
                " is not a finite number > 0");
  if (!(brdf.f0 >= 0.0 && brdf.f0 <= 1.0))
    throw Error("shadowfield brdf: GGX f0 " + std::to_string(brdf.f0) + " is outside [0, 1]");
}

double evaluate_brdf(const PhongBrdf& brdf, const glm::dvec3& w, const glm::dvec3& wo) {
  if (w.z < 0.0 || wo.z < 0.0) return 0.0;
  const glm::dvec3 mirror(-w.x, -w.y, w.z);
  // pow(0, 0) = 1 keeps n = 0 the constant it is meant to be.
  const double lobe = std::pow(std::max(0.0, glm::dot(mirror, wo)), brdf.exponent);
  return (brdf.specular * (brdf.exponent + 2.0) * lobe + 2.0 * brdf.diffuse) / (2.0 * kPi);
}

double ggx_distribution(double alpha, double cos_h) {
  if (cos_h <= 0.0) return 0.0;
  const double alpha2 = alpha * alpha;
  const double denominator = cos_h * cos_h * (alpha2 - 1.0) + 1.0;
  return alpha2 / (kPi * denominator * denominator);
}

double evaluate_brdf(const GgxBrdf& brdf, const glm::dvec3& w, const glm::dvec3& wo) {
  if (w.z <= 0.0 || wo.z <= 0.0) return 0.0;
  const glm::dvec3 h = glm::normalize(w + wo);
  const double d = ggx_distribution(brdf.alpha, h.z);
  const double g = 1.0 / (1.0 + ggx_lambda(brdf.alpha, w.z) + ggx_lambda(brdf.alpha, wo.z));
  const double f = brdf.f0 + (1.0 - brdf.f0) * std::pow(1.0 - glm::dot(w, h), 5.0);
  return d * g * f / (4.0 * w.z * wo.z);
}

BrdfFunction brdf_function(const PhongBrdf& brdf) {
  check_brdf(brdf);
  return [brdf](const glm::dvec3& w, const glm::dvec3& wo) { return evaluate_brdf(brdf, w, wo); };
}

BrdfFunction brdf_function(const GgxBrdf& brdf) {
  check_brdf(brdf);
  return [brdf](const glm::dvec3& w, const glm::dvec3& wo) { return evaluate_brdf(brdf, w, wo); };
}

// ---- The grid ----------------------------------------------------------------------------------

glm::dvec3 hemisphere_from_square(double a, double b) {
  double r = 0.0, phi = 0.0;
  if (a == 0.0 && b == 0.0) return {0.0, 0.0, 1.0};
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = kPi / 4.0 * (b / a);
  } else {
    r = b;
    phi = kPi / 2.0 - kPi / 4.0 * (a / b);
  }
  // (r cos phi, r sin phi) is on the disc; z = 1 - r^2 keeps area.
  const double lift = std::sqrt(std::max(0.0, 2.0 - r * r));
  return {r * std::cos(phi) * lift, r * std::sin(phi) * lift, 1.0 - r * r};
}

void square_from_hemisphere(const glm::dvec3& direction, double* a, double* b) {
  const glm::dvec3 d =
      glm::normalize(glm::dvec3(direction.x, direction.y, std::max(0.0, direction.z)));
  const double r = std::sqrt(std::max(0.0, 1.0 - d.z));
  if (r == 0.0) {
    *a = *b = 0.0;
    return;
  }
  double phi = std::atan2(d.y, d.x);
  if (phi < -kPi / 4.0) phi += 2.0 * kPi;
  const double to_square = 4.0 / kPi;
  if (phi < kPi / 4.0) {
    *a = r;
    *b = phi * to_square * r;
  } else if (phi < 3.0 * kPi / 4.0) {
    *a = (kPi / 2.0 - phi) * to_square * r;
    *b = r;
  } else if (phi < 5.0 * kPi / 4.0) {
    *a = -r;
    *b = -(phi - kPi) * to_square * r;
  } else {
    *a = (phi - 3.0 * kPi / 2.0) * to_square * r;
    *b = -r;
  }
}

double HemisphereGrid::solid_angle() const {
  return 2.0 * kPi / count();
}

glm::dvec3 HemisphereGrid::direction(std::uint32_t index) const {
  const std::uint32_t i = index % size, j = index / size;
  return hemisphere_from_square(-1.0 + (i + 0.5) * 2.0 / size, -1.0 + (j + 0.5) * 2.0 / size);
}

// ---- The factorisation -------------------------------------------------------------------------

double SeparableBrdf::outgoing_at(std::uint32_t term, const glm::dvec3& wo) const {
  return stencil_at(grid, wo).apply(outgoing, term_offset(*this, term));
}

double SeparableBrdf::incident_at(std::uint32_t term, const glm::dvec3& w) const {
  return stencil_at(grid, w).apply(incident, term_offset(*this, term));
}

double SeparableBrdf::evaluate(const glm::dvec3& w, const glm::dvec3& wo) const {
  const Stencil at_w = stencil_at(grid, w), at_wo = stencil_at(grid, wo);
  double value = 0.0;
  for (std::uint32_t k = 0; k < terms; ++k)
    value +=
        at_wo.apply(outgoing, term_offset(*this, k)) * at_w.apply(incident, term_offset(*this, k));
  return value;
}

double SeparableBrdf::relative_error() const {
  double total = 0.0, tail = 0.0;
  for (std::size_t k = 0; k < singular_values.size(); ++k) {
    total += singular_values[k] * singular_values[k];
    if (k >= terms) tail += singular_values[k] * singular_values[k];
  }
  return total > 0.0 ? std::sqrt(tail / total) : 0.0;
}

std::uint32_t whole_pair_terms(const std::vector<double>& singular_values, std::uint32_t terms,
                               std::uint32_t max_terms) {
  const std::size_t count = singular_values.size();
  if (terms >= count) return terms;
  // Whether keeping n terms cuts between two groups.
  const auto whole = [&](std::size_t n) {
    return n >= count || singular_values[n - 1] - singular_values[n] >
                             kSingularValuePairTolerance * singular_values[n - 1];
  };
  const std::size_t most = std::min<std::size_t>(count, std::max(terms, max_terms));
  for (std::size_t n = terms; n <= most; ++n)
    if (whole(n)) return std::uint32_t(n);
  for (std::size_t n = terms - 1; n >= 1; --n)
    if (whole(n)) return std::uint32_t(n);
  return terms;
}

std::vector<double> tabulate_brdf(const BrdfFunction& f, const HemisphereGrid& grid) {
  const std::uint32_t count = grid.count();
  std::vector<glm::dvec3> directions(count);
  for (std::uint32_t i = 0; i < count; ++i) directions[i] = grid.direction(i);
  std::vector<double> table(std::size_t(count) * count);
  for (std::uint32_t i = 0; i < count; ++i)
    for (std::uint32_t j = 0; j < count; ++j)
      table[std::size_t(i) * count + j] = f(directions[j], directions[i]);
  return table;
}

SeparableBrdf separate_brdf(const BrdfFunction& f, const SeparableBrdfOptions& options) {
  check_brdf_options(options);
  SeparableBrdf result;
  result.grid.size = options.grid_size;
  result.requested_terms = options.terms;
  const Eigen::Index count = result.grid.count();
  // Every cell has the same solid angle, so sqrt(dw_i) sqrt(dw_j) is one factor.
  const double cell = result.grid.solid_angle();
  const std::vector<double> table = tabulate_brdf(f, result.grid);
  const Eigen::MatrixXd weighted =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          table.data(), count, count) *
      cell;
  const ThinSvd svd = thin_svd(weighted, true);
  const Eigen::VectorXd& sigma = svd.singular_values;
  result.singular_values.assign(sigma.data(), sigma.data() + sigma.size());
  result.terms = whole_pair_terms(result.singular_values, options.terms, options.max_terms);

  const Eigen::VectorXd root = sigma.head(result.terms).cwiseSqrt() / std::sqrt(cell);
  // Each term's pair keeps thin_svd's sign: h_k's entry of largest magnitude is positive.
  const Eigen::MatrixXd u = svd.u.leftCols(result.terms) * root.asDiagonal();
  const Eigen::MatrixXd v = svd.v.leftCols(result.terms) * root.asDiagonal();
  // Column-major u and v store each term's samples contiguously: term-major as is.
  result.outgoing.assign(u.data(), u.data() + u.size());
  result.incident.assign(v.data(), v.data() + v.size());
  return result;
}

SeparableBrdf truncate_separable_brdf(const SeparableBrdf& brdf, std::uint32_t terms) {
  if (terms == 0 || terms > brdf.terms)
    throw Error("shadowfield brdf: cannot keep " + std::to_string(terms) + " of " +
                std::to_string(brdf.terms) + " terms");
  SeparableBrdf result = brdf;
  result.terms = terms;
  result.requested_terms = terms;
  result.outgoing.resize(std::size_t(terms) * brdf.grid.count());
  result.incident.resize(std::size_t(terms) * brdf.grid.count());
  return result;
}

SeparableBrdfErrors measure_separable_brdf(const BrdfFunction& f, const SeparableBrdf& truncated,
                                           const SeparableBrdf& full_rank) {
  if (full_rank.grid.size != truncated.grid.size || full_rank.terms != full_rank.grid.count() ||
      truncated.terms > full_rank.terms)
    throw Error("shadowfield brdf: measuring needs a truncation and the full-rank SVD of one grid");
  return RadianceReference(f, full_rank).measure(truncated);
}

std::vector<SeparableBrdfErrorRow> separable_brdf_error_table(const SeparableBrdfOptions& options) {
  check_brdf_options({options.grid_size, 16});
  std::vector<SeparableBrdfErrorRow> rows;
  for (const double n : {1.0, 4.0, 10.0, 16.0, 64.0, 256.0, 1000.0})
    append_rows("phong", n, brdf_function(PhongBrdf{n, 1.0, 0.0}), options.grid_size, &rows);
  for (const double alpha : {0.5, 0.3, 0.1})
    append_rows("ggx", alpha, brdf_function(GgxBrdf{alpha, 0.04}), options.grid_size, &rows);
  return rows;
}

}  // namespace prt::bake
