// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "solve/detail/cholmod_solver.h"

namespace meshmorph::detail {

/// MINRES preconditioned by the diagonal of A ("minres-jacobi"): paper 003's solver for the
/// Newton directions of fitting, kept as the baseline that the Cholesky and CG-AMG backends
/// are compared against. factorize() only inverts the diagonal and keeps a view of A: A must
/// stay alive and unchanged until the solves with it are done.
class MinresJacobiSolver final : public LinearSolver {
 public:
  explicit MinresJacobiSolver(const LinearSolverOptions& options) : options_(options) {}

  /// False when a diagonal entry is not positive (A is then not positive definite).
  bool factorize(const Eigen::SparseMatrix<double>& A) override;
  /// Stops when ‖b − Ax‖ ≤ rtol·‖b‖ (checked on the true residual) or after the options'
  /// max_iterations (ok = false).
  LinearSolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol = 0.0,
                         double decrease = 0.0) override;
  std::string name() const override { return "minres-jacobi"; }

 private:
  LinearSolverOptions options_;
  SparseView A_{};
  bool ready_ = false;
  Eigen::VectorXd inverse_diagonal_;
};

}  // namespace meshmorph::detail
