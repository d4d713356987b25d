// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include <Eigen/Eigenvalues>

#include "meshmorph/error.h"
#include "meshmorph/log.h"
#include "meshmorph/solve/linear_solver.h"
#include "meshmorph/solve/newton.h"
#include "solve/detail/line_search.h"

namespace meshmorph {
namespace {

struct CgResult {
  int iterations = 0;
  bool converged = false;  // reached the relative residual asked for
  bool curvature = false;  // stopped at a direction of nonpositive curvature
};

// The inverses of H's node blocks, each made positive definite: eigenvalues λ → max(|λ|, floor),
// floor 1e-3 of the mean |H_ii|, so that the null rows of a projected Hessian stay
// preconditioned (as newton()'s shift scales).
class BlockJacobi {
 public:
  explicit BlockJacobi(HessianBlocks blocks) : b_(std::move(blocks)) {
    const int s = b_.size;
    const auto n_blocks = static_cast<std::ptrdiff_t>(b_.first.size()) - 1;
    double sum = 0.0;
    for (std::ptrdiff_t b = 0; b < n_blocks; ++b)
      for (int i = 0; i < size(b); ++i) sum += std::abs(b_.values[static_cast<std::size_t>(b * s * s + i * (s + 1))]);
    const std::int32_t n = b_.first.empty() ? 0 : b_.first.back();
    const double floor = 1e-3 * (n > 0 && sum > 0.0 ? sum / n : 1.0);
    using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 3, 3>;  // no allocation
    MESHMORPH_CHECK(s <= 3, "newton_matrix_free: node blocks of at most 3 DOFs");
    for (std::ptrdiff_t b = 0; b < n_blocks; ++b) {
      const int m = size(b);
      Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>> B(b_.values.data() + b * s * s, m, m, Eigen::OuterStride<>(s));
      const Eigen::SelfAdjointEigenSolver<Block> eig(Block{B});
      B = eig.eigenvectors() * eig.eigenvalues().cwiseAbs().cwiseMax(floor).cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
    }
  }
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
    const int s = b_.size;
    z.resize(r.size());
    for (std::ptrdiff_t b = 0; b + 1 < static_cast<std::ptrdiff_t>(b_.first.size()); ++b) {
      const int m = size(b), f = b_.first[static_cast<std::size_t>(b)];
      const double* inv = b_.values.data() + b * s * s;
      for (int i = 0; i < m; ++i) {
        double sum = 0.0;
        for (int j = 0; j < m; ++j) sum += inv[i + s * j] * r[f + j];
        z[f + i] = sum;
      }
    }
  }

 private:
  int size(std::ptrdiff_t b) const { return b_.first[static_cast<std::size_t>(b) + 1] - b_.first[static_cast<std::size_t>(b)]; }
  HessianBlocks b_;
};

// Block Jacobi plus, where set, the coarse correction R A⁻¹ Rᵀ (additive two-level; SPD when
// A is).
class TwoLevel {
 public:
  explicit TwoLevel(HessianBlocks blocks) : fine_(std::move(blocks)) {}
  void set_coarse(const Eigen::SparseMatrix<double>* R, LinearSolver* solver) {
    R_ = R;
    coarse_ = solver;
  }
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
    fine_.apply(r, z);
    if (!coarse_) return;
    rc_.noalias() = R_->transpose() * r;
    coarse_->solve(rc_, xc_);
    z.noalias() += *R_ * xc_;
  }

 private:
  BlockJacobi fine_;
  const Eigen::SparseMatrix<double>* R_ = nullptr;
  LinearSolver* coarse_ = nullptr;
  mutable Eigen::VectorXd rc_, xc_;
};

// Preconditioned CG on H p = b from p = 0, truncated at nonpositive curvature
// (Steihaug): p is then the last iterate, a descent direction for −b, or none (iterations 0).
CgResult truncated_cg(MatrixFreeNewtonProblem& problem, const TwoLevel& preconditioner, const Eigen::VectorXd& b,
                      double rtol, int max_iterations, Eigen::VectorXd& p) {
  const PhaseTimer timer(Phase::Solve);
  CgResult result;
  p.setZero(b.size());
  Eigen::VectorXd r = b, z, s, Hs(b.size());
  preconditioner.apply(r, z);
  s = z;
  double rz = r.dot(z);
  const double target = rtol * b.norm();
  while (result.iterations < max_iterations) {
    problem.apply_hessian(s, Hs);
    const double curvature = s.dot(Hs);
    if (!(curvature > 0.0)) {
      result.curvature = true;
      return result;
    }
    const double step = rz / curvature;
    p += step * s;
    r -= step * Hs;
    ++result.iterations;
    if (r.norm() <= target) {
      result.converged = true;
      return result;
    }
    preconditioner.apply(r, z);
    const double rz_next = r.dot(z);
    s = z + (rz_next / rz) * s;
    rz = rz_next;
  }
  return result;
}

}  // namespace

