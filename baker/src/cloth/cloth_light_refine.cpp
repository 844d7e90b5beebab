// SPDX-License-Identifier: MIT
// The SG light's refinement against the smoothed map: variable projection (the amplitudes by
// non-negative least squares for given axes and sharpnesses) with Levenberg-Marquardt steps on
// the free lobes' axes (two tangent angles each) and log sharpness. The residual rows are the
// smoothed targets' points, each weighted by sqrt(solid angle / the target's norm), so the
// objective is the sum of the squared relative smoothed errors.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "cloth_light_detail.hpp"

namespace prt::bake::sg_light {

namespace {

// Largest change of an axis (radians) and of a log sharpness in one step.
constexpr double kMaxTurn = 0.3;
constexpr double kMaxLogSharpness = 1.0;
// The refinement stops once a step lowers the objective by less than this share.
constexpr double kConverged = 1e-3;

// The residual rows of every target.
struct Rows {
  std::vector<glm::dvec3> points;
  std::vector<double> kappa, scale;  // kernel; sqrt(solid angle / norm) / start error
  Eigen::MatrixXd wanted;            // rows x 3: scaled target less the fixed lobes
};

Rows rows_of(const std::vector<SmoothedTarget>& targets, const std::vector<double>& start_errors,
             const std::vector<Lobe>& fixed) {
  Rows rows;
  std::size_t count = 0;
  for (std::size_t k = 0; k < targets.size(); ++k)
    if (start_errors[k] > 0.0) count += targets[k].points.size();
  rows.wanted.resize(static_cast<Eigen::Index>(count), 3);
  Eigen::Index at = 0;
  for (std::size_t k = 0; k < targets.size(); ++k) {
    const SmoothedTarget& t = targets[k];
    if (!(start_errors[k] > 0.0)) continue;  // a black target, or one met exactly already
    for (std::size_t i = 0; i < t.points.size(); ++i, ++at) {
      const double scale = std::sqrt(t.weights[i] / t.norm) / start_errors[k];
      glm::dvec3 wanted = t.target[i];
      for (const Lobe& lobe : fixed)
        wanted -=
            lobe.rgb * smoothed_lobe(lobe.sharpness, t.kappa, glm::dot(lobe.axis, t.points[i]));
      rows.points.push_back(t.points[i]);
      rows.kappa.push_back(t.kappa);
      rows.scale.push_back(scale);
      for (int c = 0; c < 3; ++c) rows.wanted(at, c) = scale * wanted[c];
    }
  }
  return rows;
}

// Two unit tangents of an axis.
void tangents(const glm::dvec3& axis, glm::dvec3* e1, glm::dvec3* e2) {
  const glm::dvec3 helper = std::fabs(axis.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  *e1 = glm::normalize(glm::cross(axis, helper));
  *e2 = glm::cross(axis, *e1);
}

template <typename Body>
void parallel_rows(const Context& ctx, std::size_t count, const Body& body) {
  tbb::task_arena arena(static_cast<int>(ctx.thread_count()));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i < range.end(); ++i) body(i);
                      });
  });
}

// The unit-amplitude smoothed lobes at every row (rows x lobes), and with `derivatives` their
// derivatives in each lobe's two tangent angles and log sharpness (rows x 3 lobes).
void columns(const Rows& rows, const std::vector<Lobe>& lobes, const Context& ctx,
             Eigen::MatrixXd* values, Eigen::MatrixXd* derivatives) {
  const auto n = static_cast<Eigen::Index>(rows.points.size());
  const auto k = static_cast<Eigen::Index>(lobes.size());
  values->resize(n, k);
  if (derivatives) derivatives->resize(n, 3 * k);
  std::vector<glm::dvec3> e1(lobes.size()), e2(lobes.size());
  for (std::size_t j = 0; j < lobes.size(); ++j) tangents(lobes[j].axis, &e1[j], &e2[j]);
  parallel_rows(ctx, rows.points.size(), [&](std::size_t i) {
    const auto row = static_cast<Eigen::Index>(i);
    for (Eigen::Index j = 0; j < k; ++j) {
      const Lobe& lobe = lobes[static_cast<std::size_t>(j)];
      const glm::dvec3& v = rows.points[i];
      double value, d_l, d_t;
      smoothed_lobe_derivatives(lobe.sharpness, rows.kappa[i], glm::dot(lobe.axis, v), &value, &d_l,
                                &d_t);
      (*values)(row, j) = rows.scale[i] * value;
      if (!derivatives) continue;
      (*derivatives)(row, 3 * j) =
          rows.scale[i] * d_t * glm::dot(v, e1[static_cast<std::size_t>(j)]);
      (*derivatives)(row, 3 * j + 1) =
          rows.scale[i] * d_t * glm::dot(v, e2[static_cast<std::size_t>(j)]);
      (*derivatives)(row, 3 * j + 2) = rows.scale[i] * d_l * lobe.sharpness;
    }
  });
}

