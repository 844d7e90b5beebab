// SPDX-License-Identifier: MIT
// The glossy BRDFs of technique `shadowfield` (paper 000) and their separable approximation
// f(w, wo) ~ sum_k g_k(wo) h_k(w), by a truncated SVD of the BRDF tabulated over both hemispheres.
//
// Conventions, for every function here:
// - Directions are unit vectors in the surface's local frame, normal +Z, both pointing away from
//   the surface: w towards the light (incident), wo towards the viewer (outgoing). Only the upper
//   hemisphere (z >= 0) is meaningful; a BRDF is 0 when either direction is below it.
// - f(w, wo) is the BRDF alone, in 1/sr: the cosine of the incident direction is NOT in f, so
//   outgoing radiance is L_o(wo) = integral over the hemisphere of f(w, wo) L(w) cos(w) dw.
// - Both models are reciprocal, f(w, wo) = f(wo, w).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "prt/baker/context.hpp"

namespace prt::bake {

// Normalised Phong about the mirror direction plus an optional Lambertian part:
// f = specular (n + 2) / (2 pi) max(0, r . wo)^n + diffuse / pi, r = (-w.x, -w.y, w.z) the mirror
// of w about +Z. n = 0 makes the specular part the constant 1 / pi. With the lobe inside the
// hemisphere (wo = +Z), integral f(w, wo) cos(w) dw = specular + diffuse.
struct PhongBrdf {
  double exponent = 10.0;  // n >= 0
  double specular = 1.0;   // >= 0
  double diffuse = 0.0;    // kd >= 0
};

// Microfacet model: f = D(h) G(w, wo) F(w . h) / (4 cos(w) cos(wo)), h = normalize(w + wo), with
// the GGX (Trowbridge-Reitz) D of roughness alpha (integral D(h) cos(h) dh = 1), Smith's
// height-correlated G for GGX, and Schlick's F = f0 + (1 - f0) (1 - w . h)^5.
struct GgxBrdf {
  double alpha = 0.3;  // > 0
  double f0 = 0.04;    // in [0, 1]
};

// Throw Error naming the bad parameter.
void check_brdf(const PhongBrdf& brdf);
void check_brdf(const GgxBrdf& brdf);

double evaluate_brdf(const PhongBrdf& brdf, const glm::dvec3& w, const glm::dvec3& wo);
double evaluate_brdf(const GgxBrdf& brdf, const glm::dvec3& w, const glm::dvec3& wo);
// GGX's normal distribution at a half vector with cos(theta_h) = cos_h.
double ggx_distribution(double alpha, double cos_h);

// A BRDF as a function f(w, wo), with the conventions above.
using BrdfFunction = std::function<double(const glm::dvec3& w, const glm::dvec3& wo)>;
// The model checked (throws Error) and bound.
BrdfFunction brdf_function(const PhongBrdf& brdf);
BrdfFunction brdf_function(const GgxBrdf& brdf);

// The table's directions: the upper hemisphere as the Shirley-Chiu concentric map of the square
// [-1, 1]^2 onto the disc, lifted by z = 1 - r^2. Both steps preserve area up to a constant, so
// the size x size square cells have equal solid angles, 2 pi / size^2; a direction's value is
// taken at its cell's centre. Cell (i, j) has index j size + i (i along the square's x).
struct HemisphereGrid {
  std::uint32_t size = 32;

  std::uint32_t count() const { return size * size; }
  double solid_angle() const;  // of each cell
  glm::dvec3 direction(std::uint32_t index) const;
};
// The concentric map and its inverse (square in [-1, 1]^2, direction with z >= 0).
glm::dvec3 hemisphere_from_square(double a, double b);
void square_from_hemisphere(const glm::dvec3& direction, double* a, double* b);

struct SeparableBrdfOptions {
  std::uint32_t grid_size = 32;  // the HemisphereGrid's size, 4..64 (the SVD is count()^2)
  std::uint32_t terms = 4;       // K, 1..count(): the fewest terms kept (see whole_pair_terms)
  std::uint32_t max_terms = 8;   // the most that completing a pair may reach (a blob holds 8)
};

// An isotropic BRDF's terms come singly (azimuthal order m = 0) or in pairs of equal singular
// value (a(theta) cos(m phi), a(theta) sin(m phi)). A pair kept whole sums to a function of the
// azimuth difference, so the approximation does not change when the tangent frame turns about
// the normal; half a pair does, and shows as a seam where the frame flips. Singular values whose
// relative gap (s_k - s_k+1) / s_k is within this tolerance count as one group. The grid has
// only 4-fold symmetry (its rings hold 4, 12, 20, ... cells): that keeps odd-m pairs equal to
// rounding but splits even-m pairs a little (cos 4 phi meets m = 0 on the innermost ring). The
// tolerance lies between the largest such split and the smallest gap between distinct terms of
// the lobes grids 8 to 32 resolve (the brdf tests measure both on grids 8 and 16).
constexpr double kSingularValuePairTolerance = 1.5e-3;

// How many leading terms to keep so that no group of singular values (above) is cut: `terms`
// when the cut falls between groups, else the end of the group it cuts, if that is at most
// max(terms, max_terms); else the start of that group (the last whole group before it). Rounding
// up keeps K's accuracy at least: dropping half of a pair loses the half of it that an
// approximation cut through the pair had on average over the frame's turns. When no whole count
// is within reach (a spectrum flat to within the tolerance: a lobe far narrower than the grid,
// which K terms cannot hold anyway), `terms` as asked.
std::uint32_t whole_pair_terms(const std::vector<double>& singular_values, std::uint32_t terms,
                               std::uint32_t max_terms);

// f(w, wo) ~ sum_k g_k(wo) h_k(w) with g_k, h_k sampled at the grid's cell centres. The table
// A(i, j) = sqrt(dw_i) f(w_j, wo_i) sqrt(dw_j) (rows outgoing, columns incident) has Frobenius
// norm the L2 norm of f over hemisphere x hemisphere; with A = U S V^T, each singular value is
// split as a square root into both factors: g_k(wo_i) = sqrt(s_k) U_ik / sqrt(dw_i) and
// h_k(w_j) = sqrt(s_k) V_jk / sqrt(dw_j). Signs: the entry of largest magnitude of each h_k is
// positive.
struct SeparableBrdf {
  HemisphereGrid grid;
  std::uint32_t terms = 0;              // kept (whole_pair_terms)
  std::uint32_t requested_terms = 0;    // K as asked
  std::vector<double> outgoing;         // g: terms x grid.count(), term-major
  std::vector<double> incident;         // h: terms x grid.count(), term-major
  std::vector<double> singular_values;  // all of them, descending (not only the kept ones)