NewtonStats newton_matrix_free(MatrixFreeNewtonProblem& problem, const NewtonOptions& options,
                               const KrylovNewtonOptions& krylov) {
  NewtonStats stats;
  Assembly a;
  Eigen::VectorXd p;
  CoarseHessian coarse;
  std::unique_ptr<LinearSolver> coarse_solver;  // its symbolic analysis kept between steps
  // The preconditioner of the last evaluate_action()'s Hessian.
  const auto preconditioner = [&] {
    const PhaseTimer timer(Phase::SolverSetup);
    TwoLevel M(problem.hessian_blocks());
    if (krylov.two_level && problem.coarse_hessian(coarse) && coarse.A.rows() > 0) {
      if (!coarse_solver) {
        LinearSolverOptions lo;
        lo.kind = LinearSolverKind::Cholesky;
        lo.threads = krylov.threads;
        coarse_solver = make_linear_solver(lo, static_cast<std::size_t>(coarse.A.rows()));
      }
      // An indefinite A (the exact Hessian away from a minimiser): block Jacobi alone.
      if (coarse_solver->factorize(coarse.A)) M.set_coarse(coarse.R, coarse_solver.get());
    }
    return M;
  };
  const auto evaluate_action = [&](HessianMode mode) {
    const PhaseTimer timer(Phase::Assembly);
    problem.evaluate_action(mode, a);
  };
  bool exact_ready = false;
  double forcing = krylov.max_forcing, previous_norm = 0.0;
  for (;;) {
    bool exact = options.exact_first && exact_ready;
    evaluate_action(exact ? HessianMode::Exact : HessianMode::Projected);
    if (detail::ends_at(a, stats)) return stats;
    const double norm = a.gradient.norm();
    if (previous_norm > 0.0) {
      const double ratio = norm / previous_norm;
      double next = krylov.gamma * ratio * ratio;
      if (krylov.gamma * forcing * forcing > 0.1) next = std::max(next, krylov.gamma * forcing * forcing);
      forcing = std::clamp(next, krylov.min_forcing, krylov.max_forcing);
    }
    previous_norm = norm;
    CgResult cg = truncated_cg(problem, preconditioner(), -a.gradient, forcing, krylov.max_iterations, p);
    ++stats.linear_solves;
    stats.krylov_iterations += cg.iterations;
    if (exact && cg.curvature) {
      // The exact Hessian curves down within the Krylov space: the iterate is not yet where it
      // is convex, and CG's truncated step there was far too long (fichq3_rs3_o3: α = 1/128
      // after seven trials through inverted cells). Projected steps until one is taken in full.
      log_detail("newton: the exact Hessian is not positive definite on the Krylov space; projected steps");
      exact = exact_ready = false;
      evaluate_action(HessianMode::Projected);
      cg = truncated_cg(problem, preconditioner(), -a.gradient, forcing, krylov.max_iterations, p);
      ++stats.linear_solves;
      stats.krylov_iterations += cg.iterations;
    }
    if (cg.iterations == 0) {
      stats.message = "no descent direction: the projected Hessian has no positive curvature along the gradient";
      return stats;
    }
    stats.decrement = -0.5 * a.gradient.dot(p);
    // CG's −½gᵀp only grows towards ½gᵀH⁻¹g: the test is trusted from a converged solve only.
    if (cg.converged && stats.decrement <= options.decrement_tolerance) {
      stats.converged = true;
      return stats;
    }
    if (stats.iterations >= options.max_iterations) {
      stats.message = "Newton reached its iteration limit";
      return stats;
    }
    const detail::LineSearch s = detail::line_search(problem, a.value, a.gradient, p, options);
    if (s.alpha < options.min_step) {
      if (!exact) {
        stats.message = "the line search found no acceptable step";
        return stats;
      }
      log_detail("newton: no acceptable step along the exact Hessian's direction; projected steps");
      exact_ready = false;
      continue;
    }
    problem.accept(p, s.alpha);
    if (!exact && s.alpha == 1.0) exact_ready = true;
    stats.value = s.value;
    ++stats.iterations;
    if (log_enabled(LogLevel::Detail)) {
      char line[200];
      std::snprintf(line, sizeof line, "newton %d: %s step, alpha %.3g, forcing %.2g, %d CG iterations, decrement %.3e, energy %.10g",
                    stats.iterations, exact ? "exact" : "projected", s.alpha, forcing, cg.iterations, stats.decrement, s.value);
      log_detail(line);
    }
    if (options.on_step && !options.on_step(stats.iterations, s.alpha)) {
      stats.stopped = true;
      return stats;
    }
  }
}

}  // namespace meshmorph