// Lawson and Hanson's active-set NNLS on the normal equations: x >= 0 minimising
// x^T M x - 2 c^T x (M = A^T A, c = A^T b).
Eigen::VectorXd nnls(const Eigen::MatrixXd& m, const Eigen::VectorXd& c) {
  const Eigen::Index n = c.size();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(static_cast<std::size_t>(n), false);
  const double tolerance = 1e-12 * std::max(1.0, c.cwiseAbs().maxCoeff());
  for (int outer = 0; outer < 3 * n + 10; ++outer) {
    const Eigen::VectorXd gradient = c - m * x;
    Eigen::Index best = -1;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!passive[static_cast<std::size_t>(j)] && gradient(j) > tolerance &&
          (best < 0 || gradient(j) > gradient(best)))
        best = j;
    if (best < 0) break;
    passive[static_cast<std::size_t>(best)] = true;
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      std::vector<Eigen::Index> set;
      for (Eigen::Index j = 0; j < n; ++j)
        if (passive[static_cast<std::size_t>(j)]) set.push_back(j);
      Eigen::MatrixXd sub(set.size(), set.size());
      Eigen::VectorXd rhs(set.size());
      for (std::size_t a = 0; a < set.size(); ++a) {
        rhs(a) = c(set[a]);
        for (std::size_t b = 0; b < set.size(); ++b) sub(a, b) = m(set[a], set[b]);
      }
      sub.diagonal().array() += 1e-14 * std::max(1.0, sub.diagonal().maxCoeff());
      const Eigen::VectorXd z = sub.ldlt().solve(rhs);
      if ((z.array() > 0.0).all()) {
        x.setZero();
        for (std::size_t a = 0; a < set.size(); ++a) x(set[a]) = z(a);
        break;
      }
      double alpha = 1.0;
      for (std::size_t a = 0; a < set.size(); ++a)
        if (z(a) <= 0.0) alpha = std::min(alpha, x(set[a]) / (x(set[a]) - z(a)));
      for (std::size_t a = 0; a < set.size(); ++a) {
        x(set[a]) += alpha * (z(a) - x(set[a]));
        if (x(set[a]) <= tolerance * 1e-3) {
          x(set[a]) = 0.0;
          passive[static_cast<std::size_t>(set[a])] = false;
        }
      }
    }
  }
  return x;
}

// A state of the refinement: the free lobes with their best amplitudes, and its objective.
struct State {
  std::vector<Lobe> lobes;
  Eigen::MatrixXd values;  // rows x lobes
  double objective = 0.0;
};

// The free lobes' amplitudes by NNLS (per channel) and the objective.
void solve_amplitudes(const Rows& rows, State* state) {
  const Eigen::MatrixXd gram = state->values.transpose() * state->values;
  const Eigen::MatrixXd rhs = state->values.transpose() * rows.wanted;
  Eigen::MatrixXd amplitudes(gram.rows(), 3);
  for (int c = 0; c < 3; ++c) amplitudes.col(c) = nnls(gram, rhs.col(c));
  for (std::size_t j = 0; j < state->lobes.size(); ++j)
    for (int c = 0; c < 3; ++c)
      state->lobes[j].rgb[c] = amplitudes(static_cast<Eigen::Index>(j), c);
  state->objective = (state->values * amplitudes - rows.wanted).squaredNorm();
}

Eigen::MatrixXd amplitudes_of(const std::vector<Lobe>& lobes) {
  Eigen::MatrixXd a(static_cast<Eigen::Index>(lobes.size()), 3);
  for (std::size_t j = 0; j < lobes.size(); ++j)
    for (int c = 0; c < 3; ++c) a(static_cast<Eigen::Index>(j), c) = lobes[j].rgb[c];
  return a;
}

// The Gauss-Newton system at `state` in the free lobes' angles and log sharpness (3 per lobe)
// and their amplitudes (3 more per lobe, after them): H = J^T J and g = J^T r. The amplitudes
// are part of the system so that the geometric step allows for how they would follow it (the
// step's amplitudes are then replaced by the NNLS ones).
void normal_equations(const Rows& rows, const State& state, const Eigen::MatrixXd& derivatives,
                      Eigen::MatrixXd* h, Eigen::VectorXd* g) {
  const Eigen::MatrixXd a = amplitudes_of(state.lobes);
  const Eigen::MatrixXd residual = state.values * a - rows.wanted;
  const Eigen::MatrixXd dd = derivatives.transpose() * derivatives;
  const Eigen::MatrixXd dv = derivatives.transpose() * state.values;
  const Eigen::MatrixXd vv = state.values.transpose() * state.values;
  const Eigen::MatrixXd dr = derivatives.transpose() * residual;
  const Eigen::MatrixXd vr = state.values.transpose() * residual;
  const Eigen::Index geo = dd.rows(), n = 2 * geo;
  h->setZero(n, n);
  g->resize(n);
  for (Eigen::Index p = 0; p < geo; ++p) {
    (*g)(p) = a.row(p / 3).dot(dr.row(p));
    (*g)(geo + p) = vr(p / 3, p % 3);
    for (Eigen::Index s = 0; s < geo; ++s) {
      (*h)(p, s) = dd(p, s) * a.row(p / 3).dot(a.row(s / 3));
      // Angle or sharpness p against amplitude (lobe s / 3, channel s % 3).
      (*h)(p, geo + s) = (*h)(geo + s, p) = a(p / 3, s % 3) * dv(p, s / 3);
      if (p % 3 == s % 3) (*h)(geo + p, geo + s) = vv(p / 3, s / 3);
    }
  }
}

