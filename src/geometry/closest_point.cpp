// SPDX-License-Identifier: MIT
// The general closest-point iteration (docs/level-sets.md#closest-points). The manifold
// M = {σ_i = 0} is reached by minimum-norm Gauss–Newton steps δ = −Jᵀ(JJᵀ)⁻¹σ with
// backtracking on ‖σ‖. On M, the residual of optimality is the tangential part
// t = (I − Jᵀ(JJᵀ)⁻¹J)(x0 − p) of x0 − p; the step p ← proj_M(p + α t) moves towards x0
// along M. For a surface of curvature κ at distance d the undamped step (α = 1) contracts
// the error by κd, so it diverges beyond the centre of curvature; α comes from a secant
// estimate of that factor (exact for a sphere), with backtracking, which makes the
// iteration converge superlinearly in practice.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "geometry/detail/level_set_node.h"

namespace meshmorph::detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kConverged = 1e-13;  // |t| relative to the scale of the problem
constexpr double kAcceptable = 1e-9;  // |t| at which a stalled iteration still succeeds

struct Linearization {
  Vec sigma;          // k values
  Eigen::MatrixXd J;  // k × d gradients
  bool ok = false;
};

Linearization linearize(const std::vector<const LevelSetNode*>& c, const Vec& y) {
  Linearization l;
  const auto k = static_cast<Eigen::Index>(c.size());
  l.sigma.resize(k);
  l.J.resize(k, y.size());
  Vec g;
  for (Eigen::Index i = 0; i < k; ++i) {
    l.sigma(i) = c[static_cast<std::size_t>(i)]->value_gradient(y, g);
    l.J.row(i) = g.transpose();
  }
  l.ok = l.sigma.allFinite() && l.J.allFinite();
  return l;
}

// (JJᵀ)⁻¹ applied through a rank-revealing factorization; false when the gradients are
// (nearly) linearly dependent or vanish.
bool solve_normal(const Eigen::MatrixXd& J, const Vec& rhs, Vec& out) {
  const Eigen::MatrixXd A = J * J.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  const double largest = eig.eigenvalues().maxCoeff();
  if (!(largest > 0) || eig.eigenvalues().minCoeff() <= 1e-20 * largest || largest < 1e-280) return false;
  out = eig.eigenvectors() * (eig.eigenvectors().transpose() * rhs).cwiseQuotient(eig.eigenvalues());
  return true;
}

double scale_of(const Vec& x0, const Vec& y) {
  return std::max({x0.norm(), y.norm(), (x0 - y).norm(), std::numeric_limits<double>::min()});
}

// Moves y onto {σ_i = 0}; false when Gauss–Newton cannot reduce ‖σ‖ or JJᵀ is singular.
bool project(const std::vector<const LevelSetNode*>& c, const Vec& x0, Vec& y) {
  Linearization l = linearize(c, y);
  for (int it = 0; it < 60; ++it) {
    if (!l.ok) return false;
    if (l.sigma.isZero(0.0)) return true;
    Vec lambda;
    if (!solve_normal(l.J, l.sigma, lambda)) return false;
    const Vec delta = -l.J.transpose() * lambda;
    const double scale = scale_of(x0, y);
    if (delta.norm() <= 1e-14 * scale) {
      y += delta;
      return true;
    }
    const double r0 = l.sigma.norm();
    double a = 1;
    bool moved = false;
    for (int back = 0; back < 40; ++back, a /= 2) {
      const Vec trial = y + a * delta;
      Linearization lt = linearize(c, trial);
      if (lt.ok && lt.sigma.norm() < r0) {
        y = trial;
        l = std::move(lt);
        moved = true;
        break;
      }
    }
    if (!moved) return false;
  }
  return false;
}

// Tangential part of x0 − p at the linearization l (k × d Jacobian).
bool tangential(const Linearization& l, const Vec& x0, const Vec& p, Vec& t) {
  const Vec r = x0 - p;
  Vec lambda;
  if (!solve_normal(l.J, l.J * r, lambda)) return false;
  t = r - l.J.transpose() * lambda;
  return true;
}

}  // namespace

std::optional<Vec> constrained_closest_point(const Vec& x0, const std::vector<const LevelSetNode*>& constraints,
                                             const Vec& start) {
  if (constraints.empty() || static_cast<Eigen::Index>(constraints.size()) > x0.size()) return std::nullopt;
  Vec p = start;
  if (!project(constraints, x0, p)) return std::nullopt;
  Linearization l = linearize(constraints, p);
  Vec t;
  if (!l.ok || !tangential(l, x0, p, t)) return std::nullopt;
  double alpha = 1;
  for (int it = 0; it < 200; ++it) {
    const double scale = scale_of(x0, p);
    const double tn = t.norm();
    if (tn <= kConverged * scale) return p;
    const double f = 0.5 * (x0 - p).squaredNorm();
    bool accepted = false;
    for (int back = 0; back < 50 && !accepted; ++back) {
      Vec q = p + alpha * t;
      Vec tq;
      if (project(constraints, x0, q)) {
        Linearization lq = linearize(constraints, q);
        if (lq.ok && tangential(lq, x0, q, tq)) {
          const double fq = 0.5 * (x0 - q).squaredNorm();
          // Armijo on the distance, or (once its decrease is below rounding) a smaller
          // residual without a visible increase of the distance.
          const bool armijo = fq <= f - 1e-4 * alpha * tn * tn;
          const bool closer = tq.norm() < tn && fq <= f + 8 * kEps * scale * scale;
          if (armijo || closer) {
            // Secant estimate of the contraction factor c in t' ≈ (1 − αc) t.
            const double rho = tq.dot(t) / (tn * tn);
            const double c = (1 - rho) / alpha;
            alpha = c > 1e-6 ? std::clamp(1 / c, 1e-6, 1e6) : alpha;
            p = std::move(q);
            t = std::move(tq);
            accepted = true;
            continue;
          }
        }
      }
      alpha /= 2;
    }
    if (!accepted) return tn <= kAcceptable * scale ? std::optional<Vec>(p) : std::nullopt;
  }
  return t.norm() <= kAcceptable * scale_of(x0, p) ? std::optional<Vec>(p) : std::nullopt;
}

std::optional<Vec> LevelSetNode::closest_point(const Vec& x) const {
  return constrained_closest_point(x, {this}, x);
}

}  // namespace meshmorph::detail
