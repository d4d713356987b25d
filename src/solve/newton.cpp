// SPDX-License-Identifier: MIT
#include "meshmorph/solve/newton.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "meshmorph/log.h"

namespace meshmorph {
namespace {

// Solves (H + τ·diag(s)) p = −g, s_i ≈ |H_ii|, for the smallest τ of the sequence τ₀, 4τ₀, 16τ₀, … (τ₀ = 0
// first) for which the shifted matrix is positive definite and p a descent direction: a
// Levenberg–Marquardt modification scaled per row, so rows stiffened by a large penalty and
// soft interior rows are shifted alike. Returns the τ used, or a negative value on failure.
double newton_direction(LinearSolver& solver, Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, double tau0,
                        double tau_max, double rtol, Eigen::VectorXd& p, NewtonStats& stats) {
  const Eigen::VectorXd diagonal = H.diagonal();
  // Row scales |H_ii|, at least 1e-3 of their mean so that zero rows (a projected Hessian's
  // null directions) are shifted too.
  const double mean = diagonal.size() > 0 && diagonal.cwiseAbs().mean() > 0.0 ? diagonal.cwiseAbs().mean() : 1.0;
  const Eigen::VectorXd scale = diagonal.cwiseAbs().cwiseMax(1e-3 * mean);
  for (double tau = tau0;; tau = tau == 0.0 ? 1e-6 : 4.0 * tau) {
    if (tau > tau_max) return -1.0;
    if (tau > 0.0)
      for (Eigen::Index i = 0; i < H.rows(); ++i)
        H.coeffRef(i, i) = diagonal[i] + tau * scale[i];
    if (solver.factorize(H)) {
      p.setZero(g.size());
      const LinearSolveStats s = solver.solve(-g, p, rtol);
      ++stats.linear_solves;
      stats.krylov_iterations += s.iterations;
      if (s.ok && g.dot(p) < 0.0) return tau;
    }
  }
}

}  // namespace

NewtonStats newton(NewtonProblem& problem, LinearSolver& solver, const NewtonOptions& options) {
  NewtonStats stats;
  Assembly a;
  Eigen::VectorXd p;
  double tau_next = 0.0;  // shift to start from: a quarter of the last one that worked
  for (;;) {
    bool exact = options.exact_first;
    problem.evaluate(exact ? HessianMode::Exact : HessianMode::Projected, a);
    stats.value = a.value;
    if (!std::isfinite(a.value)) {
      stats.message = "the energy is not finite at the starting point (an inverted element)";
      return stats;
    }
    if (a.gradient.size() == 0) {
      stats.converged = true;
      return stats;
    }
    double tau = -1.0;
    if (exact) {
      tau = newton_direction(solver, a.hessian, a.gradient, tau_next, options.max_shift, options.linear_rtol, p, stats);
      tau_next = tau > 1e-6 ? tau / 4.0 : 0.0;
      if (tau < 0.0) {
        log_detail("newton: the exact Hessian is far from positive definite; projected step");
        exact = false;
        tau_next = 0.0;
        problem.evaluate(HessianMode::Projected, a);
      }
    }
    if (!exact && newton_direction(solver, a.hessian, a.gradient, 0.0, 1e12, options.linear_rtol, p, stats) < 0.0) {
      stats.message = "no descent direction: the linear solver failed on the projected Hessian";
      return stats;
    }
    stats.decrement = -0.5 * a.gradient.dot(p);
    if (stats.decrement <= options.decrement_tolerance) {
      stats.converged = true;
      return stats;
    }
    if (stats.iterations >= options.max_iterations) {
      stats.message = "Newton reached its iteration limit";
      return stats;
    }
    // Backtracking Armijo (c = options.armijo) on ∇E(x_k); never past a non-finite energy or
    // an inadmissible point.
    double alpha = 1.0;
    const double slope = a.gradient.dot(p);
    double trial = problem.trial_value(p, alpha);
    while (!(std::isfinite(trial) && trial <= a.value + options.armijo * alpha * slope && problem.admissible(p, alpha))) {
      alpha *= options.backtrack;
      if (alpha < options.min_step) break;
      trial = problem.trial_value(p, alpha);
    }
    if (alpha < options.min_step) {
      if (!exact) {
        stats.message = "the line search found no acceptable step";
        return stats;
      }
      tau_next = std::max(1.0, 4.0 * tau);  // next time start from a more strongly shifted Hessian
      continue;
    }
    problem.accept(p, alpha);
    stats.value = trial;
    ++stats.iterations;
    if (log_enabled(LogLevel::Detail)) {
      char line[200];
      std::snprintf(line, sizeof line, "newton %d: %s step (shift %.2g), alpha %.3g, decrement %.3e, energy %.10g",
                    stats.iterations, exact ? "exact" : "projected", exact ? tau : 0.0, alpha, stats.decrement, trial);
      log_detail(line);
    }
  }
}

}  // namespace meshmorph