// The free lobes moved by step (two tangent angles and a log sharpness per lobe), sharpness
// kept within [PRT_CLOTH_MIN_SHARPNESS, max_sharpness].
std::vector<Lobe> moved(const std::vector<Lobe>& lobes, const Eigen::VectorXd& step,
                        double max_sharpness) {
  std::vector<Lobe> out = lobes;
  for (std::size_t j = 0; j < lobes.size(); ++j) {
    glm::dvec3 e1, e2;
    tangents(lobes[j].axis, &e1, &e2);
    double a = step(3 * j), b = step(3 * j + 1);
    const double turn = std::hypot(a, b), angle = std::min(turn, kMaxTurn);
    if (turn > kMaxTurn) a *= kMaxTurn / turn, b *= kMaxTurn / turn;
    // Along the great circle (the exponential map of the sphere at the axis).
    if (angle > 0.0)
      out[j].axis = glm::normalize(std::cos(angle) * lobes[j].axis +
                                   std::sin(angle) / angle * (a * e1 + b * e2));
    const double log_step = std::clamp(step(3 * j + 2), -kMaxLogSharpness, kMaxLogSharpness);
    out[j].sharpness = std::clamp(lobes[j].sharpness * std::exp(log_step),
                                  double(PRT_CLOTH_MIN_SHARPNESS), max_sharpness);
  }
  return out;
}

}  // namespace

Refinement refine(const std::vector<SmoothedTarget>& targets, const std::vector<Lobe>& start,
                  double fixed_sharpness, std::uint32_t max_steps, const Context& ctx) {
  Refinement result;
  result.lobes = start;
  std::vector<Lobe> fixed;
  State current;
  for (const Lobe& lobe : start)
    (lobe.sharpness >= fixed_sharpness ? fixed : current.lobes).push_back(lobe);
  result.fixed = static_cast<std::uint32_t>(fixed.size());
  if (max_steps == 0 || current.lobes.empty()) return result;
  // Admissible: no smoothed error above the start's.
  std::vector<double> start_errors;
  for (const SmoothedTarget& t : targets) start_errors.push_back(smoothed_error(t, start));
  const Rows rows = rows_of(targets, start_errors, fixed);
  if (rows.points.empty()) return result;
  const auto admissible = [&](const State& s) {
    std::vector<Lobe> all = fixed;
    all.insert(all.end(), s.lobes.begin(), s.lobes.end());
    for (std::size_t i = 0; i < targets.size(); ++i)
      if (smoothed_error(targets[i], all) > start_errors[i]) return false;
    return true;
  };
  double max_sharpness = fixed_sharpness;
  for (const Lobe& lobe : current.lobes) max_sharpness = std::max(max_sharpness, lobe.sharpness);
  max_sharpness = std::min<double>(max_sharpness, PRT_CLOTH_MAX_SHARPNESS);

  columns(rows, current.lobes, ctx, &current.values, nullptr);
  current.objective = (current.values * amplitudes_of(current.lobes) - rows.wanted).squaredNorm();
  State best = current;
  std::uint32_t best_steps = 0, steps = 0;
  solve_amplitudes(rows, &current);
  ++steps;
  if (current.objective < best.objective && admissible(current)) best = current, best_steps = steps;
  double damping = 1e-3;
  while (steps < max_steps) {
    const double before = current.objective;
    Eigen::MatrixXd derivatives, h;
    Eigen::VectorXd g;
    columns(rows, current.lobes, ctx, &current.values, &derivatives);
    normal_equations(rows, current, derivatives, &h, &g);
    bool progressed = false;
    for (int attempt = 0; attempt < 10 && !progressed; ++attempt) {
      Eigen::MatrixXd damped = h;
      damped.diagonal() += damping * h.diagonal() +
                           Eigen::VectorXd::Constant(h.rows(), 1e-12 * h.diagonal().maxCoeff());
      State candidate;
      const Eigen::VectorXd step = damped.ldlt().solve(-g);
      candidate.lobes = moved(current.lobes, step.head(h.rows() / 2), max_sharpness);
      columns(rows, candidate.lobes, ctx, &candidate.values, nullptr);
      solve_amplitudes(rows, &candidate);
      if (candidate.objective < current.objective) {
        current = std::move(candidate);
        damping = std::max(damping / 3.0, 1e-9);
        progressed = true;
      } else {
        damping *= 4.0;
      }
    }
    if (!progressed) break;
    ++steps;
    if (current.objective < best.objective && admissible(current))
      best = current, best_steps = steps;
    if (before - current.objective < kConverged * before) break;
  }
  result.lobes = fixed;
  result.lobes.insert(result.lobes.end(), best.lobes.begin(), best.lobes.end());
  result.steps = best_steps;
  return result;
}

}  // namespace prt::bake::sg_light