  double g(std::uint32_t term, std::uint32_t cell) const {
    return outgoing[std::size_t(term) * grid.count() + cell];
  }
  double h(std::uint32_t term, std::uint32_t cell) const {
    return incident[std::size_t(term) * grid.count() + cell];
  }
  // g_k or h_k at any direction, bilinear between cell centres on the square (clamped at its
  // edge, the horizon); below the horizon a direction is read at z = 0.
  double outgoing_at(std::uint32_t term, const glm::dvec3& wo) const;
  double incident_at(std::uint32_t term, const glm::dvec3& w) const;
  // sum_k g_k(wo) h_k(w), interpolated.
  double evaluate(const glm::dvec3& w, const glm::dvec3& wo) const;
  // ||A - A_K||_F / ||A||_F from the singular values' tail (Eckart-Young).
  double relative_error() const;
};

// f tabulated on the grid, unweighted: table[i count + j] = f(w_j, wo_i).
std::vector<double> tabulate_brdf(const BrdfFunction& f, const HemisphereGrid& grid);
// The truncated SVD of f's table, cut at whole_pair_terms(options.terms, options.max_terms).
// Throws Error for a bad grid or term count.
SeparableBrdf separate_brdf(const BrdfFunction& f, const SeparableBrdfOptions& options);
// The first `terms` terms of an approximation (the truncation of the same SVD), exactly that many
// whether or not the cut splits a pair.
SeparableBrdf truncate_separable_brdf(const SeparableBrdf& brdf, std::uint32_t terms);

// How far sum_k g_k h_k is from f.
// - grid: the relative L2 error over the grid (relative_error()), the truncation alone.
// - sky, disc: as paper 000's Fig. 10 compares images, the relative L2 error over view directions
//   of outgoing radiance L_o(wo) = integral f(w, wo) L(w) cos(w) dw, computed with the
//   interpolated factors as a renderer would, against the exact f: truncation, the grid's
//   resolution and the interpolation together. Views lie on a grid independent of the table's.
//   sky: L = 1 everywhere (low frequency); disc: L = 1 within a cone of half-angle 0.2 rad, 30
//   degrees off the normal (a small area light, where a glossy lobe's truncation shows).
// - sky_truncation, disc_truncation: the same against the full-rank approximation instead of f,
//   so the truncation alone as radiance sees it.
struct SeparableBrdfErrors {
  double grid = 0.0;
  double sky = 0.0;
  double disc = 0.0;
  double sky_truncation = 0.0;
  double disc_truncation = 0.0;
};
// `full_rank`: the same SVD with every term (grid.count()); `truncated`: a truncation of it.
SeparableBrdfErrors measure_separable_brdf(const BrdfFunction& f, const SeparableBrdf& truncated,
                                           const SeparableBrdf& full_rank);

// The errors of K in {1, 2, 4, 8, 16} for Phong n in {1, 4, 10, 16, 64, 256, 1000} and GGX alpha
// in {0.5, 0.3, 0.1}, one SVD per model on options' grid (options.terms is ignored), each K cut
// at whole pairs as separate_brdf cuts it.
struct SeparableBrdfErrorRow {
  std::string model;       // "phong" or "ggx"
  double parameter = 0.0;  // n or alpha
  std::uint32_t requested_terms = 0;
  std::uint32_t terms = 0;  // kept
  SeparableBrdfErrors errors;
};
std::vector<SeparableBrdfErrorRow> separable_brdf_error_table(const SeparableBrdfOptions& options);

}  // namespace prt::bake
